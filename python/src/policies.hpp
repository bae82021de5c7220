#pragma once
// The run-time choices of a render from Python and the policy types they select. The names are
// mpr's one table of them (include/mpr/policy_names.hpp, which mpr-render and mpr-view parse
// too); each choice is one std::variant alternative, resolved by one std::visit per render
// (render_tiles.hpp).

#include "bindings.hpp"

#include <mpr/core/region.hpp>
#include <mpr/glc/aperture.hpp>
#include <mpr/glc/finite_aperture.hpp>
#include <mpr/lightfield/cylinder_aperture.hpp>
#include <mpr/lightfield/depth_proxy.hpp>
#include <mpr/lightfield/frame_sampler.hpp>
#include <mpr/lightfield/nearest_camera.hpp>
#include <mpr/lightfield/synthetic_aperture.hpp>
#include <mpr/policy_names.hpp>
#include <mpr/sampling.hpp>

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>

namespace mpr_py {

/// The interpolations a light-field render can use (names: `mpr::interpolation_names`).
using Interpolation = mpr::InterpolationChoice;

template <class Px>
using SamplerVariant = std::variant<
    mpr::CameraFrameSampler<mpr::NearestCamera, T, Px>, mpr::CameraFrameSampler<mpr::SyntheticAperture, T, Px>,
    mpr::CameraFrameSampler<mpr::CylinderAperture, T, Px>, mpr::CameraFrameSampler<mpr::DepthProxy, T, Px>>;

template <class Px>
[[nodiscard]] SamplerVariant<Px> make_sampler(std::shared_ptr<const mpr::CameraFrameSet<T, Px>> frames,
                                              Interpolation interpolation, double radius) {
  switch (interpolation) {
  case Interpolation::nearest:
    return mpr::CameraFrameSampler<mpr::NearestCamera, T, Px>(std::move(frames));
  case Interpolation::synthetic:
    return mpr::CameraFrameSampler<mpr::SyntheticAperture, T, Px>(std::move(frames));
  case Interpolation::depth: {
    mpr::DepthProxy proxy;
    proxy.radius = radius;
    return mpr::CameraFrameSampler<mpr::DepthProxy, T, Px>(std::move(frames), proxy);
  }
  case Interpolation::cylinder:
    break;
  }
  return mpr::CameraFrameSampler<mpr::CylinderAperture, T, Px>(std::move(frames), mpr::CylinderAperture{radius});
}

/// The pixel sampling of a render: the pixel centre, or `spp` Owen-scrambled Sobol samples
/// combined by a filter.
using PixelSamplingVariant = std::variant<mpr::PixelCentre, mpr::Supersample<mpr::OwenSobol, mpr::AnyFilter>>;

/// `spp` samples per pixel weighted by `filter` of radius `radius` pixels (0: its default): the
/// pixel centre for one sample.
[[nodiscard]] inline PixelSamplingVariant make_pixel_sampling(int spp, mpr::FilterChoice filter, double radius) {
  if (spp == 1) return mpr::PixelCentre{};
  return mpr::Supersample<mpr::OwenSobol, mpr::AnyFilter>(mpr::OwenSobol(spp), mpr::make_filter(filter, radius));
}

/// The filter named `filter` (`mpr::filter_names`) after checking `spp` ([1, 4096]) and `radius`
/// ([0, 64] pixels, 0: the filter's default); ValueError naming the argument.
[[nodiscard]] inline mpr::FilterChoice checked_filter(int spp, const std::string& filter, double radius) {
  if (spp < 1 || spp > 4096) throw mpr::argument_error("spp", "must lie in [1, 4096]");
  const mpr::FilterChoice choice = mpr::choose(mpr::filter_names, filter, "filter");
  if (!(radius >= 0 && radius <= 64))
    throw mpr::argument_error("filter_radius", "must lie in [0, 64] pixels (0: default)");
  return choice;
}

/// `make_pixel_sampling` of a filter name, checked (`checked_filter`).
[[nodiscard]] inline PixelSamplingVariant make_pixel_sampling(int spp, const std::string& filter, double radius) {
  return make_pixel_sampling(spp, checked_filter(spp, filter, radius), radius);
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
