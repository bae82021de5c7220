#pragma once
/// \file
/// The projective-row kernel of the light-field row paths: one camera's bilinear pixels at n
/// points evenly spaced along a line, whose pixel coordinates are a projective function of the
/// point's index (the camera's homography of the line: x_i = (a + i b) / (c + i d)). This is the
/// row of any planar focal surface, tilted or not, at any output scale. Written once as plain
/// C++ (any scalar, any texel channel type) and once with Highway for float coordinates, where
/// the four bilinear taps are gathered (kernels/projective_row_hwy.hpp; one body for SSE4, AVX2
/// and AVX-512).

#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/projective_row_hwy.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace mpr::detail {

/// One camera seen along a row: the homogeneous pixel of point i is (h0 + i hs) (x, y, w; the
/// camera's 3x4 projection applied to p_0 and to the step between points), and the image it
/// reads: `width` x `height` texels of three channels each, row-major and packed (`texels[3 t +
/// k]` is channel k of texel t), colour = `channel_value(channel, lut)` x `scale` (`lut`: the
/// decode table of 8-bit codes, else unused). 8-bit texels need readable bytes after the last
/// (`HugePageAllocator`'s padding): the gathers load each texel as a 32-bit word.
template <class T, class C>
struct ProjectiveRow {
  T h0[3], hs[3];
  int width, height;
  const C* texels;
  float scale;
  const std::uint16_t* lut = nullptr;
};

/// Whether the kernels can index every channel of a `width` x `height` image with 32-bit
/// offsets (as the gathers do), two channels to spare.
[[nodiscard]] constexpr bool gather_indexable(int width, int height) noexcept {
  return width > 0 && height > 0 && 3.0 * width * static_cast<double>(height) + 2 < 2147483647.0;
}

/// Point i of the row (i in [0, n)) with weight rw[i] (rw nullptr: weight 1): when the camera
/// sees it -- w > 0 and the pixel (x, y) inside [-0.5, width - 0.5) x [-0.5, height - 0.5), the
/// test of `FrameTable::project` -- and the weight is positive, acc[3 i + k] += weight x (the
/// bilinear pixel, edge texels repeated) and seen[i] += weight. The plain loop: every level's
/// reference, and the body for scalars and texels without a hand-written step.
template <class T, class C>
MPR_ALWAYS_INLINE void projective_row_portable(const ProjectiveRow<T, C>& r, std::size_t begin, std::size_t n,
                                               const float* rw, float* acc, float* seen) noexcept {
  const T xmax = static_cast<T>(r.width) - T(0.5), ymax = static_cast<T>(r.height) - T(0.5);
  for (std::size_t i = begin; i < n; ++i) {
    const float wt = rw != nullptr ? rw[i] : 1.0f;
    if (!(wt > 0)) continue;
    const T t = static_cast<T>(i);
    const T w = r.h0[2] + t * r.hs[2];
    if (!(w > 0)) continue;
    const T x = (r.h0[0] + t * r.hs[0]) / w, y = (r.h0[1] + t * r.hs[1]) / w;
    if (!(x >= T(-0.5) && x < xmax && y >= T(-0.5) && y < ymax)) continue;
    const T fx = std::floor(x), fy = std::floor(y);
    const float ax = static_cast<float>(x - fx), ay = static_cast<float>(y - fy);
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    const std::ptrdiff_t xa = std::max(x0, 0), xb = std::min(x0 + 1, r.width - 1);
    const std::ptrdiff_t ya = std::max(y0, 0), yb = std::min(y0 + 1, r.height - 1);
    const C* ra = r.texels + 3 * ya * r.width;
    const C* rb = r.texels + 3 * yb * r.width;
    const float s = wt * r.scale;
    const float w00 = (1 - ax) * (1 - ay) * s, w10 = ax * (1 - ay) * s, w01 = (1 - ax) * ay * s, w11 = ax * ay * s;
    for (int k = 0; k < 3; ++k)
      acc[3 * i + k] += w00 * channel_value(ra[3 * xa + k], r.lut) + w10 * channel_value(ra[3 * xb + k], r.lut) +
                        w01 * channel_value(rb[3 * xa + k], r.lut) + w11 * channel_value(rb[3 * xb + k], r.lut);
    seen[i] += wt;
  }
}

/// `projective_row_portable` over [0, n), at `level` by the Highway kernel
/// (kernels/projective_row_hwy.hpp) for float coordinates, 8-bit or float channels (the texels of
/// `CameraFrameSet`) and images `gather_indexable`; other scalars and channel types, and builds or
/// CPUs without a Highway target for `level`, run the plain loop.
template <class T, class C>
inline void projective_row(const ProjectiveRow<T, C>& r, std::size_t n, const float* rw, float* acc, float* seen,
                           SimdLevel level = dispatch_level()) noexcept {
#if MPR_HAVE_HWY && defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<T, float> && (std::is_same_v<C, float> || std::is_same_v<C, std::uint8_t>)) {
    if (gather_indexable(r.width, r.height) && kernels::projective_row_hwy(r, n, rw, acc, seen, level)) return;
  }
#endif
  run_at(level, [&]() MPR_INLINE_LAMBDA { projective_row_portable(r, 0, n, rw, acc, seen); });
}

} // namespace mpr::detail
