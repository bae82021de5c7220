#pragma once
/// \file
/// The inner loops of `CameraFrameSampler`'s row paths, with the instruction set chosen at run
/// time: shift-and-add of two camera rows with fixed bilinear weights (refocusing as in
/// Isaksen et al. 2000; the "shift-and-add" of synthetic-aperture photography, Vaish et al.
/// 2004), on rows stored as flat channel arrays (r g b r g b ..., see `Srgb8Texel`), and the
/// test that proves one camera nearest to each ray of a run (planar arrays).
///
/// Each kernel is written once as plain C++ and compiled up to three times (core/simd.hpp): for
/// the baseline of the build, and, on x86 with GCC or Clang, for AVX2+FMA and for AVX-512,
/// which the compiler's vectoriser fills at full width.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <mpr/core/detail/prefetch.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/geometry/detail/plane_kernels.hpp>
#include <mpr/lightfield/kernels/decode_vbmi.hpp>
#include <mpr/lightfield/kernels/lerp_row_hwy.hpp>

namespace mpr::detail {

/// The bilinear weights of one shift-and-add row, the channel scale of the texel type folded in.
struct RowWeights {
  float w00, w10, w01, w11;
};

/// acc[j] += rw[j] * (w00 a[j] + w10 a[j + 3] + w01 b[j] + w11 b[j + 3]) for j in [0, m): the
/// bilinear blend of rows a and b at a fixed sub-pixel offset, over flat RGB rows (so j + 3 is
/// the same channel one pixel to the right). `rw` (nullptr: weight 1) holds one weight per
/// channel slot. Reads a[0, m + 3) and b[0, m + 3); acc must not overlap them.
template <class C>
MPR_ALWAYS_INLINE void shift_add_flat_body(const C* MPR_RESTRICT a, const C* MPR_RESTRICT b, RowWeights w,
                                           const float* MPR_RESTRICT rw, float* MPR_RESTRICT acc,
                                           std::size_t m) noexcept {
  if (rw == nullptr) {
    for (std::size_t j = 0; j < m; ++j)
      acc[j] += w.w00 * static_cast<float>(a[j]) + w.w10 * static_cast<float>(a[j + 3]) +
                w.w01 * static_cast<float>(b[j]) + w.w11 * static_cast<float>(b[j + 3]);
  } else {
    for (std::size_t j = 0; j < m; ++j)
      acc[j] += rw[j] * (w.w00 * static_cast<float>(a[j]) + w.w10 * static_cast<float>(a[j + 3]) +
                         w.w01 * static_cast<float>(b[j]) + w.w11 * static_cast<float>(b[j + 3]));
  }
}

/// `shift_add_flat_body` compiled for `level` (default: the widest this CPU runs).
template <class C>
inline void shift_add_flat(const C* a, const C* b, RowWeights w, const float* rw, float* acc, std::size_t m,
                           SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { shift_add_flat_body(a, b, w, rw, acc, m); });
}

/// The value of a stored channel: the channel itself, or for 8-bit codes its entry of the 16-bit
/// linear decode table `lut` (`Srgb8Texel::linear16()`).
template <class C>
MPR_ALWAYS_INLINE float channel_value(C c, const std::uint16_t* lut) noexcept {
  if constexpr (std::is_same_v<C, std::uint8_t>)
    return static_cast<float>(lut[c]);
  else
    return static_cast<float>(c);
}

/// h[j] = scale ((1 - ax) v(a[j]) + ax v(a[j + 3])) for j in [0, m), v = `channel_value`: one
/// camera row interpolated horizontally at a fixed sub-pixel offset, over flat RGB channels
/// (the first half of a separable bilinear shift-and-add). Reads a[0, m + 3). With `ahead`
/// (nullptr: none), the row to be interpolated next (the next camera's) is asked of the cache
/// along the way, a line per 64 channels: rows taken camera after camera are not followed by the
/// hardware prefetcher (docs/performance.md). Its addresses are only prefetched, never read.
template <class C>
MPR_ALWAYS_INLINE void lerp_row_portable(const C* MPR_RESTRICT a, const std::uint16_t* MPR_RESTRICT lut, float ax,
                                         float scale, float* MPR_RESTRICT h, std::size_t m,
                                         const C* ahead = nullptr) noexcept {
  const float w0 = (1 - ax) * scale, w1 = ax * scale;
  constexpr std::size_t kLine = 64 / sizeof(C);
  for (std::size_t j0 = 0; j0 < m; j0 += kLine) {
    if (ahead != nullptr) prefetch_l2(ahead, j0 * sizeof(C));
    const std::size_t j1 = std::min(m, j0 + kLine);
    for (std::size_t j = j0; j < j1; ++j) h[j] = w0 * channel_value(a[j], lut) + w1 * channel_value(a[j + 3], lut);
  }
}

