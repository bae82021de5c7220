// mpr-view's run for double (viewer.hpp): one scalar type per translation unit keeps each unit's
// compiler memory and time small (docs/mpr-render.md, Building).
#include "viewer.hpp"

namespace mpr_view {

template int run_viewer<double>(const mpr_cli::Job&, const ViewerSettings&, const std::vector<ScriptCommand>&);

} // namespace mpr_view
