// mpr_tools: loading for float (load<float>, loading.hpp: scene, OBJ, light fields and their depth
// maps), declared `extern template` in its header. A unit of its own keeps each unit's compiler
// memory and time small (docs/mpr-render.md, Building).
#include "mpr-render/loading.hpp"

namespace mpr_cli {

template Loaded<float> load<float>(const Job&);

} // namespace mpr_cli
