#pragma once
// The one run-time dispatch of a render, split for compile cost: render_view (render_job.hpp)
// visits the sampler variant and calls render_with_sampler for the concrete sampler type. Its
// definition (tools/dispatch/render_with_sampler.hpp) is compiled once, in the static library
// mpr_tools, one translation unit per sampler family (tools/dispatch/*.cpp, explicit
// instantiations for float and double), so that no unit instantiates every surface x selector x
// sampler x pixel-sampling combination and mpr-render, mpr-view, the tests and the benchmarks
// share the same object code.

#include "aperture.hpp"
#include "framing.hpp"
#include "pixel_sampling.hpp"

#include <mpr/core/image.hpp>
#include <mpr/render/renderer.hpp>

namespace mpr_cli {

/// Where and how one view is rendered: the tile `region` of `out` (linear light; the outputs
/// encode it, output.hpp and encode_output.hpp), the pixel sampling of --spp /
/// --filter, and (with a supersampling policy) the finite aperture of --aperture opened to
/// `aperture_size` (null: a pinhole GLC view; ignored with mpr::PixelCentre).
struct ViewTarget {
  mpr::ImageView<mpr::Color> out;
  mpr::Region region;
  mpr::RenderOptions options;
  const PixelSamplingVariant* sampling = nullptr; ///< not null
  const ApertureSpec* aperture = nullptr;
  double aperture_size = 0;
};

/// Renders `camera` (either variant alternative) with one concrete sampler of SamplerVariant<T>
/// into `target`. Defined only in tools/dispatch/ (explicit instantiations for every alternative
/// of SamplerVariant<float> and SamplerVariant<double>); link mpr_tools.
template <std::floating_point T, class Sampler>
void render_with_sampler(const CameraVariant<T>& camera, const Sampler& sampler, const ViewTarget& target);

} // namespace mpr_cli
