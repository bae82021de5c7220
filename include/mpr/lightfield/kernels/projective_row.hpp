#pragma once
/// \file
/// The projective-row kernel of the light-field row paths: one camera's bilinear pixels at n
/// points evenly spaced along a line, whose pixel coordinates are a projective function of the
/// point's index (the camera's homography of the line: x_i = (a + i b) / (c + i d)). This is the
/// row of any planar focal surface, tilted or not, at any output scale. Written once as plain
/// C++ (any scalar, any texel channel type), once with Highway for float coordinates below
/// AVX-512 (kernels/projective_row_hwy.hpp: SSE4 and AVX2), and with AVX-512 intrinsics, where
/// r and g of 16 texels are decoded by one 32-lane 16-bit table lookup (Highway 1.0's
/// per-channel cubic there measured 9% slower on the tilted plane in the -march=native build).
/// The four bilinear taps are gathered.

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
/// (`HugePageAllocator`'s padding): the AVX-512 step loads each texel as a 32-bit word.
/// `linear` (8-bit texels only; nullptr: none): the same channels as 16-bit decode-table values
/// (`CameraFrameSet::linear16`, `linear[k] = lut[texels[k]]`, readable values after the last),
/// which the Highway kernel gathers in place of decoding the codes (the same sums).
template <class T, class C>
struct ProjectiveRow {
  T h0[3], hs[3];
  int width, height;
  const C* texels;
  float scale;
  const std::uint16_t* lut = nullptr;
  const std::uint16_t* linear = nullptr;
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

#if defined(MPR_SIMD_X86)
// The interleave of 16 r, g and b lanes into 48 channel slots (r g b r g b ...): slot s of output
// vector q holds channel (16 q + s) % 3 of point (16 q + s) / 3; r and g are merged first
// (indices `rg`), then b (indices `b`).
struct InterleaveRgb16 {
  alignas(64) int rg[3][16]{};
  alignas(64) int b[3][16]{};
  constexpr InterleaveRgb16() noexcept {
    for (int q = 0; q < 3; ++q)
      for (int s = 0; s < 16; ++s) {
        const int slot = 16 * q + s, point = slot / 3, channel = slot % 3;
        rg[q][s] = channel == 1 ? 16 + point : point;
        b[q][s] = channel == 2 ? 16 + point : s;
      }
  }
};

// Every lane. The masked forms of the intrinsics are used throughout: GCC 12's unmasked ones
// pass an undefined vector that -Wmaybe-uninitialized reports (GCC bug 105593).
inline constexpr __mmask16 kAll = 0xFFFF;

// 16 unsigned 16-bit lanes as floats.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 words_to_floats(__m256i words) noexcept {
  return _mm512_maskz_cvtepi32_ps(kAll, _mm512_maskz_cvtepu16_epi32(kAll, words));
}

// The three channels of sixteen gathered 8-bit texels (lane l: r g b in its low three bytes,
// the fourth ignored), decoded by the table `d` to floats: r and g in one 32-lane lookup, b in
// another.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void decode_texel_words(const Decode16x512& d, __m512i g, __m512 (&v)[3]) noexcept {
  const __m512i byte = _mm512_set1_epi32(0xFF);
  const __m256i r8 = _mm512_maskz_cvtepi32_epi16(kAll, _mm512_and_si512(g, byte));
  const __m256i g8 = _mm512_maskz_cvtepi32_epi16(kAll, _mm512_and_si512(_mm512_maskz_srli_epi32(kAll, g, 8), byte));
  const __m256i b8 = _mm512_maskz_cvtepi32_epi16(kAll, _mm512_and_si512(_mm512_maskz_srli_epi32(kAll, g, 16), byte));
  const __m512i rg = decode16x32(d, _mm512_maskz_inserti64x4(0xFF, zext256(r8), g8, 1));
  const __m512i bb = decode16x32(d, zext256(b8));
  v[0] = words_to_floats(low256(rg));
  v[1] = words_to_floats(_mm512_maskz_extracti64x4_epi64(0xF, rg, 1));
  v[2] = words_to_floats(low256(bb));
}

