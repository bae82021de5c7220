#pragma once
/// \file
/// `mpr::scene::Bvh`: a bounding volume hierarchy over a scene's triangles, built with the binned
/// surface area heuristic (Wald, "On fast construction of SAH-based bounding volume
/// hierarchies", IRT 2007), and closest-hit ray queries with the watertight ray/triangle test of
/// Woop, Benthin and Wald ("Watertight Ray/Triangle Intersection", JCGT 2(1), 2013): a ray that
/// crosses a shared edge or vertex hits at least one of the triangles (no cracks), and the
/// closest-hit query reports exactly one of them (no double hits).

#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/scene/scene.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

namespace mpr::scene {

/// The closest hit of a ray: parameter `t` (in units of the ray's direction, which need not be
/// unit length), barycentric weights `b1`, `b2` of the triangle's p[1] and p[2], and the
/// triangle's index in `Scene::triangles()`.
template <std::floating_point T> struct Hit {
  T t = std::numeric_limits<T>::infinity();
  T b1 = 0;
  T b2 = 0;
  std::uint32_t triangle = std::numeric_limits<std::uint32_t>::max();
  [[nodiscard]] bool valid() const noexcept { return triangle != std::numeric_limits<std::uint32_t>::max(); }
};

/// Build settings.
struct BvhConfig {
  /// SAH bins per axis.
  int bins = 16;
  /// Largest leaf; nodes with more triangles are always split.
  int max_leaf = 4;
  /// Relative cost of a box test against a triangle test in the SAH.
  float traversal_cost = 1.0f;
};

template <std::floating_point T> class Bvh {
public:
  using scalar_type = T;

  struct Node {
    /// The box: lo x, y, z, then hi x, y, z.
    std::array<T, 6> bounds;
    /// Leaf: first triangle in `order`; interior: index of the second child (the first is next).
    std::uint32_t index;
    /// Leaf: number of triangles (> 0); interior: 0.
    std::uint16_t count;
    /// Interior: the split axis (children ordered along it).
    std::uint16_t axis;
  };

  Bvh() = default;
  /// Builds over every triangle of `scene` (an empty scene gives an empty BVH that hits nothing).
  explicit Bvh(const Scene<T>& scene, const BvhConfig& config = {}) { build(scene, config); }

  [[nodiscard]] const std::vector<Node>& nodes() const noexcept { return nodes_; }
  [[nodiscard]] std::size_t triangle_count() const noexcept { return order_.size(); }
  [[nodiscard]] int depth() const noexcept { return depth_; }

  /// The closest triangle hit by `ray` with t in (0, t_max). Never throws; a ray with a NaN or
  /// zero direction hits nothing.
  [[nodiscard]] Hit<T> closest_hit(const Ray<T>& ray, T t_max = std::numeric_limits<T>::infinity()) const noexcept {
    Hit<T> hit;
    hit.t = t_max;
    if (nodes_.empty()) return hit;
    const T* d = ray.direction.data();
    const T* o = ray.origin.data();
    // Woop et al.: the dimension where |d| is largest becomes z; swap x, y to keep the winding.
    int kz = 0;
    {
      const T ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
      kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    }
    if (!(std::abs(d[kz]) > 0)) return hit; // zero or NaN direction
    int kx = kz + 1 == 3 ? 0 : kz + 1;
    int ky = kx + 1 == 3 ? 0 : kx + 1;
    if (d[kz] < 0) std::swap(kx, ky);
    const T sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = T(1) / d[kz];
    const T ox = o[kx], oy = o[ky], oz = o[kz]; // locals: hit updates cannot alias them

    // Per-ray slab set-up: t = p * inv - o * inv for each axis; the near plane of each axis
    // follows the sign of the direction.
    Ray3 r;
    for (int a = 0; a < 3; ++a) {
      const T da = std::abs(d[a]) < T(1e-30) ? std::copysign(T(1e-30), d[a]) : d[a];
      r.inv[a] = T(1) / da;
      r.offset[a] = -o[a] * r.inv[a];
      r.near[a] = r.inv[a] < 0 ? a + 3 : a;
      r.far[a] = r.inv[a] < 0 ? a : a + 3;
    }
    const auto enter = [&](const Node& node) noexcept { return box_entry(node, r, hit.t); };
    if (!(enter(nodes_[0]) < hit.t)) return hit;

    struct Entry {
      std::uint32_t node;
      T t;
    };
    Entry stack[128];
    int top = 0;
    std::uint32_t current = 0;
    for (;;) {
      const Node& node = nodes_[current];
      if (node.count > 0) {
        for (std::uint32_t i = node.index, end = node.index + node.count; i < end; ++i)
          intersect(i, ox, oy, oz, kx, ky, kz, sx, sy, sz, hit);
      } else {
        // Test both children; descend into the nearer, keep the farther for later.
        const std::uint32_t a = current + 1, b = node.index;
        const T ta = enter(nodes_[a]), tb = enter(nodes_[b]);
        const bool hit_a = ta < hit.t, hit_b = tb < hit.t;
        if (hit_a && hit_b) {
          if (ta <= tb) {
            stack[top++] = {b, tb};
            current = a;
          } else {
            stack[top++] = {a, ta};
            current = b;
          }
          continue;
        }
        if (hit_a || hit_b) {
          current = hit_a ? a : b;
          continue;
        }
      }
      // Pop the next subtree that can still hold a closer hit.
      bool found = false;
      while (top > 0) {
        const Entry e = stack[--top];
        if (e.t < hit.t) {
          current = e.node;
          found = true;
          break;
        }
      }
      if (!found) break;
    }
    return hit;
  }

private:
  struct Ray3 {
    std::array<T, 3> inv, offset;
    /// Index in `Node::bounds` of the near and far slab of each axis.
    std::array<int, 3> near, far;
  };

  /// The entry parameter of the ray into the node's box, or +inf when it misses the box or
  /// enters at or beyond `t_max`. Robust box test (Ize, "Robust BVH ray traversal", JCGT 2013):
  /// the exit parameter is widened by 1 + 2 gamma(3).
  static T box_entry(const Node& node, const Ray3& r, T t_max) noexcept {
    constexpr T eps = std::numeric_limits<T>::epsilon() / 2;
    constexpr T widen = T(1) + 2 * (3 * eps / (1 - 3 * eps));
    const T* b = node.bounds.data();
    const T n0 = b[r.near[0]] * r.inv[0] + r.offset[0], f0 = (b[r.far[0]] * r.inv[0] + r.offset[0]) * widen;
    const T n1 = b[r.near[1]] * r.inv[1] + r.offset[1], f1 = (b[r.far[1]] * r.inv[1] + r.offset[1]) * widen;
    const T n2 = b[r.near[2]] * r.inv[2] + r.offset[2], f2 = (b[r.far[2]] * r.inv[2] + r.offset[2]) * widen;
    const T t_near = std::max(std::max(n0, n1), std::max(n2, T(0)));
    const T t_far = std::min(std::min(f0, f1), std::min(f2, t_max));
    return t_near <= t_far ? t_near : std::numeric_limits<T>::infinity();
  }

  struct Packed {
    std::array<Vec3<T>, 3> p;
  };

  /// Woop, Benthin & Wald 2013, fig. 2 and 3 (with the double-precision fallback for edge hits).
  void intersect(std::uint32_t i, T ox, T oy, T oz, int kx, int ky, int kz, T sx, T sy, T sz,
                 Hit<T>& hit) const noexcept {
    const Packed& tri = packed_[i];
    const T ax = tri.p[0][kx] - ox, ay = tri.p[0][ky] - oy, az = tri.p[0][kz] - oz;
    const T bx = tri.p[1][kx] - ox, by = tri.p[1][ky] - oy, bz = tri.p[1][kz] - oz;
    const T cx = tri.p[2][kx] - ox, cy = tri.p[2][ky] - oy, cz = tri.p[2][kz] - oz;
    const T Ax = ax - sx * az, Ay = ay - sy * az;
    const T Bx = bx - sx * bz, By = by - sy * bz;
    const T Cx = cx - sx * cz, Cy = cy - sy * cz;
    T U = Cx * By - Cy * Bx;
    T V = Ax * Cy - Ay * Cx;
    T W = Bx * Ay - By * Ax;
    if (U == 0 || V == 0 || W == 0) {
      using W_t = std::conditional_t<std::is_same_v<T, float>, double, long double>;
      U = static_cast<T>(static_cast<W_t>(Cx) * By - static_cast<W_t>(Cy) * Bx);
      V = static_cast<T>(static_cast<W_t>(Ax) * Cy - static_cast<W_t>(Ay) * Cx);
      W = static_cast<T>(static_cast<W_t>(Bx) * Ay - static_cast<W_t>(By) * Ax);
    }
    if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return;
    const T det = U + V + W;
    if (det == 0) return;
    const T t_scaled = U * (sz * az) + V * (sz * bz) + W * (sz * cz);
    // t = t_scaled / det must lie in (0, hit.t); compare without dividing.
    if (det > 0 ? (t_scaled <= 0 || t_scaled >= hit.t * det) : (t_scaled >= 0 || t_scaled <= hit.t * det)) return;
    const T rcp = T(1) / det;
    const T t = t_scaled * rcp;
    if (!(t < hit.t)) return;
    hit.t = t;
    hit.b1 = V * rcp;
    hit.b2 = W * rcp;
    hit.triangle = index_[i];
  }

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

  static std::array<T, 6> pack(const Bounds& b) { return {b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]}; }

