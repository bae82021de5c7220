#pragma once
// mpr-view's run for one scalar type: the data loaded and checked before any window opens (as
// mpr-render does), then the window or the benchmark. Compiled once per type
// (viewer_float.cpp, viewer_double.cpp) so that no unit of the viewer holds both.

#include "app.hpp"
#include "benchmark.hpp"
#include "script.hpp"
#include "view_options.hpp"

#include <concepts>
#include <iostream>
#include <string>
#include <vector>

namespace mpr_view {

/// Loads, checks and shows `given` (see the file comment); returns the exit status.
template <std::floating_point T>
int run_viewer(const mpr_cli::Job& given, const ViewerSettings& settings, const std::vector<ScriptCommand>& script) {
  // Data and every camera are checked before any window opens (mpr-render's preflight).
  mpr_cli::check_ranges<T>(given);
  const mpr_cli::Loaded<T> loaded = mpr_cli::load<T>(given);
  for (const std::string& note : loaded.notes) std::cout << note << '\n'; // e.g. --depth-maps estimate's time
  // An array's defaults as in mpr-render (light_field_views.hpp): a cylinder of the camera
  // spacing for views other than the reference, and its warnings on stderr.
  // --focus-at and --write-depth as in mpr-render (render_job.hpp): the focus set before the
  // first frame, the depth of the command line's view written once.
  const mpr_cli::Job job = mpr_cli::with_focus_at(mpr_cli::with_array_defaults(given, loaded), loaded, &std::cout);
  mpr_cli::preflight(job, loaded);
  mpr_cli::save_depth_maps(job, loaded, &std::cout);
  mpr_cli::warn_job(std::cerr, job, loaded);
  mpr_cli::write_view_depth(job, loaded, &std::cout);
  if (settings.benchmark) return run_benchmark(job, loaded, settings.benchmark_frames);
  return run_window(job, loaded, settings, script);
}

extern template int run_viewer<float>(const mpr_cli::Job&, const ViewerSettings&, const std::vector<ScriptCommand>&);
extern template int run_viewer<double>(const mpr_cli::Job&, const ViewerSettings&, const std::vector<ScriptCommand>&);

} // namespace mpr_view
