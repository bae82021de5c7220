#pragma once
/// \file
/// The ray-box slab test of one ray against the four child boxes of a BVH node with SSE (x86-64
/// only, `MPR_BVH_SSE`): the float twin of `box4_portable` (bvh/slab.hpp), bit for bit.

#include <mpr/core/config.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/slab.hpp>

#if MPR_BVH_SSE
#include <emmintrin.h>
#endif

namespace mpr::scene::detail {

MPR_EXACT_FP_BEGIN

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

#endif

MPR_EXACT_FP_END

} // namespace mpr::scene::detail
