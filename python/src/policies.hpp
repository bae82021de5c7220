#pragma once
// The run-time choices of a render from Python. The names are mpr's one table of them
// (include/mpr/render/policy_names.hpp, which mpr-render and mpr-view parse too), and the policy types
// they select, the functions that build them and the visit that resolves them are the library's
// (include/mpr/render/policy_dispatch.hpp), which mpr-render and mpr-view render through too
// (render_tiles.hpp).

#include "bindings.hpp"

#include <mpr/core/region.hpp>
#include <mpr/glc/aperture.hpp>
#include <mpr/render/policy_dispatch.hpp>
#include <mpr/render/policy_names.hpp>

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>

namespace mpr_py {

/// The interpolations a light-field render can use (names: `mpr::interpolation_names`).
using Interpolation = mpr::InterpolationChoice;

/// The filter named `filter` (`mpr::filter_names`) after checking `spp` ([1, 4096]) and `radius`
/// ([0, 64] pixels, 0: the filter's default); ValueError naming the argument.
[[nodiscard]] inline mpr::FilterChoice checked_filter(int spp, const std::string& filter, double radius) {
  if (spp < 1 || spp > 4096) throw mpr::argument_error("spp", "must lie in [1, 4096]");
  const mpr::FilterChoice choice = mpr::choose(mpr::filter_names, filter, "filter");
  if (!(radius >= 0 && radius <= 64))
    throw mpr::argument_error("filter_radius", "must lie in [0, 64] pixels (0: default)");
  return choice;
}

/// One render job: the choices above plus the output.
struct RenderJob {
  Interpolation interpolation = Interpolation::synthetic;
  double radius = 1;
  int spp = 1;
  mpr::FilterChoice filter = mpr::FilterChoice::box;
  /// Pixels; 0: the filter's default (`mpr::default_filter_radius`).
  double filter_radius = 0;
  int threads = 0;
  /// The finite aperture's shape (none: the pinhole of the view's GLC), its size (radius, half
  /// side or sigma, world units), the lens plane's distance behind the image plane (0: the
  /// plane's width) and the focus depth in front of the image plane (0: on the image plane).
  std::optional<mpr::glc::AnyAperture> aperture;
  double aperture_size = 0;
  double lens_distance = 0;
  double focus_depth = 0;
};

/// The views of a render, each into its tile (x, y, width, height) of the output.
struct Tile {
  const View* view;
  mpr::Region region;
};

/// Renders every tile of `out` (8-bit sRGB or linear float pixels) from `frames` (defined in
/// render_frames8.cpp and render_frames_linear.cpp: one unit per frame pixel type).
template <class FramePx, class OutPx>
void render_tiles(const std::shared_ptr<const mpr::CameraFrameSet<T, FramePx>>& frames, const RenderJob& job,
                  std::span<const Tile> tiles, mpr::ImageView<OutPx> out);

} // namespace mpr_py
