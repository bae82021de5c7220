#pragma once
// mpr-view's controls: keys, drags and the wheel -> changes of the view, which is kept as an
// mpr-render Job (so every view the user reaches is an mpr-render command line,
// command_line.hpp). Independent of SDL: keys arrive by their SDL names ("G", "Left", "F1").

#include "mpr-render/job.hpp"

#include <mpr/core/vec.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

namespace mpr_view {

/// What the sampler allows the controls to change (from the loaded data, fixed for a session).
struct ViewContext {
  bool light_field = false; ///< --par/--stanford/--lfca: the image plane is the reference camera's focal plane
  bool raster = false;      ///< --raster: a scene sampled through a virtual camera array
  /// Scenes: the image plane the job starts from (centre, the point it faces, extent), world units.
  mpr::Vec3<double> plane_centre{0, 0, 1}, look_at{0, 0, 0};
  double plane_width = 1, plane_height = 1;
  /// The focal depth in use when the job gives none (light fields: the reference plane; raster:
  /// the median depth the array chose, known after its first render).
  double focal_depth = 1;
  /// Arrays: the interpolation and radius mpr-render's defaults give a gallery letter (a
  /// ray-dependent one; see `mpr_cli::with_array_defaults`), applied by the letter keys unless
  /// the command line chose them.
  std::optional<mpr_cli::Interpolation> letter_interpolation;
  std::optional<mpr_cli::Track> letter_radius;
  /// Does the focal depth (wheel) apply? Light fields and rasterized arrays.
  [[nodiscard]] bool has_focus() const noexcept { return light_field || raster; }
};

/// The interactive state: the view as a Job plus what the window shows around it.
struct ViewState {
  mpr_cli::Job job;
  int frame = 0;        ///< animation frame shown (job.frames >= 1), from 0
  bool help = false;    ///< help overlay shown
  char last_letter = 0; ///< the gallery letter chosen before the current one (morph target)
  std::optional<std::array<mpr::Vec3<double>, 4>> saved_rectify; ///< the --rectify quad while toggled off

