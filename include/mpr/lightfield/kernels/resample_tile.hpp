#pragma once
/// \file
/// One camera's bilinear contribution to a block of output rows that it sees at evenly spaced
/// positions along its rows, any step up to `kResampleMaxStep` (a focal plane parallel to the
/// camera plane seen at another scale than the cameras': the README's 700x400 animations of
/// 1400x800 cameras, a 960x540 window). Each output row blends two resampled camera rows
/// (`resample_row`); on AVX-512 with VBMI where the block's pixels read their texel pairs is
/// found once for all its rows, and both camera rows of an output row are resampled and blended
/// into it in one pass, with no row written in between.

#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/magnified_plan.hpp>
#include <mpr/lightfield/kernels/resample_row.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace mpr::detail {

/// A block of output rows as one camera sees it: pixel i of every row at camera column x + s i,
/// row r between camera rows iy[r] and iy[r] + 1 at vertical fraction ay[r]. Output row r gets,
/// for pixel i and channel k,
///   acc[r acc_stride + 3 i + k] += (1 - ay[r]) h_{iy[r]}[3 i + k] + ay[r] h_{iy[r]+1}[3 i + k],
/// h_y the camera row y resampled as `resample_row_portable` does (texel pairs clamped to the row,
/// `scale` applied). Preconditions: width >= 2, x >= 0, 0 < s, 0 <= iy[r] < height - 1.
template <class C>
struct ResampleTile {
  const C* texels = nullptr;             ///< the camera image, flat channels, rows of `width` texels
  std::size_t width = 0;                 ///< texels per camera row
  double x = 0, s = 1;                   ///< the first pixel's camera column and the step (camera pixels)
  std::size_t n = 0;                     ///< pixels per output row
  std::size_t rows = 0;                  ///< output rows
  const int* iy = nullptr;               ///< per output row: its upper camera row
  const float* ay = nullptr;             ///< per output row: its vertical fraction in [0, 1]
  float scale = 1;                       ///< channel scale of the texel type
  const std::uint16_t* lut = nullptr;    ///< decode table of 8-bit codes (unused otherwise)
  const std::uint16_t* linear = nullptr; ///< the texels' channels as 16-bit linear values, or nullptr
  const void* ahead = nullptr;           ///< where the next block's camera rows start (prefetched only), or nullptr
  std::ptrdiff_t ahead_stride = 0;       ///< bytes from one of those rows to the next
  float* acc = nullptr;                  ///< the output rows' accumulators (flat r g b)
  std::ptrdiff_t acc_stride = 0;         ///< channels from one output row's accumulators to the next
};

/// Where a group of 16 pixels reads its texel pairs (`ResampleGroup`), as stored between rows.
struct alignas(64) ResampleGroupStore {
  std::uint8_t index[2][64];
  float f[3][16];
  std::size_t start;
};

/// The groups of a row of n pixels at x + s i on camera rows of `width` texels, kept for the next
/// rows at the same positions (`resample_blend`: the row groups of one camera).
struct ResampleGroups {
  double x = 0, s = 0;
  std::size_t n = 0, width = 0;
  std::vector<ResampleGroupStore> groups;

  /// Whether the kept groups serve pixels at x + s i, i < n: the same row length, positions
  /// within 1e-4 pixel (as `LerpRowCache` reuses rows).
  [[nodiscard]] bool serve(double x1, double s1, std::size_t n1, std::size_t width1) const noexcept {
    return n1 == n && width1 == width && !groups.empty() && std::abs(x1 - x) <= 1e-4 &&
           std::abs(s1 - s) * static_cast<double>(n) <= 1e-4;
  }
};

/// Working memory of `resample_blend` and `resample_tile`, one per thread; it grows to the
/// longest rows seen.
struct ResampleTileWork {
  std::vector<float> h;  // two resampled rows (the portable form)
  ResampleGroups groups; // the groups of a block (the VBMI form)
#if MPR_HAVE_HWY
  kernels::MagnifiedPlan plan;    // the planned form's pairs (`resample_tile_stored`)
  std::vector<float> v;           // ... and a camera row's values (float texels)
  std::vector<std::uint16_t> v16; // ... (8-bit codes: their 16-bit table values)
#endif
};

#if defined(MPR_SIMD_X86)
// The groups of the pixels at x + s i, i < n, into `groups` ((n + 15) / 16 of them).
MPR_TARGET_AVX512_VBMI inline void fill_resample_groups(double x, double s, std::size_t n, std::size_t width,
                                                        ResampleGroupStore* groups) noexcept {
  const ResampleConstants c = load_resample_constants(s);
  const long last_pair = static_cast<long>(width) - 2;
  for (std::size_t g = 0; g < (n + 15) / 16; ++g) {
    const ResampleGroup q = resample_group(c, x, s, 16 * g, last_pair);
    for (int k = 0; k < 2; ++k) _mm512_store_si512(groups[g].index[k], q.index[k]);
    for (int k = 0; k < 3; ++k) _mm512_store_ps(groups[g].f[k], q.f[k]);
    groups[g].start = q.start;
  }
}

