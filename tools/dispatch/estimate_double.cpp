// mpr_tools: --depth-maps estimate for double (loading.hpp: the plane sweep, range and visual hull of
// mpr::estimate_scene_depth), declared `extern template` in its header. A unit of its own keeps
// each unit's compiler memory and time small (docs/mpr-render.md, Building).
#include "mpr-render/loading.hpp"

namespace mpr_cli::detail {

template std::vector<mpr::Image<float>> estimated_depth_maps<double>(const Job&, const mpr::CameraFrameSet<double>&,
                                                                     std::vector<std::string>&);

} // namespace mpr_cli::detail
