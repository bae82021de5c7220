#pragma once
/// \file
/// The synthetic aperture's fractional-shift row (`detail::lerp_row_portable` for 8-bit codes,
/// the kernel of lerp_row_hwy.hpp) written once with xsimd (https://github.com/xtensor-stack/xsimd,
/// 8.1): a body templated on xsimd's architecture type. xsimd includes an architecture's kernels
/// only when the compiler targets it (`__AVX2__`, `__AVX512BW__` ...): a build with no `-march`
/// flag has SSE2 alone (`XSIMD_WITH_AVX2` is 0), so `lerp_row_xsimd` runs the widest
/// architecture of the build's flags, lowered to `level`. Only available when xsimd's headers
/// are (`MPR_HAVE_XSIMD`, core/config.hpp).

#include <mpr/core/config.hpp>
#if MPR_HAVE_XSIMD
#include <mpr/core/detail/prefetch.hpp>
#include <mpr/core/simd.hpp>

#include <xsimd/xsimd.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace mpr::kernels {

/// The xsimd body for architecture A: reads a[0, m + 3), writes h[0, m); `ahead` (nullptr: none)
/// is prefetched a line per 64 codes. Decodes a block of codes to floats (a gather per vector
/// from the table as 256 floats), then blends each value with the one three channels on.
template <class A>
void lerp_row_codes_xsimd(A, const std::uint8_t* MPR_RESTRICT a, const std::uint16_t* MPR_RESTRICT lut, float ax,
                          float scale, float* MPR_RESTRICT h, std::size_t m, const std::uint8_t* ahead) noexcept {
  using F = xsimd::batch<float, A>;
  using I = xsimd::batch<std::int32_t, A>;
  constexpr std::size_t lanes = F::size;
  alignas(64) float table[256];
  // (A plain loop: xsimd's AVX-512 int-to-float cast trips GCC 12's -Wuninitialized, bug 105593.)
  for (std::size_t k = 0; k < 256; ++k) table[k] = static_cast<float>(lut[k]);
  const F w0((1 - ax) * scale), w1(ax * scale);
  constexpr std::size_t kBlock = 512; // channels a step
  alignas(64) float value[kBlock + 3 + lanes];
  for (std::size_t j0 = 0; j0 < m; j0 += kBlock) {
    const std::size_t n = std::min(kBlock, m - j0), codes = n + 3;
    const std::uint8_t* src = a + j0;
    if (ahead != nullptr)
      for (std::size_t b = 0; b < n; b += 64) detail::prefetch_l2(ahead, j0 + b);
    std::size_t k = 0;
    for (; k + lanes <= codes; k += lanes) F::gather(table, I::load_unaligned(src + k)).store_aligned(value + k);
    for (; k < codes; ++k) value[k] = table[src[k]];
    std::size_t j = 0;
    for (; j + lanes <= n; j += lanes)
      xsimd::fma(w1, F::load_unaligned(value + j + 3), w0 * F::load_aligned(value + j)).store_unaligned(h + j0 + j);
    for (; j < n; ++j) h[j0 + j] = (1 - ax) * scale * value[j] + ax * scale * value[j + 3];
  }
}

/// Whether the build has an xsimd architecture for `level` (the flags' own: see the file note).
[[nodiscard]] constexpr bool lerp_row_xsimd_has(detail::SimdLevel level) noexcept {
  if (level >= detail::SimdLevel::avx512) return XSIMD_WITH_AVX512BW != 0;
  if (level >= detail::SimdLevel::avx2) return XSIMD_WITH_FMA3_AVX2 != 0;
  return true;
}

/// `lerp_row_codes_xsimd` at the widest architecture of the build up to `level`: AVX-512BW,
/// AVX2+FMA, SSE4.2, SSE2 (x86), NEON (ARM), or the build's default.
inline void lerp_row_xsimd(const std::uint8_t* a, const std::uint16_t* lut, float ax, float scale, float* h,
                           std::size_t m, const std::uint8_t* ahead = nullptr,
                           detail::SimdLevel level = detail::dispatch_level()) noexcept {
#if XSIMD_WITH_AVX512BW
  if (level >= detail::SimdLevel::avx512)
    return lerp_row_codes_xsimd(xsimd::avx512bw{}, a, lut, ax, scale, h, m, ahead);
#endif
#if XSIMD_WITH_FMA3_AVX2
  if (level >= detail::SimdLevel::avx2)
    return lerp_row_codes_xsimd(xsimd::fma3<xsimd::avx2>{}, a, lut, ax, scale, h, m, ahead);
#endif
#if XSIMD_WITH_SSE4_2
  return lerp_row_codes_xsimd(xsimd::sse4_2{}, a, lut, ax, scale, h, m, ahead);
#else
  (void)level;
  lerp_row_codes_xsimd(xsimd::default_arch{}, a, lut, ax, scale, h, m, ahead);
#endif
}

} // namespace mpr::kernels
#endif // MPR_HAVE_XSIMD
