#pragma once
/// \file
/// The closest-hit walk of a `BvhTree`: depth first through the 4-wide tree, nearest child
/// first, four child boxes (bvh/slab.hpp) and up to four leaf triangles (bvh/watertight.hpp)
/// per step, with the x86 kernels of bvh/kernels/walk_kernels.hpp or the portable ones; both give the
/// same hit bit for bit.

#include <mpr/core/config.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/scene/bvh/kernels/walk_kernels.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/slab.hpp>
#include <mpr/scene/bvh/watertight.hpp>

#include <bit>
#include <concepts>
#include <cstdint>

namespace mpr::scene::detail {

MPR_EXACT_FP_BEGIN

/// Tests the triangles of the leaf whose blocks start at `first`, in leaf order: the edge
/// functions of a block at once, then the rest of the watertight test for each lane that may
/// hit (or needs the exact fallback), in lane order, with those very values.
template <class Kernels, std::floating_point T>
void intersect_leaf(const BvhTree<T>& tree, std::uint32_t first, const Shear<T>& sh, Hit<T>& hit) noexcept {
  for (std::uint32_t b = first;; ++b) {
    const TriBlock<T>& block = tree.blocks[b];
    typename Kernels::EdgeValues e;
    unsigned candidates = Kernels::edges4(block, sh, e);
    while (candidates != 0) {
      const int lane = std::countr_zero(candidates);
      candidates &= candidates - 1;
      watertight_finish(e.lane(lane), sh.sz, block.index[lane], hit);
    }
    if (block.last) return;
  }
}

/// The closest triangle of `tree` hit by `ray` with t in (0, t_max), with the box and edge
/// kernels of `Kernels` (bvh/kernels/walk_kernels.hpp); see `Bvh::closest_hit`.
template <class Kernels, std::floating_point T>
[[nodiscard]] Hit<T> closest_hit_walk(const BvhTree<T>& tree, const Ray<T>& ray, T t_max) noexcept {
  Hit<T> hit;
  hit.t = t_max;
  if (tree.wide.empty() && tree.blocks.empty()) return hit;
  Shear<T> sh;
  if (!Shear<T>::make(ray, sh)) return hit;
  const typename Kernels::BoxRayType r = Kernels::box_ray(BoxRay<T>::make(ray));

  // A single-leaf tree has no box to test (its root is the leaf).
  if (tree.root & kLeafRef) {
    intersect_leaf<Kernels>(tree, tree.root & ~kLeafRef, sh, hit);
    return hit;
  }
  struct Entry {
    std::uint32_t ref;
    T t;
  };
  // Each level pushes at most three entries; kMaxWideDepth bounds the levels (checked at build).
  Entry stack[3 * kMaxWideDepth + 1];
  int top = 0;
  std::uint32_t current = tree.root;
  for (;;) {
    if (current & kLeafRef) {
      intersect_leaf<Kernels>(tree, current & ~kLeafRef, sh, hit);
    } else {
      const WideNode<T>& node = tree.wide[current];
      alignas(16) T t_near[4];
      const unsigned mask = Kernels::box4(node, r, cull_bound(hit.t), t_near);
      if (mask != 0) {
        // Visit the nearest child next; push the others farthest first, so that they pop
        // nearest first (ties: lower lane first, for a result independent of the kernel).
        std::uint32_t ref[4];
        T t[4];
        int n = 0;
        for (int lane = 0; lane < 4; ++lane) {
          if (!(mask >> lane & 1U)) continue;
          int k = n++;
          for (; k > 0 && t[k - 1] > t_near[lane]; --k) {
            t[k] = t[k - 1];
            ref[k] = ref[k - 1];
          }
          t[k] = t_near[lane];
          ref[k] = node.child[lane];
        }
        for (int k = n - 1; k > 0; --k) stack[top++] = {ref[k], t[k]};
        current = ref[0];
        continue;
      }
    }
    // Pop the next subtree that can still hold a closer hit.
    bool found = false;
    while (top > 0) {
      const Entry e = stack[--top];
      if (e.t < cull_bound(hit.t)) {
        current = e.ref;
        found = true;
        break;
      }
    }
    if (!found) break;
  }
  return hit;
}

MPR_EXACT_FP_END

} // namespace mpr::scene::detail
