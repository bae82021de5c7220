#pragma once
/// \file
/// `mpr::SceneSampler<scene::Scene<float>, mpr::EmbreeRayCast, Output>`: the ray-cast scene
/// sampler with Intel Embree 3 (https://www.embree.org) in place of mpr's BVH, for users with
/// large scenes (docs/scene.md says when to choose which). Optional: this header is not part of
/// `<mpr/scene.hpp>` or `<mpr/mpr.hpp>`; include it yourself, and link Embree through its CMake
/// package (`find_package(embree 3)`, target `embree`). Float scenes only (Embree's precision).
///
/// The same interface and outputs as `SceneSampler<Scene, RayCast, Output>`: `sample` traces one
/// ray (`rtcIntersect1`); `sample_rays` and `sample_tile` trace 16-ray packets
/// (`rtcIntersect16`, 4 x 4 pixel blocks for tiles, coherent flag). Hits agree with mpr's to
/// Embree's rounding (its own watertight test; ties on shared edges may go to the other
/// triangle), so images match mpr's except for rare pixels.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/scene/scene.hpp>
#include <mpr/scene/scene_sampler.hpp>

#include <embree3/rtcore.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <utility>

namespace mpr {

/// Sampling policy tag: cast each ray with Embree 3 (header mpr/scene/embree_sampler.hpp).
struct EmbreeRayCast {};

/// The Embree ray-cast scene sampler. Copies share one immutable scene and Embree scene (a
/// `shared_ptr`); queries are thread-safe, as Embree's are.
template <class Output>
class SceneSampler<scene::Scene<float>, EmbreeRayCast, Output> {
  static_assert(std::is_same_v<Output, ShadedColor> || std::is_same_v<Output, HitDepth>,
                "Output must be mpr::ShadedColor or mpr::HitDepth");

public:
  using scalar_type = float;
  using color_type = std::conditional_t<std::is_same_v<Output, HitDepth>, float, Color>;
  using scene_type = scene::Scene<float>;

  /// Takes the scene and builds Embree's BVH with `quality` (HIGH: slower build, faster
  /// queries; MEDIUM builds several times faster). Throws `mpr::error` when Embree fails
  /// (its error code in the message).
  explicit SceneSampler(scene::Scene<float> scene, RTCBuildQuality quality = RTC_BUILD_QUALITY_HIGH)
      : SceneSampler(std::make_shared<const scene::Scene<float>>(std::move(scene)), quality) {}
  /// Shares an existing scene. Throws `argument_error` for a null pointer.
  explicit SceneSampler(std::shared_ptr<const scene::Scene<float>> scene,
                        RTCBuildQuality quality = RTC_BUILD_QUALITY_HIGH) {
    if (!scene) throw argument_error("scene", "null");
    state_ = std::make_shared<const State>(std::move(scene), quality);
  }

  [[nodiscard]] const scene::Scene<float>& scene() const noexcept { return *state_->scene; }
  /// The Embree scene (committed; for queries of your own).
  [[nodiscard]] RTCScene embree_scene() const noexcept { return state_->rtc; }

