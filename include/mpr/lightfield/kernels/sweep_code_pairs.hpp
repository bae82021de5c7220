#pragma once
/// \file
/// The bilinear blend of the plane sweep's 16-bit kernel (kernels/sweep_code_kernels.hpp) with
/// the x86 byte multiply-add `pmaddubsw` (SSSE3, AVX2, AVX-512 BW): the 16-bit lanes of a load
/// of codes from x are the *pair words* code[x + 2i] | code[x + 2i + 1] << 8, and times the lane
/// weights (w_left | w_right << 8) w_left code[x + 2i] + w_right code[x + 2i + 1] in one
/// instruction, so a blend of four taps is two loads, two multiply-adds and an add. `pmaddubsw` multiplies unsigned
/// bytes (the codes) by signed ones (the weights): each weight must be at most 127 (`sweep_code_set_weights` keeps them
/// so), and then no sum saturates (at most 255 x 128 = 32640). The compiler's vector types have no such operation (nor
/// Highway 1.0.3's), hence the intrinsics; the portable level without SSSE3 and AArch64 compute the same integers with
/// plain multiplies.

#include <mpr/core/config.hpp>

#include <cstdint>

#if defined(MPR_SIMD_X86)
#include <immintrin.h>

namespace mpr::detail {

/// p = 32 blends: maddubs(top[0..64), wt) + maddubs(bottom[0..64), wb), `top` and `bottom`
/// codes (any alignment), `wt` / `wb` the weights of the top / bottom row as bytes (left,
/// right) of each 16-bit lane, each in [0, 127]. Not forced inline: the level-generic kernel
/// body that calls it is compiled without the instruction set (GCC and Clang refuse to force
/// it into such a function), and inlined into the level's function, where the compiler then
/// inlines this step (vectors by reference, so that no call could change the ABI).
MPR_TARGET_AVX512 inline void sweep_pairs_blend(__m512i& p, const std::uint8_t* top, const std::uint8_t* bottom,
                                                const __m512i& wt, const __m512i& wb) noexcept {
  p = _mm512_add_epi16(_mm512_maddubs_epi16(_mm512_loadu_si512(top), wt),
                       _mm512_maddubs_epi16(_mm512_loadu_si512(bottom), wb));
}

/// 16 blends (as the 32 above).
MPR_TARGET_AVX2 inline void sweep_pairs_blend(__m256i& p, const std::uint8_t* top, const std::uint8_t* bottom,
                                              const __m256i& wt, const __m256i& wb) noexcept {
  const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(top));
  const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(bottom));
  p = _mm256_add_epi16(_mm256_maddubs_epi16(a, wt), _mm256_maddubs_epi16(b, wb));
}

#if defined(__SSSE3__)
/// 8 blends (as the 32 above), where the build's baseline has SSSE3 (`-march=native` builds;
/// the default x86-64 baseline, SSE2, takes the plain multiplies).
MPR_ALWAYS_INLINE void sweep_pairs_blend(__m128i& p, const std::uint8_t* top, const std::uint8_t* bottom,
                                         const __m128i& wt, const __m128i& wb) noexcept {
  const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(top));
  const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(bottom));
  p = _mm_add_epi16(_mm_maddubs_epi16(a, wt), _mm_maddubs_epi16(b, wb));
}
#endif

} // namespace mpr::detail
#endif
