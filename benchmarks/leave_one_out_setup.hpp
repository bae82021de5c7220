#pragma once
// The leave-one-out set-ups on real data, shared by examples/leave_one_out.cpp and
// benchmarks/error_vs_time.cpp: which views are held out, the focal plane and the cylinder radius
// of each data set, and the render of a held-out view from the remaining views.
//
// - Stanford Chess (7x7 views of 1400x800): held-out views (06,06), (08,08), (10,10) (indices 8,
//   24, 40); focal plane z = 820, the middle of the board's depth range (about 700-950 with the
//   default planar-array options); cylinder radius 10 (about 12 of the 48 cameras).
// - Middlebury templeSparseRing (16 views of 640x480): held-out views 3, 7, 13 (0-based); focal
//   plane through the centre of the data set's bounding box, facing the held-out camera;
//   cylinder radius 0.3 (the ring's neighbours are about 0.22 apart).

#include <mpr/lightfield.hpp>
#include <mpr/mpr.hpp>

#include <filesystem>
#include <functional>
#include <memory>
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
};

template <std::floating_point T>
LooSetup<T> chess_setup() {
  return {"chess", {8, 24, 40}, 10.0, [](const mpr::PinholeCamera<T>&) { return T(820); }};
}

template <std::floating_point T>
std::filesystem::path temple_par_file(const std::filesystem::path& data) {
  return data / "middlebury" / "templeSparseRing" / "templeSR_par.txt";
}

template <std::floating_point T>
LooSetup<T> temple_setup() {
  // The centre of the bounding box in the data set's README.
  const mpr::Vec3<T> target(T(0.5 * (-0.073568 + 0.028855)), T(0.5 * (0.021728 + 0.181892)),
                            T(0.5 * (-0.012445 + 0.062736)));
  return {"temple", {3, 7, 13}, 0.3, [target](const mpr::PinholeCamera<T>& c) {
            return c.forward().dot(target - c.centre());
          }};
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
