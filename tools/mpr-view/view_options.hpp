#pragma once
// mpr-view's command line: every mpr-render option (options.hpp of mpr-render, parsed into the
// same Job by make_job) plus the viewer's own (--script, --benchmark, --benchmark-frames).

#include "mpr-render/cli_args.hpp"
#include "mpr-render/job.hpp"
#include "mpr-render/options.hpp"
#include "overlay.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mpr_view {

/// The options only mpr-view has.
inline const std::vector<mpr_cli::OptionSpec>& viewer_options() {
  static const std::vector<mpr_cli::OptionSpec> specs = {
      {"script", "FILE",
       "Drive the window from a script of timed events (wait MS, key NAME, drag X0,Y0 X1,Y1 [BUTTON], wheel N, "
       "click X,Y, screenshot PATH) and exit when it ends; errors are reported before the window opens.",
       "--script tests/view.txt"},
      {"benchmark", "",
       "Open no window: render the view repeatedly through the viewer's render thread and print frames/s and the "
       "time from an input event to the first quarter-resolution frame.",
       "--benchmark --size 960x540 --threads 2"},
      {"benchmark-frames", "N", "Frames per benchmark measurement (default 30).", "--benchmark-frames 10"},
  };
  return specs;
}

/// mpr-render's options (except its animation-file ones, which keep their meaning: --frames
/// gives the frames to step through, --output the base name of saved PNGs) and the viewer's.
inline std::vector<mpr_cli::OptionSpec> all_options() {
  std::vector<mpr_cli::OptionSpec> specs = mpr_cli::options();
  for (const mpr_cli::OptionSpec& s : viewer_options()) specs.push_back(s);
  return specs;
}

/// The viewer's settings besides the Job.
struct ViewerSettings {
  std::optional<std::filesystem::path> script;
  bool benchmark = false;
  int benchmark_frames = 30;
  bool output_given = false; ///< --output: base name of the PNGs `S` saves (else mpr-view.png)
};

/// Parses the command line; throws mpr::argument_error naming the option.
inline std::pair<mpr_cli::Job, ViewerSettings> parse_command_line(int argc, const char* const* argv) {
  const mpr_cli::ParsedArgs args = mpr_cli::parse_args(argc, argv, all_options());
  ViewerSettings v;
  if (args.has("shard"))
    throw mpr::argument_error("--shard", "splits mpr-render's frames between processes; the viewer shows them all");
  for (const char* option : {"bit-depth", "exr-pixel"})
    if (args.has(option))
      throw mpr::argument_error(std::string("--") + option, "sets mpr-render's output file; the viewer saves 8-bit PNG");
  mpr_cli::Job job = mpr_cli::make_job(args, {.reads_depth_maps = true}); // click-to-focus reads them
  if (const auto s = args.get("script")) {
    if (s->empty()) throw mpr::argument_error("--script", "empty file name");
    v.script = *s;
  }
  v.benchmark = args.has("benchmark");
  if (v.benchmark && v.script) throw mpr::argument_error("--benchmark", "give --benchmark or --script, not both");
  if (const auto n = args.get("benchmark-frames"))
    v.benchmark_frames = mpr_cli::parse_int(*n, "--benchmark-frames", 1, 10000);
  v.output_given = args.has("output");
  if (!v.output_given) job.output = "mpr-view.png";
  return {job, v};
}

inline void print_help() {
  std::printf("usage: mpr-view [OPTIONS]\n\nAn interactive window onto General Linear Camera views of a scene or a "
              "light field.\nTakes every mpr-render option (the same inputs and VIEW specifications) and opens "
              "the view in a window.\n\nCONTROLS\n");
  for (const std::string& line : control_lines()) std::printf("  %s\n", line.c_str());
  std::printf("\nVIEWER OPTIONS\n");
  for (const mpr_cli::OptionSpec& s : viewer_options()) {
    const std::string head = "--" + s.name + (s.value.empty() ? "" : " " + s.value);
    std::printf("  %s\n      %s\n      e.g. %s\n", head.c_str(), s.help.c_str(), s.example.c_str());
  }
  std::printf("\nMPR-RENDER OPTIONS (--output: base name of the PNGs that S saves, default mpr-view.png; --frames N: "
              "the frames ',' and '.' step through)\n");
  for (const mpr_cli::OptionSpec& s : mpr_cli::options()) {
    if (s.name == "help" || s.name == "no-video" || s.name == "print-camera" || s.name == "shard" ||
        s.name == "bit-depth" || s.name == "exr-pixel")
      continue;
    const std::string head = "--" + s.name + (s.value.empty() ? "" : " " + s.value);
    std::printf("  %s\n      %s\n", head.c_str(), s.help.c_str());
  }
  std::printf("\n%s", mpr_cli::view_help());
}

} // namespace mpr_view
