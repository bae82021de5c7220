#pragma once
/// \file
/// Building a `BvhTree`: a binary tree by the binned surface area heuristic (Wald, "On fast
/// construction of SAH-based bounding volume hierarchies", IRT 2007), then its collapse into
/// the 4-wide tree the walk uses, with leaves packed as blocks of four triangles. The builders
/// hold only build-time state; the result is plain data (bvh/node.hpp).

#include <mpr/core/error.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/scene.hpp>

#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <span>
#include <string>
#include <vector>

namespace mpr::scene {

/// Build settings. The SAH counts a leaf's cost in blocks of four triangles (`TriBlock`, tested
/// together), so that it fills the blocks instead of splitting off leaves of one or two.
struct BvhConfig {
  /// SAH bins per axis.
  int bins = 16;
  /// Largest leaf (two blocks by default); nodes with more triangles are always split.
  int max_leaf = 8;
  /// Relative cost of a node (its box test) against a block of four triangles in the SAH.
  float traversal_cost = 2.0f;
};

namespace detail {

/// The binned-SAH binary build over a list of triangle boxes: `build()` returns the nodes
/// (depth first, root at 0) and leaves `order` holding the triangle indices in leaf order.
template <std::floating_point T>
class BinnedSahBuilder {
public:
  struct Bounds {
    std::array<T, 3> lo{std::numeric_limits<T>::infinity(), std::numeric_limits<T>::infinity(),
                        std::numeric_limits<T>::infinity()};
    std::array<T, 3> hi{-std::numeric_limits<T>::infinity(), -std::numeric_limits<T>::infinity(),
                        -std::numeric_limits<T>::infinity()};
    void grow(const std::array<T, 3>& a, const std::array<T, 3>& b) {
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], a[k]);
        hi[k] = std::max(hi[k], b[k]);
      }
    }
    void grow(const Bounds& b) { grow(b.lo, b.hi); }
    void grow_point(const std::array<T, 3>& p) { grow(p, p); }
    [[nodiscard]] T area() const {
      const T dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
      if (!(dx >= 0)) return 0;
      return 2 * (dx * dy + dy * dz + dz * dx);
    }
  };

  /// The blocks of four triangles `count` triangles take: the SAH's cost of a leaf per unit area.
  static T blocks(std::uint32_t count) { return static_cast<T>((count + 3) / 4); }

  static std::array<T, 6> pack(const Bounds& b) { return {b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]}; }

  /// Prepares the build over `tris` (not empty, fewer than `kLeafRef` triangles).
  BinnedSahBuilder(const std::vector<Triangle<T>>& tris, const BvhConfig& config) {
    const std::size_t n = tris.size();
    boxes_.resize(n);
    centroids_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      Bounds b;
      for (const Vec3<T>& p : tris[i].p) b.grow_point({p.x(), p.y(), p.z()});
      boxes_[i] = b;
      for (int k = 0; k < 3; ++k) centroids_[i][k] = (b.lo[k] + b.hi[k]) / 2;
    }
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), std::uint32_t{0});
    config_ = config;
    config_.bins = std::clamp(config.bins, 2, 64);
    config_.max_leaf = std::clamp(config.max_leaf, 1, 255);
  }

  /// Builds the tree; `depth` receives its number of levels.
  [[nodiscard]] std::vector<BvhNode<T>> build(int& depth) {
    nodes_.reserve(2 * order_.size());
    build_node(0, static_cast<std::uint32_t>(order_.size()), 1);
    depth = depth_;
    return std::move(nodes_);
  }
  /// Triangle indices in leaf order (a leaf's `index` and `count` select a range).
  [[nodiscard]] const std::vector<std::uint32_t>& order() const noexcept { return order_; }