// One output row of n pixels from camera rows top and bottom (`bytes` codes each) through the
// stored groups: acc[3 i + k] += rw[i] ((1 - ay) scale h_top + ay scale h_bottom) (rw nullptr:
// weight 1).
MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE void blend_resampled_row(const DecodeBytes& d,
                                                                  const ResampleGroupStore* groups,
                                                                  const std::uint8_t* top, const std::uint8_t* bottom,
                                                                  std::size_t bytes, std::size_t n, float scale,
                                                                  float ay, const float* rw, float* acc) noexcept {
  const __m512 w0 = _mm512_set1_ps((1 - ay) * scale), w1 = _mm512_set1_ps(ay * scale);
  const __m512i lane_pixel[3] = {_mm512_loadu_si512(kResamplePatterns.lane_pixel[0]),
                                 _mm512_loadu_si512(kResamplePatterns.lane_pixel[1]),
                                 _mm512_loadu_si512(kResamplePatterns.lane_pixel[2])};
  for (std::size_t g = 0; g < (n + 15) / 16; ++g) {
    ResampleGroup q;
    for (int k = 0; k < 2; ++k) q.index[k] = _mm512_load_si512(groups[g].index[k]);
    for (int k = 0; k < 3; ++k) q.f[k] = _mm512_load_ps(groups[g].f[k]);
    q.start = groups[g].start;
    __m512 a[3], b[3];
    resample_group_values(d, top, bytes, q, a);
    resample_group_values(d, bottom, bytes, q, b);
    const std::size_t pixels = std::min<std::size_t>(16, n - 16 * g), floats = 3 * pixels;
    const __m512 weights = rw != nullptr
                               ? _mm512_maskz_loadu_ps(static_cast<__mmask16>((1u << pixels) - 1), rw + 16 * g)
                               : _mm512_setzero_ps();
    for (int k = 0; k < 3; ++k) {
      const std::size_t first = 16 * static_cast<std::size_t>(k);
      if (floats <= first) break;
      const __mmask16 keep =
          floats >= first + 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << (floats - first)) - 1);
      float* at = acc + 48 * g + first;
      const __m512 old = _mm512_maskz_loadu_ps(keep, at);
      __m512 out;
      if (rw != nullptr) {
        const __m512 sum = _mm512_fmadd_ps(w1, b[k], _mm512_mul_ps(w0, a[k]));
        out = _mm512_fmadd_ps(_mm512_maskz_permutexvar_ps(0xFFFF, lane_pixel[k], weights), sum, old);
      } else {
        out = _mm512_fmadd_ps(w1, b[k], _mm512_fmadd_ps(w0, a[k], old));
      }
      _mm512_mask_storeu_ps(at, keep, out);
    }
  }
}

// The VBMI form of `resample_blend` on stored groups.
MPR_TARGET_AVX512_VBMI inline void resample_blend_codes_vbmi(const ResampleGroupStore* groups, const std::uint8_t* top,
                                                             const std::uint8_t* bottom, std::size_t bytes,
                                                             const std::uint16_t* lut, std::size_t n, float scale,
                                                             float ay, const float* rw, float* acc) noexcept {
  blend_resampled_row(load_decode_bytes(lut), groups, top, bottom, bytes, n, scale, ay, rw, acc);
}

#endif

/// acc[3 i + k] += rw[i] ((1 - ay) h_0[3 i + k] + ay h_1[3 i + k]) for pixels i in [0, n) (rw
/// nullptr: weight 1), h_0 and h_1 the camera rows `top` and `bottom` (of `width` texels)
/// resampled at x + s i as `resample_row_portable` does: one output row of a resampled
/// shift-and-add, both rows resampled and blended in one pass on AVX-512 with VBMI, where the
/// pixels read their texel pairs found once for both and kept in `work.groups` for the next row
/// at the same positions. False (nothing added) when working memory cannot grow. Preconditions
/// as `resample_row`'s.
template <class C>
[[nodiscard]] bool resample_blend(const C* top, const C* bottom, std::size_t width, const std::uint16_t* lut, double x,
                                  double s, float scale, float ay, const float* rw, float* acc, std::size_t n,
                                  ResampleTileWork& work, SimdLevel level = dispatch_level()) noexcept {
#if defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<C, std::uint8_t>) {
    if (level >= SimdLevel::avx512vbmi && s <= kResampleMaxStep) {
      ResampleGroups& g = work.groups;
      if (!g.serve(x, s, n, width)) {
        try {
          if (g.groups.size() < (n + 15) / 16) g.groups.resize((n + 15) / 16);
        } catch (...) {
          return false;
        }
        fill_resample_groups(x, s, n, width, g.groups.data());
        g.x = x, g.s = s, g.n = n, g.width = width;
      }
      resample_blend_codes_vbmi(g.groups.data(), top, bottom, 3 * width, lut, n, scale, ay, rw, acc);
      return true;
    }
  }
#endif
  try {
    if (work.h.size() < 6 * n) work.h.resize(6 * n);
  } catch (...) {
    return false;
  }
  float* h = work.h.data();
  resample_row(top, width, lut, x, s, scale, h, n, static_cast<const C*>(nullptr), level);
  resample_row(bottom, width, lut, x, s, scale, h + 3 * n, n, static_cast<const C*>(nullptr), level);
  blend_rows(h, h + 3 * n, 1 - ay, ay, rw, acc, n, level);
  return true;
}

/// Adds the block `t` (see `ResampleTile`) to its accumulators at `level`, an output row at a
/// time (`resample_blend`: on AVX-512 with VBMI the groups are found for the first row and kept
/// for the others); false (nothing added) when working memory cannot grow.
template <class C>
[[nodiscard]] bool resample_tile(const ResampleTile<C>& t, ResampleTileWork& work,
                                 SimdLevel level = dispatch_level()) noexcept {
  const std::size_t stride = 3 * t.width;
  for (std::size_t r = 0; r < t.rows; ++r) {
    const C* top = t.texels + stride * static_cast<std::size_t>(t.iy[r]);
    // Only the first row can ask for memory (the others have the same length): a failure adds
    // nothing.
    if (!resample_blend(top, top + stride, t.width, t.lut, t.x, t.s, t.scale, t.ay[r], nullptr,
                        t.acc + static_cast<std::ptrdiff_t>(r) * t.acc_stride, t.n, work, level))
      return false;
  }
  return true;
}

} // namespace mpr::detail