  [[nodiscard]] color_type sample(const Ray<float>& ray) const noexcept {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray.org_x = ray.origin.x();
    rh.ray.org_y = ray.origin.y();
    rh.ray.org_z = ray.origin.z();
    rh.ray.dir_x = ray.direction.x();
    rh.ray.dir_y = ray.direction.y();
    rh.ray.dir_z = ray.direction.z();
    rh.ray.tnear = 0;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.time = 0;
    rh.ray.mask = ~0U;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(state_->rtc, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return answer(ray, 0, 0, 0, false, 0);
    return answer(ray, rh.ray.tfar, rh.hit.u, rh.hit.v, true, rh.hit.primID);
  }

  /// `out[i] = sample(rays[i])` for every i, to Embree's rounding (packets of 16 consecutive
  /// rays). Precondition: equal lengths.
  void sample_rays(std::span<const Ray<float>> rays, std::span<color_type> out) const noexcept {
    const Ray<float>* block[16];
    for (std::size_t i0 = 0; i0 < rays.size(); i0 += 16) {
      const std::size_t n = std::min<std::size_t>(16, rays.size() - i0);
      for (std::size_t k = 0; k < n; ++k) block[k] = &rays[i0 + k];
      trace16(block, n, out.data() + i0, nullptr);
    }
  }

  /// The same for `mpr::TileRaySampler`: rows of `width` rays, traced as 4 x 4 pixel packets.
  /// Preconditions: `width > 0`, sizes a multiple of it and equal.
  void sample_tile(std::span<const Ray<float>> rays, int width, std::span<color_type> out) const noexcept {
    const std::size_t w = static_cast<std::size_t>(width), rows = rays.size() / w;
    const Ray<float>* block[16];
    std::size_t index[16];
    for (std::size_t y0 = 0; y0 < rows; y0 += 4)
      for (std::size_t x0 = 0; x0 < w; x0 += 4) {
        std::size_t n = 0;
        for (std::size_t y = y0; y < std::min(y0 + 4, rows); ++y)
          for (std::size_t x = x0; x < std::min(x0 + 4, w); ++x) {
            index[n] = y * w + x;
            block[n++] = &rays[y * w + x];
          }
        trace16(block, n, out.data(), index);
      }
  }

private:
  /// Traces `rays[0..n)` (n <= 16) as one packet; ray k's answer goes to out[index[k]] (out[k]
  /// without `index`).
  void trace16(const Ray<float>* const* rays, std::size_t n, color_type* out, const std::size_t* index) const noexcept {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) int valid[16];
    RTCRayHit16 rh;
    for (std::size_t k = 0; k < 16; ++k) {
      const Ray<float>& ray = *rays[std::min(k, n - 1)];
      valid[k] = k < n ? -1 : 0;
      rh.ray.org_x[k] = ray.origin.x();
      rh.ray.org_y[k] = ray.origin.y();
      rh.ray.org_z[k] = ray.origin.z();
      rh.ray.dir_x[k] = ray.direction.x();
      rh.ray.dir_y[k] = ray.direction.y();
      rh.ray.dir_z[k] = ray.direction.z();
      rh.ray.tnear[k] = 0;
      rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
      rh.ray.time[k] = 0;
      rh.ray.mask[k] = ~0U;
      rh.ray.id[k] = 0;
      rh.ray.flags[k] = 0;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, state_->rtc, &context, &rh);
    for (std::size_t k = 0; k < n; ++k) {
      const bool hit = rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
      out[index != nullptr ? index[k] : k] =
          answer(*rays[k], rh.ray.tfar[k], rh.hit.u[k], rh.hit.v[k], hit, rh.hit.primID[k]);
    }
  }

  /// What `Output` asks for, given the hit (t, barycentrics of p[1] and p[2], triangle).
  [[nodiscard]] color_type answer(const Ray<float>& ray, float t, float b1, float b2, bool hit,
                                  std::uint32_t triangle) const noexcept {
    if constexpr (std::is_same_v<Output, HitDepth>) {
      (void)ray, (void)b1, (void)b2, (void)triangle;
      return hit ? t : std::numeric_limits<float>::infinity();
    } else {
      (void)t;
      const scene::Scene<float>& s = *state_->scene;
      if (!hit) return s.background();
      const bool front = ray.direction.dot(s.triangles()[triangle].normal) < 0;
      return s.shade(triangle, b1, b2, front);
    }
  }

  /// The scene and its Embree device and scene (one triangle geometry, triangles in scene
  /// order, so Embree's primID is the scene's triangle index).
  struct State {
    State(std::shared_ptr<const scene::Scene<float>> s, RTCBuildQuality quality) : scene(std::move(s)) {
      device = rtcNewDevice(nullptr);
      if (device == nullptr)
        throw error("mpr: Embree: rtcNewDevice failed (error " +
                    std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
      rtc = rtcNewScene(device);
      rtcSetSceneBuildQuality(rtc, quality);
      const std::size_t n = scene->size();
      if (n > 0) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
        if (v == nullptr || idx == nullptr) {
          rtcReleaseGeometry(g);
          release();
          throw error("mpr: Embree: cannot allocate the geometry buffers of " + std::to_string(n) + " triangles");
        }
        for (std::size_t i = 0; i < n; ++i)
          for (int j = 0; j < 3; ++j) {
            for (int a = 0; a < 3; ++a) v[9 * i + 3 * j + a] = scene->triangles()[i].p[j][a];
            idx[3 * i + j] = static_cast<unsigned>(3 * i + j);
          }
        rtcSetGeometryBuildQuality(g, quality);
        rtcCommitGeometry(g);
        rtcAttachGeometry(rtc, g);
        rtcReleaseGeometry(g);
      }
      rtcCommitScene(rtc);
      const RTCError e = rtcGetDeviceError(device);
      if (e != RTC_ERROR_NONE) {
        release();
        throw error("mpr: Embree: scene build failed (error " + std::to_string(static_cast<int>(e)) + ")");
      }
    }
    State(const State&) = delete;
    State& operator=(const State&) = delete;
    ~State() { release(); }
    void release() noexcept {
      if (rtc != nullptr) rtcReleaseScene(rtc);
      if (device != nullptr) rtcReleaseDevice(device);
      rtc = nullptr;
      device = nullptr;
    }
    std::shared_ptr<const scene::Scene<float>> scene;
    RTCDevice device = nullptr;
    RTCScene rtc = nullptr;
  };
  std::shared_ptr<const State> state_;
};

} // namespace mpr
