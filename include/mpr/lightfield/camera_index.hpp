#pragma once
/// \file
/// `mpr::CameraCentreIndex`: a ball tree over camera centres answering "which centre is nearest
/// to this line" and "which centres lie within r of this line" without a linear scan. Works for
/// any camera layout (planes, rings, spheres); used by `CameraFrameSampler`.

#include <mpr/core/vec.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>
#include <vector>

namespace mpr {

/// Squared distance from point `c` to the line through `origin` along `direction`, given
/// `inverse_length2 = 1 / |direction|^2`. The one formula used by the index and by brute force.
template <std::floating_point T>
[[nodiscard]] inline T line_distance2(const Vec3<T>& c, const Vec3<T>& origin, const Vec3<T>& direction,
                                      T inverse_length2) noexcept {
  const Vec3<T> offset = c - origin;
  const Vec3<T> cross = offset.cross(direction);
  return cross.squaredNorm() * inverse_length2;
}

/// Ball tree over a fixed set of points (camera centres). Queries are `const noexcept` and
/// allocation-free, so threads may share one index.
template <std::floating_point T>
class CameraCentreIndex {
public:
  CameraCentreIndex() = default;

  /// Builds the tree (median splits along the widest axis, leaves of at most 4 points).
  explicit CameraCentreIndex(std::span<const Vec3<T>> centres) : centres_(centres.begin(), centres.end()) {
    order_.resize(centres_.size());
    std::iota(order_.begin(), order_.end(), 0);
    if (!centres_.empty()) build(0, static_cast<int>(order_.size()));
  }

  [[nodiscard]] std::size_t size() const noexcept { return centres_.size(); }

  /// The index of the centre nearest to the line (origin, direction); among centres at exactly
  /// the same computed distance, the lowest index. -1 when empty or the direction is zero/NaN.
  [[nodiscard]] int nearest(const Vec3<T>& origin, const Vec3<T>& direction) const noexcept {
    const T dd = direction.squaredNorm();
    if (centres_.empty() || !(dd > 0) || !std::isfinite(dd)) return -1;
    const T inv = T(1) / dd;
    T best = std::numeric_limits<T>::infinity();
    int best_index = -1;
    int stack[kMaxDepth];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
      if (lower_bound2(node, origin, direction, inv) > best) continue;
      if (node.left < 0) {
        for (int k = node.begin; k < node.end; ++k) {
          const int i = order_[static_cast<std::size_t>(k)];
          const T d2 = line_distance2(centres_[static_cast<std::size_t>(i)], origin, direction, inv);
          if (d2 < best || (d2 == best && i < best_index)) {
            best = d2;
            best_index = i;
          }
        }
        continue;
      }
      // Visit the nearer child first (pushed last).
      const T dl = line_distance2(nodes_[static_cast<std::size_t>(node.left)].centre, origin, direction, inv);
      const T dr = line_distance2(nodes_[static_cast<std::size_t>(node.right)].centre, origin, direction, inv);
      if (dl <= dr) {
        stack[top++] = node.right;
        stack[top++] = node.left;
      } else {
        stack[top++] = node.left;
        stack[top++] = node.right;
      }
    }
    return best_index;
  }

  /// Calls `visit(index, distance)` for every centre at distance < `radius` from the line, in a
  /// fixed order (depth first) that depends only on the tree, never on the query.
  template <class Visit>
  void within(const Vec3<T>& origin, const Vec3<T>& direction, T radius, Visit&& visit) const noexcept {
    const T dd = direction.squaredNorm();
    if (centres_.empty() || !(dd > 0) || !std::isfinite(dd) || !(radius > 0)) return;
    const T inv = T(1) / dd;
    const T r2 = radius * radius;
    int stack[kMaxDepth];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
      if (lower_bound2(node, origin, direction, inv) >= r2) continue;
      if (node.left < 0) {
        for (int k = node.begin; k < node.end; ++k) {
          const int i = order_[static_cast<std::size_t>(k)];
          const T d2 = line_distance2(centres_[static_cast<std::size_t>(i)], origin, direction, inv);
          if (d2 < r2) visit(i, std::sqrt(d2));
        }
        continue;
      }
      stack[top++] = node.right;
      stack[top++] = node.left;
    }
  }

  /// The nearest centre by a linear scan (the reference the tree must reproduce).
  [[nodiscard]] int nearest_brute_force(const Vec3<T>& origin, const Vec3<T>& direction) const noexcept {
    const T dd = direction.squaredNorm();
    if (centres_.empty() || !(dd > 0) || !std::isfinite(dd)) return -1;
    const T inv = T(1) / dd;
    T best = std::numeric_limits<T>::infinity();
    int best_index = -1;
    for (std::size_t i = 0; i < centres_.size(); ++i) {
      const T d2 = line_distance2(centres_[i], origin, direction, inv);
      if (d2 < best) {
        best = d2;
        best_index = static_cast<int>(i);
      }
    }
    return best_index;
  }

private:
  // Depth of a median-split tree over at most 2^40 points, times two for the pending siblings.
  static constexpr int kMaxDepth = 96;
  static constexpr int kLeafSize = 4;

  struct Node {
    Vec3<T> centre = Vec3<T>::Zero();
    T radius = 0; // inflated slightly so that rounding never prunes a true candidate
    int begin = 0, end = 0;
    int left = -1, right = -1;
  };

  // A lower bound on the squared distance from the line to any point of the node's ball.
  [[nodiscard]] T lower_bound2(const Node& node, const Vec3<T>& origin, const Vec3<T>& direction,
                               T inv) const noexcept {
    const T d = std::sqrt(line_distance2(node.centre, origin, direction, inv)) - node.radius;
    return d > 0 ? d * d : T(0);
  }

  int build(int begin, int end) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Vec3<T> lo = Vec3<T>::Constant(std::numeric_limits<T>::infinity()), hi = -lo, sum = Vec3<T>::Zero();
    for (int k = begin; k < end; ++k) {
      const Vec3<T>& c = centres_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])];
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
      sum += c;
    }
    const Vec3<T> centre = sum / static_cast<T>(end - begin);
    T radius = 0;
    for (int k = begin; k < end; ++k)
      radius =
          std::max(radius, (centres_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])] - centre).norm());
    radius = radius * T(1.0001) + T(1e-4) * (hi - lo).norm() + std::numeric_limits<T>::min();
    nodes_[static_cast<std::size_t>(index)].centre = centre;
    nodes_[static_cast<std::size_t>(index)].radius = radius;
    nodes_[static_cast<std::size_t>(index)].begin = begin;
    nodes_[static_cast<std::size_t>(index)].end = end;
    if (end - begin > kLeafSize) {
      int axis = 0;
      (hi - lo).maxCoeff(&axis);
      const int mid = (begin + end) / 2;
      std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int a, int b) {
        const T ca = centres_[static_cast<std::size_t>(a)][axis], cb = centres_[static_cast<std::size_t>(b)][axis];
        return ca < cb || (ca == cb && a < b);
      });
      const int left = build(begin, mid);
      const int right = build(mid, end);
      nodes_[static_cast<std::size_t>(index)].left = left;
      nodes_[static_cast<std::size_t>(index)].right = right;
    }
    return index;
  }

  std::vector<Vec3<T>> centres_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

} // namespace mpr
