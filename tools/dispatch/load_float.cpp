// mpr_tools: loading for float (load<float>, loading.hpp: scene, OBJ, a light field's depth maps
// and framing; the light-field readers and the plane sweep have units of their own), declared
// `extern template` in its header. A unit of its own keeps each unit's compiler memory and time
// small (docs/mpr-render.md, Building).
#include "mpr-render/loading.hpp"

namespace mpr_cli {

template Loaded<float> load<float>(const Job&);

} // namespace mpr_cli
