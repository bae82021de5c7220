// mpr_tools: loading for double (load<double>, loading.hpp: scene, OBJ, a light field's depth maps
// and framing; the light-field readers and the plane sweep have units of their own), declared
// `extern template` in its header. A unit of its own keeps each unit's compiler memory and time
// small (docs/mpr-render.md, Building).
#include "mpr-render/loading.hpp"

namespace mpr_cli {

template Loaded<double> load<double>(const Job&);

} // namespace mpr_cli
