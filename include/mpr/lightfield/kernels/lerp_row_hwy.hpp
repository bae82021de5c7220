// No #pragma once: Highway's foreach_target.h includes this file again once per target; the
// parts below are guarded by hand (the outer guard, the per-target toggle, HWY_ONCE).
/// \file
/// The synthetic aperture's fractional-shift row, h[j] = scale ((1 - ax) v(a[j]) + ax v(a[j + 3]))
/// for 8-bit sRGB codes a (v: their entry of the 16-bit linear table, `Srgb8Texel::linear16()`),
/// written once with Highway (https://github.com/google/highway) and compiled by it for every x86
/// target (SSE4, AVX2, AVX-512, AVX-512 with VBMI; NEON or SVE elsewhere) through its
/// `#pragma` target regions, so a build with no `-march` flag holds every target. Same inputs,
/// outputs and preconditions as `detail::lerp_row_portable` (kernels.hpp) for 8-bit codes.
///
/// Each step decodes a block of codes into a float buffer (the table as 256 floats, one gather
/// per vector), then blends each value with the one three channels on (unaligned loads).
///
/// Header-only use: the per-target functions are `inline` in Highway's per-target namespaces
/// (`hwy::N_AVX2` ...), and the choice of target is mpr's (`lerp_row_hwy` below takes the
/// `SimdLevel`), not `HWY_DYNAMIC_DISPATCH`, which needs libhwy's run-time target detection
/// (`hwy::GetChosenTarget()`, a symbol of libhwy.so). Only available when Highway's headers are
/// (`MPR_HAVE_HWY`, core/config.hpp).

#include <mpr/core/config.hpp>
#if MPR_HAVE_HWY
#ifndef MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_OUTER
#define MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_OUTER
#include <mpr/core/detail/prefetch.hpp>
#include <mpr/core/simd.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>

// Every target this compiler can build (not only those above the build's baseline), so that
// MPR_SIMD can lower the choice in a -march=native build too; and AVX-512 with VBMI (AVX3_DL).
#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE
#endif
#ifndef HWY_WANT_AVX3_DL
#define HWY_WANT_AVX3_DL
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "mpr/lightfield/kernels/lerp_row_hwy.hpp"
#include <hwy/foreach_target.h> // includes this file once per target
#endif

#include <hwy/highway.h>

#if defined(MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_TOGGLE) == defined(HWY_TARGET_TOGGLE)
#ifdef MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_TOGGLE
#undef MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_TOGGLE
#else
#define MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_TOGGLE
#endif

HWY_BEFORE_NAMESPACE();
namespace mpr::kernels::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// `detail::lerp_row_portable` for 8-bit codes at this target: reads a[0, m + 3), writes
/// h[0, m); `ahead` (nullptr: none) is prefetched a line per 64 codes.
inline void lerp_row_codes(const std::uint8_t* HWY_RESTRICT a, const std::uint16_t* HWY_RESTRICT lut, float ax,
                           float scale, float* HWY_RESTRICT h, std::size_t m, const std::uint8_t* ahead) noexcept {
  const hn::ScalableTag<float> df;
  const hn::Rebind<std::int32_t, decltype(df)> di;
  const hn::Rebind<std::uint16_t, decltype(df)> d16;
  const hn::Rebind<std::uint8_t, decltype(df)> d8;
  const std::size_t lanes = hn::Lanes(df);
  // The table as floats (256 entries; a whole number of vectors at every target).
  HWY_ALIGN float table[256];
  for (std::size_t k = 0; k < 256; k += lanes)
    hn::Store(hn::ConvertTo(df, hn::PromoteTo(di, hn::LoadU(d16, lut + k))), df, table + k);
  const auto w0 = hn::Set(df, (1 - ax) * scale), w1 = hn::Set(df, ax * scale);
  constexpr std::size_t kBlock = 512; // channels a step
  HWY_ALIGN float value[kBlock + 3];
  for (std::size_t j0 = 0; j0 < m; j0 += kBlock) {
    const std::size_t n = std::min(kBlock, m - j0), codes = n + 3;
    const std::uint8_t* src = a + j0;
    if (ahead != nullptr)
      for (std::size_t b = 0; b < n; b += 64) mpr::detail::prefetch_l2(ahead, j0 + b);
    std::size_t k = 0;
    for (; k + lanes <= codes; k += lanes)
      hn::Store(hn::GatherIndex(df, table, hn::PromoteTo(di, hn::LoadU(d8, src + k))), df, value + k);
    for (; k < codes; ++k) value[k] = table[src[k]];
    std::size_t j = 0;
    for (; j + lanes <= n; j += lanes)
      hn::StoreU(hn::MulAdd(w1, hn::LoadU(df, value + j + 3), hn::Mul(w0, hn::Load(df, value + j))), df, h + j0 + j);
    for (; j < n; ++j) h[j0 + j] = (1 - ax) * scale * value[j] + ax * scale * value[j + 3];
  }
}

} // namespace mpr::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif // per-target toggle

