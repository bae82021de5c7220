#pragma once
/// \file
/// Coherent rays through the 4-wide BVH: up to `kPacketRays` rays (a 4 x 4 block of an image
/// tile, say) walk the tree together. At each node the packet's beam — per axis the least and
/// greatest inverse direction and slab offset of its rays — is tested against the four child
/// boxes first; a child the beam misses is missed by every ray, with no ray tested. Children the
/// beam enters are tested against each active ray (the slab test of bvh/slab.hpp, the same
/// operations per ray), and leaves with the watertight test of each active ray
/// (bvh/traverse.hpp's `intersect_leaf`), so every ray gets the hit `closest_hit_walk` gives
/// it: the least (t, triangle index) pair, bit for bit.
///
/// The beam test is conservative in floating point, not only in exact arithmetic: rounding is
/// monotonic, so a bound computed with the same operations from the least (greatest) operands
/// is a lower (upper) bound of every ray's computed value. It needs every ray's near plane on the
/// same side of each box, i.e. the same direction signs: packets whose rays differ in sign (or
/// whose slab constants are not finite) are not formed, and their rays walk one by one.
///
/// The kernels here are portable (any scalar type); bvh/kernels/ has the x86
/// ones and the entry point that picks them.

#include <mpr/core/config.hpp>
#include <mpr/core/detail/prefetch.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/slab.hpp>
#include <mpr/scene/bvh/traverse.hpp>
#include <mpr/scene/bvh/watertight.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

namespace mpr::scene::detail {

MPR_EXACT_FP_BEGIN

/// Rays per packet (at most): a 4 x 4 block of pixels.
inline constexpr int kPacketRays = 16;

/// A packet's per-ray constants, structure-of-arrays (lane r is ray r), and its beam.
template <std::floating_point T>
struct RayPacket {
  /// Slab constants of `BoxRay::make` per ray: t = p * inv + offset.
  alignas(64) T inv[3][kPacketRays];
  alignas(64) T offset[3][kPacketRays];
  /// `cull_bound` of each ray's closest hit so far; -inf in lanes without a ray (never enter).
  alignas(64) T cull[kPacketRays];
  /// Each ray's closest hit parameter so far (`Hit::t`, kept beside `cull` for SIMD leaves).
  alignas(64) T best[kPacketRays];
  /// Each ray's watertight set-up.
  Shear<T> shear[kPacketRays];
  /// The same, structure-of-arrays (shear and permuted origin per ray), for leaf kernels that
  /// test several rays at once; valid when `same_axes`.
  alignas(64) T sx[kPacketRays], sy[kPacketRays], sz[kPacketRays];
  alignas(64) T ox[kPacketRays], oy[kPacketRays], oz[kPacketRays];
  /// True when every active ray has the same axis permutation, (kx, ky, kz).
  bool same_axes = true;
  int kx = 0, ky = 1, kz = 2;
  /// The beam: least and greatest `inv` and `offset` over the active rays, per axis.
  std::array<T, 3> inv_lo, inv_hi, off_lo, off_hi;
  /// Rows of `WideNode::bounds` with each axis' near and far plane, common to all rays.
  std::array<int, 3> near, far;
  /// Rays that can hit (valid direction), bit r for ray r.
  std::uint32_t active = 0;

