#pragma once
// mpr-render's pixel sampling: --spp N and --filter NAME[:RADIUS] parsed into the renderer's
// fourth policy, one std::variant alternative per policy type: the pixel centre (the default,
// --spp 1) or N scrambled Sobol samples per pixel combined by the chosen filter.

#include "cli_args.hpp"

#include <mpr/sampling.hpp>

#include <string>
#include <variant>

namespace mpr_cli {

/// Largest --spp accepted (a 480x360 view at 4096 spp is 700 million rays).
inline constexpr int kMaxSpp = 4096;
/// Largest --filter radius accepted, pixels.
inline constexpr double kMaxFilterRadius = 64;

/// The pixel sampling of a render: the pixel centre, or supersampling with a filter.
using PixelSamplingVariant = std::variant<mpr::PixelCentre, mpr::Supersample<mpr::OwenSobol, mpr::AnyFilter>>;

/// --spp: an integer in [1, kMaxSpp].
inline int parse_spp(const std::string& text) { return parse_int(text, "--spp", 1, kMaxSpp); }

/// --filter NAME[:RADIUS]: box, tent, gaussian, mitchell or lanczos, each with pbrt-v4's default
/// radius (box 0.5, tent 2, gaussian 1.5, mitchell 2, lanczos 4) unless RADIUS (pixels, in
/// (0, 64]) is given.
inline mpr::AnyFilter parse_filter(const std::string& text) {
  const std::vector<std::string> parts = split(text, ':');
  if (parts.size() > 2) throw mpr::argument_error("--filter", "'" + text + "' is not NAME or NAME:RADIUS");
  const std::string& name = parts[0];
  if (name != "box" && name != "tent" && name != "triangle" && name != "gaussian" && name != "mitchell" &&
      name != "lanczos")
    throw mpr::argument_error("--filter", "'" + name + "' is not box, tent, gaussian, mitchell or lanczos");
  double radius = 0;
  if (parts.size() == 2) {
    radius = parse_number(parts[1], "--filter");
    if (!(radius > 0 && radius <= kMaxFilterRadius))
      throw mpr::argument_error("--filter", "radius " + parts[1] + " must lie in (0, 64] pixels");
  }
  const auto r = [&](double fallback) { return radius > 0 ? radius : fallback; };
  if (name == "box") return mpr::BoxFilter(r(0.5));
  if (name == "tent" || name == "triangle") return mpr::TentFilter(r(2));
  if (name == "gaussian") return mpr::GaussianFilter(r(1.5));
  if (name == "mitchell") return mpr::MitchellFilter(r(2));
  return mpr::LanczosFilter(r(4));
}

/// The pixel sampling of `spp` samples per pixel with `filter`: the pixel centre for 1 sample.
inline PixelSamplingVariant make_pixel_sampling(int spp, const mpr::AnyFilter& filter) {
  if (spp <= 1) return mpr::PixelCentre{};
  return mpr::Supersample<mpr::OwenSobol, mpr::AnyFilter>(mpr::OwenSobol(spp), filter);
}

} // namespace mpr_cli
