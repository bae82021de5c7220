#pragma once
// The parsed command line -> mpr-render's Job (job.hpp): each value read as its option declares
// (option_values.hpp), then the rules between options ("--filter needs --spp N", "--radius needs
// --interp cylinder or depth", ...), each an argument_error naming the option.

#include "option_values.hpp"

#include "mpr-render/job.hpp"

#include <string>
#include <utility>

namespace mpr_cli {

/// What the program calling `make_job` does with the options beyond mpr-render's use of them.
struct JobContext {
  /// The program reads --depth-maps itself (mpr-view: click-to-focus), so they need no other
  /// reader on the command line. Default false (mpr-render).
  bool reads_depth_maps = false;
};

/// --shard K/N of an animation of `frames` frames: N in [1, frames], K in [0, N - 1] (0-based, as
/// Slurm's $SLURM_ARRAY_TASK_ID of --array=0-(N-1)).
[[nodiscard]] std::pair<int, int> parse_shard(const std::string& text, int frames);

/// Builds the Job from a parsed command line; throws argument_error naming the option.
[[nodiscard]] Job make_job(const OptionValues& args, const JobContext& context = {});

/// Parses mpr-render's command line (argv[0] is skipped) into a Job.
[[nodiscard]] Job parse_job(int argc, const char* const* argv);

} // namespace mpr_cli
