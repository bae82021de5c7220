#pragma once
/// \file
/// The weights of `CylinderAperture` (lightfield/cylinder_aperture.hpp) for a row of rays: the
/// linear falloff with the distance from a camera centre to each ray line, and the span of the
/// rays it weighs, portable and in AVX2 and AVX-512 kernels with the same arithmetic.

#include <mpr/core/config.hpp>
#include <mpr/core/simd.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

#if defined(MPR_SIMD_X86)
#include <immintrin.h>
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

#if defined(MPR_SIMD_X86)
// The span of positive weights, gathered vector by vector (`positive`: the mask of the weights
// from i that are > 0), then the portable tail's from i.
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

// Written with intrinsics: with errno-setting sqrt (the default), compilers do not vectorise
// std::sqrt, and this loop is mostly the square root.
MPR_TARGET_AVX2 inline std::array<std::size_t, 2> cylinder_weights_avx2(const float* xu, const float* xv,
                                                                        const float* du, const float* dv,
                                                                        const float* inv_dd, std::size_t n, float cu,
                                                                        float cv, float inv_radius, float* w) noexcept {
  const __m256 vcu = _mm256_set1_ps(cu), vcv = _mm256_set1_ps(cv), vinv = _mm256_set1_ps(inv_radius);
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  PositiveSpan span{n, n, n};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256 eu = _mm256_sub_ps(vcu, _mm256_loadu_ps(xu + i)), ev = _mm256_sub_ps(vcv, _mm256_loadu_ps(xv + i));
    const __m256 ed = _mm256_fmadd_ps(eu, _mm256_loadu_ps(du + i), _mm256_mul_ps(ev, _mm256_loadu_ps(dv + i)));
    const __m256 r2 = _mm256_fmadd_ps(eu, eu, _mm256_mul_ps(ev, ev));
    const __m256 d2 = _mm256_max_ps(_mm256_fnmadd_ps(_mm256_mul_ps(ed, ed), _mm256_loadu_ps(inv_dd + i), r2), zero);
    const __m256 wi = _mm256_max_ps(_mm256_fnmadd_ps(_mm256_sqrt_ps(d2), vinv, one), zero);
    _mm256_storeu_ps(w + i, wi);
    span.add(i, static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(wi, zero, _CMP_GT_OQ))));
  }
  return span.with_tail(
      i, cylinder_weights_portable(xu + i, xv + i, du + i, dv + i, inv_dd + i, n - i, cu, cv, inv_radius, w + i));
}

// The AVX2 kernel's arithmetic sixteen lanes at a time (masked forms: GCC bug 105593,
// -Wmaybe-uninitialized).
MPR_TARGET_AVX512 inline std::array<std::size_t, 2>
cylinder_weights_avx512(const float* xu, const float* xv, const float* du, const float* dv, const float* inv_dd,
                        std::size_t n, float cu, float cv, float inv_radius, float* w) noexcept {
  const __m512 vcu = _mm512_set1_ps(cu), vcv = _mm512_set1_ps(cv), vinv = _mm512_set1_ps(inv_radius);
  const __m512 one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
  PositiveSpan span{n, n, n};
  std::size_t i = 0;
  for (; i + 16 <= n; i += 16) {
    const __m512 eu = _mm512_sub_ps(vcu, _mm512_loadu_ps(xu + i)), ev = _mm512_sub_ps(vcv, _mm512_loadu_ps(xv + i));
    const __m512 ed = _mm512_fmadd_ps(eu, _mm512_loadu_ps(du + i), _mm512_mul_ps(ev, _mm512_loadu_ps(dv + i)));
    const __m512 r2 = _mm512_fmadd_ps(eu, eu, _mm512_mul_ps(ev, ev));
    const __m512 d2 =
        _mm512_maskz_max_ps(0xFFFF, _mm512_fnmadd_ps(_mm512_mul_ps(ed, ed), _mm512_loadu_ps(inv_dd + i), r2), zero);
    const __m512 wi = _mm512_maskz_max_ps(0xFFFF, _mm512_fnmadd_ps(_mm512_maskz_sqrt_ps(0xFFFF, d2), vinv, one), zero);
    _mm512_storeu_ps(w + i, wi);
    span.add(i, _mm512_cmp_ps_mask(wi, zero, _CMP_GT_OQ));
  }
  return span.with_tail(
      i, cylinder_weights_portable(xu + i, xv + i, du + i, dv + i, inv_dd + i, n - i, cu, cv, inv_radius, w + i));
}
#endif

/// `cylinder_weights_portable`, or the AVX2 / AVX-512 kernel (float, the same arithmetic) when
/// `level` allows.
template <class T>
inline std::array<std::size_t, 2> cylinder_weights(const T* xu, const T* xv, const T* du, const T* dv, const T* inv_dd,
                                                   std::size_t n, T cu, T cv, T inv_radius, float* w,
                                                   SimdLevel level = dispatch_level()) noexcept {
#if defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<T, float>) {
    if (level >= SimdLevel::avx512) return cylinder_weights_avx512(xu, xv, du, dv, inv_dd, n, cu, cv, inv_radius, w);
    if (level == SimdLevel::avx2) return cylinder_weights_avx2(xu, xv, du, dv, inv_dd, n, cu, cv, inv_radius, w);
  }
#endif
  (void)level;
  return cylinder_weights_portable(xu, xv, du, dv, inv_dd, n, cu, cv, inv_radius, w);
}

} // namespace mpr::detail
