#pragma once
/// \file
/// The beam test of the x86 packet kernels (bvh/detail/packet_kernels.hpp and
/// packet_kernels_avx512.hpp): `PortablePacketKernels<float>::beam4` with SSE, the four child
/// boxes per instruction, in the same order of operations, so the same mask. No add follows a
/// multiply directly, so no target's compiler can fuse one.

#include <mpr/core/config.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/packet.hpp>
#include <mpr/scene/bvh/slab.hpp>

#if MPR_BVH_SSE
#include <immintrin.h>

namespace mpr::scene::detail {

/// Bit `lane` set when the beam of `p` may enter child `lane` of `node` before `cull_max`.
[[nodiscard]] MPR_ALWAYS_INLINE unsigned beam4_sse(const WideNode<float>& node, const RayPacket<float>& p,
                                                   float cull_max) noexcept {
  const float* b = &node.bounds[0][0];
  const __m128 widen = _mm_set1_ps(kBoxWiden<float>);
  const __m128 cmax = _mm_set1_ps(cull_max);
  __m128 tn = _mm_setzero_ps(), tf = cmax;
  for (int a = 0; a < 3; ++a) {
    const __m128 bn = _mm_load_ps(b + 4 * p.near[a]), bf = _mm_load_ps(b + 4 * p.far[a]);
    const __m128 ilo = _mm_set1_ps(p.inv_lo[a]), ihi = _mm_set1_ps(p.inv_hi[a]);
    const __m128 n = _mm_add_ps(_mm_min_ps(_mm_mul_ps(bn, ihi), _mm_mul_ps(bn, ilo)), _mm_set1_ps(p.off_lo[a]));
    const __m128 f =
        _mm_mul_ps(_mm_add_ps(_mm_max_ps(_mm_mul_ps(bf, ihi), _mm_mul_ps(bf, ilo)), _mm_set1_ps(p.off_hi[a])), widen);
    tn = _mm_max_ps(n, tn);
    tf = _mm_min_ps(f, tf);
  }
  return static_cast<unsigned>(_mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(tn, tf), _mm_cmplt_ps(tn, cmax))));
}

} // namespace mpr::scene::detail
#endif