#if HWY_ONCE && !defined(MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_ONCE)
#define MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_ONCE
namespace mpr::kernels {

/// Whether `lerp_row_hwy` has a Highway target compiled for `level` (the byte-permute form of
/// `avx512` counts as `avx512`): the targets of the build are Highway's `HWY_TARGETS`.
[[nodiscard]] inline bool lerp_row_hwy_has(detail::SimdLevel level) noexcept {
  if (level >= detail::SimdLevel::avx512) return (HWY_TARGETS & (HWY_AVX3 | HWY_AVX3_DL)) != 0;
  if (level >= detail::SimdLevel::avx2) return (HWY_TARGETS & HWY_AVX2) != 0;
  return true;
}

/// `detail::lerp_row_portable` for 8-bit codes, the Highway kernel compiled for `level`: levels
/// above `avx512` (AVX-512 with VBMI) or `avx512` with `vbmi` run the AVX3_DL target, `avx512`
/// the AVX3 one, `avx2` the AVX2 one, `portable` SSE4 when the CPU has SSE4.2, else the build's
/// baseline. A level the build has no target for falls to the best lower one. Precondition: the
/// CPU runs `level` (and VBMI with `vbmi`).
inline void lerp_row_hwy(const std::uint8_t* a, const std::uint16_t* lut, float ax, float scale, float* h,
                         std::size_t m, const std::uint8_t* ahead = nullptr,
                         detail::SimdLevel level = detail::dispatch_level(), bool vbmi = false) noexcept {
#if HWY_ARCH_X86
  const int rank = static_cast<int>(level), avx512 = static_cast<int>(detail::SimdLevel::avx512);
  if (rank >= avx512) {
#if HWY_TARGETS & HWY_AVX3_DL
    if (vbmi || rank > avx512) return N_AVX3_DL::lerp_row_codes(a, lut, ax, scale, h, m, ahead);
#endif
#if HWY_TARGETS & HWY_AVX3
    return N_AVX3::lerp_row_codes(a, lut, ax, scale, h, m, ahead);
#endif
  }
#if HWY_TARGETS & HWY_AVX2
  if (rank >= static_cast<int>(detail::SimdLevel::avx2)) return N_AVX2::lerp_row_codes(a, lut, ax, scale, h, m, ahead);
#endif
#if HWY_TARGETS & HWY_SSE4
  if (__builtin_cpu_supports("sse4.2")) return N_SSE4::lerp_row_codes(a, lut, ax, scale, h, m, ahead);
#endif
#endif
  (void)level;
  (void)vbmi;
  HWY_STATIC_DISPATCH(lerp_row_codes)(a, lut, ax, scale, h, m, ahead);
}

} // namespace mpr::kernels
#endif
#endif // MPR_HAVE_HWY
