#pragma once
/// \file
/// The data of `mpr::scene::Bvh`: the hit record, the binary SAH tree's nodes, and the 4-wide
/// tree the queries walk (nodes of four child boxes, leaves as blocks of four triangles), all in
/// one `BvhTree`. Builders fill it (bvh/build.hpp); the traversal only reads it
/// (bvh/traverse.hpp).

#include <array>
#include <concepts>
#include <cstdint>
#include <limits>
#include <vector>

namespace mpr::scene {

/// The closest hit of a ray: parameter `t` (in units of the ray's direction, which need not be
/// unit length), barycentric weights `b1`, `b2` of the triangle's p[1] and p[2], and the
/// triangle's index in `Scene::triangles()`.
template <std::floating_point T>
struct Hit {
  T t = std::numeric_limits<T>::infinity();
  T b1 = 0;
  T b2 = 0;
  std::uint32_t triangle = std::numeric_limits<std::uint32_t>::max();
  [[nodiscard]] bool valid() const noexcept { return triangle != std::numeric_limits<std::uint32_t>::max(); }
};

/// A node of the binary SAH tree (`Bvh::nodes()`), depth-first: an interior node's first child
/// follows it.
template <std::floating_point T>
struct BvhNode {
  /// The box: lo x, y, z, then hi x, y, z (world units).
  std::array<T, 6> bounds;
  /// Leaf: first triangle in the build order; interior: index of the second child.
  std::uint32_t index;
  /// Leaf: number of triangles (> 0); interior: 0.
  std::uint16_t count;
  /// Interior: the split axis (children ordered along it).
  std::uint16_t axis;
};

namespace detail {

/// A child reference of the 4-wide tree with this bit set is a leaf: the low bits index its
/// first `TriBlock`. Without it, the reference indexes a `WideNode`.
inline constexpr std::uint32_t kLeafRef = 0x8000'0000U;
/// Deepest 4-wide tree the traversal stack holds (3 entries per level). The binary build splits
/// by SAH down to depth 60 and by the median below, so it is never deeper than 60 + 32 levels,
/// and collapsing only makes it shallower.
inline constexpr int kMaxWideDepth = 96;

/// A node of the 4-wide tree: the boxes of its (up to) four children, one SIMD lane each.
/// `bounds` rows are lo x, y, z, then hi x, y, z; an unused lane has lo = +inf, hi = -inf, which
/// no ray enters.
template <std::floating_point T>
struct alignas(64) WideNode {
  T bounds[6][4];
  /// A `WideNode` index, or `kLeafRef | first block` for a leaf; 0 in unused lanes.
  std::uint32_t child[4];
};

/// Up to four triangles of one leaf, structure-of-arrays: `p[vertex][axis][lane]`, world units.
/// A leaf is a run of blocks in `Bvh::triangle_blocks()`; its last block has `last` set.
template <std::floating_point T>
struct alignas(16) TriBlock {
  T p[3][3][4];
  /// Triangle index in `Scene::triangles()`, per lane.
  std::uint32_t index[4];
  /// Lanes in use, 1-4 (the first `count`); unused lanes hold zeros.
  std::uint32_t count;
  /// Non-zero in the last block of a leaf.
  std::uint32_t last;
};

} // namespace detail

/// Everything a built BVH holds. Empty vectors (and `triangle_count` 0) for an empty scene.
template <std::floating_point T>
struct BvhTree {
  /// The binary SAH tree, root first.
  std::vector<BvhNode<T>> nodes;
  /// The 4-wide collapse of `nodes` that queries walk.
  std::vector<detail::WideNode<T>> wide;
  /// The leaf triangles of the 4-wide tree, in leaf order, four per block.
  std::vector<detail::TriBlock<T>> blocks;
  /// The wide root: a `WideNode` index, or `kLeafRef | block` when the whole tree is one leaf.
  std::uint32_t root = 0;
  std::uint32_t triangle_count = 0;
  /// Levels of the binary tree (1 for a single leaf, 0 when empty).
  int depth = 0;
};

} // namespace mpr::scene
