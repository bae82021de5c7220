#pragma once
// mpr-view's command line: the options of the shared option table (tools/options/) that the
// viewer takes, mpr-render's parsed into the same Job by make_job, plus the viewer's own
// (--script, --benchmark, --benchmark-frames).

#include "mpr-render/job.hpp"
#include "options/help.hpp"
#include "options/make_job.hpp"
#include "options/parse.hpp"
#include "overlay.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

namespace mpr_view {

/// The viewer's settings besides the Job.
struct ViewerSettings {
  std::optional<std::filesystem::path> script;
  bool benchmark = false;
  int benchmark_frames = 30;
  bool output_given = false; ///< --output: base name of the PNGs `S` saves (else mpr-view.png)
};

/// Parses the command line; throws mpr::argument_error naming the option.
inline std::pair<mpr_cli::Job, ViewerSettings> parse_command_line(int argc, const char* const* argv) {
  const mpr_cli::OptionValues args = mpr_cli::parse_options(argc, argv, mpr_cli::Tools::view);
  ViewerSettings v;
  if (args.has("shard"))
    throw mpr::argument_error("--shard", "splits mpr-render's frames between processes; the viewer shows them all");
  for (const char* option : {"bit-depth", "exr-pixel"})
    if (args.has(option))
      throw mpr::argument_error(std::string("--") + option,
                                "sets mpr-render's output file; the viewer saves 8-bit PNG");
  mpr_cli::Job job = mpr_cli::make_job(args, {.reads_depth_maps = true}); // click-to-focus reads them
  if (const auto s = args.get("script")) {
    if (s->empty()) throw mpr::argument_error("--script", "empty file name");
    v.script = *s;
  }
  v.benchmark = args.has("benchmark");
  if (v.benchmark && v.script) throw mpr::argument_error("--benchmark", "give --benchmark or --script, not both");
  if (const auto n = args.integer("benchmark-frames")) {
    if (!v.benchmark)
      throw mpr::argument_error("--benchmark-frames", "needs --benchmark (it sets the benchmark's frames)");
    v.benchmark_frames = *n;
  }
  v.output_given = args.has("output");
  if (!v.output_given) job.output = "mpr-view.png";
  return {job, v};
}

inline void print_help() {
  std::printf("usage: mpr-view [OPTIONS]\n\nAn interactive window onto General Linear Camera views of a scene or a "
              "light field.\nTakes every mpr-render option (the same inputs and VIEW specifications) and opens "
              "the view in a window.\n\nCONTROLS\n");
  for (const std::string& line : control_lines()) std::printf("  %s\n", line.c_str());
  std::printf("\nVIEWER OPTIONS\n%s", mpr_cli::option_help(mpr_cli::Group::viewer, mpr_cli::Tools::view, true).c_str());
  std::printf("\nMPR-RENDER OPTIONS\n");
  for (const mpr_cli::Group g : {mpr_cli::Group::input, mpr_cli::Group::light_field, mpr_cli::Group::image,
                                 mpr_cli::Group::surface, mpr_cli::Group::animation, mpr_cli::Group::run})
    std::printf("%s", mpr_cli::option_help(g, mpr_cli::Tools::view, false).c_str());
  std::printf("\n%s", std::string(mpr_cli::view_help()).c_str());
}

} // namespace mpr_view
