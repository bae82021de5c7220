// mpr-view: an interactive window onto any General Linear Camera view of a scene or a light
// field. Takes mpr-render's command line (the same inputs and view specifications, parsed by
// mpr-render's own code) and renders on a background thread while keys, mouse and wheel change
// the view. See `mpr-view --help` and docs/mpr-view.md.
#include "app.hpp"
#include "benchmark.hpp"
#include "view_options.hpp"

#include <SDL.h>

#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

namespace {

template <std::floating_point T>
int run_typed(const mpr_cli::Job& given, const mpr_view::ViewerSettings& settings,
              const std::vector<mpr_view::ScriptCommand>& script) {
  // Data and every camera are checked before any window opens (mpr-render's preflight).
  const mpr_cli::Loaded<T> loaded = mpr_cli::load<T>(given);
  for (const std::string& note : loaded.notes) std::cout << note << '\n'; // e.g. --depth-maps estimate's time
  // An array's defaults as in mpr-render (light_field_views.hpp): a cylinder of the camera
  // spacing for views other than the reference, and its warnings on stderr.
  // --focus-at and --write-depth as in mpr-render (render_job.hpp): the focus set before the
  // first frame, the depth of the command line's view written once.
  const mpr_cli::Job job = mpr_cli::with_focus_at(mpr_cli::with_array_defaults(given, loaded), loaded, &std::cout);
  mpr_cli::preflight(job, loaded);
  mpr_cli::warn_job(std::cerr, job, loaded);
  mpr_cli::write_view_depth(job, loaded, &std::cout);
  if (settings.benchmark) return mpr_view::run_benchmark(job, loaded, settings.benchmark_frames);
  return mpr_view::run_window(job, loaded, settings, script);
}

} // namespace

int main(int argc, char** argv) try {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
      mpr_view::print_help();
      return 0;
    }
  const auto [job, settings] = mpr_view::parse_command_line(argc, argv);
  std::vector<mpr_view::ScriptCommand> script;
  if (settings.script)
    script = mpr_view::read_script(
        *settings.script, [](const std::string& name) { return SDL_GetKeyFromName(name.c_str()) != SDLK_UNKNOWN; });
  return job.use_double ? run_typed<double>(job, settings, script) : run_typed<float>(job, settings, script);
} catch (const std::exception& e) {
  // One line, as mpr-render: "mpr-view: invalid --size: ...", "mpr-view: script.txt:3: ...".
  std::string what = e.what();
  if (what.rfind("mpr: ", 0) == 0) what.erase(0, 5);
  for (char& c : what)
    if (c == '\n') c = ' ';
  std::fprintf(stderr, "mpr-view: %s\n", what.c_str());
  return 1;
}
