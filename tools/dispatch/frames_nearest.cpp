// mpr_tools: render_with_sampler for light-field frames, --interp nearest (float and double). One sampler family per
// translation unit keeps each unit's compiler memory and time small (docs/mpr-render.md, Building).
#include "render_with_sampler.hpp"

#include "mpr-render/samplers.hpp"

namespace mpr_cli {

template void render_with_sampler(const CameraVariant<float>&,
                                  const mpr::CameraFrameSampler<mpr::NearestCamera, float>&, const ViewTarget&);
template void render_with_sampler(const CameraVariant<double>&,
                                  const mpr::CameraFrameSampler<mpr::NearestCamera, double>&, const ViewTarget&);

} // namespace mpr_cli