#if defined(MPR_SIMD_X86)
// The low half of a 512-bit vector, and a 256-bit vector widened with zeros: GCC 12's own casts
// pass an undefined vector that -Wmaybe-uninitialized reports (GCC bug 105593).
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m256i low256(__m512i v) noexcept {
  return _mm512_maskz_extracti64x4_epi64(0xF, v, 0);
}
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512i zext256(__m256i v) noexcept {
  return _mm512_maskz_inserti64x4(0xFF, _mm512_setzero_si512(), v, 0);
}

// The 16-bit decode table in eight AVX-512 registers, 32 entries each.
struct Decode16x512 {
  __m512i t[8];
};

MPR_TARGET_AVX512 MPR_ALWAYS_INLINE Decode16x512 load_decode16(const std::uint16_t* lut) noexcept {
  Decode16x512 d;
  for (int k = 0; k < 8; ++k) d.t[k] = _mm512_loadu_si512(lut + 32 * k);
  return d;
}

// The table entries of 32 codes held as 16-bit lanes (0..255): a two-register permute per 64
// entries (index bits 0-5), then bits 6 and 7 choose among the four.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512i decode16x32(const Decode16x512& d, __m512i codes) noexcept {
  const __m512i r0 = _mm512_permutex2var_epi16(d.t[0], codes, d.t[1]);
  const __m512i r1 = _mm512_permutex2var_epi16(d.t[2], codes, d.t[3]);
  const __m512i r2 = _mm512_permutex2var_epi16(d.t[4], codes, d.t[5]);
  const __m512i r3 = _mm512_permutex2var_epi16(d.t[6], codes, d.t[7]);
  const __mmask32 b6 = _mm512_test_epi16_mask(codes, _mm512_set1_epi16(64));
  const __mmask32 b7 = _mm512_test_epi16_mask(codes, _mm512_set1_epi16(128));
  const __m512i low = _mm512_mask_mov_epi16(r0, b6, r1), high = _mm512_mask_mov_epi16(r2, b6, r3);
  return _mm512_mask_mov_epi16(low, b7, high);
}

// The decoded values of the `count` (<= 32) codes at p as floats, lanes 0-15 and 16-31; lanes at
// or past `count` are not read and hold the value of code 0.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void decode_codes32(const Decode16x512& d, const std::uint8_t* p, std::size_t count,
                                                        __m512& first, __m512& second) noexcept {
  const __m256i bytes = count >= 32 ? _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))
                                    : _mm256_maskz_loadu_epi8(static_cast<__mmask32>((1ull << count) - 1), p);
  const __m512i codes = _mm512_maskz_cvtepu8_epi16(0xFFFFFFFFu, bytes);
  const __m512i v = decode16x32(d, codes);
  first = _mm512_maskz_cvtepi32_ps(0xFFFF, _mm512_maskz_cvtepu16_epi32(0xFFFF, low256(v)));
  second =
      _mm512_maskz_cvtepi32_ps(0xFFFF, _mm512_maskz_cvtepu16_epi32(0xFFFF, _mm512_maskz_extracti64x4_epi64(0xF, v, 1)));
}

