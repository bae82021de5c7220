#pragma once
/// \file
/// Running sums of a row of steps added into a row of weights: weight[i] += steps[0] + ... +
/// steps[i]. The inner loop of `add_weight_steps` (frame_tiles.hpp), which folds a tile's
/// per-camera difference array of counts into its per-pixel weights; portable, and on x86 with
/// AVX-512 16 at a time (four shifted adds per vector plus the carry of the vectors before).

#include <mpr/core/simd.hpp>

#include <cstddef>

namespace mpr::detail {
// weight[i] += steps[0] + ... + steps[i] for i in [0, n).
inline void add_running_sums_portable(const float* steps, std::size_t n, float* weight) noexcept {
  float running = 0;
  for (std::size_t i = 0; i < n; ++i) {
    running += steps[i];
    weight[i] += running;
  }
}

#if defined(MPR_SIMD_X86)
// v plus v shifted up by `Lanes` lanes (zeros shifted in): one step of a running sum. The masked
// form of the shift: GCC 12's unmasked one passes an undefined vector (GCC bug 105593).
template <int Lanes>
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 plus_shifted(__m512 v) noexcept {
  return _mm512_add_ps(v, _mm512_castsi512_ps(_mm512_maskz_alignr_epi32(0xFFFF, _mm512_castps_si512(v),
                                                                        _mm512_setzero_si512(), 16 - Lanes)));
}

// The same, 16 at a time: each vector's running sums by four shifted adds, plus the carry of the
// vectors before (lane 15 of their sums; sums of whole numbers, exact in any order).
MPR_TARGET_AVX512 inline void add_running_sums_avx512(const float* steps, std::size_t n, float* weight) noexcept {
  const __m512i last = _mm512_set1_epi32(15);
  __m512 carry = _mm512_setzero_ps();
  for (std::size_t i = 0; i < n; i += 16) {
    const __mmask16 keep = n - i >= 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << (n - i)) - 1);
    const __m512 v =
        plus_shifted<8>(plus_shifted<4>(plus_shifted<2>(plus_shifted<1>(_mm512_maskz_loadu_ps(keep, steps + i)))));
    const __m512 sums = _mm512_add_ps(carry, v);
    _mm512_mask_storeu_ps(weight + i, keep, _mm512_add_ps(_mm512_maskz_loadu_ps(keep, weight + i), sums));
    carry = _mm512_maskz_permutexvar_ps(0xFFFF, last, sums);
  }
}
#endif
} // namespace mpr::detail
