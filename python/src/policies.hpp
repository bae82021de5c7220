#pragma once
// The run-time choices of a render from Python and the policy types they select: ONE table per
// choice (interpolation, pixel filter), each choice one std::variant alternative, resolved by one
// std::visit per render (render_tiles.hpp). The names are mpr-render's (--interpolation, --filter).

#include "bindings.hpp"

#include <mpr/core/region.hpp>
#include <mpr/glc/aperture.hpp>
#include <mpr/glc/finite_aperture.hpp>
#include <mpr/lightfield/cylinder_aperture.hpp>
#include <mpr/lightfield/depth_proxy.hpp>
#include <mpr/lightfield/frame_sampler.hpp>
#include <mpr/lightfield/nearest_camera.hpp>
#include <mpr/lightfield/synthetic_aperture.hpp>
#include <mpr/sampling.hpp>

#include <array>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <variant>

namespace mpr_py {

/// The interpolations a light-field render can use.
enum class Interpolation { nearest, synthetic_aperture, cylinder, depth };

struct InterpolationEntry {
  std::string_view name;
  Interpolation value;
  std::string_view help;
};

/// The table of interpolations: name -> policy (make_sampler maps each to its type).
inline constexpr std::array<InterpolationEntry, 4> interpolations{{
    {"nearest", Interpolation::nearest, "the camera whose centre is nearest the ray"},
    {"synthetic_aperture", Interpolation::synthetic_aperture, "every camera that sees the focal point, averaged"},
    {"cylinder", Interpolation::cylinder, "cameras within `radius` (world units) of the ray line, averaged"},
    {"depth", Interpolation::depth, "the cameras near the ray, blended at the surface their depth maps give"},
}};

struct FilterEntry {
  std::string_view name;
  /// pbrt-v4's default radius, pixels.
  double default_radius;
};

/// The table of pixel filters of supersampling (spp > 1).
inline constexpr std::array<FilterEntry, 5> filters{{
    {"box", 0.5},
    {"tent", 2},
    {"gaussian", 1.5},
    {"mitchell", 2},
    {"lanczos", 4},
}};

[[nodiscard]] inline Interpolation parse_interpolation(const std::string& name) {
  for (const InterpolationEntry& e : interpolations)
    if (e.name == name) return e.value;
  throw mpr::argument_error("interpolation", "'" + name + "' is not nearest, synthetic_aperture, cylinder or depth");
}

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
  case Interpolation::synthetic_aperture:
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

/// The filter `name` (an entry of `filters`) of radius `r` pixels.
[[nodiscard]] inline mpr::AnyFilter make_filter(std::string_view name, double r) {
  if (name == "box") return mpr::BoxFilter(r);
  if (name == "tent") return mpr::TentFilter(r);
  if (name == "gaussian") return mpr::GaussianFilter(r);
  if (name == "mitchell") return mpr::MitchellFilter(r);
  return mpr::LanczosFilter(r);
}

[[nodiscard]] inline PixelSamplingVariant make_pixel_sampling(int spp, const std::string& filter, double radius) {
  if (spp < 1 || spp > 4096) throw mpr::argument_error("spp", "must lie in [1, 4096]");
  const FilterEntry* entry = nullptr;
  for (const FilterEntry& e : filters)
    if (e.name == filter) entry = &e;
  if (entry == nullptr)
    throw mpr::argument_error("filter", "'" + filter + "' is not box, tent, gaussian, mitchell or lanczos");
  if (!(radius >= 0 && radius <= 64))
    throw mpr::argument_error("filter_radius", "must lie in [0, 64] pixels (0: default)");
  if (spp == 1) return mpr::PixelCentre{};
  const double r = radius > 0 ? radius : entry->default_radius;
  return mpr::Supersample<mpr::OwenSobol, mpr::AnyFilter>(mpr::OwenSobol(spp), make_filter(entry->name, r));
}

/// The table of finite-aperture shapes (mpr-render's --aperture SHAPE): "none" is the pinhole.
inline constexpr std::array<std::string_view, 4> apertures{{"none", "disc", "square", "gaussian"}};

/// A finite aperture's shape, one alternative per policy type.
using ApertureShapeVariant = std::variant<mpr::glc::DiscAperture, mpr::glc::SquareAperture, mpr::glc::GaussianAperture>;

/// The shape of `apertures[index]` (index >= 1).
[[nodiscard]] inline ApertureShapeVariant make_aperture_shape(std::size_t index) {
  if (index == 1) return mpr::glc::DiscAperture{};
  if (index == 2) return mpr::glc::SquareAperture{};
  return mpr::glc::GaussianAperture{};
}

/// One render job: the choices above plus the output.
struct RenderJob {
  Interpolation interpolation = Interpolation::synthetic_aperture;
  double radius = 1;
  int spp = 1;
  std::string filter = "box";
  double filter_radius = 0;
  int threads = 0;
  /// Index into `apertures` (0: pinhole), its size (radius, half side or sigma, world units),
  /// the lens plane's distance behind the image plane (0: the plane's width) and the focus depth
  /// in front of the image plane (0: on the image plane).
  std::size_t aperture = 0;
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