// sum[k] += weight x channel k of the texels at channel offsets `offset` (16 lanes).
template <class C>
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void gather_tap_avx512(const C* texels, const Decode16x512* decode, __m512i offset,
                                                           __m512 weight, __m512 (&sum)[3]) noexcept {
  if constexpr (std::is_same_v<C, std::uint8_t>) {
    // One 32-bit gather per texel (r g b and a byte past it), the three codes decoded together.
    const __m512i g = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), kAll, offset, texels, 1);
    __m512 v[3];
    decode_texel_words(*decode, g, v);
    for (int k = 0; k < 3; ++k) sum[k] = _mm512_fmadd_ps(weight, v[k], sum[k]);
  } else {
    static_assert(std::is_same_v<C, float>, "8-bit codes or float channels");
    for (int k = 0; k < 3; ++k) {
      const __m512 v = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), kAll,
                                                _mm512_add_epi32(offset, _mm512_set1_epi32(k)), texels, 4);
      sum[k] = _mm512_fmadd_ps(weight, v, sum[k]);
    }
  }
}

// Points ahead of the current ones whose texels are prefetched, and every how many lanes.
inline constexpr int kAhead = 64;
inline constexpr int kPrefetchLanes = 2;

// The 16 points from i on: their pixel coordinates, their weights (1, or rw) and the lanes the
// camera sees with a positive weight (`m`; none past n).
struct ProjectiveLanes {
  __m512 x, y, wt;
  __mmask16 m;
};

template <class C>
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE ProjectiveLanes projective_lanes(const ProjectiveRow<float, C>& r, std::size_t i,
                                                                     std::size_t n, const float* rw) noexcept {
  const __m512 zero = _mm512_setzero_ps(), lo = _mm512_set1_ps(-0.5f);
  const __m512 iota = _mm512_setr_ps(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __mmask16 live = n - i >= 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << (n - i)) - 1);
  const __m512 t = _mm512_add_ps(_mm512_set1_ps(static_cast<float>(i)), iota);
  const __m512 w = _mm512_fmadd_ps(t, _mm512_set1_ps(r.hs[2]), _mm512_set1_ps(r.h0[2]));
  const __m512 nx = _mm512_fmadd_ps(t, _mm512_set1_ps(r.hs[0]), _mm512_set1_ps(r.h0[0]));
  const __m512 ny = _mm512_fmadd_ps(t, _mm512_set1_ps(r.hs[1]), _mm512_set1_ps(r.h0[1]));
  ProjectiveLanes p;
  p.x = _mm512_div_ps(nx, w);
  p.y = _mm512_div_ps(ny, w);
  p.m = live & _mm512_cmp_ps_mask(w, zero, _CMP_GT_OQ);
  p.m &= _mm512_cmp_ps_mask(p.x, lo, _CMP_GE_OQ) &
         _mm512_cmp_ps_mask(p.x, _mm512_set1_ps(static_cast<float>(r.width) - 0.5f), _CMP_LT_OQ);
  p.m &= _mm512_cmp_ps_mask(p.y, lo, _CMP_GE_OQ) &
         _mm512_cmp_ps_mask(p.y, _mm512_set1_ps(static_cast<float>(r.height) - 0.5f), _CMP_LT_OQ);
  p.wt = _mm512_set1_ps(1.0f);
  if (rw != nullptr) {
    p.wt = _mm512_maskz_loadu_ps(live, rw + i);
    p.m &= _mm512_cmp_ps_mask(p.wt, zero, _CMP_GT_OQ);
  }
  return p;
}