// `lerp_row_portable` for 8-bit codes, 32 channels a step. Each code is decoded once: the
// values three channels on (one pixel to the right) come from the decoded block and the next by
// a lane shift.
MPR_TARGET_AVX512 inline void lerp_row_codes_avx512(const std::uint8_t* a, const std::uint16_t* lut, float ax,
                                                    float scale, float* h, std::size_t m,
                                                    const std::uint8_t* ahead = nullptr) noexcept {
  const Decode16x512 d = load_decode16(lut);
  const __m512 w0 = _mm512_set1_ps((1 - ax) * scale), w1 = _mm512_set1_ps(ax * scale);
  const std::size_t codes = m + 3; // readable codes
  __m512 lo, hi;
  decode_codes32(d, a, std::min<std::size_t>(32, codes), lo, hi);
  for (std::size_t j = 0; j < m; j += 32) {
    if (ahead != nullptr && j % 64 == 0) prefetch_l2(ahead, j);
    __m512 next_lo = lo, next_hi = hi;
    if (j + 32 < codes) decode_codes32(d, a + j + 32, std::min<std::size_t>(32, codes - j - 32), next_lo, next_hi);
    const __m512 right_lo =
        _mm512_castsi512_ps(_mm512_maskz_alignr_epi32(0xFFFF, _mm512_castps_si512(hi), _mm512_castps_si512(lo), 3));
    const __m512 right_hi = _mm512_castsi512_ps(
        _mm512_maskz_alignr_epi32(0xFFFF, _mm512_castps_si512(next_lo), _mm512_castps_si512(hi), 3));
    const __m512 h0 = _mm512_fmadd_ps(w1, right_lo, _mm512_mul_ps(w0, lo));
    const __m512 h1 = _mm512_fmadd_ps(w1, right_hi, _mm512_mul_ps(w0, hi));
    const std::size_t count = std::min<std::size_t>(32, m - j);
    if (count == 32) {
      _mm512_storeu_ps(h + j, h0);
      _mm512_storeu_ps(h + j + 16, h1);
    } else {
      const __mmask16 k0 = count >= 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << count) - 1);
      const __mmask16 k1 = count > 16 ? static_cast<__mmask16>((1u << (count - 16)) - 1) : __mmask16(0);
      _mm512_mask_storeu_ps(h + j, k0, h0);
      _mm512_mask_storeu_ps(h + j + 16, k1, h1);
    }
    lo = next_lo;
    hi = next_hi;
  }
}
#endif

/// `lerp_row_portable` at `level`, with the hand-written AVX-512 step for 8-bit codes (its VBMI
/// form where the CPU has it), and below AVX-512 for 8-bit codes the Highway kernel
/// (kernels/lerp_row_hwy.hpp) when Highway is present.
template <class C>
inline void lerp_row(const C* a, const std::uint16_t* lut, float ax, float scale, float* h, std::size_t m,
                     const C* ahead = nullptr, SimdLevel level = dispatch_level()) noexcept {
#if defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<C, std::uint8_t>) {
    if (level >= SimdLevel::avx512vbmi) return lerp_row_codes_vbmi(a, lut, ax, scale, h, m, ahead);
    if (level >= SimdLevel::avx512) return lerp_row_codes_avx512(a, lut, ax, scale, h, m, ahead);
  }
#endif
#if MPR_HAVE_HWY // below AVX-512: the Highway row (docs/simd.md)
  if constexpr (std::is_same_v<C, std::uint8_t>) return kernels::lerp_row_hwy(a, lut, ax, scale, h, m, ahead, level);
#endif
  run_at(level, [&]() MPR_INLINE_LAMBDA { lerp_row_portable(a, lut, ax, scale, h, m, ahead); });
}

/// acc[j] += scale v(a[j]) for j in [0, m), v = `channel_value`: one camera row added unshifted
/// within its texels (the 2-D shift at offsets of 0). Reads a[0, m).
template <class C>
MPR_ALWAYS_INLINE void add_scaled_row_body(const C* MPR_RESTRICT a, const std::uint16_t* MPR_RESTRICT lut, float scale,
                                           float* MPR_RESTRICT acc, std::size_t m) noexcept {
  for (std::size_t j = 0; j < m; ++j) acc[j] += scale * channel_value(a[j], lut);
}