private:
  std::uint32_t build_node(std::uint32_t begin, std::uint32_t end, int depth) {
    depth_ = std::max(depth_, depth);
    const std::uint32_t self = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    Bounds bounds, cbounds;
    for (std::uint32_t i = begin; i < end; ++i) {
      bounds.grow(boxes_[order_[i]]);
      cbounds.grow_point(centroids_[order_[i]]);
    }
    const std::uint32_t count = end - begin;
    const auto make_leaf = [&] {
      nodes_[self] = BvhNode<T>{pack(bounds), begin, static_cast<std::uint16_t>(count), 0};
      return self;
    };
    if (count == 1) return make_leaf();

    // Binned SAH, every axis with a non-zero centroid extent.
    const int nb = config_.bins;
    T best_cost = std::numeric_limits<T>::infinity();
    int best_axis = -1, best_split = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const T extent = cbounds.hi[axis] - cbounds.lo[axis];
      if (!(extent > 0)) continue;
      Bounds bin_bounds[64];
      std::uint32_t bin_count[64] = {};
      const T scale = static_cast<T>(nb) / extent;
      for (std::uint32_t i = begin; i < end; ++i) {
        const std::uint32_t tri = order_[i];
        const int b = std::min(nb - 1, static_cast<int>((centroids_[tri][axis] - cbounds.lo[axis]) * scale));
        bin_bounds[b].grow(boxes_[tri]);
        ++bin_count[b];
      }
      T right_area[64];
      std::uint32_t right_count[64];
      Bounds acc;
      std::uint32_t c = 0;
      for (int b = nb - 1; b > 0; --b) {
        acc.grow(bin_bounds[b]);
        c += bin_count[b];
        right_area[b] = acc.area();
        right_count[b] = c;
      }
      acc = Bounds{};
      c = 0;
      for (int b = 1; b < nb; ++b) {
        acc.grow(bin_bounds[b - 1]);
        c += bin_count[b - 1];
        if (c == 0 || right_count[b] == 0) continue;
        const T cost = acc.area() * blocks(c) + right_area[b] * blocks(right_count[b]);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_split = b;
        }
      }
    }
    const T leaf_cost = bounds.area() * blocks(count);
    const T split_cost = static_cast<T>(config_.traversal_cost) * bounds.area() + best_cost;
    const bool must_split = count > static_cast<std::uint32_t>(config_.max_leaf);
    if (!must_split && (best_axis < 0 || split_cost >= leaf_cost)) return make_leaf();

    std::uint32_t mid = 0;
    int axis = best_axis;
    if (best_axis >= 0 && depth < 60) {
      const T scale = static_cast<T>(nb) / (cbounds.hi[axis] - cbounds.lo[axis]);
      const auto it = std::partition(order_.begin() + begin, order_.begin() + end, [&](std::uint32_t tri) {
        return std::min(nb - 1, static_cast<int>((centroids_[tri][axis] - cbounds.lo[axis]) * scale)) < best_split;
      });
      mid = static_cast<std::uint32_t>(it - order_.begin());
    }
    if (mid <= begin || mid >= end) {
      // No useful SAH split (equal centroids, or too deep): split at the median of the widest axis.
      axis = 0;
      for (int k = 1; k < 3; ++k)
        if (cbounds.hi[k] - cbounds.lo[k] > cbounds.hi[axis] - cbounds.lo[axis]) axis = k;
      mid = begin + count / 2;
      std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                       [&](std::uint32_t a, std::uint32_t b) { return centroids_[a][axis] < centroids_[b][axis]; });
    }
    build_node(begin, mid, depth + 1);
    const std::uint32_t second = build_node(mid, end, depth + 1);
    nodes_[self] = BvhNode<T>{pack(bounds), second, 0, static_cast<std::uint16_t>(axis)};
    return self;
  }

  BvhConfig config_{};
  std::vector<BvhNode<T>> nodes_;
  std::vector<std::uint32_t> order_;
  std::vector<Bounds> boxes_;
  std::vector<std::array<T, 3>> centroids_;
  int depth_ = 0;
};

/// The collapse of a binary tree into the 4-wide tree and its triangle blocks.
template <std::floating_point T>
class WideCollapser {
public:
  /// Writes into `wide` and `blocks` (emptied by the caller), reading `nodes` and `order` from
  /// the binary build of `tris`.
  WideCollapser(const std::vector<BvhNode<T>>& nodes, std::span<const std::uint32_t> order,
                const std::vector<Triangle<T>>& tris, std::vector<WideNode<T>>& wide, std::vector<TriBlock<T>>& blocks)
      : nodes_(nodes), order_(order), wide_(wide), blocks_(blocks) {
    blocks_.reserve(tris.size());
    wide_.reserve(nodes_.size() / 2 + 1);
  }