  /// Sets up `p` for `rays` (at most `kPacketRays`) with the closest hits so far `hits` (t_max
  /// in `hits[r].t` for none). False when the rays cannot walk as one packet: their direction
  /// signs differ, or a slab constant is not finite. Rays with a zero or NaN direction hit
  /// nothing and are left out of `active`.
  [[nodiscard]] static bool make(std::span<const Ray<T>> rays, const Hit<T>* hits, RayPacket& p) noexcept {
    p.active = 0;
    p.same_axes = true;
    for (int r = 0; r < kPacketRays; ++r) {
      p.sx[r] = p.sy[r] = p.sz[r] = p.ox[r] = p.oy[r] = p.oz[r] = 0;
      for (int a = 0; a < 3; ++a) {
        p.inv[a][r] = 1;
        p.offset[a][r] = 0;
      }
      p.cull[r] = -std::numeric_limits<T>::infinity();
      p.best[r] = 0;
    }
    for (std::size_t r = 0; r < rays.size(); ++r) {
      if (!Shear<T>::make(rays[r], p.shear[r])) continue;
      const BoxRay<T> b = BoxRay<T>::make(rays[r]);
      for (int a = 0; a < 3; ++a)
        if (!std::isfinite(b.inv[a]) || !std::isfinite(b.offset[a])) return false;
      if (p.active == 0) {
        p.near = b.near;
        p.far = b.far;
        for (int a = 0; a < 3; ++a) {
          p.inv_lo[a] = p.inv_hi[a] = b.inv[a];
          p.off_lo[a] = p.off_hi[a] = b.offset[a];
        }
      } else if (b.near != p.near) {
        return false;
      }
      for (int a = 0; a < 3; ++a) {
        p.inv[a][r] = b.inv[a];
        p.offset[a][r] = b.offset[a];
        p.inv_lo[a] = std::min(p.inv_lo[a], b.inv[a]);
        p.inv_hi[a] = std::max(p.inv_hi[a], b.inv[a]);
        p.off_lo[a] = std::min(p.off_lo[a], b.offset[a]);
        p.off_hi[a] = std::max(p.off_hi[a], b.offset[a]);
      }
      p.cull[r] = cull_bound(hits[r].t);
      p.best[r] = hits[r].t;
      const Shear<T>& sh = p.shear[r];
      if (p.active == 0) {
        p.kx = sh.kx;
        p.ky = sh.ky;
        p.kz = sh.kz;
      } else {
        p.same_axes = p.same_axes && sh.kx == p.kx && sh.ky == p.ky && sh.kz == p.kz;
      }
      p.sx[r] = sh.sx;
      p.sy[r] = sh.sy;
      p.sz[r] = sh.sz;
      p.ox[r] = sh.ox;
      p.oy[r] = sh.oy;
      p.oz[r] = sh.oz;
      p.active |= 1U << r;
    }
    return true;
  }

  /// The greatest `cull` over the active rays (-inf when none).
  [[nodiscard]] T max_cull() const noexcept {
    T m = -std::numeric_limits<T>::infinity();
    for (int r = 0; r < kPacketRays; ++r) m = std::max(m, cull[r]);
    return m;
  }
};

/// The portable packet kernels (any scalar type): the reference for the x86 ones.
template <std::floating_point T>
struct PortablePacketKernels {
  /// What `rays` gives for the least entry parameter, and its value (`least_value`): the x86
  /// kernels keep a vector and reduce it only when the walk needs the number.
  using Least = T;
  [[nodiscard]] static T least_value(T t) noexcept { return t; }

  /// Bit `lane` set when the beam of `p` may enter child `lane` of `node` before `cull_max`
  /// (the greatest `p.cull`): clear only if every ray's slab test (`rays`) misses it.
  [[nodiscard]] static unsigned beam4(const WideNode<T>& node, const RayPacket<T>& p, T cull_max) noexcept {
    unsigned mask = 0;
    for (int lane = 0; lane < 4; ++lane) {
      T tn = 0, tf = cull_max;
      for (int a = 0; a < 3; ++a) {
        const T bn = node.bounds[p.near[a]][lane], bf = node.bounds[p.far[a]][lane];
        const T n = std::min(bn * p.inv_lo[a], bn * p.inv_hi[a]) + p.off_lo[a];
        const T f = (std::max(bf * p.inv_lo[a], bf * p.inv_hi[a]) + p.off_hi[a]) * kBoxWiden<T>;
        tn = std::max(tn, n);
        tf = std::min(tf, f);
      }
      if (tn <= tf && tn < cull_max) mask |= 1U << lane;
    }
    return mask;
  }

