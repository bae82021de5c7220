#pragma once
// mpr-view's `S` key: the mpr-render command line that renders the view on screen (one frame:
// animated values are written at the time of the frame shown). Written from the option table
// (tools/options/save_command.hpp), so no option name is spelled here.

#include "mpr-render/job.hpp"
#include "options/save_command.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace mpr_view {

/// The arguments (without the program name) of the mpr-render command that renders frame
/// `time` of `job` as one image of views `view_width` x `view_height` into `output`.
[[nodiscard]] inline std::vector<std::string> render_arguments(const mpr_cli::Job& job, double time, int view_width,
                                                               int view_height, const std::filesystem::path& output) {
  return mpr_cli::save_arguments(job, time, view_width, view_height, output);
}

/// `render_arguments` as one shell line starting with "mpr-render".
[[nodiscard]] inline std::string render_command(const mpr_cli::Job& job, double time, int view_width, int view_height,
                                                const std::filesystem::path& output) {
  return mpr_cli::save_command(job, time, view_width, view_height, output);
}

} // namespace mpr_view
