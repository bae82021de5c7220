#pragma once
/// \file
/// `mpr::scene::Bvh`: a bounding volume hierarchy over a scene's triangles, built with the binned
/// surface area heuristic (Wald, "On fast construction of SAH-based bounding volume
/// hierarchies", IRT 2007), and closest-hit ray queries with the watertight ray/triangle test of
/// Woop, Benthin and Wald ("Watertight Ray/Triangle Intersection", JCGT 2(1), 2013): a ray that
/// crosses a shared edge or vertex hits at least one of the triangles (no cracks), and the
/// closest-hit query reports exactly one of them (no double hits). Queries walk a 4-wide collapse
/// of the binary tree with SSE box and triangle-edge tests (float, x86-64), bit-identical to the
/// portable kernels.

#include <mpr/core/config.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/scene/scene.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

#if MPR_BVH_SSE
#include <emmintrin.h>
#endif

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

/// Per-ray slab set-up: t = p * inv + offset for each axis; `near`, `far` are the rows of
/// `WideNode::bounds` holding each axis' near and far plane (they follow the direction's sign).
/// Direction components smaller than 1e-30 in magnitude are replaced by +-1e-30 so that `inv`
/// is finite.
template <std::floating_point T>
struct BoxRay {
  std::array<T, 3> inv, offset;
  std::array<int, 3> near, far;
  [[nodiscard]] static BoxRay make(const Ray<T>& ray) noexcept {
    BoxRay r;
    for (int a = 0; a < 3; ++a) {
      const T d = ray.direction[a];
      const T da = std::abs(d) < T(1e-30) ? std::copysign(T(1e-30), d) : d;
      r.inv[a] = T(1) / da;
      r.offset[a] = -ray.origin[a] * r.inv[a];
      r.near[a] = r.inv[a] < 0 ? a + 3 : a;
      r.far[a] = r.inv[a] < 0 ? a : a + 3;
    }
    return r;
  }
};

/// Factor that widens a box's exit parameter so that rounding never culls a box the ray
/// crosses (Ize, "Robust BVH ray traversal", JCGT 2(2), 2013): 1 + 2 gamma(3).
template <std::floating_point T>
inline constexpr T kBoxWiden = [] {
  constexpr T eps = std::numeric_limits<T>::epsilon() / 2;
  return T(1) + 2 * (3 * eps / (1 - 3 * eps));
}();

/// The four child boxes of `node` against the ray: bit `lane` of the result is set when the ray
/// enters that box at a parameter in [0, t_max) (and leaves it no earlier); `t_near[lane]` is
/// then the entry parameter. Other lanes of `t_near` are unspecified. Portable reference.
template <std::floating_point T>
[[nodiscard]] unsigned box4_portable(const WideNode<T>& node, const BoxRay<T>& r, T t_max, T* t_near) noexcept {
  unsigned mask = 0;
  for (int lane = 0; lane < 4; ++lane) {
    T n[3], f[3];
    for (int a = 0; a < 3; ++a) {
      n[a] = node.bounds[r.near[a]][lane] * r.inv[a] + r.offset[a];
      f[a] = (node.bounds[r.far[a]][lane] * r.inv[a] + r.offset[a]) * kBoxWiden<T>;
    }
    const T tn = std::max(std::max(n[0], n[1]), std::max(n[2], T(0)));
    const T tf = std::min(std::min(f[0], f[1]), std::min(f[2], t_max));
    t_near[lane] = tn;
    if (tn <= tf && tn < t_max) mask |= 1U << lane;
  }
  return mask;
}

/// The edge functions of one triangle in the ray's sheared frame (Woop et al. fig. 2): vertices
/// relative to the origin (A, B, C; z unsheared) and U, V, W.
template <std::floating_point T>
struct Edges {
  T Ax, Ay, Bx, By, Cx, Cy, az, bz, cz, U, V, W;
};

