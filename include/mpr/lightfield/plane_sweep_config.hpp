#pragma once
/// \file
/// The settings of the plane sweep of `estimate_depth` (lightfield/depth_estimation.hpp): how the
/// neighbours are picked, how many planes and kept costs, the truncation, the edge-aware
/// aggregation and final filters, threads and memory, progress reports; their check
/// (`validate`), and what the sweep returns per camera (`DepthEstimate`).

#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/lightfield/depth_median.hpp>
#include <mpr/lightfield/edge_snap.hpp>

#include <cmath>
#include <cstddef>
#include <functional>

namespace mpr {

/// How `estimate_depth` picks the cameras a camera is compared with.
enum class NeighbourSelection {
  /// The `neighbours` nearest by centre distance.
  nearest,
  /// In a camera grid: the cameras whose baseline, seen in the camera's image plane, lies within
  /// `kSweepAxisDegrees` of its image rows, and those within it of its columns; of each line the
  /// `neighbours / 2` nearest (the rest of `neighbours` from the other line when one is short).
  /// Baselines along both image axes make edges of every direction count, and the longer
  /// baselines of a whole row and column give finer depth than the nearest few cameras of a
  /// dense grid (all one step away). Where the rows or the columns hold fewer than two cameras
  /// (a ring, a single row): `nearest`.
  axes,
};

/// The angle within which a baseline counts as running along an image axis
/// (`NeighbourSelection::axes`), degrees.
inline constexpr double kSweepAxisDegrees = 10.0;

/// Where a depth estimation stands, for `PlaneSweepConfig::progress`.
struct DepthProgress {
  /// "range" (the sweep range from the calibration, `sweep_range`), "sweep" (the cameras' plane
  /// sweeps), or a later stage of a caller (`estimate_scene_depth`: "backdrop", "hull").
  const char* stage = "";
  /// Units of the stage done (cameras of "sweep") and in all; done == total ends the stage.
  std::size_t done = 0;
  std::size_t total = 0;
  /// Seconds since the stage began.
  double seconds = 0;
};

/// Settings of `estimate_depth`. Depths are along the camera's optical axis, world units.
struct PlaneSweepConfig {
  /// Depth range swept, 0 < near < far, finite; near = far = 0 (the default): from the
  /// calibration and the images, `sweep_range` (sweep_range.hpp).
  double near = 0;
  double far = 0;
  /// Planes between near and far, uniform in inverse depth, 2..1024.
  int planes = 64;
  /// How the neighbours are picked (see `NeighbourSelection`).
  NeighbourSelection selection = NeighbourSelection::axes;
  /// Cameras compared with each camera, 1..32.
  int neighbours = 16;
  /// The cost of a pixel at a plane is the mean of the `best` smallest neighbour costs
  /// (1..neighbours): cameras that are occluded there do not count.
  int best = 8;
  /// A neighbour's cost per pixel is the sum over channels of |difference| of the sRGB codes
  /// / 255, truncated at this value (robust to specularities and occlusion), > 0 and finite.
  /// Values above 3 act as 3: no cost is larger, so nothing is truncated, and a neighbour that
  /// does not see a pixel counts 3 there.
  double truncation = 0.3;
  /// Edge-aware aggregation (domain transform): spatial extent in pixels (>= 0; 0: none) and the
  /// colour difference (sum over channels of sRGB codes / 255) that cuts the support, > 0.
  double spatial = 12;
  double range = 0.2;
  /// The final edge-aware filter of the refined plane coordinates (depth_median.hpp: a joint
  /// weighted median guided by the camera's image and weighted by the confidence); radius 0:
  /// none. Default: a 7 x 7 window, range 0.16, windows within one plane left alone.
  WeightedMedianConfig median;
  /// Then the mixed pixels of depth edges decided by their colour (edge_snap.hpp), in planes:
  /// a pixel whose neighbours differ by more than `snap.jump` planes (default 8) takes the value
  /// of the one whose colour it is nearer to in linear light; jump = infinity: none.
  EdgeSnapConfig snap;
  /// Worker threads (the caller included); 0 or less: all hardware threads.
  int threads = 0;
  /// Where a row's neighbours are all translations of it (a rectified array; more than four of
  /// them), their costs on 16-bit integers (kernels/sweep_code_kernels.hpp: the weights rounded
  /// to 1/128, the costs to 1/32 code; about twice as fast) when the sums fit (up to 26
  /// neighbours at truncation 0.3); false: in float (the per-pixel sweep's values, up to
  /// rounding).
  bool integer_costs = true;
  /// Working memory of the sweep, bytes, > 0: each worker holds about 94 bytes per pixel of the
  /// camera it sweeps plus 15 per neighbour (`plane_sweep_bytes`; 310 MB for a Chess view of
  /// 1400x800 with its 12 neighbours of row and column), so
  /// `estimate_depth_maps` runs no more workers at once than fit (at least one), and a camera
  /// that alone needs more is refused. Default 2 GiB.
  double memory_limit = 2.0 * (1 << 30);
  /// Called as the estimation proceeds (`estimate_depth_maps`: once the range is found, after
  /// each camera's sweep), one call at a time, from the caller's thread or a worker; empty: not
  /// called. Must not throw.
  std::function<void(const DepthProgress&)> progress;
};

/// A camera's estimated depth and, per pixel, a confidence in [0, 1]: 1 - (the best plane's
/// aggregated cost / the mean over planes); near 0 where every plane fits alike (no texture).
struct DepthEstimate {
  Image<float> depth;
  Image<float> confidence;
};

/// Checks `config`; throws `argument_error` naming the field ("near", "far", "planes",
/// "neighbours", "best", "truncation", "spatial", "range", "memory_limit").
inline void validate(const PlaneSweepConfig& c) {
  if (c.near == 0 && c.far == 0) {
    // The range comes from the calibration (`with_sweep_range`).
  } else if (!(c.near >= 1e-30 && c.near <= 1e30))
    throw argument_error("near", "must lie in [1e-30, 1e30]");
  else if (!(c.far > c.near && c.far <= 1e30))
    throw argument_error("far", "must lie beyond near, at most 1e30");
  if (c.planes < 2 || c.planes > 1024) throw argument_error("planes", "must be in 2..1024");
  if (c.neighbours < 1 || c.neighbours > 32) throw argument_error("neighbours", "must be in 1..32");
  if (c.best < 1 || c.best > c.neighbours) throw argument_error("best", "must be in 1..neighbours");
  if (!(c.truncation > 0) || !std::isfinite(c.truncation)) throw argument_error("truncation", "must be positive");
  if (!(c.spatial >= 0) || !std::isfinite(c.spatial)) throw argument_error("spatial", "must be finite and >= 0");
  if (!(c.range > 0) || !std::isfinite(c.range)) throw argument_error("range", "must be positive");
  if (!(c.memory_limit > 0)) throw argument_error("memory_limit", "must be positive");
  validate(c.median);
  validate(c.snap);
}

} // namespace mpr