  /// The rays whose `cull` exceeds `t` (bit r for ray r).
  [[nodiscard]] static std::uint32_t beyond(const RayPacket<T>& p, T t) noexcept {
    std::uint32_t mask = 0;
    for (int r = 0; r < kPacketRays; ++r)
      if (t < p.cull[r]) mask |= 1U << r;
    return mask;
  }

  /// The rays of `active` whose slab test enters child `lane` of `node` (at a parameter below
  /// their `cull`), as a bit mask; `t_min` gets the least entry parameter among them.
  [[nodiscard]] static std::uint32_t rays(const WideNode<T>& node, int lane, const RayPacket<T>& p,
                                          std::uint32_t active, T& t_min) noexcept {
    T bn[3], bf[3];
    for (int a = 0; a < 3; ++a) {
      bn[a] = node.bounds[p.near[a]][lane];
      bf[a] = node.bounds[p.far[a]][lane];
    }
    std::uint32_t mask = 0;
    t_min = std::numeric_limits<T>::infinity();
    for (; active != 0; active &= active - 1) {
      const int r = std::countr_zero(active);
      T n[3], f[3];
      for (int a = 0; a < 3; ++a) {
        n[a] = bn[a] * p.inv[a][r] + p.offset[a][r];
        f[a] = (bf[a] * p.inv[a][r] + p.offset[a][r]) * kBoxWiden<T>;
      }
      const T tn = std::max(std::max(n[0], n[1]), std::max(n[2], T(0)));
      const T tf = std::min(std::min(f[0], f[1]), std::min(f[2], p.cull[r]));
      if (tn <= tf && tn < p.cull[r]) {
        mask |= 1U << r;
        t_min = std::min(t_min, tn);
      }
    }
    return mask;
  }
};

/// Leaf `first` (bvh/traverse.hpp's `intersect_leaf`) for each ray of `rays` with `LeafKernels`,
/// one ray after another; updates `hits` and `p.cull`.
template <class LeafKernels, std::floating_point T>
void packet_leaf_per_ray(const BvhTree<T>& tree, std::uint32_t first, RayPacket<T>& p, std::uint32_t rays,
                         Hit<T>* hits) noexcept {
  for (; rays != 0; rays &= rays - 1) {
    const int r = std::countr_zero(rays);
    intersect_leaf<LeafKernels>(tree, first, p.shear[r], hits[r]);
    p.best[r] = hits[r].t;
    p.cull[r] = cull_bound(hits[r].t);
  }
}

/// Starts loading child `ref` of a wide node (its `WideNode`, or the first two blocks of its
/// leaf) into L1, so that the walk need not wait for it when it gets there.
template <std::floating_point T>
MPR_ALWAYS_INLINE void prefetch_child(const BvhTree<T>& tree, std::uint32_t ref) noexcept {
  if (ref & kLeafRef) {
    const TriBlock<T>* b = tree.blocks.data() + (ref & ~kLeafRef);
    for (std::size_t at = 0; at < 2 * sizeof(TriBlock<T>); at += 64) mpr::detail::prefetch_l1(b, at);
  } else {
    const WideNode<T>* w = tree.wide.data() + ref;
    for (std::size_t at = 0; at < sizeof(WideNode<T>); at += 64) mpr::detail::prefetch_l1(w, at);
  }
}

/// The packet walk: depth first through the 4-wide tree with the rays of `p.active`, children
/// in order of their least entry parameter, each child with the rays that enter it; leaves with
/// `PacketKernels::leaf` when it has one, else `intersect_leaf` per ray (`LeafKernels`,
/// bvh/kernels/walk_kernels.hpp). `hits[r]` holds ray r's
/// closest hit so far (in: t_max and no triangle) and gets its closest hit.
template <class PacketKernels, class LeafKernels, std::floating_point T>
MPR_ALWAYS_INLINE void packet_walk(const BvhTree<T>& tree, RayPacket<T>& p, Hit<T>* hits) noexcept {
  if (p.active == 0 || (tree.wide.empty() && tree.blocks.empty())) return;
  const auto leaf = [&](std::uint32_t first, std::uint32_t rays) noexcept {
    if constexpr (requires { PacketKernels::leaf(tree, first, p, rays, hits); })
      PacketKernels::leaf(tree, first, p, rays, hits);
    else
      packet_leaf_per_ray<LeafKernels>(tree, first, p, rays, hits);
  };
  if (tree.root & kLeafRef) {
    leaf(tree.root & ~kLeafRef, p.active);
    return;
  }
  struct Entry {
    std::uint32_t ref, rays;
    T t;
  };
  // Each level pushes at most three entries; kMaxWideDepth bounds the levels (checked at build).
  Entry stack[3 * kMaxWideDepth + 1];
  int top = 0;
  std::uint32_t current = tree.root, rays = p.active;
  T cull_max = p.max_cull();
  for (;;) {
    if (current & kLeafRef) {
      leaf(current & ~kLeafRef, rays);
      cull_max = p.max_cull();
    } else {
      const WideNode<T>& node = tree.wide[current];
      std::uint32_t ref[4], sub[4];
      typename PacketKernels::Least least[4];
      int n = 0;
      for (unsigned beam = PacketKernels::beam4(node, p, cull_max); beam != 0; beam &= beam - 1) {
        const int lane = std::countr_zero(beam);
        const std::uint32_t m = PacketKernels::rays(node, lane, p, rays, least[n]);
        if (m == 0) continue;
        prefetch_child(tree, node.child[lane]);
        ref[n] = node.child[lane];
        sub[n++] = m;
      }
      if (n == 1) {
        current = ref[0];
        rays = sub[0];
        continue;
      }
      if (n > 1) {
        // Nearest first (ties: lower lane first); only now are the entry parameters needed.
        T t[4];
        for (int k = 0; k < n; ++k) t[k] = PacketKernels::least_value(least[k]);
        for (int i = 1; i < n; ++i) {
          const T ti = t[i];
          const std::uint32_t ri = ref[i], si = sub[i];
          int k = i;
          for (; k > 0 && t[k - 1] > ti; --k) {
            t[k] = t[k - 1];
            ref[k] = ref[k - 1];
            sub[k] = sub[k - 1];
          }
          t[k] = ti;
          ref[k] = ri;
          sub[k] = si;
        }
        for (int k = n - 1; k > 0; --k) stack[top++] = {ref[k], sub[k], t[k]};
        current = ref[0];
        rays = sub[0];
        continue;
      }
    }
    // Pop the next subtree that some ray may still find a closer hit in, with those rays only:
    // a ray whose cull bound is not beyond the subtree's least entry parameter (hence its own)
    // skips it, as the single-ray walk would.
    bool found = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (!(e.t < cull_max)) continue;
      const std::uint32_t alive = e.rays & PacketKernels::beyond(p, e.t);
      if (alive != 0) {
        current = e.ref;
        rays = alive;
        found = true;
        break;
      }
    }
    if (!found) break;
  }
}

/// `hits[r]` = the closest hit of `rays[r]` in (0, t_max) through `tree` for each r (at most
/// `kPacketRays` rays, equal lengths), with the given kernels: as one packet when the rays
/// allow it (`RayPacket::make`), else one `closest_hit_walk` per ray. The same hits either way.
template <class PacketKernels, class LeafKernels, std::floating_point T>
void packet_closest_hits_with(const BvhTree<T>& tree, std::span<const Ray<T>> rays, std::span<Hit<T>> hits,
                              T t_max) noexcept {
  for (Hit<T>& h : hits) h = Hit<T>{t_max};
  RayPacket<T> p;
  if (RayPacket<T>::make(rays, hits.data(), p)) {
    packet_walk<PacketKernels, LeafKernels>(tree, p, hits.data());
  } else {
    for (std::size_t r = 0; r < rays.size(); ++r) hits[r] = closest_hit_walk<LeafKernels>(tree, rays[r], t_max);
  }
}

MPR_EXACT_FP_END

} // namespace mpr::scene::detail