  /// The animation time of the frame shown (0 for a single image).
  [[nodiscard]] double time() const noexcept { return mpr_cli::frame_time(frame, std::max(job.frames, 1)); }
};

/// The result of an input event.
enum class Action {
  none,    ///< nothing changed
  redraw,  ///< the overlay changed (help), not the view
  changed, ///< the view changed: render again
  save,    ///< save a PNG and its mpr-render command line
  quit
};

enum class Button { left, middle, right };

/// Tuning of the controls (degrees, fractions and factors per event).
struct ControlConfig {
  double orbit_degrees_per_pixel = 0.3; ///< scenes: left drag
  double tilt_degrees_per_pixel = 0.2;  ///< light fields: left drag
  double tilt_key_degrees = 2;          ///< arrow keys
  double max_tilt_degrees = 80;         ///< |tilt| limit (mpr-render refuses 89)
  double focus_factor = 1.03;           ///< focal depth factor per wheel notch
  double dolly_factor = 0.9;            ///< distance to the look-at point per dolly notch
  double radius_factor = 1.25;          ///< aperture radius factor per '[' / ']'
  double morph_step = 0.125;            ///< morph weight per 'M' / 'N'
};

namespace detail {

inline double clamp_tilt(double degrees, const ControlConfig& c) {
  return std::clamp(degrees, -c.max_tilt_degrees, c.max_tilt_degrees);
}

/// Scenes: makes the job's image plane explicit (plane centre, look-at, size), so that orbit,
/// pan and dolly can move it and the command line can state it.
inline void make_plane_explicit(mpr_cli::Job& job, const ViewContext& ctx) {
  if (job.plane_centre) return;
  job.plane_centre = ctx.plane_centre;
  job.look_at = ctx.look_at;
  job.plane_size = std::pair<double, double>{ctx.plane_width, ctx.plane_height};
}

inline mpr::Vec3<double> rotate(const mpr::Vec3<double>& v, const mpr::Vec3<double>& axis, double degrees) {
  const Eigen::AngleAxisd r(degrees * std::numbers::pi / 180, axis.normalized());
  return r * v;
}

} // namespace detail

/// The focal depth shown now (a job value at the frame's time, or the context's default).
[[nodiscard]] inline double current_focal_depth(const ViewState& s, const ViewContext& ctx) {
  return s.job.focal_depth ? s.job.focal_depth->at(s.time()) : ctx.focal_depth;
}

/// Scenes: how far the image plane has orbited from the command line's (ViewContext's plane
/// centre and look-at): {azimuth, elevation} in degrees, the azimuth about the job's up direction
/// (counter-clockwise seen from above: a left drag to the left is positive), the elevation the
/// change of the angle above the plane normal to up. {0, 0} for light fields and before any
/// orbit, pan or dolly; a pan or dolly alone leaves both at 0.
[[nodiscard]] inline std::pair<double, double> orbit_degrees(const ViewState& s, const ViewContext& ctx) {
  if (ctx.light_field || !s.job.plane_centre || !s.job.look_at) return {0, 0};
  const mpr::Vec3<double> up = s.job.up.normalized();
  const mpr::Vec3<double> from = ctx.plane_centre - ctx.look_at, to = *s.job.plane_centre - *s.job.look_at;
  if (!(from.norm() > 0) || !(to.norm() > 0) || !up.allFinite()) return {0, 0};
  const mpr::Vec3<double> h0 = from - from.dot(up) * up, h1 = to - to.dot(up) * up;
  constexpr double degrees = 180 / std::numbers::pi;
  const double azimuth = std::atan2(up.dot(h0.cross(h1)), h0.dot(h1)) * degrees;
  const auto elevation = [&](const mpr::Vec3<double>& a) {
    return std::asin(std::clamp(a.normalized().dot(up), -1.0, 1.0));
  };
  return {azimuth, (elevation(to) - elevation(from)) * degrees};
}

/// A key press, by SDL key name ("G", "Left", "F1", "[", "Escape").
inline Action on_key(ViewState& s, const ViewContext& ctx, const std::string& key, const ControlConfig& c = {}) {
  mpr_cli::Job& job = s.job;
  const double t = s.time();
  if (key == "Escape" || key == "Q") return Action::quit;
  if (key == "F1" || key == "/" || key == "?") {
    s.help = !s.help;
    return Action::redraw;
  }
  if (key == "S") return Action::save;
  if (key.size() == 1 && key[0] >= 'A' && key[0] <= 'I') {
    const char letter = key[0];
    const std::string current = job.views.size() == 1 ? job.views[0] : std::string();
    if (current.size() == 1 && current[0] != letter) s.last_letter = current[0];
    if (job.views.size() == 1 && current == std::string(1, letter)) return Action::none;
    job.views = {std::string(1, letter)};
    job.cols = job.rows = 1;
    if (!job.interpolation_given && !job.radius_given && ctx.letter_interpolation) {
      job.interpolation = *ctx.letter_interpolation;
      if (ctx.letter_radius) job.radius = *ctx.letter_radius;
    }
    return Action::changed;
  }
  if (key == "Left" || key == "Right") {
    job.tilt_y =
        mpr_cli::Track(detail::clamp_tilt(job.tilt_y.at(t) + (key == "Right" ? 1 : -1) * c.tilt_key_degrees, c));
    return Action::changed;
  }
  if (key == "Up" || key == "Down") {
    job.tilt_x = mpr_cli::Track(detail::clamp_tilt(job.tilt_x.at(t) + (key == "Up" ? 1 : -1) * c.tilt_key_degrees, c));
    return Action::changed;
  }
  if (key == "T") { // level the plane
    if (job.tilt_x.at(t) == 0 && job.tilt_y.at(t) == 0) return Action::none;
    job.tilt_x = job.tilt_y = mpr_cli::Track(0);
    return Action::changed;
  }
  if (key == "R") {
    if (job.rectify || job.rectify_to_plane) {
      if (job.rectify) s.saved_rectify = job.rectify;
      job.rectify.reset();
      job.rectify_to_plane = false;
    } else if (s.saved_rectify) {
      job.rectify = s.saved_rectify;
    } else {
      job.rectify_to_plane = true;
    }
    return Action::changed;
  }
  if (ctx.has_focus() && (key == "1" || key == "2" || key == "3")) {
    const mpr_cli::Interpolation next = key == "1"   ? mpr_cli::Interpolation::nearest
                                        : key == "2" ? mpr_cli::Interpolation::synthetic
                                                     : mpr_cli::Interpolation::cylinder;
    if (next == job.interpolation) return Action::none;
    job.interpolation = next;
    return Action::changed;
  }
  if (ctx.has_focus() && (key == "[" || key == "]")) {
    const double r = job.radius.at(t) * (key == "]" ? c.radius_factor : 1 / c.radius_factor);
    job.radius = mpr_cli::Track(std::clamp(r, 1e-6, 1e6));
    job.interpolation = mpr_cli::Interpolation::cylinder;
    return Action::changed;
  }
  if (key == "M" || key == "N") {
    if (!job.morph_to) {
      const std::string current = job.views.size() == 1 ? job.views[0] : std::string();
      job.morph_to = s.last_letter != 0 ? std::string(1, s.last_letter) : (current == "G" ? "A" : "G");
      job.morph = mpr_cli::Track(0);
    }
    double w = job.morph.at(t) + (key == "M" ? c.morph_step : -c.morph_step);
    if (w > 1 + 1e-9) w = 0;
    if (w < -1e-9) w = 1;
    job.morph = mpr_cli::Track(std::clamp(w, 0.0, 1.0));
    return Action::changed;
  }
  if (key == "PageUp" || key == "PageDown") {
    if (ctx.light_field) return Action::none;
    detail::make_plane_explicit(job, ctx);
    const double f = key == "PageUp" ? c.dolly_factor : 1 / c.dolly_factor;
    const mpr::Vec3<double> away = *job.plane_centre - *job.look_at;
    job.plane_centre = mpr::Vec3<double>(*job.look_at + f * away);
    return Action::changed;
  }
  if ((key == "," || key == ".") && job.frames > 1) {
    const int next = std::clamp(s.frame + (key == "." ? 1 : -1), 0, job.frames - 1);
    if (next == s.frame) return Action::none;
    s.frame = next;
    return Action::changed;
  }
  return Action::none;
}

/// The mouse wheel, `notches` > 0 away from the user: the focal depth farther (light fields,
/// --raster), or with `dolly` (Shift held; always for plain scenes) the image plane nearer to
/// the point it faces.
inline Action on_wheel(ViewState& s, const ViewContext& ctx, int notches, bool dolly, const ControlConfig& c = {}) {
  if (notches == 0) return Action::none;
  if (ctx.has_focus() && !dolly) {
    const double d = current_focal_depth(s, ctx) * std::pow(c.focus_factor, notches);
    s.job.focal_depth = mpr_cli::Track(std::clamp(d, 1e-6, 1e12));
    return Action::changed;
  }
  if (ctx.light_field) return Action::none;
  detail::make_plane_explicit(s.job, ctx);
  const mpr::Vec3<double> away = *s.job.plane_centre - *s.job.look_at;
  s.job.plane_centre = mpr::Vec3<double>(*s.job.look_at + std::pow(c.dolly_factor, notches) * away);
  return Action::changed;
}

/// A drag of (dx, dy) window pixels in a window of `width` x `height`. Scenes: left orbits the
/// image plane about the point it faces, right (or middle) pans it. Light fields: left tilts
/// the focal plane (the image plane is the reference camera's, so it does not orbit or pan).
inline Action on_drag(ViewState& s, const ViewContext& ctx, Button button, double dx, double dy, int width, int height,
                      const ControlConfig& c = {}) {
  if (dx == 0 && dy == 0) return Action::none;
  mpr_cli::Job& job = s.job;
  const double t = s.time();
  if (ctx.light_field) {
    if (button != Button::left) return Action::none;
    job.tilt_y = mpr_cli::Track(detail::clamp_tilt(job.tilt_y.at(t) + dx * c.tilt_degrees_per_pixel, c));
    job.tilt_x = mpr_cli::Track(detail::clamp_tilt(job.tilt_x.at(t) - dy * c.tilt_degrees_per_pixel, c));
    return Action::changed;
  }
  detail::make_plane_explicit(job, ctx);
  const mpr::Vec3<double> centre = *job.plane_centre, look = *job.look_at, up = job.up;
  const mpr::Vec3<double> forward = (look - centre).normalized();
  const mpr::Vec3<double> right = forward.cross(up).normalized(); // as framing.hpp's base_plane
  if (!right.allFinite()) return Action::none;
  if (button == Button::left) {
    mpr::Vec3<double> away = centre - look;
    away = detail::rotate(away, up, -dx * c.orbit_degrees_per_pixel);
    const mpr::Vec3<double> pitched = detail::rotate(away, right, dy * c.orbit_degrees_per_pixel);
    // Keep the viewing direction at least 5 degrees from the up direction.
    const double cosine = pitched.normalized().dot(up.normalized());
    if (std::abs(cosine) < std::cos(5 * std::numbers::pi / 180)) away = pitched;
    job.plane_centre = mpr::Vec3<double>(look + away);
    return Action::changed;
  }
  const mpr::Vec3<double> down = forward.cross(right);
  const auto [w, h] = *job.plane_size;
  const mpr::Vec3<double> shift = -(dx / std::max(width, 1)) * w * right - (dy / std::max(height, 1)) * h * down;
  job.plane_centre = mpr::Vec3<double>(centre + shift);
  job.look_at = mpr::Vec3<double>(look + shift);
  return Action::changed;
}

} // namespace mpr_view
