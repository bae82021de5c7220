#pragma once
/// \file
/// Depth maps of a new data set with no per-set settings: `estimate_scene_depth` runs the plane
/// sweep (`estimate_depth_maps`) over the range the calibration and the images give
/// (`sweep_range`, unless the config sets one), notices an object on an empty backdrop
/// (`detect_backdrop`) and then keeps the maps inside the visual hull of the views' silhouettes
/// against that backdrop (`visual_hull_depth_maps`, `constrain_to_visual_hull`: the backdrop
/// becomes +inf, nothing is nearer than the hull), and says what it found, for a tool to print.
/// `depth_proxy_radius` is the depth proxy's radius from the camera spacing.

#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/lightfield/backdrop.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/sweep_range.hpp>
#include <mpr/lightfield/visual_hull.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace mpr {

/// Settings of `estimate_scene_depth`.
struct SceneDepthConfig {
  /// The plane sweep; near = far = 0 (the default): the range from `sweep_range`. Its
  /// `progress` also hears the stages "backdrop" and "hull".
  PlaneSweepConfig sweep;
  /// Look for an empty backdrop and constrain the maps to the visual hull when one is found.
  bool use_backdrop = true;
  BackdropConfig backdrop;
  /// Depths the visual hull tries between the sweep's near and far, 2..4096.
  int hull_planes = 256;
};

/// What `estimate_scene_depth` produced and found.
struct SceneDepth {
  /// One depth map per camera (+inf: nothing seen: the backdrop, when one was found).
  std::vector<Image<float>> maps;
  /// The range swept (`SweepRangeSource::given` when the config set it).
  SweepRange range;
  /// The backdrop found and used for the silhouettes, if any.
  std::optional<Backdrop> backdrop;
};

/// Twice the median distance from a camera centre to its nearest other camera centre (cameras
/// at the same place skipped): the `DepthProxy::radius` that takes in the one or two rings of
/// cameras around a ray (about twice the camera spacing, as its documentation advises). 1 for
/// fewer than two distinct centres.
template <std::floating_point T, class Px>
[[nodiscard]] double depth_proxy_radius(const CameraFrameSet<T, Px>& frames) {
  std::vector<double> nearest;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < frames.size(); ++j) {
      const double d = static_cast<double>((frames.camera(i).centre() - frames.camera(j).centre()).norm());
      if (j != i && d > 0) best = std::min(best, d);
    }
    if (std::isfinite(best)) nearest.push_back(best);
  }
  if (nearest.empty()) return 1;
  std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2), nearest.end());
  return 2 * nearest[nearest.size() / 2];
}

/// The depth maps of every camera of `frames` (see the file comment). Throws as
/// `estimate_depth_maps`, `sweep_range` and `visual_hull_depth_maps`, and `argument_error`
/// ("hull_planes") outside 2..4096.
template <std::floating_point T, class Px>
[[nodiscard]] SceneDepth estimate_scene_depth(const CameraFrameSet<T, Px>& frames,
                                              const SceneDepthConfig& config = {}) {
  validate(config.sweep);
  validate(config.backdrop);
  if (config.hull_planes < 2 || config.hull_planes > 4096) throw argument_error("hull_planes", "must be in 2..4096");
  if (frames.size() < 2) throw argument_error("frames", "a plane sweep needs at least two cameras");
  const auto seconds_since = [](std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const auto& progress = config.sweep.progress;
  SceneDepth out;
  PlaneSweepConfig sweep = config.sweep;
  if (sweep.near == 0 && sweep.far == 0) {
    const auto start = std::chrono::steady_clock::now();
    out.range = sweep_range(frames);
    sweep.near = out.range.near;
    sweep.far = out.range.far;
    if (progress) progress({"range", 1, 1, seconds_since(start)});
  } else {
    out.range.near = sweep.near;
    out.range.far = sweep.far;
    out.range.source = SweepRangeSource::given;
  }
  if (config.use_backdrop) {
    const auto start = std::chrono::steady_clock::now();
    out.backdrop = detect_backdrop(frames, config.backdrop);
    if (progress) progress({"backdrop", 1, 1, seconds_since(start)});
  }
  out.maps = estimate_depth_maps(frames, sweep);
  if (out.backdrop) {
    const auto start = std::chrono::steady_clock::now();
    VisualHullConfig hull;
    hull.near = sweep.near;
    hull.far = sweep.far;
    hull.planes = config.hull_planes;
    hull.threads = sweep.threads;
    const BackdropSilhouette silhouette{out.backdrop->colour, out.backdrop->tolerance};
    for (std::size_t i = 0; i < frames.size(); ++i) {
      constrain_to_visual_hull(out.maps[i], visual_hull_depth(frames, i, silhouette, hull));
      if (progress) progress({"hull", i + 1, frames.size(), seconds_since(start)});
    }
  }
  return out;
}

} // namespace mpr
