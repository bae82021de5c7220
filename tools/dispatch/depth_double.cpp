// mpr_tools: the depth outputs for double (depth_output.hpp: the focus of --focus-at, the depth of
// --write-depth), declared `extern template` in their header. A unit of its own keeps each unit's
// compiler memory and time small (docs/mpr-render.md, Building).
#include "mpr-render/depth_output.hpp"

namespace mpr_cli {

template Job with_focus_at<double>(const Job&, const Loaded<double>&, std::ostream*);
template void write_view_depth<double>(const Job&, const Loaded<double>&, std::ostream*, Publication*);

} // namespace mpr_cli
