#pragma once
/// \file
/// `mpr::SceneSampler<Scene, mpr::RayCast, Output>`: a ray sampler that answers each ray with the
/// first surface of a triangle scene it hits, found by a BVH ray cast (exact, per ray).
///
/// `Output` chooses what a hit returns, at compile time, and only that is computed:
/// - `mpr::ShadedColor` (default): the scene's shaded colour (`Scene::shade`), or the background;
/// - `mpr::HitDepth`: the ray parameter `t` of the hit as a `float` (+inf on a miss), no shading,
///   no texture lookup. With a GLC ray (direction scaled to unit normal component) `t` is the
///   depth in front of the image plane.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/scene/bvh/bvh.hpp>
#include <mpr/scene/scene.hpp>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>

namespace mpr {

/// Sampling policy tag: cast each ray into a BVH. Stateless (empty).
struct RayCast {};

/// Output tag: the shaded colour of the first hit.
struct ShadedColor {};
/// Output tag: the ray parameter of the first hit (float, +inf for a miss).
struct HitDepth {};

template <class SceneT, class Policy, class Output = ShadedColor>
class SceneSampler;

/// The ray-cast scene sampler. Copies share one immutable scene and BVH (a `shared_ptr`), so a
/// sampler is one pointer wide and cheap to copy into a `Renderer`.
template <std::floating_point T, class Output>
class SceneSampler<scene::Scene<T>, RayCast, Output> {
  static_assert(std::is_same_v<Output, ShadedColor> || std::is_same_v<Output, HitDepth>,
                "Output must be mpr::ShadedColor or mpr::HitDepth");

public:
  using scalar_type = T;
  using color_type = std::conditional_t<std::is_same_v<Output, HitDepth>, float, Color>;
  using scene_type = scene::Scene<T>;

  /// Takes the scene and builds its BVH (the only expensive step).
  explicit SceneSampler(scene::Scene<T> scene, const scene::BvhConfig& config = {})
      : SceneSampler(std::make_shared<const scene::Scene<T>>(std::move(scene)), config) {}
  /// Shares an existing scene. Throws `argument_error` for a null pointer.
  explicit SceneSampler(std::shared_ptr<const scene::Scene<T>> scene, const scene::BvhConfig& config = {}) {
    if (!scene) throw argument_error("scene", "null");
    state_ = std::make_shared<const State>(std::move(scene), config);
  }

  [[nodiscard]] const scene::Scene<T>& scene() const noexcept { return *state_->scene; }
  [[nodiscard]] const scene::Bvh<T>& bvh() const noexcept { return state_->bvh; }

  [[nodiscard]] color_type sample(const Ray<T>& ray) const noexcept {
    return answer(ray, state_->bvh.closest_hit(ray));
  }

  /// `out[i] = sample(rays[i])` for every i (`mpr::BatchRaySampler`): the same values, from
  /// `Bvh::closest_hits_coherent` on runs of 16 neighbouring rays and then shading, 64 rays at a
  /// time. Precondition: equal lengths.
  void sample_rays(std::span<const Ray<T>> rays, std::span<color_type> out) const noexcept {
    constexpr std::size_t kChunk = 64;
    scene::Hit<T> hits[kChunk];
    for (std::size_t i0 = 0; i0 < rays.size(); i0 += kChunk) {
      const std::size_t n = std::min(kChunk, rays.size() - i0);
      state_->bvh.closest_hits_coherent(rays.subspan(i0, n), std::span<scene::Hit<T>>(hits, n));
      for (std::size_t i = 0; i < n; ++i) out[i0 + i] = answer(rays[i0 + i], hits[i]);
    }
  }

  /// `out[i] = sample(rays[i])` for every i (`mpr::TileRaySampler`: `rays` holds image rows of
  /// `width` rays): the same values, from packets of 4 x 4 neighbouring pixels
  /// (`Bvh::closest_hits_coherent`, whose beams are tight for a GLC's affine rays), so the
  /// renderer traces coherent packets without being asked. Preconditions: `width > 0`, sizes a
  /// multiple of it and equal.
  void sample_tile(std::span<const Ray<T>> rays, int width, std::span<color_type> out) const noexcept {
    const std::size_t w = static_cast<std::size_t>(width), rows = rays.size() / w;
    constexpr std::size_t kSide = 4;
    static_assert(kSide * kSide == scene::detail::kPacketRays);
    Ray<T> block[kSide * kSide];
    std::size_t index[kSide * kSide];
    scene::Hit<T> hits[kSide * kSide];
    for (std::size_t y0 = 0; y0 < rows; y0 += kSide)
      for (std::size_t x0 = 0; x0 < w; x0 += kSide) {
        std::size_t n = 0;
        for (std::size_t y = y0; y < std::min(y0 + kSide, rows); ++y)
          for (std::size_t x = x0; x < std::min(x0 + kSide, w); ++x) {
            index[n] = y * w + x;
            block[n++] = rays[y * w + x];
          }
        state_->bvh.closest_hits_coherent(std::span<const Ray<T>>(block, n), std::span<scene::Hit<T>>(hits, n));
        for (std::size_t i = 0; i < n; ++i) out[index[i]] = answer(block[i], hits[i]);
      }
  }

private:
  /// What `Output` asks for, given the ray's closest hit.
  [[nodiscard]] color_type answer(const Ray<T>& ray, const scene::Hit<T>& hit) const noexcept {
    if constexpr (std::is_same_v<Output, HitDepth>) {
      return hit.valid() ? static_cast<float>(hit.t) : std::numeric_limits<float>::infinity();
    } else {
      const scene::Scene<T>& s = *state_->scene;
      if (!hit.valid()) return s.background();
      const bool front = ray.direction.dot(s.triangles()[hit.triangle].normal) < 0;
      return s.shade(hit.triangle, hit.b1, hit.b2, front);
    }
  }

  struct State {
    State(std::shared_ptr<const scene::Scene<T>> s, const scene::BvhConfig& config)
        : scene(std::move(s)), bvh(*scene, config) {}
    std::shared_ptr<const scene::Scene<T>> scene;
    scene::Bvh<T> bvh;
  };
  std::shared_ptr<const State> state_;
};

} // namespace mpr
