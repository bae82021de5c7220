#pragma once
/// \file
/// 8-bit sRGB codes decoded to the 16-bit linear table (`Srgb8Texel::linear16()`) 64 at a time
/// with the byte permutes of AVX-512 VBMI: the table is held as two byte planes (low and high
/// bytes of its 256 entries, four registers each), each code picks its two bytes with two-register
/// permutes (seven index bits) and its top bit chooses between the halves; the bytes are then
/// interleaved into words (`decode16x64`: ten instructions for 64 codes, against two 32-code
/// word-permute decodes, `decode16x32`, eighteen with the widening), or spread straight into
/// 32-bit lanes and converted to floats (`decode_floats64`). And the horizontal row interpolation
/// of the separable shift-and-add on top of it (`lerp_row_codes_vbmi`), alone, fused with the
/// vertical blend of the row above (`lerp_blend_row_codes_vbmi`, the 2-D shift of
/// shift_tile.hpp) or added to accumulators (`lerp_add_row_codes_vbmi`), also times a weight per
/// pixel (`lerp_add_weighted_row_codes_vbmi`; at a whole-pixel offset `add_weighted_codes_vbmi`,
/// which sums the weights in the same pass).

#include <mpr/core/detail/prefetch.hpp>
#include <mpr/core/simd.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>

#if defined(MPR_SIMD_X86)
#include <immintrin.h>

