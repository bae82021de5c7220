#pragma once
/// \file
/// The watertight test's edge functions of one ray against the four triangles of a leaf block
/// with SSE (x86-64 only, `MPR_BVH_SSE`): the float twin of `edges_portable`
/// (bvh/watertight.hpp), bit for bit.

#include <mpr/core/config.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/slab.hpp>
#include <mpr/scene/bvh/watertight.hpp>

#if MPR_BVH_SSE
#include <emmintrin.h>
#endif

namespace mpr::scene::detail {

MPR_EXACT_FP_BEGIN

#if MPR_BVH_SSE

/// `Edges` of the four lanes of a block, as computed by `edges4_sse`.
struct EdgeValues4 {
  alignas(16) float Ax[4], Ay[4], Bx[4], By[4], Cx[4], Cy[4], az[4], bz[4], cz[4], U[4], V[4], W[4];
  [[nodiscard]] Edges<float> lane(int k) const noexcept {
    return {Ax[k], Ay[k], Bx[k], By[k], Cx[k], Cy[k], az[k], bz[k], cz[k], U[k], V[k], W[k]};
  }
};

/// `edges_portable` for all four lanes of a float block with SSE (the same operations, so the
/// same values). Returns the lanes in use that the watertight test cannot reject from these
/// values alone: U, V, W not of mixed sign, or one of them zero (those need the exact fallback).
/// `e` is written only when the result is non-zero.
[[nodiscard]] inline unsigned edges4_sse(const TriBlock<float>& block, int kx, int ky, int kz, float sx, float sy,
                                         float ox, float oy, float oz, EdgeValues4& e) noexcept {
  const __m128 vox = _mm_set1_ps(ox), voy = _mm_set1_ps(oy), voz = _mm_set1_ps(oz);
  const __m128 vsx = _mm_set1_ps(sx), vsy = _mm_set1_ps(sy);
  const __m128 az = _mm_sub_ps(_mm_load_ps(block.p[0][kz]), voz);
  const __m128 bz = _mm_sub_ps(_mm_load_ps(block.p[1][kz]), voz);
  const __m128 cz = _mm_sub_ps(_mm_load_ps(block.p[2][kz]), voz);
  const __m128 Ax = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(block.p[0][kx]), vox), _mm_mul_ps(vsx, az));
  const __m128 Ay = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(block.p[0][ky]), voy), _mm_mul_ps(vsy, az));
  const __m128 Bx = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(block.p[1][kx]), vox), _mm_mul_ps(vsx, bz));
  const __m128 By = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(block.p[1][ky]), voy), _mm_mul_ps(vsy, bz));
  const __m128 Cx = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(block.p[2][kx]), vox), _mm_mul_ps(vsx, cz));
  const __m128 Cy = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(block.p[2][ky]), voy), _mm_mul_ps(vsy, cz));
  const __m128 U = _mm_sub_ps(_mm_mul_ps(Cx, By), _mm_mul_ps(Cy, Bx));
  const __m128 V = _mm_sub_ps(_mm_mul_ps(Ax, Cy), _mm_mul_ps(Ay, Cx));
  const __m128 W = _mm_sub_ps(_mm_mul_ps(Bx, Ay), _mm_mul_ps(By, Ax));
  const __m128 zero = _mm_setzero_ps();
  const __m128 neg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(U, zero), _mm_cmplt_ps(V, zero)), _mm_cmplt_ps(W, zero));
  const __m128 pos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(U, zero), _mm_cmpgt_ps(V, zero)), _mm_cmpgt_ps(W, zero));
  const __m128 any_zero = _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(U, zero), _mm_cmpeq_ps(V, zero)), _mm_cmpeq_ps(W, zero));
  // Rejected: mixed signs with no zero (a zero goes to the double-precision recomputation).
  const unsigned rejected = static_cast<unsigned>(_mm_movemask_ps(_mm_andnot_ps(any_zero, _mm_and_ps(neg, pos))));
  const unsigned candidates = ((1U << block.count) - 1U) & ~rejected;
  if (candidates != 0) {
    _mm_store_ps(e.Ax, Ax);
    _mm_store_ps(e.Ay, Ay);
    _mm_store_ps(e.Bx, Bx);
    _mm_store_ps(e.By, By);
    _mm_store_ps(e.Cx, Cx);
    _mm_store_ps(e.Cy, Cy);
    _mm_store_ps(e.az, az);
    _mm_store_ps(e.bz, bz);
    _mm_store_ps(e.cz, cz);
    _mm_store_ps(e.U, U);
    _mm_store_ps(e.V, V);
    _mm_store_ps(e.W, W);
  }
  return candidates;
}

#endif

MPR_EXACT_FP_END

} // namespace mpr::scene::detail
