#pragma once
// mpr-view's picture on screen: the rendered frame scaled to the window, the one-line HUD (view,
// GLC type from mpr::glc::classify, focal depth, aperture, frame time) and the help overlay.

#include "controls.hpp"
#include "font.hpp"
#include "mpr-render/job.hpp"
#include "render_thread.hpp"

#include <mpr/core/image.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace mpr_view {

/// The controls, one per line, for --help and the overlay (F1).
inline const std::vector<std::string>& control_lines() {
  static const std::vector<std::string> lines = {
      "A-I          gallery GLC (A pinhole .. I bilinear)",
      "M / N        morph to / from the previous GLC",
      "left drag    orbit plane (light field: tilt it)",
      "right drag   pan plane (scenes)",
      "wheel        focal depth (scenes: dolly)",
      "shift+wheel  dolly (also PageUp / PageDown)",
      "arrows       tilt plane (T: level it)",
      "1 2 3        nearest / synthetic / cylinder",
      "[ ]          aperture radius smaller / larger",
      "R            rectification on / off",
      ", .          animation frame back / on",
      "click        ray under the cursor (--raster, --depth-maps: focus there)",
      "S            save PNG + mpr-render command",
      "0            back to the command line's view",
      "F1 or /      help; Esc or Q: quit",
  };
  return lines;
}

/// The HUD text: view, GLC type, focal depth, aperture and frame time, then (when not zero) the
/// plane's tilt about its x and y axes ("tilt X,Y", degrees) and a scene plane's orbit from the
/// command line's view ("orbit AZIMUTH,ELEVATION", degrees, orbit_degrees).
[[nodiscard]] inline std::string hud_text(const ViewState& s, const ViewContext& ctx, const RenderedFrame& frame) {
  if (!frame.error.empty()) return "CANNOT RENDER: " + frame.error;
  std::string view = s.job.views.size() == 1 ? s.job.views[0] : std::to_string(s.job.views.size()) + " views";
  if (view.size() > 12) view = view.substr(0, 12) + "~";
  char text[256];
  std::string focus = "-", aperture = "-";
  if (ctx.has_focus()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4g", s.job.focal_depth ? current_focal_depth(s, ctx) : frame.focal_depth);
    focus = buf;
    if (s.job.interpolation == mpr_cli::Interpolation::cylinder) {
      std::snprintf(buf, sizeof buf, "r %.3g", s.job.radius.at(s.time()));
      aperture = buf;
    } else {
      aperture = mpr_cli::interpolation_name(s.job.interpolation); // mpr::interpolation_names
    }
  }
  const std::string preview = frame.full ? "" : " (1/" + std::to_string(frame.scale * frame.scale) + ")";
  if (ctx.has_focus())
    std::snprintf(text, sizeof text, "%s %s | focus %s | %s | %.1f ms%s", view.c_str(), frame.type.c_str(),
                  focus.c_str(), aperture.c_str(), frame.milliseconds, preview.c_str());
  else
    std::snprintf(text, sizeof text, "%s %s | %.1f ms%s", view.c_str(), frame.type.c_str(), frame.milliseconds,
                  preview.c_str());
  std::string out = text;
  if (s.job.morph_to && s.job.morph.at(s.time()) != 0) {
    std::snprintf(text, sizeof text, " | morph %.3g to %s", s.job.morph.at(s.time()), s.job.morph_to->c_str());
    out += text;
  }
  if (s.job.frames > 1) out += " | frame " + std::to_string(s.frame + 1) + "/" + std::to_string(s.job.frames);
  if (const double tx = s.job.tilt_x.at(s.time()), ty = s.job.tilt_y.at(s.time()); tx != 0 || ty != 0) {
    std::snprintf(text, sizeof text, " | tilt %.3g,%.3g", tx, ty);
    out += text;
  }
  // Below 0.005 degrees: rounding of the rotations, shown as 0.
  const auto shown = [](double degrees) { return std::abs(degrees) < 0.005 ? 0.0 : degrees; };
  if (const auto [azimuth, elevation] = orbit_degrees(s, ctx); shown(azimuth) != 0 || shown(elevation) != 0) {
    std::snprintf(text, sizeof text, " | orbit %.3g,%.3g", shown(azimuth), shown(elevation));
    out += text;
  }
  return out;
}

/// Draws `picture` (any size; scaled to fill `out` by nearest pixel), then the HUD bar at the
/// bottom and, when `help`, the controls over a darkened picture.
inline void compose(mpr::ImageView<mpr::Rgb8> out, mpr::ImageView<const mpr::Rgb8> picture, const std::string& hud,
                    bool hud_is_error, bool help) {
  const int W = out.width(), H = out.height();
  if (!picture.empty()) {
    for (int y = 0; y < H; ++y) {
      const mpr::Rgb8* src = picture.row(static_cast<int>(static_cast<long>(y) * picture.height() / H));
      mpr::Rgb8* dst = out.row(y);
      for (int x = 0; x < W; ++x) dst[x] = src[static_cast<long>(x) * picture.width() / W];
    }
  } else {
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) out(x, y) = mpr::Rgb8{40, 40, 40};
  }
  const int scale = font_scale(W), bar = hud_height(W);
  darken(out, 0, H - bar, W, bar, 48);
  const mpr::Rgb8 ink = hud_is_error ? mpr::Rgb8{255, 110, 90} : mpr::Rgb8{255, 255, 180};
  draw_text(out, 2 * scale, H - bar + scale, hud, ink, scale);
  if (help) {
    darken(out, 0, 0, W, H - bar, 72);
    int y = 2 * scale;
    draw_text(out, 2 * scale, y, "MPR-VIEW CONTROLS", mpr::Rgb8{255, 255, 255}, scale);
    y += 2 * kLineHeight * scale;
    for (const std::string& line : control_lines()) {
      draw_text(out, 2 * scale, y, line, mpr::Rgb8{220, 230, 255}, scale);
      y += kLineHeight * scale;
    }
  }
}

} // namespace mpr_view
