#pragma once
/// \file
/// The kernel sets of the BVH walk (bvh/traverse.hpp): `PortableKernels<T>` (the box test of
/// bvh/slab.hpp and the edge functions of bvh/watertight.hpp, one lane after another) and, on
/// x86-64, `SseKernels`, their float twins four lanes at once (kernels/box4_sse.hpp and
/// kernels/triangle_edges4_sse.hpp). SSE2 is part of x86-64, so they need no run-time check; they do the same
/// operations in the same order as the portable ones, hence the same values bit for bit. `WalkKernels<T>` is the set
/// `Bvh::closest_hit` uses (`MPR_BVH_SSE`, core/config.hpp, turns the SSE set off).
///
/// Unlike the streaming kernels of core/ and lightfield/, the walk is not also compiled for
/// AVX2+FMA through `run_at`: there the compiler may fuse the scalar multiply-adds of the
/// triangle test (GCC does so by default in GNU mode), which would change hits; and the 4-wide
/// kernels gain nothing from wider registers.

#include <mpr/core/config.hpp>
#include <mpr/scene/bvh/kernels/box4_sse.hpp>
#include <mpr/scene/bvh/kernels/triangle_edges4_sse.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/slab.hpp>
#include <mpr/scene/bvh/watertight.hpp>

#include <concepts>
#include <cstdint>
#include <type_traits>

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