namespace mpr::detail {

// Byte orders of the VBMI decode: `even` / `odd` pick the low / high bytes of 64 table words
// held in two registers; `order` places codes so that the in-lane byte unpacks give words for
// codes 0-31, then 32-63 (unpack lane k takes bytes 16k..16k+7 or 16k+8..16k+15).
struct DecodeVbmiOrders {
  std::uint8_t even[64], odd[64], order[64];
};

constexpr DecodeVbmiOrders make_decode_vbmi_orders() noexcept {
  DecodeVbmiOrders o{};
  for (int i = 0; i < 64; ++i) {
    o.even[i] = static_cast<std::uint8_t>(2 * i);
    o.odd[i] = static_cast<std::uint8_t>(2 * i + 1);
    const int lane = i / 16, k = i % 16;
    o.order[i] = static_cast<std::uint8_t>(k < 8 ? 8 * lane + k : 32 + 8 * lane + (k - 8));
  }
  return o;
}

inline constexpr DecodeVbmiOrders kDecodeVbmiOrders = make_decode_vbmi_orders();

/// The decode table as byte planes: entries 64k .. 64k + 63 in `lo[k]` / `hi[k]`.
struct DecodeBytes {
  __m512i lo[4], hi[4], order;
};

MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE DecodeBytes load_decode_bytes(const std::uint16_t* lut) noexcept {
  DecodeBytes d;
  const __m512i even = _mm512_loadu_si512(kDecodeVbmiOrders.even);
  const __m512i odd = _mm512_loadu_si512(kDecodeVbmiOrders.odd);
  for (int k = 0; k < 4; ++k) {
    const __m512i a = _mm512_loadu_si512(lut + 64 * k), b = _mm512_loadu_si512(lut + 64 * k + 32);
    d.lo[k] = _mm512_permutex2var_epi8(a, even, b);
    d.hi[k] = _mm512_permutex2var_epi8(a, odd, b);
  }
  d.order = _mm512_loadu_si512(kDecodeVbmiOrders.order);
  return d;
}

/// The table entries of the 64 codes of `codes` (bytes): codes 0-31 as the 16-bit lanes of
/// `first`, 32-63 of `second`.
MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE void decode16x64(const DecodeBytes& d, __m512i codes, __m512i& first,
                                                          __m512i& second) noexcept {
  const __m512i c = _mm512_maskz_permutexvar_epi8(~__mmask64(0), d.order, codes);
  const __mmask64 top = _mm512_movepi8_mask(c);
  const __m512i lo = _mm512_mask_blend_epi8(top, _mm512_permutex2var_epi8(d.lo[0], c, d.lo[1]),
                                            _mm512_permutex2var_epi8(d.lo[2], c, d.lo[3]));
  const __m512i hi = _mm512_mask_blend_epi8(top, _mm512_permutex2var_epi8(d.hi[0], c, d.hi[1]),
                                            _mm512_permutex2var_epi8(d.hi[2], c, d.hi[3]));
  first = _mm512_unpacklo_epi8(lo, hi);
  second = _mm512_unpackhi_epi8(lo, hi);
}

/// 16-bit lanes 0-15 / 16-31 of v as floats.
MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE __m512 words_low_ps(__m512i v) noexcept {
  return _mm512_maskz_cvtepi32_ps(0xFFFF,
                                  _mm512_maskz_cvtepu16_epi32(0xFFFF, _mm512_maskz_extracti64x4_epi64(0xF, v, 0)));
}
MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE __m512 words_high_ps(__m512i v) noexcept {
  return _mm512_maskz_cvtepi32_ps(0xFFFF,
                                  _mm512_maskz_cvtepu16_epi32(0xFFFF, _mm512_maskz_extracti64x4_epi64(0xF, v, 1)));
}

/// Byte indices that spread the low and high table bytes of 64 codes (two planes, code order)
/// into 32-bit lanes, 16 codes a vector: lane k of vector q holds the bytes (0, lo, hi, 0) of code
/// 16 q + k, its table value times 256 -- a float exactly (below 2^24) after one conversion, with
/// no word interleave or widening in between. `kSpreadKeep` marks the bytes taken (the others
/// are zeroed).
struct DecodeSpread {
  std::uint8_t index[4][64];
};

constexpr DecodeSpread make_decode_spread() noexcept {
  DecodeSpread s{};
  for (int q = 0; q < 4; ++q)
    for (int k = 0; k < 16; ++k) {
      s.index[q][4 * k + 1] = static_cast<std::uint8_t>(16 * q + k);
      s.index[q][4 * k + 2] = static_cast<std::uint8_t>(64 + 16 * q + k);
    }
  return s;
}

inline constexpr DecodeSpread kDecodeSpread = make_decode_spread();
inline constexpr __mmask64 kSpreadKeep = 0x6666666666666666ull;

/// What `decode_spread64` and `decode_floats64` return per table unit: callers fold
/// 1 / kDecodedScale into their weights (a power of two: exact).
inline constexpr float kDecodedScale = 256.0f;

// The table values of the `count` (<= 64) codes at p times `kDecodedScale`, as 32-bit integers,
// 16 a vector (codes 16 q .. 16 q + 15 in out[q]); lanes at or past `count` are not read and hold
// the value of code 0. Each code picks its low and high table bytes in code order (two-register
// permutes, the top bit choosing the half), and the two planes are spread into 32-bit lanes by
// one two-register permute per vector: eight permutes for 64 codes.
MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE void decode_spread64(const DecodeBytes& d, const std::uint8_t* p,
                                                              std::size_t count, __m512i (&out)[4]) noexcept {
  const __m512i c = count >= 64 ? _mm512_loadu_si512(p) : _mm512_maskz_loadu_epi8((__mmask64(1) << count) - 1, p);
  const __mmask64 top = _mm512_movepi8_mask(c);
  const __m512i lo = _mm512_mask_blend_epi8(top, _mm512_permutex2var_epi8(d.lo[0], c, d.lo[1]),
                                            _mm512_permutex2var_epi8(d.lo[2], c, d.lo[3]));
  const __m512i hi = _mm512_mask_blend_epi8(top, _mm512_permutex2var_epi8(d.hi[0], c, d.hi[1]),
                                            _mm512_permutex2var_epi8(d.hi[2], c, d.hi[3]));
  for (int q = 0; q < 4; ++q)
    out[q] = _mm512_maskz_permutex2var_epi8(kSpreadKeep, lo, _mm512_loadu_si512(kDecodeSpread.index[q]), hi);
}

// `decode_spread64` as floats (exact: below 2^24).
MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE void decode_floats64(const DecodeBytes& d, const std::uint8_t* p,
                                                              std::size_t count, __m512 (&out)[4]) noexcept {
  __m512i v[4];
  decode_spread64(d, p, count, v);
  for (int q = 0; q < 4; ++q) out[q] = _mm512_maskz_cvtepi32_ps(0xFFFF, v[q]);
}

// What the row pass of `lerp_row_codes_vbmi_impl` does with each 16 interpolated channels:
// store them to h; store them and blend them with the row above (hp) into acc; add them to acc;
// add them to acc times their pixel's weight (rw).
enum class RowPass { store, blend, add, weighted_add };

// Lane l of 16 channels starting at channel 3 p + o (o < 3) belongs to pixel p + (o + l) / 3: the
// permutes that spread 16 pixel weights from p over them, one per o.
struct WeightSpread {
  std::int32_t index[3][16];
};

constexpr WeightSpread make_weight_spread() noexcept {
  WeightSpread s{};
  for (int o = 0; o < 3; ++o)
    for (int l = 0; l < 16; ++l) s.index[o][l] = (o + l) / 3;
  return s;
}

inline constexpr WeightSpread kWeightSpread = make_weight_spread();

// The loop of the row kernels below. Without `Right` (ax == 0) the right neighbours are not
// formed.
template <RowPass Pass, bool Right>
MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE void
lerp_row_codes_vbmi_impl(const std::uint8_t* a, const std::uint16_t* lut, float ax, float scale, float* h,
                         std::size_t m, const std::uint8_t* ahead, const float* hp, float wy0, float wy1, float* acc,
                         const float* rw = nullptr) noexcept {
  const DecodeBytes d = load_decode_bytes(lut);
  __m512i spread[3] = {}; // weighted_add: the weight permutes
  if constexpr (Pass == RowPass::weighted_add)
    for (int o = 0; o < 3; ++o) spread[o] = _mm512_loadu_si512(kWeightSpread.index[o]);
  const float unit = scale / kDecodedScale;
  const __m512 w0 = _mm512_set1_ps((1 - ax) * unit), w1 = _mm512_set1_ps(ax * unit);
  const __m512 v0 = _mm512_set1_ps(wy0), v1 = _mm512_set1_ps(wy1);
  const std::size_t codes = m + (Right ? 3 : 0); // readable codes
  __m512 cur[4];
  decode_floats64(d, a, std::min<std::size_t>(64, codes), cur);
  for (std::size_t j = 0; j < m; j += 64) {
    if (ahead != nullptr) prefetch_l2(ahead, j);
    __m512 next[4] = {cur[0], cur[1], cur[2], cur[3]};
    if (j + 64 < codes) decode_floats64(d, a + j + 64, std::min<std::size_t>(64, codes - j - 64), next);
    const std::size_t count = std::min<std::size_t>(64, m - j);
    for (int k = 0; k < 4; ++k) {
      const std::size_t first = 16 * static_cast<std::size_t>(k);
      if (count <= first) break;
      const __mmask16 keep =
          count >= first + 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << (count - first)) - 1);
      const std::size_t at = j + first;
      __m512 right = _mm512_setzero_ps();
      if constexpr (Right) {
        const __m512 after = k < 3 ? cur[k + 1] : next[0];
        right = _mm512_castsi512_ps(
            _mm512_maskz_alignr_epi32(0xFFFF, _mm512_castps_si512(after), _mm512_castps_si512(cur[k]), 3));
      }
      if constexpr (Pass == RowPass::add) {
        __m512 sum = _mm512_fmadd_ps(w0, cur[k], _mm512_maskz_loadu_ps(keep, acc + at));
        if constexpr (Right) sum = _mm512_fmadd_ps(w1, right, sum);
        _mm512_mask_storeu_ps(acc + at, keep, sum);
      } else if constexpr (Pass == RowPass::weighted_add) {
        const std::size_t p = at / 3, left = m / 3 - p; // at < m: left >= 1
        const __mmask16 have = left >= 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << left) - 1);
        const __m512 weights = _mm512_maskz_permutexvar_ps(0xFFFF, spread[at % 3], _mm512_maskz_loadu_ps(have, rw + p));
        const __m512 value = Right ? _mm512_fmadd_ps(w1, right, _mm512_mul_ps(w0, cur[k])) : _mm512_mul_ps(w0, cur[k]);
        _mm512_mask_storeu_ps(acc + at, keep, _mm512_fmadd_ps(weights, value, _mm512_maskz_loadu_ps(keep, acc + at)));
      } else {
        const __m512 value = Right ? _mm512_fmadd_ps(w1, right, _mm512_mul_ps(w0, cur[k])) : _mm512_mul_ps(w0, cur[k]);
        _mm512_mask_storeu_ps(h + at, keep, value);
        if constexpr (Pass == RowPass::blend) {
          const __m512 sum = _mm512_fmadd_ps(
              v1, value,
              _mm512_fmadd_ps(v0, _mm512_maskz_loadu_ps(keep, hp + at), _mm512_maskz_loadu_ps(keep, acc + at)));
          _mm512_mask_storeu_ps(acc + at, keep, sum);
        }
      }
    }
    for (int k = 0; k < 4; ++k) cur[k] = next[k];
  }
}