/// `add_scaled_row_body` compiled for `level`; for 8-bit codes at `avx2` and `avx512` (without
/// VBMI) the Highway kernel (`kernels::sum_code_rows_hwy` of one row: the decode in registers).
template <class C>
inline void add_scaled_row(const C* a, const std::uint16_t* lut, float scale, float* acc, std::size_t m,
                           SimdLevel level = dispatch_level()) noexcept {
#if MPR_HAVE_HWY
  if constexpr (std::is_same_v<C, std::uint8_t>)
    if (level == SimdLevel::avx2 || level == SimdLevel::avx512)
      return kernels::sum_code_rows_hwy(&a, 1, lut, scale, acc, m, level);
#endif
  run_at(level, [&]() MPR_INLINE_LAMBDA { add_scaled_row_body(a, lut, scale, acc, m); });
}

/// acc[3 i + k] += rw[i] (w0 h0[3 i + k] + w1 h1[3 i + k]) for pixels i in [0, n) (rw nullptr:
/// weight 1): the vertical half of a separable bilinear shift-and-add, on rows from `lerp_row`.
MPR_ALWAYS_INLINE void blend_rows_body(const float* MPR_RESTRICT h0, const float* MPR_RESTRICT h1, float w0, float w1,
                                       const float* MPR_RESTRICT rw, float* MPR_RESTRICT acc, std::size_t n) noexcept {
  if (rw == nullptr) {
    for (std::size_t j = 0; j < 3 * n; ++j) acc[j] += w0 * h0[j] + w1 * h1[j];
  } else {
    // The per-pixel weights spread over the three channel slots, a stack buffer at a time, so
    // that the blend stays one flat loop.
    constexpr std::size_t kStep = 256;
    float spread[3 * kStep];
    for (std::size_t s0 = 0; s0 < n; s0 += kStep) {
      const std::size_t m = std::min(kStep, n - s0);
      for (std::size_t i = 0; i < m; ++i) spread[3 * i] = spread[3 * i + 1] = spread[3 * i + 2] = rw[s0 + i];
      const float* a = h0 + 3 * s0;
      const float* b = h1 + 3 * s0;
      float* out = acc + 3 * s0;
      for (std::size_t j = 0; j < 3 * m; ++j) out[j] += spread[j] * (w0 * a[j] + w1 * b[j]);
    }
  }
}

/// `blend_rows_body` compiled for `level`.
inline void blend_rows(const float* h0, const float* h1, float w0, float w1, const float* rw, float* acc, std::size_t n,
                       SimdLevel level = dispatch_level()) noexcept {
  // A weight of 0 on the second row (a vertical offset of 0): the first alone, the second not read.
  if (w1 == 0)
    run_at(level, [&]() MPR_INLINE_LAMBDA { blend_rows_body(h0, h0, w0, 0.0f, rw, acc, n); });
  else
    run_at(level, [&]() MPR_INLINE_LAMBDA { blend_rows_body(h0, h1, w0, w1, rw, acc, n); });
}

/// out[3 i + k] = acc[3 i + k] / weight[i] for pixels i in [0, n) with weight[i] > 0, 0 for the
/// others (their colour is the caller's): the averages of a row of sums, as `FrameTable::finish`
/// computes them (the reciprocal, then three products), a stack buffer at a time.
MPR_ALWAYS_INLINE void average_rows_body(const float* MPR_RESTRICT acc, const float* MPR_RESTRICT weight,
                                         float* MPR_RESTRICT out, std::size_t n) noexcept {
  constexpr std::size_t kStep = 256;
  float spread[3 * kStep];
  for (std::size_t s0 = 0; s0 < n; s0 += kStep) {
    const std::size_t m = std::min(kStep, n - s0);
    for (std::size_t i = 0; i < m; ++i) {
      // The reciprocal of every weight, then 0 by its bits where the weight is not positive:
      // under a select the compiler moves the division into a branch below AVX-512, and the
      // loop no longer vectorises there.
      const float w = weight[s0 + i];
      const std::int32_t keep = w > 0 ? -1 : 0;
      const float inv = std::bit_cast<float>(std::bit_cast<std::int32_t>(1.0f / w) & keep);
      spread[3 * i] = spread[3 * i + 1] = spread[3 * i + 2] = inv;
    }
    for (std::size_t j = 0; j < 3 * m; ++j) out[3 * s0 + j] = acc[3 * s0 + j] * spread[j];
  }
}

/// `average_rows_body` compiled for `level`.
inline void average_rows(const float* acc, const float* weight, float* out, std::size_t n,
                         SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { average_rows_body(acc, weight, out, n); });
}

