#pragma once
/// \file
/// One camera row resampled at evenly spaced positions x + s i, any step s: the horizontal half
/// of a separable bilinear shift-and-add when the output is not at the cameras' scale (a focal
/// plane parallel to the camera plane seen at another pixel spacing, e.g. a 960x540 view of
/// 1400x800 cameras). Plain C++ for every level, a Highway kernel per level where Highway is
/// present (kernels/resample_row_hwy.inl, gathers), and on AVX-512 with VBMI a step that picks
/// each group of 16 pixels' texel pairs out of a 128-byte window of 8-bit codes with byte
/// permutes, decodes them to linear light in registers and interpolates them (no gathers).

#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/decode_vbmi.hpp>
#include <mpr/lightfield/kernels/lerp_row_hwy.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace mpr::detail {

/// The largest step (camera pixels per output pixel) of the hand-written step: 16 pixels then
/// span at most 3 (15 s + 3) bytes of codes, inside its 128-byte window.
inline constexpr double kResampleMaxStep = 2.5;

/// h[3 i + k] = scale ((1 - f) v(row[3 j + k]) + f v(row[3 j + 3 + k])) for pixels i in [0, n),
/// where x_i = x + s i (camera pixels, texel centres at integers), j = floor(x_i) clamped to
/// [0, texels - 2] and f = x_i - j clamped to [0, 1]; v = `channel_value`. `row` holds `texels`
/// flat RGB texels (3 texels channels). With `ahead` (nullptr: none), the texels of the row to be
/// resampled next (the next camera's, from where its first pixel falls) are prefetched along the
/// way, over the span this row reads (see `lerp_row_portable`). Preconditions: texels >= 2,
/// x >= 0, 0 < s.
template <class C>
MPR_ALWAYS_INLINE void resample_row_portable(const C* MPR_RESTRICT row, std::size_t texels,
                                             const std::uint16_t* MPR_RESTRICT lut, double x, double s, float scale,
                                             float* MPR_RESTRICT h, std::size_t n, const C* ahead = nullptr) noexcept {
  const double last_pair = static_cast<double>(texels) - 2;
  // floor(v) for v >= 0 (x >= 0, s > 0) by truncation: no libm call where the baseline (SSE2)
  // has no rounding instruction.
  const auto floor_of = [](double v) noexcept { return static_cast<double>(static_cast<long long>(v)); };
  const double j_first = std::clamp(floor_of(x), 0.0, last_pair);
  const std::size_t span = 48 * sizeof(C) * static_cast<std::size_t>(std::ceil(s)) + 6 * sizeof(C);
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = x + s * static_cast<double>(i);
    const double j = std::clamp(floor_of(xi), 0.0, last_pair);
    if (ahead != nullptr && i % 16 == 0) // the next 16 pixels' texels in the next row
      for (std::size_t b = 0; b < span; b += 64)
        prefetch_l2(ahead, 3 * static_cast<std::size_t>(j - j_first) * sizeof(C) + b);
    const float f = static_cast<float>(std::clamp(xi - j, 0.0, 1.0));
    const C* a = row + 3 * static_cast<std::size_t>(j);
    for (int k = 0; k < 3; ++k)
      h[3 * i + k] = scale * ((1 - f) * channel_value(a[k], lut) + f * channel_value(a[k + 3], lut));
  }
}

#if defined(MPR_SIMD_X86)
// Constant patterns of the VBMI step. Its two 64-byte blocks hold the 96 codes of 16 pixels'
// texel pairs (the second block half used): first the left texels' r g b of pixels 0..15, then
// the right ones'. Code c comes from window byte 3 d_p + (c mod 3) + 3 [right], d_p the pixel's
// texel offset from the group's first texel: `pixel` holds p per byte, `offset` the constant
// part; `lane_pixel` maps each float lane of a 16-code vector to its pixel (for the fractions).
struct ResamplePatterns {
  std::uint8_t pixel[2][64];
  std::uint8_t offset[2][64];
  std::int32_t lane_pixel[3][16];
};

constexpr ResamplePatterns make_resample_patterns() noexcept {
  ResamplePatterns p{};
  for (int k = 0; k < 2; ++k)
    for (int b = 0; b < 64; ++b) {
      const int c = 64 * k + b;
      if (c >= 96) break;
      p.pixel[k][b] = static_cast<std::uint8_t>((c % 48) / 3);
      p.offset[k][b] = static_cast<std::uint8_t>(c % 3 + (c >= 48 ? 3 : 0));
    }
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 16; ++l) p.lane_pixel[k][l] = (16 * k + l) / 3;
  return p;
}

inline constexpr ResamplePatterns kResamplePatterns = make_resample_patterns();