/// h[j] = scale ((1 - ax) v(a[j]) + ax v(a[j + 3])) for j in [0, m), v the table value of the
/// code (`lerp_row_portable` for 8-bit codes), 64 channels a step; each code decoded once, the
/// values one pixel to the right taken from the decoded block and the next by a lane shift.
/// Reads a[0, m + 3) (a[0, m) when ax = 0); `ahead` (nullptr: none) as in `lerp_row_portable`.
MPR_TARGET_AVX512_VBMI inline void lerp_row_codes_vbmi(const std::uint8_t* a, const std::uint16_t* lut, float ax,
                                                       float scale, float* h, std::size_t m,
                                                       const std::uint8_t* ahead = nullptr) noexcept {
  if (ax == 0) // the decoded codes scaled, nothing formed to their right
    lerp_row_codes_vbmi_impl<RowPass::store, false>(a, lut, ax, scale, h, m, ahead, nullptr, 0, 0, nullptr);
  else
    lerp_row_codes_vbmi_impl<RowPass::store, true>(a, lut, ax, scale, h, m, ahead, nullptr, 0, 0, nullptr);
}

/// `lerp_row_codes_vbmi` into h, and in the same pass acc[j] += wy0 hp[j] + wy1 h[j] for j in
/// [0, m): the next row of a separable shift-and-add blended with the previous one (hp) while it
/// is interpolated. h must not overlap hp or acc.
MPR_TARGET_AVX512_VBMI inline void lerp_blend_row_codes_vbmi(const std::uint8_t* a, const std::uint16_t* lut, float ax,
                                                             float scale, float* h, std::size_t m,
                                                             const std::uint8_t* ahead, const float* hp, float wy0,
                                                             float wy1, float* acc) noexcept {
  lerp_row_codes_vbmi_impl<RowPass::blend, true>(a, lut, ax, scale, h, m, ahead, hp, wy0, wy1, acc);
}