/// Asks the cache for the bytes of [begin, end) (GCC and Clang; nothing elsewhere).
template <class P>
MPR_ALWAYS_INLINE void prefetch_range(const P* begin, const P* end) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  const char* next = reinterpret_cast<const char*>(begin);
  const char* stop = reinterpret_cast<const char*>(end);
  for (; next < stop; next += 64) __builtin_prefetch(next);
#else
  (void)begin;
  (void)end;
#endif
}

/// Camera k of a planar array as the nearest-camera proof needs it: in-plane centre (cu, cv),
/// the in-plane centres of its listed neighbours, and rho2: rays crossing the plane within
/// sqrt(rho2) of the centre are farther from every unlisted camera (see
/// `CameraFrameSampler::tile_nearest`); margin2 is the absolute slack on squared distances.
/// Neighbour lists up to this length take the proof's unrolled form (`ArrayPlane` lists at most
/// 8: a square grid's ring).
inline constexpr int kProofNeighbours = 8;

template <class T>
struct NearestCandidate {
  T cu, cv, rho2, margin2;
  const T *nu, *nv;
  int neighbours;
};

/// pass[i] = all bits set when ray i of `rays` (i in [0, n)) is proved nearer to camera `k`
/// than to any other camera, 0 otherwise; `scratch` holds n values. The squared distance of an
/// in-plane centre c to the line through x with direction d is (|e|^2 |d|^2 - (e . d)^2) / |d|^2
/// with e = c - x; the test compares these numerators (all scaled by the same |d|^2): every
/// listed neighbour must be farther by a relative 1e-4 plus the margin, and the crossing must lie
/// within rho of the centre.
template <class T>
MPR_ALWAYS_INLINE void prove_nearest_body(const PlaneRays<T>& rays, std::size_t n, const NearestCandidate<T>& k,
                                          typename PlaneRays<T>::Flag* MPR_RESTRICT pass,
                                          T* MPR_RESTRICT scratch) noexcept {
  using Flag = typename PlaneRays<T>::Flag;
  const T* MPR_RESTRICT xu = rays.xu;
  const T* MPR_RESTRICT xv = rays.xv;
  const T* MPR_RESTRICT du = rays.du;
  const T* MPR_RESTRICT dv = rays.dv;
  const T* MPR_RESTRICT dd = rays.dd;
  const Flag* MPR_RESTRICT ok = rays.ok;
  if (k.neighbours >= 1 && k.neighbours <= kProofNeighbours) {
    // A fixed count of neighbours (the list padded with its first, a test that changes nothing),
    // so that the neighbour loop unrolls and each ray's flag stays in a register.
    T nu[kProofNeighbours], nv[kProofNeighbours];
    for (int j = 0; j < kProofNeighbours; ++j) {
      nu[j] = k.nu[j < k.neighbours ? j : 0];
      nv[j] = k.nv[j < k.neighbours ? j : 0];
    }
    for (std::size_t i = 0; i < n; ++i) {
      const T eu = k.cu - xu[i], ev = k.cv - xv[i];
      const T r2 = eu * eu + ev * ev, ed = eu * du[i] + ev * dv[i];
      const T own = (r2 * dd[i] - ed * ed) * T(1.0001) + k.margin2 * dd[i];
      Flag f = ok[i] & (r2 < k.rho2 ? Flag(-1) : Flag(0));
      for (int j = 0; j < kProofNeighbours; ++j) {
        const T fu = nu[j] - xu[i], fv = nv[j] - xv[i];
        const T f2 = fu * fu + fv * fv, fd = fu * du[i] + fv * dv[i];
        f &= (f2 * dd[i] - fd * fd) > own ? Flag(-1) : Flag(0);
      }
      pass[i] = f;
    }
    return;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const T eu = k.cu - xu[i], ev = k.cv - xv[i];
    const T r2 = eu * eu + ev * ev, ed = eu * du[i] + ev * dv[i];
    scratch[i] = (r2 * dd[i] - ed * ed) * T(1.0001) + k.margin2 * dd[i];
    pass[i] = ok[i] & (r2 < k.rho2 ? Flag(-1) : Flag(0));
  }
  for (int j = 0; j < k.neighbours; ++j) {
    const T cu = k.nu[j], cv = k.nv[j];
    for (std::size_t i = 0; i < n; ++i) {
      const T eu = cu - xu[i], ev = cv - xv[i];
      const T r2 = eu * eu + ev * ev, ed = eu * du[i] + ev * dv[i];
      pass[i] &= (r2 * dd[i] - ed * ed) > scratch[i] ? Flag(-1) : Flag(0);
    }
  }
}

