#pragma once
/// \file
/// The weights of `CylinderAperture` (lightfield/cylinder_aperture.hpp) for a row of rays: the
/// linear falloff with the distance from a camera centre to each ray line, and the span of the
/// rays it weighs: a portable loop, and the same arithmetic written once with Highway and
/// compiled for SSE4, AVX2 and AVX-512 (kernels/cylinder_weights_hwy.inl, included below once per
/// target as kernels/depth_lanes_hwy.hpp includes its body).

#include <mpr/core/config.hpp>
#include <mpr/core/simd.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#if MPR_HAVE_HWY && defined(MPR_SIMD_X86)
#include <mpr/lightfield/kernels/lerp_row_hwy.hpp> // Highway's ops for every attainable target

#include <hwy/highway.h>
#endif

namespace mpr::detail {

/// w[i] = max(0, 1 - d_i / radius) for i in [0, n), d_i the distance from the in-plane centre
/// (cu, cv) to ray i of a row (see `PlaneRays`; inv_dd[i] = 1 / dd[i]): the linear falloff of
/// `CylinderAperture`. d^2 = |e|^2 - (e . d)^2 / |d|^2 with e = c - x, clamped at 0 against
/// rounding. Zero weight means outside the cylinder. Returns [first, last): the first and one
/// past the last i with w[i] > 0 (first = last = n when there is none).
template <class T>
inline std::array<std::size_t, 2> cylinder_weights_portable(const T* xu, const T* xv, const T* du, const T* dv,
                                                            const T* inv_dd, std::size_t n, T cu, T cv, T inv_radius,
                                                            float* w) noexcept {
  std::size_t first = n, last = n;
  for (std::size_t i = 0; i < n; ++i) {
    const T eu = cu - xu[i], ev = cv - xv[i];
    const T ed = eu * du[i] + ev * dv[i];
    const T d2 = std::max(eu * eu + ev * ev - ed * ed * inv_dd[i], T(0));
    w[i] = static_cast<float>(std::max(T(1) - std::sqrt(d2) * inv_radius, T(0)));
    if (w[i] > 0) {
      first = std::min(first, i);
      last = i + 1;
    }
  }
  return {first, first == n ? n : last};
}

/// The span of positive weights, gathered vector by vector (`positive`: the mask of the weights
/// from i that are > 0, lane l in bit l), then the portable tail's from i.
struct PositiveSpan {
  std::size_t n, first, last;
  MPR_ALWAYS_INLINE void add(std::size_t i, unsigned positive) noexcept {
    if (positive == 0) return;
    if (first == n) first = i + static_cast<std::size_t>(__builtin_ctz(positive));
    last = i + static_cast<std::size_t>(32 - __builtin_clz(positive));
  }
  [[nodiscard]] std::array<std::size_t, 2> with_tail(std::size_t i, std::array<std::size_t, 2> tail) noexcept {
    if (tail[0] < n - i) {
      if (first == n) first = i + tail[0];
      last = i + tail[1];
    }
    return {first, first == n ? n : last};
  }
};

} // namespace mpr::detail

// The kernel, once per Highway target (AVX-512 with VBMI runs the AVX-512 one).
#if MPR_HAVE_HWY && defined(MPR_SIMD_X86)
#if HWY_TARGETS & HWY_SSE4
HWY_PUSH_ATTRIBUTES(HWY_TARGET_STR_SSE4)
namespace mpr::kernels::cylinder_sse4 {
namespace hn = hwy::N_SSE4;
#include <mpr/lightfield/kernels/cylinder_weights_hwy.inl>
} // namespace mpr::kernels::cylinder_sse4
HWY_POP_ATTRIBUTES
#endif
#if HWY_TARGETS & HWY_AVX2
HWY_PUSH_ATTRIBUTES(HWY_TARGET_STR_AVX2)
namespace mpr::kernels::cylinder_avx2 {
namespace hn = hwy::N_AVX2;
#include <mpr/lightfield/kernels/cylinder_weights_hwy.inl>
} // namespace mpr::kernels::cylinder_avx2
HWY_POP_ATTRIBUTES
#endif
#if HWY_TARGETS & HWY_AVX3
HWY_PUSH_ATTRIBUTES(HWY_TARGET_STR_AVX3)
namespace mpr::kernels::cylinder_avx512 {
namespace hn = hwy::N_AVX3;
#include <mpr/lightfield/kernels/cylinder_weights_hwy.inl>
} // namespace mpr::kernels::cylinder_avx512
HWY_POP_ATTRIBUTES
#endif
#endif

namespace mpr::detail {

/// `cylinder_weights_portable`, or for float the Highway kernel (kernels/cylinder_weights_hwy.inl:
/// the same arithmetic, fused multiply-adds where the target has them) at `level`: `avx512` and
/// above the AVX-512 target, `avx2` the AVX2 one, `portable` SSE4 when the CPU has SSE4.2.
template <class T>
inline std::array<std::size_t, 2> cylinder_weights(const T* xu, const T* xv, const T* du, const T* dv, const T* inv_dd,
                                                   std::size_t n, T cu, T cv, T inv_radius, float* w,
                                                   SimdLevel level = dispatch_level()) noexcept {
#if MPR_HAVE_HWY && defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<T, float>) {
#if HWY_TARGETS & HWY_AVX3
    if (level >= SimdLevel::avx512)
      return kernels::cylinder_avx512::cylinder_weights(xu, xv, du, dv, inv_dd, n, cu, cv, inv_radius, w);
#endif
#if HWY_TARGETS & HWY_AVX2
    if (level >= SimdLevel::avx2)
      return kernels::cylinder_avx2::cylinder_weights(xu, xv, du, dv, inv_dd, n, cu, cv, inv_radius, w);
#endif
#if HWY_TARGETS & HWY_SSE4
    if (__builtin_cpu_supports("sse4.2"))
      return kernels::cylinder_sse4::cylinder_weights(xu, xv, du, dv, inv_dd, n, cu, cv, inv_radius, w);
#endif
  }
#endif
  (void)level;
  return cylinder_weights_portable(xu, xv, du, dv, inv_dd, n, cu, cv, inv_radius, w);
}

} // namespace mpr::detail