// Asks for the texel rows of the points kAhead on from i: a tilted or scaled row walks across
// camera rows, which the hardware prefetcher does not follow.
template <class C>
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void projective_prefetch(const ProjectiveRow<float, C>& r, std::size_t i) noexcept {
  const __m512 iota = _mm512_setr_ps(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512 zero = _mm512_setzero_ps();
  const __m512 t = _mm512_add_ps(_mm512_set1_ps(static_cast<float>(i + kAhead)), iota);
  const __m512 w = _mm512_fmadd_ps(t, _mm512_set1_ps(r.hs[2]), _mm512_set1_ps(r.h0[2]));
  const __m512 inv = _mm512_maskz_rcp14_ps(kAll, w);
  __m512 x = _mm512_mul_ps(_mm512_fmadd_ps(t, _mm512_set1_ps(r.hs[0]), _mm512_set1_ps(r.h0[0])), inv);
  __m512 y = _mm512_mul_ps(_mm512_fmadd_ps(t, _mm512_set1_ps(r.hs[1]), _mm512_set1_ps(r.h0[1])), inv);
  x = _mm512_maskz_min_ps(kAll, _mm512_maskz_max_ps(kAll, x, zero), _mm512_set1_ps(static_cast<float>(r.width - 1)));
  y = _mm512_maskz_min_ps(kAll, _mm512_maskz_max_ps(kAll, y, zero), _mm512_set1_ps(static_cast<float>(r.height - 1)));
  const __m512i off =
      _mm512_add_epi32(_mm512_mullo_epi32(_mm512_maskz_cvttps_epi32(kAll, y), _mm512_set1_epi32(3 * r.width)),
                       _mm512_mullo_epi32(_mm512_maskz_cvttps_epi32(kAll, x), _mm512_set1_epi32(3)));
  alignas(64) int o[16];
  _mm512_store_si512(o, off);
  for (int l = 0; l < 16; l += kPrefetchLanes) {
    __builtin_prefetch(r.texels + o[l]);
    __builtin_prefetch(r.texels + o[l] + 3 * r.width);
  }
}

// acc[3 i ...] += the 16 points' channel sums (r, g and b of point l in lane l of sum[0], sum[1],
// sum[2]), interleaved into r g b triples; `count` points of the 16 are stored.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void add_rgb_sums(const __m512 (&sum)[3], std::size_t count, float* acc) noexcept {
  static constexpr InterleaveRgb16 order{};
  const std::size_t slots = 3 * count;
  for (int q = 0; q < 3; ++q) {
    const std::size_t first = 16 * static_cast<std::size_t>(q);
    if (first >= slots) break;
    const __mmask16 keep =
        slots - first >= 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << (slots - first)) - 1);
    const __m512 rg = _mm512_permutex2var_ps(sum[0], _mm512_load_si512(order.rg[q]), sum[1]);
    const __m512 v = _mm512_permutex2var_ps(rg, _mm512_load_si512(order.b[q]), sum[2]);
    _mm512_mask_storeu_ps(acc + first, keep, _mm512_add_ps(_mm512_maskz_loadu_ps(keep, acc + first), v));
  }
}

