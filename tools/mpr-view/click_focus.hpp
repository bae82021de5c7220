#pragma once
// mpr-view's click-to-focus: a click on a light field with depth maps (--depth-maps) or on a
// rasterized array (--raster) is mpr-render's --focus-at on the current view, so the viewer and
// `mpr-render --focus-at X,Y` choose the same focal depth.

#include "mpr-render/depth_output.hpp"
#include "mpr-render/job.hpp"
#include "mpr-render/loading.hpp"

#include <mpr/core/error.hpp>

#include <optional>
#include <ostream>
#include <utility>

namespace mpr_view {

/// Whether a click can set the focus of `l`: a light field whose frames carry depth maps, or a
/// rasterized array (whose scene gives the depth).
template <std::floating_point T>
[[nodiscard]] bool click_focuses(const mpr_cli::Job& job, const mpr_cli::Loaded<T>& l) {
  return (l.frames && l.frames->has_depth()) || (job.raster && l.scene);
}

/// The focal depth a click at window pixel (x, y) sets on `job` (mpr_cli::with_focus_at, which
/// prints its choice to `out`), or nothing where the click cannot focus (`click_focuses`) or
/// nothing is seen there (the reason printed to `out`).
template <std::floating_point T>
[[nodiscard]] std::optional<double> click_focus(const mpr_cli::Job& job, const mpr_cli::Loaded<T>& l, int x, int y,
                                                std::ostream& out) {
  if (!click_focuses(job, l)) return std::nullopt;
  mpr_cli::Job j = job;
  j.focus_at = std::pair{x, y};
  try {
    j = mpr_cli::with_focus_at(j, l, &out);
  } catch (const mpr::error& e) {
    out << "no focus: " << e.what() << "\n";
    return std::nullopt;
  }
  if (!j.focal_depth) return std::nullopt;
  return j.focal_depth->at(0);
}

} // namespace mpr_view
