#pragma once
/// \file
/// The x86 steps of the core kernels, the only hand-written intrinsics of core/: a kernel is a
/// plain loop compiled per level through `run_at` (core/simd.hpp), and calls the step of this
/// header for the levels that have one. A step handles a leading part of the input and returns
/// how much; the plain loop finishes the rest. Levels without a step return 0.

#include <mpr/core/config.hpp>
#include <mpr/core/simd.hpp>

#include <cstddef>
#include <cstdint>

namespace mpr::detail {

#if defined(MPR_SIMD_X86)
// GCC 12's AVX-512 headers start some intrinsics from _mm512_undefined_*(), which its own
// -Wmaybe-uninitialized then reports at every use.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
// `linear_to_srgb8_avx512`'s exact step for the lanes of `lanes` (the others keep `k`): the
// code at the lower edge of x's bin of `bins`, plus one where x lies at or above the bin's
// threshold, from one gather of `bin_entry` (see `SrgbTables::bin_entry`).
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512i srgb8_by_bins_avx512(__m512 x, __mmask16 lanes, __m512i k,
                                                                 const std::uint32_t* bin_entry, int bins) noexcept {
  const __m512 scaled = _mm512_mul_ps(x, _mm512_set1_ps(static_cast<float>(bins))); // exact: a power of two
  const __m512i bin = _mm512_cvttps_epi32(scaled);
  const __m512i entry = _mm512_mask_i32gather_epi32(k, lanes, bin, bin_entry, 4);
  // Where x lies in its bin, in units of 2^-23 (both steps exact, see `SrgbTables::bin_entry`).
  const __m512i at =
      _mm512_cvttps_epi32(_mm512_mul_ps(_mm512_sub_ps(scaled, _mm512_cvtepi32_ps(bin)), _mm512_set1_ps(0x1p23f)));
  const __mmask16 up = _mm512_mask_cmp_epi32_mask(lanes, at, _mm512_srli_epi32(entry, 8), _MM_CMPINT_NLT);
  const __m512i low = _mm512_and_si512(entry, _mm512_set1_epi32(0xff));
  return _mm512_mask_blend_epi32(lanes, k, _mm512_mask_add_epi32(low, up, low, _mm512_set1_epi32(1)));
}

/// `linear_to_srgb8` (core/color.hpp) on the channels [0, m - m % 16) of `in`, 16 at a time
/// with AVX-512; the same codes bit for bit. Each channel's 255 encode(x) is estimated (x 255
/// 12.92 up to 0.0031308, above it the half-octave polynomials `poly`, `SrgbTables::poly`, five
/// rows of 32 floats, their coefficients picked by two-register permutes), and its nearest
/// integer is the code unless the estimate lies within 1/1024 of k + 1/2 (five times its error
/// bound): only those channels, about 0.2% of them, take the exact step of one gather from
/// `bin_entry` (`SrgbTables::bin_entry`, bins of 1 / `bins`). NaN and values <= 0 clamp to 0,
/// values >= 1 to the largest float below 1, whose code is 255. Returns m - m % 16.
MPR_TARGET_AVX512 inline std::size_t linear_to_srgb8_avx512(const float* in, std::uint8_t* out, std::size_t m,
                                                            const std::uint32_t* bin_entry, int bins,
                                                            const float* poly) noexcept {
  constexpr int kTerms = 5;                      // SrgbTables::kPolyDegree + 1
  constexpr std::int32_t kFirstHalfOctave = 236; // the top 10 bits of 2^-9
  const __m512 zero = _mm512_setzero_ps(), below_one = _mm512_set1_ps(0x1.fffffep-1f);
  const __m512 knee = _mm512_set1_ps(0.0031308f), slope = _mm512_set1_ps(255.0f * 12.92f);
  const __m512 undecided = _mm512_set1_ps(0.5f - 0x1p-10f), centre = _mm512_set1_ps(1.25f);
  const __m512i first = _mm512_set1_epi32(kFirstHalfOctave), mantissa = _mm512_set1_epi32(0x3fffff);
  const __m512i one_bits = _mm512_set1_epi32(0x3f800000);
  __m512 c[kTerms][2];
  for (int d = 0; d < kTerms; ++d) {
    c[d][0] = _mm512_loadu_ps(poly + 32 * d);
    c[d][1] = _mm512_loadu_ps(poly + 32 * d + 16);
  }
  std::size_t j = 0;
  for (; j + 16 <= m; j += 16) {
    // max(x, 0) returns 0 for NaN (the second operand).
    const __m512 x = _mm512_min_ps(_mm512_max_ps(_mm512_loadu_ps(in + j), zero), below_one);
    const __m512i bits = _mm512_castps_si512(x);
    // Half octave (exponent and top mantissa bit; the lanes below 2^-9 take the linear segment)
    // and t = m - 1.25 - h / 2 (the mantissa without its top bit, exact).
    const __m512i half = _mm512_sub_epi32(_mm512_srli_epi32(bits, 22), first);
    const __m512 t =
        _mm512_sub_ps(_mm512_castsi512_ps(_mm512_or_si512(_mm512_and_si512(bits, mantissa), one_bits)), centre);
    __m512 p = _mm512_permutex2var_ps(c[kTerms - 1][0], half, c[kTerms - 1][1]);
    for (int d = kTerms - 2; d >= 0; --d) p = _mm512_fmadd_ps(p, t, _mm512_permutex2var_ps(c[d][0], half, c[d][1]));
    const __m512 y = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(x, knee, _CMP_LE_OQ), p, _mm512_mul_ps(x, slope));
    const __m512 nearest = _mm512_roundscale_ps(y, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    __m512i k = _mm512_cvttps_epi32(nearest);
    const __mmask16 exact = _mm512_cmp_ps_mask(_mm512_abs_ps(_mm512_sub_ps(y, nearest)), undecided, _CMP_GT_OQ);
    if (exact != 0) k = srgb8_by_bins_avx512(x, exact, k, bin_entry, bins);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + j), _mm512_cvtepi32_epi8(k));
  }
  return j;
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

