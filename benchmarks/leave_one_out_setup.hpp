#pragma once
// The leave-one-out set-ups on real data, shared by examples/leave_one_out.cpp and
// benchmarks/error_vs_time.cpp: which views are held out, the focal plane and the cylinder radius
// of each data set, and the render of a held-out view from the remaining views.
//
// - Stanford Chess (7x7 views of 1400x800): held-out views (06,06), (08,08), (10,10) (indices 8,
//   24, 40); focal plane z = 820, the middle of the board's depth range (about 700-950 with the
//   default planar-array options); cylinder radius 10 (about 12 of the 48 cameras). Depth proxy:
//   the 48 other views' depth estimated by a plane sweep of 64 planes from 600 to 1400, cameras
//   within 10 (twice the spacing) of a ray.
// - Middlebury templeSparseRing (16 views of 640x480): held-out views 3, 7, 13 (0-based); focal
//   plane through the centre of the data set's bounding box, facing the held-out camera;
//   cylinder radius 0.3 (the ring's neighbours are about 0.22 apart). Depth proxy: the 15 other
//   views' depth estimated by a plane sweep over the depths the bounding box spans in front of
//   the cameras and constrained to the visual hull of the silhouettes against the black backdrop
//   (brightest channel >= 20); cameras within 0.5 of a ray, all of them searched for the surface
//   (march_cameras 8), the 3 best blended (docs/accuracy.md has the others measured).
// - Middlebury dinoSparseRing: as the temple (its own bounding box).

#include <mpr/lightfield.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/visual_hull.hpp>
#include <mpr/mpr.hpp>

#include <algorithm>
#include <array>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mpr_loo {

/// One leave-one-out data set.
template <std::floating_point T>
struct LooSetup {
  std::string name;
  std::vector<std::size_t> held_out;
  double cylinder_radius = 1;
  /// The focal depth (in front of the held-out camera) of the perspective GLC that renders it.
  std::function<T(const mpr::PinholeCamera<T>&)> depth_of;
  /// The plane sweep that estimates the other views' depth for the depth proxy; with `bounds`
  /// set, its near and far are replaced by `sweep_range` of the frames.
  mpr::PlaneSweepConfig sweep;
  /// The scene's bounding box (lower and upper corner), when the data set gives one.
  std::optional<std::array<mpr::Vec3<T>, 2>> bounds;
  /// The depth-proxy interpolation of the geometry-aware row.
  mpr::DepthProxy depth_proxy;
  /// For objects on a black backdrop: the `BrightnessSilhouette` threshold whose visual hull
  /// constrains the estimated depth (`constrain_to_visual_hull`); unset: no hull.
  std::optional<int> silhouette;
};

/// The plane sweep of `setup` for `frames`: with `setup.bounds`, near and far are the nearest
/// and farthest depth of the box's corners along any camera's axis, widened by 10%.
template <std::floating_point T, class Px>
mpr::PlaneSweepConfig sweep_config(const LooSetup<T>& setup, const mpr::CameraFrameSet<T, Px>& frames) {
  mpr::PlaneSweepConfig c = setup.sweep;
  if (!setup.bounds) return c;
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (std::size_t i = 0; i < frames.size(); ++i)
    for (int corner = 0; corner < 8; ++corner) {
      const auto& b = *setup.bounds;
      const mpr::Vec3<T> p((corner & 1) ? b[1].x() : b[0].x(), (corner & 2) ? b[1].y() : b[0].y(),
                           (corner & 4) ? b[1].z() : b[0].z());
      const double z = static_cast<double>(frames.camera(i).forward().dot(p - frames.camera(i).centre()));
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  c.near = 0.9 * lo;
  c.far = 1.1 * hi;
  return c;
}

template <std::floating_point T>
LooSetup<T> chess_setup() {
  mpr::PlaneSweepConfig sweep;
  sweep.near = 600;
  sweep.far = 1400;
  sweep.planes = 64;
  LooSetup<T> setup;
  setup.name = "chess";
  setup.held_out = {8, 24, 40};
  setup.cylinder_radius = 10.0;
  setup.depth_of = [](const mpr::PinholeCamera<T>&) { return T(820); };
  setup.sweep = sweep;
  setup.depth_proxy.radius = 10.0;
  return setup;
}

template <std::floating_point T>
std::filesystem::path temple_par_file(const std::filesystem::path& data) {
  return data / "middlebury" / "templeSparseRing" / "templeSR_par.txt";
}

template <std::floating_point T>
LooSetup<T> temple_setup() {
  // The centre of the bounding box in the data set's README.
  const mpr::Vec3<T> lo(T(-0.073568), T(0.021728), T(-0.012445)), hi(T(0.028855), T(0.181892), T(0.062736));
  const mpr::Vec3<T> target = T(0.5) * (lo + hi);
  mpr::PlaneSweepConfig sweep;
  sweep.planes = 64;
  LooSetup<T> setup;
  setup.name = "temple";
  setup.held_out = {3, 7, 13};
  setup.cylinder_radius = 0.3;
  setup.depth_of = [target](const mpr::PinholeCamera<T>& c) { return c.forward().dot(target - c.centre()); };
  setup.sweep = sweep;
  setup.bounds = std::array<mpr::Vec3<T>, 2>{lo, hi};
  // The ring's cameras are about 0.22 apart: within 0.5 of a ray lie its two or three nearest
  // on each side; every one of them searches for the surface, and the 3 best are blended.
  setup.depth_proxy.radius = 0.5;
  setup.depth_proxy.march_cameras = 8;
  setup.depth_proxy.k = 3;
  setup.silhouette = 20;
  return setup;
}

template <std::floating_point T>
std::filesystem::path dino_par_file(const std::filesystem::path& data) {
  return data / "middlebury" / "dinoSparseRing" / "dinoSR_par.txt";
}

/// Middlebury dinoSparseRing (16 views of 640x480, an untextured dinosaur on a black backdrop):
/// held-out views 3, 7, 13 (0-based, as the temple's); focal plane through the centre of the
/// README's bounding box. The tuned depth proxy is the temple's (bounding-box sweep range,
/// visual hull of brightest channel >= 20, radius 0.5, march 8, k 3).
template <std::floating_point T>
LooSetup<T> dino_setup() {
  const mpr::Vec3<T> lo(T(-0.061897), T(-0.018874), T(-0.057845)), hi(T(0.010897), T(0.068227), T(0.015495));
  LooSetup<T> setup = temple_setup<T>();
  const mpr::Vec3<T> target = T(0.5) * (lo + hi);
  setup.name = "dino";
  setup.depth_of = [target](const mpr::PinholeCamera<T>& c) { return c.forward().dot(target - c.centre()); };
  setup.bounds = std::array<mpr::Vec3<T>, 2>{lo, hi};
  return setup;
}

/// The renderer of a held-out view: the perspective GLC of `held` on its image plane at `depth`,
/// one output pixel per camera pixel.
template <std::floating_point T, class Sampler>
auto held_out_renderer(const Sampler& sampler, const mpr::PinholeCamera<T>& held, T depth) {
  const mpr::PlanarSurface<T> plane = held.image_plane(depth);
  return mpr::Renderer(plane, mpr::pinhole_glc(held, plane), sampler);
}

/// A short view name: the file name without extension, "out_RR_CC" for Stanford files.
inline std::string view_name(const std::string& file) {
  std::string view = file.substr(0, file.find('.'));
  if (view.rfind("out_", 0) == 0) view = view.substr(0, 9);
  return view;
}

} // namespace mpr_loo
