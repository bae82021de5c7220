// mpr_tools: render_with_sampler for the rasterized virtual array (--raster), --interp depth (float and double). One
// sampler family per translation unit keeps each unit's compiler memory and time small (docs/mpr-render.md, Building).
#include "render_with_sampler.hpp"

#include "mpr-render/samplers.hpp"

namespace mpr_cli {

template void render_with_sampler(const CameraVariant<float>&,
                                  const mpr::SceneSampler<mpr::scene::Scene<float>, mpr::Rasterized<mpr::DepthProxy>>&,
                                  const ViewTarget&);
template void render_with_sampler(const CameraVariant<double>&,
                                  const mpr::SceneSampler<mpr::scene::Scene<double>, mpr::Rasterized<mpr::DepthProxy>>&,
                                  const ViewTarget&);

} // namespace mpr_cli
