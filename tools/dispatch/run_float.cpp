// mpr_tools: mpr-render's run loop for float (run_typed<float>, render_job.hpp) and the steps of it
// mpr-view shares (the preflight check, the array defaults and warnings, the sampler of a frame),
// each declared `extern template` in its header so that no other unit compiles it again; loading
// and the depth outputs have units of their own (load_float.cpp, depth_float.cpp). One scalar type
// per translation unit keeps each unit's compiler memory and time small (docs/mpr-render.md,
// Building).
#include "mpr-render/render_job.hpp"

namespace mpr_cli {

template void preflight<float>(const Job&, const Loaded<float>&);
template Job with_array_defaults<float>(const Job&, const Loaded<float>&);
template void warn_job<float>(std::ostream&, const Job&, const Loaded<float>&);
template SamplerVariant<float> make_sampler<float>(const Job&, const Loaded<float>&, const FrameParams&, int, int);
template void run_typed<float>(const Job&, const LinearFrameSink&, std::ostream*, std::ostream*, Publication*);

} // namespace mpr_cli
