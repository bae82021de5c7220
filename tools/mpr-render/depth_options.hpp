#pragma once
// mpr-render's options of depth maps and the depth proxy: --depth-maps estimate:, --sweep and
// --proxy, each parsed into the library's config struct (mpr::PlaneSweepConfig, mpr::DepthProxy).

#include "cli_args.hpp"

#include <mpr/core/error.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/depth_proxy.hpp>
#include <mpr/render/policy_names.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace mpr_cli {

/// `--depth-maps estimate[:NEAR:FAR[:PLANES]]`: the plane sweep of `mpr::estimate_scene_depth` over
/// depths NEAR to FAR along each camera's axis (world units; without them, the range the
/// calibration and the images give, `mpr::sweep_range`), PLANES planes (default 64), the other
/// settings at their defaults. Throws argument_error naming --depth-maps.
[[nodiscard]] inline mpr::PlaneSweepConfig parse_depth_estimate(const std::string& text) {
  const std::vector<std::string> f = split(text, ':');
  if (f[0] == "estimate" && f.size() == 1) return {}; // near = far = 0: from the calibration
  if (f[0] != "estimate" || f.size() < 3 || f.size() > 4)
    throw mpr::argument_error("--depth-maps", "'" + text +
                                                  "': give a FOLDER of PFMs, estimate (the depth range from the "
                                                  "calibration) or estimate:NEAR:FAR[:PLANES] (the depth range to "
                                                  "sweep along the cameras' axes, e.g. estimate:600:1400)");
  mpr::PlaneSweepConfig c;
  c.near = parse_number(f[1], "--depth-maps");
  c.far = parse_number(f[2], "--depth-maps");
  if (!(c.near > 0) || !(c.far > c.near))
    throw mpr::argument_error("--depth-maps", "'" + text + "': needs 0 < NEAR < FAR");
  if (f.size() == 4) c.planes = parse_int(f[3], "--depth-maps", 2, 1024);
  return c;
}

/// Calls set(key, value, option) for each KEY=VALUE of `text` (comma-separated), option being
/// "OPTION KEY"; throws argument_error naming `option` for an item that is not KEY=VALUE and
/// "OPTION KEY" for a key given twice. Returns the keys in order.
template <class Set>
std::vector<std::string> for_each_setting(const std::string& text, const std::string& option, const char* keys,
                                          Set&& set) {
  std::vector<std::string> given;
  for (const std::string& item : split(text, ',')) {
    const std::size_t eq = item.find('=');
    const std::string key = item.substr(0, eq);
    if (eq == std::string::npos || eq + 1 == item.size())
      throw mpr::argument_error(option, "'" + item + "' is not KEY=VALUE (" + keys + ")");
    if (std::find(given.begin(), given.end(), key) != given.end())
      throw mpr::argument_error(option + " " + key, "given twice");
    given.push_back(key);
    set(key, item.substr(eq + 1), option + " " + key);
  }
  return given;
}

/// `--sweep KEY=VALUE[,KEY=VALUE...]`: the other settings of the plane sweep of `--depth-maps
/// estimate:` (keys selection (axes or nearest), neighbours, best, truncation, spatial, range:
/// `mpr::PlaneSweepConfig`), set in `c`, each key at most once. Throws argument_error naming --sweep and the key.
inline void parse_sweep(const std::string& text, mpr::PlaneSweepConfig& c) {
  const char* keys = "keys: selection, neighbours, best, truncation, spatial, range";
  const std::vector<std::string> given = for_each_setting(
      text, "--sweep", keys, [&](const std::string& key, const std::string& value, const std::string& option) {
        if (key == "selection") {
          c.selection = mpr::choose(mpr::neighbour_selection_names, value, option);
        } else if (key == "neighbours")
          c.neighbours = parse_int(value, option, 1, 32);
        else if (key == "best")
          c.best = parse_int(value, option, 1, 32);
        else if (key == "truncation")
          c.truncation = parse_number(value, option);
        else if (key == "spatial")
          c.spatial = parse_number(value, option);
        else if (key == "range")
          c.range = parse_number(value, option);
        else
          throw mpr::argument_error("--sweep", "unknown key '" + key + "' (" + keys + ")");
      });
  if (c.best > c.neighbours) {
    const bool default_best = std::find(given.begin(), given.end(), "best") == given.end();
    throw mpr::argument_error("--sweep best", std::to_string(c.best) + (default_best ? " (the default)" : "") +
                                                  " exceeds neighbours (" + std::to_string(c.neighbours) +
                                                  "): give best=1.." + std::to_string(c.neighbours));
  }
  // Every other rule is mpr::validate's (a truncation above 3 acts as 3), under the option's name.
  try {
    mpr::validate(c);
  } catch (const mpr::argument_error& e) {
    const bool key = std::find(given.begin(), given.end(), e.parameter()) != given.end();
    throw mpr::argument_error((key ? "--sweep " : "--depth-maps ") + e.parameter(), e.reason());
  }
}

/// `--proxy KEY=VALUE[,KEY=VALUE...]`: the depth proxy's settings but its radius (keys k,
/// tolerance, visibility_tolerance, march_cameras, whole_line: `mpr::DepthProxy`), set in `p`,
/// each key at most once. Throws argument_error naming --proxy and the key.
inline void parse_proxy(const std::string& text, mpr::DepthProxy& p) {
  const char* keys = "keys: k, tolerance, visibility_tolerance, march_cameras, whole_line";
  for_each_setting(text, "--proxy", keys,
                   [&](const std::string& key, const std::string& value, const std::string& option) {
                     if (key == "k")
                       p.k = parse_int(value, option, 1, 1024); // DepthProxy::validate has the bound
                     else if (key == "tolerance")
                       p.tolerance = parse_number(value, option);
                     else if (key == "visibility_tolerance")
                       p.visibility_tolerance = parse_number(value, option);
                     else if (key == "march_cameras")
                       p.march_cameras = parse_int(value, option, 1, 64);
                     else if (key == "whole_line")
                       p.whole_line = parse_int(value, option, 0, 1) == 1;
                     else
                       throw mpr::argument_error("--proxy", "unknown key '" + key + "' (" + keys + ")");
                   });
  try { // every other rule is DepthProxy::validate's, under the option's name
    p.validate();
  } catch (const mpr::argument_error& e) {
    throw mpr::argument_error("--proxy " + e.parameter(), e.reason());
  }
}

} // namespace mpr_cli
