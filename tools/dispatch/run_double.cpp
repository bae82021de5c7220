// mpr_tools: mpr-render's run loop for double (run_typed<double>, render_job.hpp) and the steps of it
// mpr-view shares (the preflight check, the array defaults and warnings, the sampler of a frame),
// each declared `extern template` in its header so that no other unit compiles it again; loading
// and the depth outputs have units of their own (load_double.cpp, depth_double.cpp). One scalar type
// per translation unit keeps each unit's compiler memory and time small (docs/mpr-render.md,
// Building).
#include "mpr-render/render_job.hpp"

namespace mpr_cli {

template void preflight<double>(const Job&, const Loaded<double>&);
template Job with_array_defaults<double>(const Job&, const Loaded<double>&);
template void warn_job<double>(std::ostream&, const Job&, const Loaded<double>&);
template SamplerVariant<double> make_sampler<double>(const Job&, const Loaded<double>&, const FrameParams&, int, int);
template void run_typed<double>(const Job&, const LinearFrameSink&, std::ostream*, std::ostream*, Publication*);

} // namespace mpr_cli