/// `Edges` of lane `lane` of `block`; (kx, ky, kz) the axis permutation, (sx, sy) the shear and
/// (ox, oy, oz) the permuted origin.
template <std::floating_point T>
[[nodiscard]] Edges<T> edges_portable(const TriBlock<T>& block, std::uint32_t lane, int kx, int ky, int kz, T sx, T sy,
                                      T ox, T oy, T oz) noexcept {
  Edges<T> e;
  const T ax = block.p[0][kx][lane] - ox, ay = block.p[0][ky][lane] - oy;
  const T bx = block.p[1][kx][lane] - ox, by = block.p[1][ky][lane] - oy;
  const T cx = block.p[2][kx][lane] - ox, cy = block.p[2][ky][lane] - oy;
  e.az = block.p[0][kz][lane] - oz;
  e.bz = block.p[1][kz][lane] - oz;
  e.cz = block.p[2][kz][lane] - oz;
  e.Ax = ax - sx * e.az;
  e.Ay = ay - sy * e.az;
  e.Bx = bx - sx * e.bz;
  e.By = by - sy * e.bz;
  e.Cx = cx - sx * e.cz;
  e.Cy = cy - sy * e.cz;
  e.U = e.Cx * e.By - e.Cy * e.Bx;
  e.V = e.Ax * e.Cy - e.Ay * e.Cx;
  e.W = e.Bx * e.Ay - e.By * e.Ax;
  return e;
}

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
#endif

} // namespace detail

/// Build settings.
struct BvhConfig {
  /// SAH bins per axis.
  int bins = 16;
  /// Largest leaf; nodes with more triangles are always split.
  int max_leaf = 4;
  /// Relative cost of a box test against a triangle test in the SAH.
  float traversal_cost = 1.0f;
};

template <std::floating_point T>
class Bvh {
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

  /// The binary SAH tree (built first; `closest_hit` walks its 4-wide collapse, `wide_nodes()`).
  [[nodiscard]] const std::vector<Node>& nodes() const noexcept { return nodes_; }
  [[nodiscard]] std::size_t triangle_count() const noexcept { return order_.size(); }
  [[nodiscard]] int depth() const noexcept { return depth_; }

  /// The closest triangle hit by `ray` with t in (0, t_max). Never throws; a ray with a NaN or
  /// zero direction hits nothing. Traverses the 4-wide tree (`wide_nodes()`), four child boxes
  /// and up to four leaf triangles per step (SSE for float on x86-64); the result is the one the
  /// per-triangle test gives in leaf order, whatever the instruction set.
  [[nodiscard]] Hit<T> closest_hit(const Ray<T>& ray, T t_max = std::numeric_limits<T>::infinity()) const noexcept {
#if MPR_BVH_SSE
    if constexpr (std::is_same_v<T, float>) return closest_hit_impl<true>(ray, t_max);
#endif
    return closest_hit_impl<false>(ray, t_max);
  }

  /// `hits[i] = closest_hit(rays[i], t_max)` for every i (the same walk per ray, so the same
  /// hits bit for bit). Precondition: equal lengths. (Walking two or four rays in turn, one
  /// node each, to overlap their dependent chains of node fetch and box test measured 10-25%
  /// slower on the classroom than one ray after the other, so this is a plain loop.)
  void closest_hits(std::span<const Ray<T>> rays, std::span<Hit<T>> hits,
                    T t_max = std::numeric_limits<T>::infinity()) const noexcept {
    for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = closest_hit(rays[i], t_max);
  }

  /// The same query through the portable (scalar) kernels only: the reference the SIMD kernels
  /// must match (tests), and what non-x86 builds always use.
  [[nodiscard]] Hit<T> closest_hit_portable(const Ray<T>& ray,
                                            T t_max = std::numeric_limits<T>::infinity()) const noexcept {
    return closest_hit_impl<false>(ray, t_max);
  }

