#pragma once
/// \file
/// The kernel sets of the BVH walk (bvh/traverse.hpp): `PortableKernels<T>` (the box test of
/// bvh/slab.hpp and the edge functions of bvh/watertight.hpp, one lane after another) and, on
/// x86-64, `SseKernels`, their float twins four lanes at once, with every x86 specific of the
/// BVH. SSE2 is part of x86-64, so they need no run-time check; they do the same operations in
/// the same order as the portable ones, hence the same values bit for bit. `WalkKernels<T>` is
/// the set `Bvh::closest_hit` uses (`MPR_BVH_SSE`, core/config.hpp, turns the SSE set off).
///
/// Unlike the streaming kernels of core/ and lightfield/, the walk is not also compiled for
/// AVX2+FMA through `run_at`: there the compiler may fuse the scalar multiply-adds of the
/// triangle test (GCC does so by default in GNU mode), which would change hits; and the 4-wide
/// kernels gain nothing from wider registers.

#include <mpr/core/config.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/slab.hpp>
#include <mpr/scene/bvh/watertight.hpp>

#include <concepts>
#include <cstdint>
#include <type_traits>

#if MPR_BVH_SSE
#include <emmintrin.h>
#endif

namespace mpr::scene::detail {

MPR_EXACT_FP_BEGIN

/// The portable kernels, for any scalar type: the reference the SIMD ones must match.
template <std::floating_point T>
struct PortableKernels {
  using BoxRayType = BoxRay<T>;
  /// The edge functions of a block's lanes in use.
  struct EdgeValues {
    Edges<T> lanes[4];
    [[nodiscard]] const Edges<T>& lane(int k) const noexcept { return lanes[k]; }
  };
  [[nodiscard]] static BoxRayType box_ray(const BoxRay<T>& r) noexcept { return r; }
  [[nodiscard]] static unsigned box4(const WideNode<T>& node, const BoxRayType& r, T t_max, T* t_near) noexcept {
    return box4_portable(node, r, t_max, t_near);
  }
  /// Every lane in use of `block` (bit k for lane k), with its edge functions in `e`.
  [[nodiscard]] static unsigned edges4(const TriBlock<T>& block, const Shear<T>& sh, EdgeValues& e) noexcept {
    for (std::uint32_t lane = 0; lane < block.count; ++lane)
      e.lanes[lane] = edges_portable(block, lane, sh.kx, sh.ky, sh.kz, sh.sx, sh.sy, sh.ox, sh.oy, sh.oz);
    return (1U << block.count) - 1U;
  }
};

#if MPR_BVH_SSE

/// The per-ray constants of `box4_sse`, broadcast once per ray.
struct BoxRaySse {
  __m128 inv[3], offset[3];
  int near[3], far[3];
  explicit BoxRaySse(const BoxRay<float>& r) noexcept {
    for (int a = 0; a < 3; ++a) {
      inv[a] = _mm_set1_ps(r.inv[a]);
      offset[a] = _mm_set1_ps(r.offset[a]);
      near[a] = r.near[a];
      far[a] = r.far[a];
    }
  }
};

/// `box4_portable` for float with SSE: the same operations in the same order, so the same
/// values and mask. `_mm_max_ps(b, a)` is `std::max(a, b)` exactly (NaN included: both return
/// `a` unless a < b), likewise for min, hence the swapped operands.
[[nodiscard]] inline unsigned box4_sse(const WideNode<float>& node, const BoxRaySse& r, float t_max,
                                       float* t_near) noexcept {
  const float* b = &node.bounds[0][0];
  const __m128 widen = _mm_set1_ps(kBoxWiden<float>);
  __m128 n[3], f[3];
  for (int a = 0; a < 3; ++a) {
    n[a] = _mm_add_ps(_mm_mul_ps(_mm_load_ps(b + 4 * r.near[a]), r.inv[a]), r.offset[a]);
    f[a] = _mm_mul_ps(_mm_add_ps(_mm_mul_ps(_mm_load_ps(b + 4 * r.far[a]), r.inv[a]), r.offset[a]), widen);
  }
  const __m128 tmax = _mm_set1_ps(t_max);
  const __m128 tn = _mm_max_ps(_mm_max_ps(_mm_setzero_ps(), n[2]), _mm_max_ps(n[1], n[0]));
  const __m128 tf = _mm_min_ps(_mm_min_ps(tmax, f[2]), _mm_min_ps(f[1], f[0]));
  _mm_store_ps(t_near, tn);
  return static_cast<unsigned>(_mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(tn, tf), _mm_cmplt_ps(tn, tmax))));
}

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

/// The SSE kernels (float): the same interface as `PortableKernels<float>`, whose `edges4`
/// result they narrow to the lanes the watertight test cannot reject from the edge values
/// alone (a rejected lane would not have hit).
struct SseKernels {
  using BoxRayType = BoxRaySse;
  using EdgeValues = EdgeValues4;
  [[nodiscard]] static BoxRayType box_ray(const BoxRay<float>& r) noexcept { return BoxRaySse(r); }
  [[nodiscard]] static unsigned box4(const WideNode<float>& node, const BoxRayType& r, float t_max,
                                     float* t_near) noexcept {
    return box4_sse(node, r, t_max, t_near);
  }
  [[nodiscard]] static unsigned edges4(const TriBlock<float>& block, const Shear<float>& sh, EdgeValues& e) noexcept {
    return edges4_sse(block, sh.kx, sh.ky, sh.kz, sh.sx, sh.sy, sh.ox, sh.oy, sh.oz, e);
  }
};

/// The kernels `Bvh::closest_hit` walks with: SSE for float, portable otherwise.
template <std::floating_point T>
using WalkKernels = std::conditional_t<std::is_same_v<T, float>, SseKernels, PortableKernels<T>>;
#else
template <std::floating_point T>
using WalkKernels = PortableKernels<T>;
#endif

MPR_EXACT_FP_END

} // namespace mpr::scene::detail
