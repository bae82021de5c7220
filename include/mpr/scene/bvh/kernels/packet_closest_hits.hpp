#pragma once
/// \file
/// `packet_closest_hits`, the entry point of the packet walk (bvh/packet.hpp) and the one place
/// that picks its kernels: AVX-512 (kernels/packet_avx512.hpp) or AVX2 (kernels/packet_avx2.hpp)
/// for float when the CPU runs them and `MPR_SIMD` allows it (core/simd.hpp), the portable
/// kernels otherwise.

#include <mpr/core/config.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/scene/bvh/kernels/packet_avx2.hpp>
#include <mpr/scene/bvh/kernels/packet_avx512.hpp>
#include <mpr/scene/bvh/kernels/walk_kernels.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/packet.hpp>

#include <concepts>
#include <cstddef>
#include <span>
#include <type_traits>

namespace mpr::scene::detail {

MPR_EXACT_FP_BEGIN

/// `hits[r]` = the closest hit of `rays[r]` in (0, t_max) for each r (at most `kPacketRays`
/// rays, equal lengths): `packet_closest_hits_with` with the widest kernels this CPU runs. The
/// same hits as `closest_hit_walk<WalkKernels<T>>` per ray, bit for bit.
template <std::floating_point T>
void packet_closest_hits(const BvhTree<T>& tree, std::span<const Ray<T>> rays, std::span<Hit<T>> hits,
                         T t_max) noexcept {
#if MPR_BVH_PACKET_AVX512
  if constexpr (std::is_same_v<T, float>) {
    if (mpr::detail::dispatch_level() >= mpr::detail::SimdLevel::avx512) {
      for (Hit<T>& h : hits) h = Hit<T>{t_max};
      RayPacket<T> p;
      if (Avx512PacketKernels::make(rays, t_max, p)) {
        packet_walk_avx512(tree, p, hits.data());
      } else {
        for (std::size_t r = 0; r < rays.size(); ++r) hits[r] = closest_hit_walk<SseKernels>(tree, rays[r], t_max);
      }
      return;
    }
  }
#endif
#if MPR_BVH_PACKET_AVX2
  if constexpr (std::is_same_v<T, float>) {
    if (mpr::detail::dispatch_level() >= mpr::detail::SimdLevel::avx2) {
      for (Hit<T>& h : hits) h = Hit<T>{t_max};
      RayPacket<T> p;
      if (Avx2PacketKernels::make(rays, t_max, p)) {
        packet_walk_avx2(tree, p, hits.data());
      } else {
        for (std::size_t r = 0; r < rays.size(); ++r) hits[r] = closest_hit_walk<SseKernels>(tree, rays[r], t_max);
      }
      return;
    }
  }
#endif
  packet_closest_hits_with<PortablePacketKernels<T>, WalkKernels<T>>(tree, rays, hits, t_max);
}

MPR_EXACT_FP_END

} // namespace mpr::scene::detail