/// acc[j] += scale ((1 - ax) v(a[j]) + ax v(a[j + 3])) for j in [0, m): one camera row added at
/// a horizontal offset alone (a vertical offset of 0); with ax = 0, the decoded codes scaled and
/// added, nothing formed to their right. Reads a[0, m + 3), a[0, m) when ax = 0.
MPR_TARGET_AVX512_VBMI inline void lerp_add_row_codes_vbmi(const std::uint8_t* a, const std::uint16_t* lut, float ax,
                                                           float scale, float* acc, std::size_t m,
                                                           const std::uint8_t* ahead = nullptr) noexcept {
  if (ax == 0)
    lerp_row_codes_vbmi_impl<RowPass::add, false>(a, lut, ax, scale, nullptr, m, ahead, nullptr, 0, 0, acc);
  else
    lerp_row_codes_vbmi_impl<RowPass::add, true>(a, lut, ax, scale, nullptr, m, ahead, nullptr, 0, 0, acc);
}

// Channel l of the 48 of 16 pixels, in the vector o (16 o + l), belongs to pixel (16 o + l) / 3:
// the permutes that spread the 16 pixels' weights over their three vectors (`kWeightSpread`'s
// offset o, from 5 o pixels further on, over one load of 16 weights instead of three).
struct PixelSpread {
  std::int32_t index[3][16];
};

constexpr PixelSpread make_pixel_spread() noexcept {
  PixelSpread s{};
  for (int o = 0; o < 3; ++o)
    for (int l = 0; l < 16; ++l) s.index[o][l] = (16 * o + l) / 3;
  return s;
}

inline constexpr PixelSpread kPixelSpread = make_pixel_spread();

