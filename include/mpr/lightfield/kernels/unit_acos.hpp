#pragma once
/// \file
/// The angle of a cosine in [0, 1], for `DepthProxy`'s Unstructured-Lumigraph penalty: one
/// polynomial, written once for a float and once for sixteen lanes with the same operations in
/// the same order (no fused multiply-add), so that the per-ray blend and the batch path get the
/// same bits. Doubles take `std::acos`.

#include <mpr/core/config.hpp>
#include <mpr/core/simd.hpp>

#include <cmath>
#include <concepts>

namespace mpr::detail {

/// Coefficients of asin(s) = s + s z P(z), z = s^2, for |s| <= 1/2: the single-precision minimax
/// polynomial of the Cephes library (S. Moshier), about 1 ulp.
inline constexpr float kAsinP[5] = {4.2163199048e-2f, 2.4181311049e-2f, 4.5470025998e-2f, 7.4953002686e-2f,
                                    1.6666752422e-1f};

/// acos(x) for x in [0, 1] (radians): 2 asin(sqrt((1 - x) / 2)) above 1/2, pi/2 - asin(x) below;
/// within about 2 ulp of the exact angle. Doubles: `std::acos`.
template <std::floating_point T>
[[nodiscard]] inline T unit_acos(T x) noexcept {
  if constexpr (std::same_as<T, float>) {
    const bool high = x >= 0.5f;
    const float z = high ? (1 - x) * 0.5f : x * x;
    const float s = high ? std::sqrt(z) : x;
    float p = kAsinP[0];
    for (int i = 1; i < 5; ++i) p = p * z + kAsinP[i];
    const float a = s + s * z * p;
    return high ? 2 * a : 1.57079632679489662f - a;
  } else {
    return std::acos(x);
  }
}

#if defined(MPR_SIMD_X86)
/// `unit_acos` in sixteen float lanes, the same operations in the same order.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 unit_acos16(__m512 x) noexcept {
  const __mmask16 high = _mm512_cmp_ps_mask(x, _mm512_set1_ps(0.5f), _CMP_GE_OQ);
  const __m512 z =
      _mm512_mask_blend_ps(high, _mm512_maskz_mul_ps(0xFFFF, x, x),
                           _mm512_maskz_mul_ps(0xFFFF, _mm512_sub_ps(_mm512_set1_ps(1), x), _mm512_set1_ps(0.5f)));
  const __m512 s = _mm512_mask_blend_ps(high, x, _mm512_maskz_sqrt_ps(0xFFFF, z));
  __m512 p = _mm512_set1_ps(kAsinP[0]);
  for (int i = 1; i < 5; ++i) p = _mm512_add_ps(_mm512_maskz_mul_ps(0xFFFF, p, z), _mm512_set1_ps(kAsinP[i]));
  const __m512 a = _mm512_add_ps(s, _mm512_maskz_mul_ps(0xFFFF, _mm512_maskz_mul_ps(0xFFFF, s, z), p));
  return _mm512_mask_blend_ps(high, _mm512_sub_ps(_mm512_set1_ps(1.57079632679489662f), a),
                              _mm512_maskz_mul_ps(0xFFFF, _mm512_set1_ps(2), a));
}
#endif

} // namespace mpr::detail