// The gather step of 16 points (`projective_lanes`): lanes the camera does not see get zero
// weights and clamped in-range texel indices, so every gather reads inside the image.
template <class C>
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void projective_gather(const ProjectiveRow<float, C>& r, const Decode16x512* decode,
                                                           const ProjectiveLanes& p, std::size_t count,
                                                           float* acc) noexcept {
  const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f);
  const __m512i izero = _mm512_setzero_si512(), ione = _mm512_set1_epi32(1), three = _mm512_set1_epi32(3);
  const __m512i stride = _mm512_set1_epi32(3 * r.width);
  const __m512 xs = _mm512_mask_mov_ps(zero, p.m, p.x), ys = _mm512_mask_mov_ps(zero, p.m, p.y);
  const __m512 fx = _mm512_maskz_roundscale_ps(kAll, xs, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
  const __m512 fy = _mm512_maskz_roundscale_ps(kAll, ys, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
  const __m512 ax = _mm512_sub_ps(xs, fx), ay = _mm512_sub_ps(ys, fy);
  const __m512i x0 = _mm512_maskz_cvttps_epi32(kAll, fx), y0 = _mm512_maskz_cvttps_epi32(kAll, fy);
  const __m512i xa = _mm512_mullo_epi32(_mm512_maskz_max_epi32(kAll, x0, izero), three);
  const __m512i xb = _mm512_mullo_epi32(
      _mm512_maskz_min_epi32(kAll, _mm512_add_epi32(x0, ione), _mm512_set1_epi32(r.width - 1)), three);
  const __m512i ya = _mm512_mullo_epi32(_mm512_maskz_max_epi32(kAll, y0, izero), stride);
  const __m512i yb = _mm512_mullo_epi32(
      _mm512_maskz_min_epi32(kAll, _mm512_add_epi32(y0, ione), _mm512_set1_epi32(r.height - 1)), stride);
  const __m512 s = _mm512_maskz_mul_ps(p.m, p.wt, _mm512_set1_ps(r.scale));
  const __m512 bx = _mm512_sub_ps(one, ax), by = _mm512_sub_ps(one, ay);
  const __m512 w00 = _mm512_mul_ps(_mm512_mul_ps(bx, by), s), w10 = _mm512_mul_ps(_mm512_mul_ps(ax, by), s);
  const __m512 w01 = _mm512_mul_ps(_mm512_mul_ps(bx, ay), s), w11 = _mm512_mul_ps(_mm512_mul_ps(ax, ay), s);
  __m512 sum[3] = {zero, zero, zero};
  gather_tap_avx512(r.texels, decode, _mm512_add_epi32(ya, xa), w00, sum);
  gather_tap_avx512(r.texels, decode, _mm512_add_epi32(ya, xb), w10, sum);
  gather_tap_avx512(r.texels, decode, _mm512_add_epi32(yb, xa), w01, sum);
  gather_tap_avx512(r.texels, decode, _mm512_add_epi32(yb, xb), w11, sum);
  add_rgb_sums(sum, count, acc);
}

// The AVX-512 kernel: 16 points at a time, float coordinates, four gathered taps each.
template <class C>
MPR_TARGET_AVX512 inline void projective_row_avx512(const ProjectiveRow<float, C>& r, std::size_t n, const float* rw,
                                                    float* acc, float* seen) noexcept {
  Decode16x512 decode{};
  if constexpr (std::is_same_v<C, std::uint8_t>) decode = load_decode16(r.lut);
  for (std::size_t i = 0; i < n; i += 16) {
    projective_prefetch(r, i);
    const ProjectiveLanes p = projective_lanes(r, i, n, rw);
    if (p.m == 0) continue;
    projective_gather(r, &decode, p, std::min<std::size_t>(16, n - i), acc + 3 * i);
    _mm512_mask_storeu_ps(seen + i, p.m, _mm512_add_ps(_mm512_maskz_loadu_ps(p.m, seen + i), p.wt));
  }
}

#endif

/// `projective_row_portable` over [0, n) at `level`, for float coordinates, 8-bit or float
/// channels (the texels of `CameraFrameSet`) and images `gather_indexable`: the AVX-512 kernel
/// at `avx512` and above, the Highway kernel below (SSE4 at `portable` when the CPU has SSE4.2).
/// Other scalars and channel types run the plain loop.
template <class T, class C>
inline void projective_row(const ProjectiveRow<T, C>& r, std::size_t n, const float* rw, float* acc, float* seen,
                           SimdLevel level = dispatch_level()) noexcept {
#if defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<T, float> && (std::is_same_v<C, float> || std::is_same_v<C, std::uint8_t>)) {
    if (level >= SimdLevel::avx512 && gather_indexable(r.width, r.height)) {
      return projective_row_avx512(r, n, rw, acc, seen);
    }
#if MPR_HAVE_HWY
    if (gather_indexable(r.width, r.height) && kernels::projective_row_hwy(r, n, rw, acc, seen, level)) return;
#endif
  }
#endif
  run_at(level, [&]() MPR_INLINE_LAMBDA { projective_row_portable(r, 0, n, rw, acc, seen); });
}

} // namespace mpr::detail
