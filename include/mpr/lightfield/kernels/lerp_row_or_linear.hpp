#pragma once
/// \file
/// A camera row interpolated horizontally from its 8-bit codes or, where the frames hold them and
/// the level's codes row is the Highway kernel, from their 16-bit decode-table values
/// (`CameraFrameSet::linear16`): the same row either way, the second without a decode. The
/// choice for `LerpRowCache` (the separable shift-and-add of `shift_add`).

#include <mpr/core/config.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>

#include <cstddef>
#include <cstdint>

namespace mpr::detail {

/// Whether `lerp_row_or_linear` reads the 16-bit linear values at `level`: where the codes' row
/// is the Highway kernel (below AVX-512, with Highway).
[[nodiscard]] constexpr bool lerp_row_reads_linear(SimdLevel level) noexcept {
  return MPR_HAVE_HWY && level < SimdLevel::avx512;
}

/// `lerp_row` of channels that may also be held as 16-bit decode-table values (`linear`, the
/// frames' `CameraFrameSet::linear16`; nullptr: none): below AVX-512 the Highway row on those (the
/// values of the Highway row on the codes, without a decode; `linear_ahead` prefetched in place
/// of `ahead`), elsewhere `lerp_row` on `a`.
template <class C>
inline void lerp_row_or_linear(const C* a, const std::uint16_t* linear, const std::uint16_t* lut, float ax, float scale,
                               float* h, std::size_t m, const C* ahead, const std::uint16_t* linear_ahead,
                               SimdLevel level = dispatch_level()) noexcept {
#if MPR_HAVE_HWY
  if (linear != nullptr && lerp_row_reads_linear(level))
    return kernels::lerp_row_linear_hwy(linear, ax, scale, h, m, linear_ahead, level);
#endif
  (void)linear, (void)linear_ahead;
  lerp_row(a, lut, ax, scale, h, m, ahead, level);
}

} // namespace mpr::detail
