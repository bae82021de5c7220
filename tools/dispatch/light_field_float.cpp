// mpr_tools: the light-field readers for float (loading.hpp: _par.txt, Stanford, LFCA, HCI, COLMAP),
// declared `extern template` in their header. A unit of its own keeps each unit's compiler
// memory and time small (docs/mpr-render.md, Building).
#include "mpr-render/loading.hpp"

namespace mpr_cli::detail {

template ReadLightField<float> read_light_field<float>(const Job&, const mpr::LoadLimits&);

} // namespace mpr_cli::detail