  /// The 4-wide tree traversed by `closest_hit`, collapsed from the binary SAH tree `nodes()`.
  [[nodiscard]] const std::vector<detail::WideNode<T>>& wide_nodes() const noexcept { return wide_; }
  /// The leaf triangles of the 4-wide tree, in leaf order, four per block.
  [[nodiscard]] const std::vector<detail::TriBlock<T>>& triangle_blocks() const noexcept { return blocks_; }

private:
  /// Per-ray set-up of the watertight test (Woop et al. section 3): the axis permutation and
  /// shear, and the origin in the permuted frame.
  struct Shear {
    int kx, ky, kz;
    T sx, sy, sz;
    T ox, oy, oz;
  };

  template <bool Simd>
  Hit<T> closest_hit_impl(const Ray<T>& ray, T t_max) const noexcept {
    Hit<T> hit;
    hit.t = t_max;
    if (wide_.empty() && blocks_.empty()) return hit;
    const T* d = ray.direction.data();
    const T* o = ray.origin.data();
    Shear sh;
    // Woop et al.: the dimension where |d| is largest becomes z; swap x, y to keep the winding.
    {
      const T ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
      sh.kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    }
    if (!(std::abs(d[sh.kz]) > 0)) return hit; // zero or NaN direction
    sh.kx = sh.kz + 1 == 3 ? 0 : sh.kz + 1;
    sh.ky = sh.kx + 1 == 3 ? 0 : sh.kx + 1;
    if (d[sh.kz] < 0) std::swap(sh.kx, sh.ky);
    sh.sx = d[sh.kx] / d[sh.kz];
    sh.sy = d[sh.ky] / d[sh.kz];
    sh.sz = T(1) / d[sh.kz];
    sh.ox = o[sh.kx];
    sh.oy = o[sh.ky];
    sh.oz = o[sh.kz];
    const detail::BoxRay<T> r0 = detail::BoxRay<T>::make(ray);
    const auto r = [&] {
#if MPR_BVH_SSE
      if constexpr (Simd)
        return detail::BoxRaySse(r0);
      else
#endif
        return r0;
    }();

    // A single-leaf tree has no box to test (its root is the leaf).
    if (root_ & detail::kLeafRef) {
      intersect_leaf<Simd>(root_ & ~detail::kLeafRef, sh, hit);
      return hit;
    }
    struct Entry {
      std::uint32_t ref;
      T t;
    };
    // Each level pushes at most three entries; kMaxWideDepth bounds the levels (checked at build).
    Entry stack[3 * detail::kMaxWideDepth + 1];
    int top = 0;
    std::uint32_t current = root_;
    for (;;) {
      if (current & detail::kLeafRef) {
        intersect_leaf<Simd>(current & ~detail::kLeafRef, sh, hit);
      } else {
        const detail::WideNode<T>& node = wide_[current];
        alignas(16) T t_near[4];
        unsigned mask;
#if MPR_BVH_SSE
        if constexpr (Simd)
          mask = detail::box4_sse(node, r, hit.t, t_near);
        else
#endif
          mask = detail::box4_portable(node, r, hit.t, t_near);
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
        if (e.t < hit.t) {
          current = e.ref;
          found = true;
          break;
        }
      }
      if (!found) break;
    }
    return hit;
  }

  /// Tests the triangles of the leaf whose blocks start at `first`, in leaf order.
  template <bool Simd>
  void intersect_leaf(std::uint32_t first, const Shear& sh, Hit<T>& hit) const noexcept {
    for (std::uint32_t b = first;; ++b) {
      const detail::TriBlock<T>& block = blocks_[b];
#if MPR_BVH_SSE
      if constexpr (Simd) {
        // 4-wide edge functions; only the lanes that may hit (or need the exact fallback) go
        // on to the scalar part below, in lane order, with these very values.
        detail::EdgeValues4 e;
        unsigned candidates = detail::edges4_sse(block, sh.kx, sh.ky, sh.kz, sh.sx, sh.sy, sh.ox, sh.oy, sh.oz, e);
        while (candidates != 0) {
          const int lane = std::countr_zero(candidates);
          candidates &= candidates - 1;
          finish(e.lane(lane), sh.sz, block.index[lane], hit);
        }
      } else
#endif
      {
        for (std::uint32_t lane = 0; lane < block.count; ++lane)
          finish(detail::edges_portable(block, lane, sh.kx, sh.ky, sh.kz, sh.sx, sh.sy, sh.ox, sh.oy, sh.oz), sh.sz,
                 block.index[lane], hit);
      }
      if (block.last) return;
    }
  }