  void build(const Scene<T>& scene, const BvhConfig& config) {
    const auto& tris = scene.triangles();
    const std::size_t n = tris.size();
    if (n == 0) return;
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
    nodes_.reserve(2 * n);
    config_ = config;
    config_.bins = std::clamp(config.bins, 2, 64);
    config_.max_leaf = std::clamp(config.max_leaf, 1, 255);
    build_node(0, static_cast<std::uint32_t>(n), 1);
    packed_.resize(n);
    index_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      packed_[i].p = tris[order_[i]].p;
      index_[i] = order_[i];
    }
    boxes_.clear();
    boxes_.shrink_to_fit();
    centroids_.clear();
    centroids_.shrink_to_fit();
  }

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
      nodes_[self] = Node{pack(bounds), begin, static_cast<std::uint16_t>(count), 0};
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
        const T cost = acc.area() * static_cast<T>(c) + right_area[b] * static_cast<T>(right_count[b]);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_split = b;
        }
      }
    }
    const T leaf_cost = bounds.area() * static_cast<T>(count);
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
    nodes_[self] = Node{pack(bounds), second, 0, static_cast<std::uint16_t>(axis)};
    return self;
  }

  BvhConfig config_{};
  std::vector<Node> nodes_;
  std::vector<Packed> packed_;
  std::vector<std::uint32_t> index_;
  std::vector<std::uint32_t> order_;
  std::vector<Bounds> boxes_;
  std::vector<std::array<T, 3>> centroids_;
  int depth_ = 0;
};

} // namespace mpr::scene