/// `linear_to_srgb8_avx512` 8 channels at a time with AVX2's gather: the channels [0, m - m % 8)
/// of `in`, the same codes bit for bit. Returns m - m % 8.
MPR_TARGET_AVX2 inline std::size_t linear_to_srgb8_avx2(const float* in, std::uint8_t* out, std::size_t m,
                                                        const std::uint32_t* bin_entry, int bins) noexcept {
  const __m256 zero = _mm256_setzero_ps(), below_one = _mm256_set1_ps(0x1.fffffep-1f);
  const __m256 scale = _mm256_set1_ps(static_cast<float>(bins)), fraction = _mm256_set1_ps(0x1p23f);
  const __m256i byte = _mm256_set1_epi32(0xff), one = _mm256_set1_epi32(1);
  const int* entries = reinterpret_cast<const int*>(bin_entry);
  std::size_t j = 0;
  for (; j + 8 <= m; j += 8) {
    // max(x, 0) returns 0 for NaN (the second operand).
    const __m256 x = _mm256_min_ps(_mm256_max_ps(_mm256_loadu_ps(in + j), zero), below_one);
    const __m256 scaled = _mm256_mul_ps(x, scale);
    const __m256i bin = _mm256_cvttps_epi32(scaled);
    const __m256i entry = _mm256_i32gather_epi32(entries, bin, 4);
    const __m256i at = _mm256_cvttps_epi32(_mm256_mul_ps(_mm256_sub_ps(scaled, _mm256_cvtepi32_ps(bin)), fraction));
    // The code at the bin's lower edge, plus 1 unless `at` lies below the threshold (both below
    // 2^24: the signed compare is exact).
    const __m256i below = _mm256_cmpgt_epi32(_mm256_srli_epi32(entry, 8), at);
    const __m256i k = _mm256_add_epi32(_mm256_and_si256(entry, byte), _mm256_add_epi32(one, below));
    const __m128i words = _mm_packus_epi32(_mm256_castsi256_si128(k), _mm256_extracti128_si256(k, 1));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + j), _mm_packus_epi16(words, words));
  }
  return j;
}
#endif

/// The step of the sRGB row encoder at level `L` (see `linear_to_srgb8_avx512`): AVX-512 and
/// AVX2; none at the portable level. `poly`: `SrgbTables::poly` (read at AVX-512 only).
template <SimdLevel L>
MPR_ALWAYS_INLINE std::size_t linear_to_srgb8_step(SimdTag<L>, const float* in, std::uint8_t* out, std::size_t m,
                                                   const std::uint32_t* bin_entry, int bins,
                                                   const float* poly) noexcept {
#if defined(MPR_SIMD_X86)
  if constexpr (L == SimdLevel::avx512) return linear_to_srgb8_avx512(in, out, m, bin_entry, bins, poly);
  if constexpr (L == SimdLevel::avx2) return linear_to_srgb8_avx2(in, out, m, bin_entry, bins);
#endif
  (void)in, (void)out, (void)m, (void)bin_entry, (void)bins, (void)poly;
  return 0;
}

} // namespace mpr::detail
