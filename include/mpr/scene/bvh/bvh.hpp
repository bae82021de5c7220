#pragma once
/// \file
/// `mpr::scene::Bvh`: a bounding volume hierarchy over a scene's triangles, built with the binned
/// surface area heuristic (bvh/build.hpp), answering closest-hit ray queries with the watertight
/// ray/triangle test (bvh/watertight.hpp) by walking a 4-wide collapse of the binary tree
/// (bvh/traverse.hpp) with SSE box and triangle-edge tests on x86-64 (bvh/kernels/walk_kernels.hpp),
/// bit-identical to the portable kernels; coherent rays also walk it 16 at a time as packets
/// (bvh/packet.hpp), with the same hits. Every header of the walk is compiled without
/// multiply-add contraction (`MPR_EXACT_FP_BEGIN`, core/config.hpp), so the hits do not depend on
/// the program's flags: the same under any `-march` and `-ffp-contract` with GCC, and with Clang
/// except under `-ffp-contract=fast` (which ignores the pragma; `fast-honor-pragmas` keeps it).

#include <mpr/core/config.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/scene/bvh/build.hpp>
#include <mpr/scene/bvh/kernels/walk_kernels.hpp>
#include <mpr/scene/bvh/kernels/packet_closest_hits.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/traverse.hpp>
#include <mpr/scene/scene.hpp>

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

namespace mpr::scene {

MPR_EXACT_FP_BEGIN

template <std::floating_point T>
class Bvh {
public:
  using scalar_type = T;
  using Node = BvhNode<T>;

  Bvh() = default;
  /// Builds over every triangle of `scene` (an empty scene gives an empty BVH that hits nothing).
  /// Throws `mpr::argument_error` (parameter "scene") for 2^31 triangles or more.
  explicit Bvh(const Scene<T>& scene, const BvhConfig& config = {}) : tree_(build_bvh(scene, config)) {}

  /// The binary SAH tree (built first; `closest_hit` walks its 4-wide collapse, `wide_nodes()`).
  [[nodiscard]] const std::vector<Node>& nodes() const noexcept { return tree_.nodes; }
  [[nodiscard]] std::size_t triangle_count() const noexcept { return tree_.triangle_count; }
  [[nodiscard]] int depth() const noexcept { return tree_.depth; }

  /// The closest triangle hit by `ray` with t in (0, t_max). Never throws; a ray with a NaN or
  /// zero direction hits nothing. Traverses the 4-wide tree (`wide_nodes()`), four child boxes
  /// and up to four leaf triangles per step (SSE for float on x86-64); the result is the one the
  /// per-triangle test gives in leaf order, whatever the instruction set.
  [[nodiscard]] Hit<T> closest_hit(const Ray<T>& ray, T t_max = std::numeric_limits<T>::infinity()) const noexcept {
    return detail::closest_hit_walk<detail::WalkKernels<T>>(tree_, ray, t_max);
  }

  /// `hits[i] = closest_hit(rays[i], t_max)` for every i (the same walk per ray, so the same
  /// hits bit for bit). Precondition: equal lengths. One ray after the other (docs/scene.md
  /// explains why walks are not interleaved).
  void closest_hits(std::span<const Ray<T>> rays, std::span<Hit<T>> hits,
                    T t_max = std::numeric_limits<T>::infinity()) const noexcept {
    for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = closest_hit(rays[i], t_max);
  }

  /// `hits[i] = closest_hit(rays[i], t_max)` for every i, bit for bit, for coherent rays: each
  /// run of `kPacketRays` (16) consecutive rays walks the tree as one packet, its beam tested
  /// against the boxes first (bvh/packet.hpp; AVX2 kernels when the CPU has them). Best when
  /// each run is a compact block of neighbouring rays (a 4 x 4 pixel block of a view); a run
  /// whose direction signs differ walks ray by ray. Precondition: equal lengths.
  void closest_hits_coherent(std::span<const Ray<T>> rays, std::span<Hit<T>> hits,
                             T t_max = std::numeric_limits<T>::infinity()) const noexcept {
    constexpr std::size_t k = detail::kPacketRays;
    for (std::size_t i = 0; i < rays.size(); i += k) {
      const std::size_t n = std::min(k, rays.size() - i);
      detail::packet_closest_hits(tree_, rays.subspan(i, n), hits.subspan(i, n), t_max);
    }
  }

  /// The same query through the portable (scalar) kernels only: the reference the SIMD kernels
  /// must match (tests), and what non-x86 builds always use.
  [[nodiscard]] Hit<T> closest_hit_portable(const Ray<T>& ray,
                                            T t_max = std::numeric_limits<T>::infinity()) const noexcept {
    return detail::closest_hit_walk<detail::PortableKernels<T>>(tree_, ray, t_max);
  }

  /// The 4-wide tree traversed by `closest_hit`, collapsed from the binary SAH tree `nodes()`.
  [[nodiscard]] const std::vector<detail::WideNode<T>>& wide_nodes() const noexcept { return tree_.wide; }
  /// The leaf triangles of the 4-wide tree, in leaf order, four per block.
  [[nodiscard]] const std::vector<detail::TriBlock<T>>& triangle_blocks() const noexcept { return tree_.blocks; }
  /// Everything built, as plain data.
  [[nodiscard]] const BvhTree<T>& tree() const noexcept { return tree_; }

private:
  BvhTree<T> tree_;
};

MPR_EXACT_FP_END

} // namespace mpr::scene