  /// The 4-wide node (or leaf reference) for the subtree of binary node `i`, at depth `depth`
  /// of the wide tree. Each wide node takes the two children of a binary node, then keeps
  /// opening its interior child of largest surface area until it has four (the usual collapse:
  /// the children most likely to be entered are the ones worth testing together).
  [[nodiscard]] std::uint32_t collapse(std::uint32_t i, int depth, const std::vector<Triangle<T>>& tris) {
    const BvhNode<T>& binary = nodes_[i];
    if (binary.count > 0) return detail::kLeafRef | emit_leaf(binary.index, binary.count, tris);
    if (depth > detail::kMaxWideDepth)
      throw error("mpr: BVH deeper than its traversal stack (" + std::to_string(detail::kMaxWideDepth) + " levels)");
    const std::uint32_t self = static_cast<std::uint32_t>(wide_.size());
    wide_.emplace_back();
    std::uint32_t kids[4] = {i + 1, binary.index, 0, 0};
    int n = 2;
    while (n < 4) {
      int open = -1;
      T largest = -1;
      for (int k = 0; k < n; ++k) {
        const BvhNode<T>& c = nodes_[kids[k]];
        if (c.count > 0) continue;
        const T* b = c.bounds.data();
        const T dx = b[3] - b[0], dy = b[4] - b[1], dz = b[5] - b[2];
        const T area = dx * dy + dy * dz + dz * dx;
        if (area > largest) {
          largest = area;
          open = k;
        }
      }
      if (open < 0) break;
      // Replace the child by its two children, in place (keeps the children in split order_).
      const std::uint32_t first = kids[open] + 1, second = nodes_[kids[open]].index;
      for (int k = n; k > open + 1; --k) kids[k] = kids[k - 1];
      kids[open] = first;
      kids[open + 1] = second;
      ++n;
    }
    detail::WideNode<T> node{};
    for (int a = 0; a < 3; ++a)
      for (int lane = 0; lane < 4; ++lane) {
        node.bounds[a][lane] = std::numeric_limits<T>::infinity();
        node.bounds[a + 3][lane] = -std::numeric_limits<T>::infinity();
      }
    for (int k = 0; k < n; ++k) {
      for (int row = 0; row < 6; ++row) node.bounds[row][k] = nodes_[kids[k]].bounds[static_cast<std::size_t>(row)];
      node.child[k] = collapse(kids[k], depth + 1, tris);
    }
    wide_[self] = node;
    return self;
  }

private:
  /// Appends the triangles order_[first, first + count) as blocks_ of four; returns the first.
  std::uint32_t emit_leaf(std::uint32_t first, std::uint32_t count, const std::vector<Triangle<T>>& tris) {
    const std::uint32_t start = static_cast<std::uint32_t>(blocks_.size());
    for (std::uint32_t j = 0; j < count; j += 4) {
      detail::TriBlock<T> block{};
      block.count = std::min<std::uint32_t>(4, count - j);
      block.last = j + 4 >= count ? 1 : 0;
      for (std::uint32_t lane = 0; lane < block.count; ++lane) {
        const std::uint32_t tri = order_[first + j + lane];
        block.index[lane] = tri;
        for (int v = 0; v < 3; ++v)
          for (int a = 0; a < 3; ++a) block.p[v][a][lane] = tris[tri].p[static_cast<std::size_t>(v)][a];
      }
      blocks_.push_back(block);
    }
    return start;
  }

  const std::vector<BvhNode<T>>& nodes_;
  std::span<const std::uint32_t> order_;
  std::vector<WideNode<T>>& wide_;
  std::vector<TriBlock<T>>& blocks_;
};

} // namespace detail

/// Builds the BVH of every triangle of `scene` (an empty scene gives an empty tree). Throws
/// `mpr::argument_error` (parameter "scene") when the scene has 2^31 triangles or more.
template <std::floating_point T>
[[nodiscard]] BvhTree<T> build_bvh(const Scene<T>& scene, const BvhConfig& config = {}) {
  BvhTree<T> tree;
  const auto& tris = scene.triangles();
  const std::size_t n = tris.size();
  if (n == 0) return tree;
  // Leaf references keep one bit for the leaf flag.
  if (n >= detail::kLeafRef)
    throw argument_error("scene", std::to_string(n) + " triangles; a BVH holds fewer than 2^31");
  detail::BinnedSahBuilder<T> sah(tris, config);
  tree.nodes = sah.build(tree.depth);
  detail::WideCollapser<T> wide(tree.nodes, sah.order(), tris, tree.wide, tree.blocks);
  tree.root = wide.collapse(0, 1, tris);
  tree.triangle_count = static_cast<std::uint32_t>(n);
  return tree;
}

} // namespace mpr::scene
