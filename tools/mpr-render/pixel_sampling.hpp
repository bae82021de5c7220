#pragma once
// mpr-render's pixel sampling: --spp N and --filter NAME[:RADIUS] parsed into the renderer's
// fourth policy (mpr::PixelSamplingVariant, one alternative per policy type): the pixel centre (the default,
// --spp 1) or N scrambled Sobol samples per pixel combined by the chosen filter.

#include "cli_args.hpp"

#include <mpr/render/policy_dispatch.hpp>
#include <mpr/render/policy_names.hpp>
#include <mpr/sampling.hpp>

#include <string>
#include <variant>

namespace mpr_cli {

/// Largest --spp accepted (a 480x360 view at 4096 spp is 700 million rays).
inline constexpr int kMaxSpp = 4096;
/// Largest --filter radius accepted, pixels.
inline constexpr double kMaxFilterRadius = 64;

/// The pixel sampling of a render and its choice (--spp, --filter): the library's, which the
/// Python module uses too (include/mpr/render/policy_dispatch.hpp).
using mpr::make_pixel_sampling;
using mpr::PixelSamplingVariant;

/// --spp: an integer in [1, kMaxSpp].
inline int parse_spp(const std::string& text) { return parse_int(text, "--spp", 1, kMaxSpp); }

/// --filter NAME[:RADIUS]: a name of `mpr::filter_names` (box, tent, gaussian, mitchell or
/// lanczos), with its default radius (`mpr::default_filter_radius`) unless RADIUS (pixels, in
/// (0, 64]) is given.
inline mpr::AnyFilter parse_filter(const std::string& text) {
  const std::vector<std::string> parts = split(text, ':');
  if (parts.size() > 2) throw mpr::argument_error("--filter", "'" + text + "' is not NAME or NAME:RADIUS");
  const mpr::FilterChoice filter = mpr::choose(mpr::filter_names, parts[0], "--filter");
  double radius = 0;
  if (parts.size() == 2) {
    radius = parse_number(parts[1], "--filter");
    if (!(radius > 0 && radius <= kMaxFilterRadius))
      throw mpr::argument_error("--filter", "radius " + parts[1] + " must lie in (0, 64] pixels");
  }
  return mpr::make_filter(filter, radius);
}

} // namespace mpr_cli