// The bytes [start, start + 64) of a row of `bytes` bytes, zero past its end (masked: nothing
// past the end is touched).
MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE __m512i load_window64(const std::uint8_t* row, std::size_t start,
                                                               std::size_t bytes) noexcept {
  if (start >= bytes) return _mm512_setzero_si512();
  const std::size_t left = bytes - start;
  if (left >= 64) return _mm512_loadu_si512(row + start);
  const __mmask64 k = left >= 64 ? ~__mmask64(0) : (__mmask64(1) << left) - 1;
  return _mm512_maskz_loadu_epi8(k, row + start);
}

// The constants of the VBMI step.
struct ResampleConstants {
  __m512i pixel[2], offset[2], lane_pixel[3];
  __m512 lanes, step;
};

MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE ResampleConstants load_resample_constants(double s) noexcept {
  ResampleConstants c;
  for (int k = 0; k < 2; ++k) {
    c.pixel[k] = _mm512_loadu_si512(kResamplePatterns.pixel[k]);
    c.offset[k] = _mm512_loadu_si512(kResamplePatterns.offset[k]);
  }
  for (int k = 0; k < 3; ++k) c.lane_pixel[k] = _mm512_loadu_si512(kResamplePatterns.lane_pixel[k]);
  c.lanes = _mm512_setr_ps(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  c.step = _mm512_set1_ps(static_cast<float>(s));
  return c;
}

/// Where the 16 pixels from pixel i of a resampled row read their texel pairs: the byte of the
/// group's first texel j0 in the row (`start`), the window byte of each of the 96 codes of their
/// pairs (`index`, two blocks, see `ResamplePatterns`) and each channel lane's fraction (`f`, r g b
/// of pixels 0-15 over three vectors).
struct ResampleGroup {
  std::size_t start;
  __m512i index[2];
  __m512 f[3];
};

// The group of pixel i at x + s i (j0 in double, the lanes' offsets from it in float, below 40).
MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE ResampleGroup resample_group(const ResampleConstants& c, double x, double s,
                                                                      std::size_t i, long last_pair) noexcept {
  const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f);
  const double xg = x + s * static_cast<double>(i);
  const long j0 = std::clamp(static_cast<long>(std::floor(xg)), 0L, last_pair);
  const __m512 xl = _mm512_fmadd_ps(c.step, c.lanes, _mm512_set1_ps(static_cast<float>(xg - static_cast<double>(j0))));
  __m512i jl = _mm512_maskz_cvttps_epi32(0xFFFF, _mm512_maskz_max_ps(0xFFFF, xl, zero));
  jl = _mm512_maskz_min_epi32(0xFFFF, jl, _mm512_set1_epi32(static_cast<int>(std::min(last_pair - j0, 40L))));
  const __m512 f = _mm512_maskz_min_ps(
      0xFFFF, _mm512_maskz_max_ps(0xFFFF, _mm512_sub_ps(xl, _mm512_maskz_cvtepi32_ps(0xFFFF, jl)), zero), one);
  const __m128i jb = _mm512_maskz_cvtepi32_epi8(0xFFFF, jl);
  const __m512i j3 = _mm512_maskz_broadcast_i32x4(0xFFFF, _mm_add_epi8(jb, _mm_add_epi8(jb, jb)));
  ResampleGroup g;
  g.start = 3 * static_cast<std::size_t>(j0);
  for (int k = 0; k < 2; ++k)
    g.index[k] = _mm512_add_epi8(_mm512_maskz_permutexvar_epi8(~__mmask64(0), c.pixel[k], j3), c.offset[k]);
  for (int k = 0; k < 3; ++k) g.f[k] = _mm512_maskz_permutexvar_ps(0xFFFF, c.lane_pixel[k], f);
  return g;
}

// The group's interpolated channels of the row of `bytes` codes at `row` (table values, the
// scale not applied): r g b of pixels 0-15 over three vectors.
MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE void resample_group_values(const DecodeBytes& d, const std::uint8_t* row,
                                                                    std::size_t bytes, const ResampleGroup& g,
                                                                    __m512 (&value)[3]) noexcept {
  const __m512i lo = load_window64(row, g.start, bytes), hi = load_window64(row, g.start + 64, bytes);
  __m512i v[4];
  for (int k = 0; k < 2; ++k) decode16x64(d, _mm512_permutex2var_epi8(lo, g.index[k], hi), v[2 * k], v[2 * k + 1]);
  // v: codes 0-31, 32-63, 64-95 (and 32 unused).
  const __m512 left[3] = {words_low_ps(v[0]), words_high_ps(v[0]), words_low_ps(v[1])};
  const __m512 right[3] = {words_high_ps(v[1]), words_low_ps(v[2]), words_high_ps(v[2])};
  for (int k = 0; k < 3; ++k) value[k] = _mm512_fmadd_ps(g.f[k], _mm512_sub_ps(right[k], left[k]), left[k]);
}

