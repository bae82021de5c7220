// mpr-view: an interactive window onto any General Linear Camera view of a scene or a light
// field. Takes mpr-render's command line (the same inputs and view specifications, parsed by
// mpr-render's own code) and renders on a background thread while keys, mouse and wheel change
// the view. See `mpr-view --help` and docs/mpr-view.md.
#include "app.hpp"
#include "benchmark.hpp"
#include "mpr-render/error_line.hpp"
#include "view_options.hpp"
#include "viewer.hpp"

#include <SDL.h>

#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

int main(int argc, char** argv) try {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
      mpr_view::print_help();
      return 0;
    }
  const auto [job, settings] = mpr_view::parse_command_line(argc, argv);
  mpr_cli::check_output_folder(job.output, "--output");
  std::vector<mpr_view::ScriptCommand> script;
  if (settings.script)
    script = mpr_view::read_script(
        *settings.script, [](const std::string& name) { return SDL_GetKeyFromName(name.c_str()) != SDLK_UNKNOWN; });
  return job.use_double ? mpr_view::run_viewer<double>(job, settings, script)
                        : mpr_view::run_viewer<float>(job, settings, script);
} catch (const std::exception& e) {
  // One line, as mpr-render: "mpr-view: invalid --size: ...", "mpr-view: script.txt:3: ...".
  std::fprintf(stderr, "mpr-view: %s\n", mpr_cli::error_line(e.what()).c_str());
  return 1;
}
