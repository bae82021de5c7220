#pragma once
// The mpr-render command line that renders one frame of a Job (mpr-view's "save command", the
// `S` key), written from the option table: each option's own writer (option_table.hpp) decides
// whether and how it is written, in the table's order; animated values are written at the time
// of the frame, every number so that it reads back to the same double.

#include "mpr-render/job.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace mpr_cli {

/// The arguments (without the program name) of the mpr-render command that renders frame `time`
/// (0..1) of `job` as one image of views `view_width` x `view_height` into `output`.
[[nodiscard]] std::vector<std::string> save_arguments(const Job& job, double time, int view_width, int view_height,
                                                      const std::filesystem::path& output);

/// `s` quoted for a POSIX shell when it holds anything but [A-Za-z0-9_./,:=+-].
[[nodiscard]] std::string shell_word(const std::string& s);

/// `save_arguments` as one shell line starting with "mpr-render".
[[nodiscard]] std::string save_command(const Job& job, double time, int view_width, int view_height,
                                       const std::filesystem::path& output);

} // namespace mpr_cli