  /// Woop, Benthin & Wald 2013, fig. 2 and 3, from the edge functions on: the double-precision
  /// fallback for edge hits, the sign test, and the hit distance compared with `hit.t` without a
  /// division.
  static void finish(const detail::Edges<T>& e, T sz, std::uint32_t triangle, Hit<T>& hit) noexcept {
    T U = e.U, V = e.V, W = e.W;
    if (U == 0 || V == 0 || W == 0) {
      using W_t = std::conditional_t<std::is_same_v<T, float>, double, long double>;
      U = static_cast<T>(static_cast<W_t>(e.Cx) * e.By - static_cast<W_t>(e.Cy) * e.Bx);
      V = static_cast<T>(static_cast<W_t>(e.Ax) * e.Cy - static_cast<W_t>(e.Ay) * e.Cx);
      W = static_cast<T>(static_cast<W_t>(e.Bx) * e.Ay - static_cast<W_t>(e.By) * e.Ax);
    }
    if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return;
    const T det = U + V + W;
    if (det == 0) return;
    const T t_scaled = U * (sz * e.az) + V * (sz * e.bz) + W * (sz * e.cz);
    // t = t_scaled / det must lie in (0, hit.t); compare without dividing.
    if (det > 0 ? (t_scaled <= 0 || t_scaled >= hit.t * det) : (t_scaled >= 0 || t_scaled <= hit.t * det)) return;
    const T rcp = T(1) / det;
    const T t = t_scaled * rcp;
    if (!(t < hit.t)) return;
    hit.t = t;
    hit.b1 = V * rcp;
    hit.b2 = W * rcp;
    hit.triangle = triangle;
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
    // Leaf references keep one bit for the leaf flag.
    if (n >= detail::kLeafRef) throw std::length_error("mpr::scene::Bvh: too many triangles");
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
    blocks_.reserve(n);
    wide_.reserve(nodes_.size() / 2 + 1);
    root_ = collapse(0, 1, tris);
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

  /// The 4-wide node (or leaf reference) for the subtree of binary node `i`, at depth `depth`
  /// of the wide tree. Each wide node takes the two children of a binary node, then keeps
  /// opening its interior child of largest surface area until it has four (the usual collapse:
  /// the children most likely to be entered are the ones worth testing together).
  std::uint32_t collapse(std::uint32_t i, int depth, const std::vector<Triangle<T>>& tris) {
    const Node& binary = nodes_[i];
    if (binary.count > 0) return detail::kLeafRef | emit_leaf(binary.index, binary.count, tris);
    if (depth > detail::kMaxWideDepth) throw std::length_error("mpr::scene::Bvh: tree too deep");
    const std::uint32_t self = static_cast<std::uint32_t>(wide_.size());
    wide_.emplace_back();
    std::uint32_t kids[4] = {i + 1, binary.index, 0, 0};
    int n = 2;
    while (n < 4) {
      int open = -1;
      T largest = -1;
      for (int k = 0; k < n; ++k) {
        const Node& c = nodes_[kids[k]];
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
      // Replace the child by its two children, in place (keeps the children in split order).
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

  /// Appends the triangles order_[first, first + count) as blocks of four; returns the first.
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

  BvhConfig config_{};
  std::vector<Node> nodes_;
  std::vector<detail::WideNode<T>> wide_;
  std::vector<detail::TriBlock<T>> blocks_;
  /// The wide root: a `WideNode` index, or `kLeafRef | block` when the whole tree is one leaf.
  std::uint32_t root_ = 0;
  std::vector<std::uint32_t> order_;
  std::vector<Bounds> boxes_;
  std::vector<std::array<T, 3>> centroids_;
  int depth_ = 0;
};

} // namespace mpr::scene
