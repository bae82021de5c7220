#pragma once
/// \file
/// The projective-row kernel (kernels/projective_row.hpp: one camera's bilinear pixels at n
/// points whose pixel coordinates are x_i = (a + i b) / (c + i d)) written once with Highway for
/// float coordinates and 8-bit or float channels, and compiled for SSE4 and AVX2
/// (`projective_row_hwy` picks one for a `SimdLevel`; AVX-512 has its own kernel,
/// kernels/projective_row.hpp). Each vector of points: the projective map
/// per lane (a division), the seen-mask (w > 0, pixel inside the image, weight > 0), the four
/// bilinear taps gathered (8-bit texels a 32-bit word each, decoded to linear light by the sRGB
/// cubic or the decode table, as kernels/lerp_row_hwy.hpp decodes; or, where the row carries the
/// frames' 16-bit linear copy, two 32-bit words of it a texel, no decode), weighed and added to
/// the interleaved r g b sums.
///
/// Header-only use as kernels/depth_lanes_hwy.hpp: Highway's ops exist once per target in a
/// translation unit (its foreach_target.h runs once, through kernels/lerp_row_hwy.hpp, for every
/// attainable target), so the body (kernels/projective_row_hwy.inl) is included below once per
/// target, in a namespace of its own under that target's attributes. x86 only; only when
/// Highway's headers are there (`MPR_HAVE_HWY`, core/config.hpp).

#include <mpr/core/config.hpp>
#if MPR_HAVE_HWY && defined(MPR_SIMD_X86)
#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/lerp_row_hwy.hpp> // Highway's ops for every attainable target

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>
#include <type_traits>

// The kernel's body, once per target.
#if HWY_TARGETS & HWY_SSE4
HWY_PUSH_ATTRIBUTES(HWY_TARGET_STR_SSE4)
namespace mpr::kernels::projective_sse4 {
namespace hn = hwy::N_SSE4;
#include <mpr/lightfield/kernels/projective_row_hwy.inl>
} // namespace mpr::kernels::projective_sse4
HWY_POP_ATTRIBUTES
#endif

#if HWY_TARGETS & HWY_AVX2
HWY_PUSH_ATTRIBUTES(HWY_TARGET_STR_AVX2)
namespace mpr::kernels::projective_avx2 {
namespace hn = hwy::N_AVX2;
#include <mpr/lightfield/kernels/projective_row_hwy.inl>
} // namespace mpr::kernels::projective_avx2
HWY_POP_ATTRIBUTES
#endif

namespace mpr::kernels {

/// The projective row of `r` (`detail::ProjectiveRow<float, C>`, C std::uint8_t or float; 8-bit
/// texels with readable bytes after the last, image `detail::gather_indexable`) over [0, n), as
/// `detail::projective_row_portable` computes it, at the Highway target for `level`: `avx2` and
/// above the AVX2 one, `portable` SSE4 when the CPU has SSE4.2.
/// False, with nothing done, when the build or the CPU has no target for `level`.
/// Precondition: the CPU runs `level`.
template <class Row>
[[nodiscard]] inline bool projective_row_hwy(const Row& r, std::size_t n, const float* rw, float* acc, float* seen,
                                             detail::SimdLevel level) noexcept {
#if HWY_TARGETS & HWY_AVX2
  if (level >= detail::SimdLevel::avx2) return projective_avx2::projective_row(r, n, rw, acc, seen), true;
#endif
#if HWY_TARGETS & HWY_SSE4
  if (__builtin_cpu_supports("sse4.2")) return projective_sse4::projective_row(r, n, rw, acc, seen), true;
#endif
  (void)r, (void)n, (void)rw, (void)acc, (void)seen, (void)level;
  return false;
}

} // namespace mpr::kernels
#endif