/// `prove_nearest_body` compiled for `level`.
template <class T>
inline void prove_nearest(const PlaneRays<T>& rays, std::size_t n, const NearestCandidate<T>& k,
                          typename PlaneRays<T>::Flag* pass, T* scratch, SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { prove_nearest_body(rays, n, k, pass, scratch); });
}

/// The least of v[0, n) (+inf when n = 0; NaNs ignored), with eight independent running minima
/// so that the loop is not one chain of dependent comparisons.
template <class T>
[[nodiscard]] inline T min_of(const T* v, std::size_t n) noexcept {
  T m[8];
  for (T& x : m) x = std::numeric_limits<T>::infinity();
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (std::size_t l = 0; l < 8; ++l) m[l] = std::min(m[l], v[i + l]);
  for (; i < n; ++i) m[0] = std::min(m[0], v[i]);
  T out = m[0];
  for (std::size_t l = 1; l < 8; ++l) out = std::min(out, m[l]);
  return out;
}

/// lo = min(lo, v[0, n)), hi = max(hi, v[0, n)) (NaNs ignored), with eight independent running
/// bounds as in `min_of`.
template <class T>
inline void widen_bounds(const T* v, std::size_t n, T& lo, T& hi) noexcept {
  T l[8], h[8];
  for (std::size_t k = 0; k < 8; ++k) {
    l[k] = lo;
    h[k] = hi;
  }
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (std::size_t k = 0; k < 8; ++k) {
      l[k] = v[i + k] < l[k] ? v[i + k] : l[k];
      h[k] = v[i + k] > h[k] ? v[i + k] : h[k];
    }
  for (; i < n; ++i) {
    l[0] = v[i] < l[0] ? v[i] : l[0];
    h[0] = v[i] > h[0] ? v[i] : h[0];
  }
  for (std::size_t k = 0; k < 8; ++k) {
    lo = l[k] < lo ? l[k] : lo;
    hi = h[k] > hi ? h[k] : hi;
  }
}

/// Whether the points (x[i], y[i], z[i]), i in [0, n), lie at p_0 + i (p_{n-1} - p_0) / (n - 1)
/// within `tolerance` per coordinate (NaN never does). Structure of arrays, so that it vectorises.
template <class T>
MPR_ALWAYS_INLINE bool evenly_spaced_body(const T* MPR_RESTRICT x, const T* MPR_RESTRICT y, const T* MPR_RESTRICT z,
                                          int n, T tolerance) noexcept {
  if (n < 3) return true;
  const T span = static_cast<T>(n - 1);
  const T sx = (x[n - 1] - x[0]) / span, sy = (y[n - 1] - y[0]) / span, sz = (z[n - 1] - z[0]) / span;
  const T x0 = x[0], y0 = y[0], z0 = z[0];
  int bad = 0;
  for (int i = 1; i < n - 1; ++i) {
    const T t = static_cast<T>(i);
    // `&` of ints, not `&&`: no branch, so the loop vectorises.
    const int good = static_cast<int>(std::abs(x[i] - (x0 + t * sx)) <= tolerance) &
                     static_cast<int>(std::abs(y[i] - (y0 + t * sy)) <= tolerance) &
                     static_cast<int>(std::abs(z[i] - (z0 + t * sz)) <= tolerance);
    bad |= good ^ 1;
  }
  return bad == 0;
}

/// `evenly_spaced_body` compiled for `level`.
template <class T>
inline bool evenly_spaced(const T* x, const T* y, const T* z, int n, T tolerance,
                          SimdLevel level = dispatch_level()) noexcept {
  bool even = false;
  run_at(level, [&]() MPR_INLINE_LAMBDA { even = evenly_spaced_body(x, y, z, n, tolerance); });
  return even;
}

} // namespace mpr::detail