// `resample_row_portable` for 8-bit codes, 16 pixels a step. Precondition: s <= kResampleMaxStep.
MPR_TARGET_AVX512_VBMI inline void resample_row_codes_vbmi(const std::uint8_t* row, std::size_t texels,
                                                           const std::uint16_t* lut, double x, double s, float scale,
                                                           float* h, std::size_t n,
                                                           const std::uint8_t* ahead = nullptr) noexcept {
  const DecodeBytes d = load_decode_bytes(lut);
  const ResampleConstants c = load_resample_constants(s);
  const __m512 vscale = _mm512_set1_ps(scale);
  const long last_pair = static_cast<long>(texels) - 2;
  const std::size_t bytes = 3 * texels;
  const std::size_t start_first =
      3 * static_cast<std::size_t>(std::clamp(static_cast<long>(std::floor(x)), 0L, last_pair));
  for (std::size_t i = 0; i < n; i += 16) {
    const ResampleGroup g = resample_group(c, x, s, i, last_pair);
    if (ahead != nullptr) { // the group's 16 s + 1 texels (at most 123 bytes) in the next row
      prefetch_l2(ahead, g.start - start_first);
      prefetch_l2(ahead, g.start - start_first + 64);
    }
    __m512 value[3];
    resample_group_values(d, row, bytes, g, value);
    const std::size_t count = 3 * std::min<std::size_t>(16, n - i); // floats to store
    for (int k = 0; k < 3; ++k) {
      const std::size_t first = 16 * static_cast<std::size_t>(k);
      if (count >= first + 16)
        _mm512_storeu_ps(h + 3 * i + first, _mm512_mul_ps(vscale, value[k]));
      else if (count > first)
        _mm512_mask_storeu_ps(h + 3 * i + first, static_cast<__mmask16>((1u << (count - first)) - 1),
                              _mm512_mul_ps(vscale, value[k]));
    }
  }
}
#endif

#if defined(MPR_SIMD_X86)
// `decode_row16` on AVX-512 with VBMI, 64 codes a step (the last step masked).
MPR_TARGET_AVX512_VBMI inline void decode_row16_vbmi(const std::uint8_t* a, const std::uint16_t* lut,
                                                     std::uint16_t* out, std::size_t count) noexcept {
  const DecodeBytes d = load_decode_bytes(lut);
  for (std::size_t k = 0; k < count; k += 64) {
    const std::size_t m = std::min<std::size_t>(64, count - k);
    const __mmask64 keep = m == 64 ? ~__mmask64(0) : (__mmask64(1) << m) - 1;
    __m512i first, second;
    decode16x64(d, _mm512_maskz_loadu_epi8(keep, a + k), first, second);
    _mm512_mask_storeu_epi16(out + k, static_cast<__mmask32>(keep), first);
    _mm512_mask_storeu_epi16(out + k + 32, static_cast<__mmask32>(keep >> 32), second);
  }
}
#endif

/// out[k] = lut[a[k]] for k in [0, count): a row of 8-bit codes as their 16-bit table values (a
/// row of the frames' 16-bit linear copy, `linear16_copy`), with byte permutes on AVX-512 with
/// VBMI, a plain loop below.
inline void decode_row16(const std::uint8_t* a, const std::uint16_t* lut, std::uint16_t* out, std::size_t count,
                         SimdLevel level = dispatch_level()) noexcept {
#if defined(MPR_SIMD_X86)
  if (level >= SimdLevel::avx512vbmi) return decode_row16_vbmi(a, lut, out, count);
#endif
  (void)level;
  for (std::size_t k = 0; k < count; ++k) out[k] = lut[a[k]];
}

/// `resample_row_portable` at `level`: for 8-bit codes, the VBMI step when `level` is
/// `avx512vbmi` and s <= `kResampleMaxStep`; else (and for float channels) the Highway kernel of
/// `level` (kernels/resample_row_hwy.inl) where Highway is present, the plain loop compiled for
/// `level` where it is not.
template <class C>
inline void resample_row(const C* row, std::size_t texels, const std::uint16_t* lut, double x, double s, float scale,
                         float* h, std::size_t n, const C* ahead = nullptr,
                         SimdLevel level = dispatch_level()) noexcept {
#if defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<C, std::uint8_t>)
    if (level >= SimdLevel::avx512vbmi && s <= kResampleMaxStep)
      return resample_row_codes_vbmi(row, texels, lut, x, s, scale, h, n, ahead);
#endif
#if MPR_HAVE_HWY
  if constexpr (std::is_same_v<C, std::uint8_t> || std::is_same_v<C, float>)
    return kernels::resample_row_hwy(row, texels, lut, x, s, scale, h, n, ahead, level);
#endif
  run_at(level, [&]() MPR_INLINE_LAMBDA { resample_row_portable(row, texels, lut, x, s, scale, h, n, ahead); });
}

} // namespace mpr::detail