// `lerp_add_weighted_row_codes_vbmi` at ax = 0, 64 pixels (three 64-code decodes) a step: each
// 16 pixels' weights are loaded once, summed into `weight`, scaled by `unit` and spread over
// their 48 channels by three permutes. Reads a[0, 3 pixels).
MPR_TARGET_AVX512_VBMI inline void add_weighted_codes_vbmi(const std::uint8_t* a, const std::uint16_t* lut, float unit,
                                                           const float* rw, float* acc, float* weight,
                                                           std::size_t pixels, const std::uint8_t* ahead) noexcept {
  const DecodeBytes d = load_decode_bytes(lut);
  __m512i spread[3];
  for (int o = 0; o < 3; ++o) spread[o] = _mm512_loadu_si512(kPixelSpread.index[o]);
  const __m512 scale = _mm512_set1_ps(unit), zero = _mm512_setzero_ps();
  for (std::size_t p = 0; p < pixels; p += 64) {
    const std::size_t left = std::min<std::size_t>(64, pixels - p), codes = 3 * left, j = 3 * p;
    __m512 v[12];
    for (std::size_t k = 0; k < 3; ++k) {
      if (ahead != nullptr) prefetch_l2(ahead, j + 64 * k);
      __m512 part[4] = {zero, zero, zero, zero};
      if (64 * k < codes) decode_floats64(d, a + j + 64 * k, std::min<std::size_t>(64, codes - 64 * k), part);
      for (std::size_t q = 0; q < 4; ++q) v[4 * k + q] = part[q];
    }
    for (std::size_t b = 0; 16 * b < left; ++b) {
      const std::size_t px = std::min<std::size_t>(16, left - 16 * b), at = j + 48 * b;
      const __mmask16 have = px == 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << px) - 1);
      const __m512 r = _mm512_maskz_loadu_ps(have, rw + p + 16 * b);
      float* sum = weight + p + 16 * b;
      _mm512_mask_storeu_ps(sum, have,
                            _mm512_add_ps(_mm512_maskz_loadu_ps(have, sum), _mm512_maskz_max_ps(0xFFFF, r, zero)));
      const __m512 scaled = _mm512_mul_ps(r, scale);
      for (std::size_t o = 0; o < 3; ++o) {
        const std::size_t first = 16 * o, count = 3 * px;
        if (count <= first) break;
        const __mmask16 keep =
            count >= first + 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << (count - first)) - 1);
        const __m512 w = _mm512_maskz_permutexvar_ps(0xFFFF, spread[o], scaled);
        float* out = acc + at + first;
        _mm512_mask_storeu_ps(out, keep, _mm512_fmadd_ps(w, v[3 * b + o], _mm512_maskz_loadu_ps(keep, out)));
      }
    }
  }
}

/// acc[j] += rw[j / 3] scale ((1 - ax) v(a[j]) + ax v(a[j + 3])) for j in [0, m), m a multiple of
/// 3: `lerp_add_row_codes_vbmi` with a weight per pixel (rw[0, m / 3)), spread over its three
/// channels by a permute; and weight[i] += max(rw[i], 0) for the m / 3 pixels (a NaN weight adds
/// 0). Reads a[0, m + 3), a[0, m) when ax = 0.
MPR_TARGET_AVX512_VBMI inline void lerp_add_weighted_row_codes_vbmi(const std::uint8_t* a, const std::uint16_t* lut,
                                                                    float ax, float scale, const float* rw, float* acc,
                                                                    float* weight, std::size_t m,
                                                                    const std::uint8_t* ahead = nullptr) noexcept {
  if (ax == 0) return add_weighted_codes_vbmi(a, lut, scale / kDecodedScale, rw, acc, weight, m / 3, ahead);
  lerp_row_codes_vbmi_impl<RowPass::weighted_add, true>(a, lut, ax, scale, nullptr, m, ahead, nullptr, 0, 0, acc, rw);
  const std::size_t pixels = m / 3;
  const __m512 zero = _mm512_setzero_ps();
  for (std::size_t i = 0; i < pixels; i += 16) {
    const std::size_t left = pixels - i;
    const __mmask16 keep = left >= 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << left) - 1);
    const __m512 w = _mm512_maskz_max_ps(0xFFFF, _mm512_maskz_loadu_ps(keep, rw + i), zero);
    _mm512_mask_storeu_ps(weight + i, keep, _mm512_add_ps(_mm512_maskz_loadu_ps(keep, weight + i), w));
  }
}

} // namespace mpr::detail
#endif
