#pragma once
/// \file
/// The blend of `DepthProxy`'s batch path for 8-bit frames (lightfield/depth_proxy.hpp), sixteen
/// rays to a register: the Unstructured-Lumigraph weights of each ray's chosen cameras
/// (`DepthProxy::weigh`) and their bilinear texels (`FrameTable::fetch_add`): per camera four
/// taps, each a pair of eight-lane 32-bit gathers from 64-bit addresses (the lanes' cameras
/// differ), decoded to linear light as the projective rows' gathers are (`decode_texel_words`).
/// Every sum is formed in the per-ray code's order with no fused multiply-add, so the lanes give
/// the per-ray bits where that code is not contracted either (as detail/depth_lanes.hpp says).

#include <mpr/core/config.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/lightfield/detail/depth_lanes.hpp>
#include <mpr/lightfield/detail/kernels.hpp>
#include <mpr/lightfield/detail/projective_row.hpp>

#include <cstddef>
#include <cstdint>

namespace mpr::detail {

#if defined(MPR_SIMD_X86)

/// What `weigh16` reads of a camera: its 8-bit texels (3 bytes each, with at least one readable
/// byte past the last: `HugePageAllocator`'s padding) and size, `gather_indexable`.
struct WeighCamera {
  const std::uint8_t* texels;
  int width, height;
};

/// acc[c][l] and weight[l] for the lanes l of `lanes`: `DepthProxy::weigh` of lane l's chosen
/// cameras `choice` (slots [0, slots) filled from the first, by increasing penalty; camera -1 in
/// the empty ones) with k blended, each camera's texels bilinear at its pixel
/// (`FrameTable::fetch_add` with the bilinear filter, `scale` the texel scale, `lut` the 16-bit
/// decode table). `cameras[i]` describes camera i. Other lanes: zero.
MPR_TARGET_AVX512 inline void weigh16(const WeighCamera* cameras, const LaneChoice& choice, int slots, int k,
                                      unsigned lanes, const std::uint16_t* lut, float scale, float (*acc)[16],
                                      float* weight) noexcept {
  const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f), tiny = _mm512_set1_ps(1e-6f);
  const __m512i none = _mm512_set1_epi32(-1);
  const Decode16x512 decode = load_decode16(lut);
  // The threshold per lane: the (k+1)-th smallest penalty when more than k cameras see the
  // point, else twice the largest (the last filled slot's).
  __mmask16 filled[kDepthLaneSlots];
  __m512 last = zero;
  for (int j = 0; j < slots; ++j) {
    filled[j] =
        static_cast<__mmask16>(lanes & _mm512_cmp_epi32_mask(_mm512_load_si512(choice.camera[j]), none, _MM_CMPINT_NE));
    last = _mm512_mask_mov_ps(last, filled[j], _mm512_load_ps(choice.penalty[j]));
  }
  __m512 threshold = _mm512_add_ps(mul16(_mm512_set1_ps(2.0f), last), tiny);
  if (k < slots)
    threshold =
        _mm512_mask_mov_ps(threshold, filled[k], _mm512_maskz_max_ps(0xFFFF, _mm512_load_ps(choice.penalty[k]), tiny));
  __m512 sum[3] = {zero, zero, zero}, total = zero;
  for (int j = 0; j < slots; ++j) {
    const __m512 p = _mm512_load_ps(choice.penalty[j]);
    const __mmask16 m = filled[j] & _mm512_cmp_ps_mask(p, threshold, _CMP_LT_OQ);
    if (m == 0) continue;
    // (1 - p / threshold) / (p + 1e-6), as `weigh` computes it.
    const __m512 w =
        _mm512_maskz_div_ps(m, _mm512_sub_ps(one, _mm512_maskz_div_ps(m, p, threshold)), _mm512_add_ps(p, tiny));
    total = _mm512_mask_add_ps(total, m, total, w);
    // Each lane's camera: its texels (64-bit addresses, two halves of eight) and size.
    alignas(64) std::int64_t base[16];
    alignas(64) int width[16], height[16];
    for (int l = 0; l < 16; ++l) {
      const int i = (m >> l & 1u) != 0 ? choice.camera[j][l] : -1;
      base[l] = i >= 0 ? reinterpret_cast<std::int64_t>(cameras[i].texels) : 0;
      width[l] = i >= 0 ? cameras[i].width : 1;
      height[l] = i >= 0 ? cameras[i].height : 1;
    }
    const __m512i wv = _mm512_load_si512(width), hv = _mm512_load_si512(height);
    const __m512 x = _mm512_maskz_load_ps(m, choice.x[j]), y = _mm512_maskz_load_ps(m, choice.y[j]);
    const __m512 fx = _mm512_maskz_roundscale_ps(0xFFFF, x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    const __m512 fy = _mm512_maskz_roundscale_ps(0xFFFF, y, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    const __m512 ax = _mm512_sub_ps(x, fx), ay = _mm512_sub_ps(y, fy);
    const __m512i x0 = _mm512_maskz_cvttps_epi32(0xFFFF, fx), y0 = _mm512_maskz_cvttps_epi32(0xFFFF, fy);
    const __m512i ione = _mm512_set1_epi32(1), izero = _mm512_setzero_si512();
    const __m512i xa = _mm512_maskz_max_epi32(0xFFFF, x0, izero);
    const __m512i xb = _mm512_maskz_min_epi32(0xFFFF, _mm512_add_epi32(x0, ione), _mm512_sub_epi32(wv, ione));
    const __m512i ya = _mm512_mullo_epi32(_mm512_maskz_max_epi32(0xFFFF, y0, izero), wv);
    const __m512i yb =
        _mm512_mullo_epi32(_mm512_maskz_min_epi32(0xFFFF, _mm512_add_epi32(y0, ione), _mm512_sub_epi32(hv, ione)), wv);
    // fetch_add: w00 = (1 - ax) (1 - ay) s, ..., acc += w00 v00 + w10 v10 + w01 v01 + w11 v11.
    const __m512 s = mul16(w, _mm512_set1_ps(scale));
    const __m512 bx = _mm512_sub_ps(one, ax), by = _mm512_sub_ps(one, ay);
    const __m512 tap_weight[4] = {mul16(mul16(bx, by), s), mul16(mul16(ax, by), s), mul16(mul16(bx, ay), s),
                                  mul16(mul16(ax, ay), s)};
    const __m512i tap_index[4] = {_mm512_add_epi32(ya, xa), _mm512_add_epi32(ya, xb), _mm512_add_epi32(yb, xa),
                                  _mm512_add_epi32(yb, xb)};
    const __m512i base_lo = _mm512_load_si512(base), base_hi = _mm512_load_si512(base + 8);
    __m512 part[3] = {zero, zero, zero};
    for (int t = 0; t < 4; ++t) {
      // Byte offsets 3 (y width + x), below 2^31 (`gather_indexable`), then addresses.
      const __m512i offset = _mm512_mullo_epi32(tap_index[t], _mm512_set1_epi32(3));
      const __m512i lo = _mm512_add_epi64(base_lo, _mm512_maskz_cvtepi32_epi64(0xFF, low256(offset)));
      const __m512i hi =
          _mm512_add_epi64(base_hi, _mm512_maskz_cvtepi32_epi64(0xFF, _mm512_maskz_extracti64x4_epi64(0xF, offset, 1)));
      const __m256i g0 = _mm512_mask_i64gather_epi32(_mm256_setzero_si256(), static_cast<__mmask8>(m), lo, nullptr, 1);
      const __m256i g1 =
          _mm512_mask_i64gather_epi32(_mm256_setzero_si256(), static_cast<__mmask8>(m >> 8), hi, nullptr, 1);
      __m512 v[3];
      decode_texel_words(decode, _mm512_maskz_inserti64x4(0xFF, zext256(g0), g1, 1), v);
      for (int c = 0; c < 3; ++c) {
        const __m512 term = mul16(tap_weight[t], v[c]);
        part[c] = t == 0 ? term : _mm512_add_ps(part[c], term);
      }
    }
    for (int c = 0; c < 3; ++c) sum[c] = _mm512_mask_add_ps(sum[c], m, sum[c], part[c]);
  }
  for (int c = 0; c < 3; ++c) _mm512_store_ps(acc[c], sum[c]);
  _mm512_store_ps(weight, total);
}

#endif

} // namespace mpr::detail
