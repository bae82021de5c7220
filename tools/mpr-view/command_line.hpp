#pragma once
// mpr-view's `S` key: the mpr-render command line that renders the view on screen (one frame:
// animated values are written at the time of the frame shown), with every number written so
// that it reads back to the same double.

#include "mpr-render/job.hpp"

#include <mpr/core/vec.hpp>

#include <cctype>
#include <charconv>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

namespace mpr_view {

namespace detail {

/// The shortest text that reads back as `v` (std::to_chars round trip).
inline std::string number(double v) {
  char text[32];
  const std::to_chars_result r = std::to_chars(text, text + sizeof text, v);
  return std::string(text, r.ptr);
}

inline std::string vec3(const mpr::Vec3<double>& v) {
  return number(v.x()) + "," + number(v.y()) + "," + number(v.z());
}

/// `s` quoted for a POSIX shell when it holds anything but [A-Za-z0-9_./,:=+-].
inline std::string shell_word(const std::string& s) {
  bool plain = !s.empty();
  for (const char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) ||
          std::string_view("_./,:=+-").find(c) != std::string_view::npos))
      plain = false;
  if (plain) return s;
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// --filter NAME:RADIUS of `filter` (mpr-render's parse_filter reads it back).
inline std::string filter_text(const mpr::AnyFilter& filter) {
  const char* name = std::visit(
      [](const auto& f) -> const char* {
        using F = std::remove_cvref_t<decltype(f)>;
        if constexpr (std::is_same_v<F, mpr::BoxFilter>) return "box";
        if constexpr (std::is_same_v<F, mpr::TentFilter>) return "tent";
        if constexpr (std::is_same_v<F, mpr::GaussianFilter>) return "gaussian";
        if constexpr (std::is_same_v<F, mpr::MitchellFilter>) return "mitchell";
        return "lanczos";
      },
      filter.variant());
  return std::string(name) + ":" + number(filter.radius());
}

/// --aperture SHAPE:SIZE of `spec` at animation time `time`.
inline std::string aperture_text(const mpr_cli::ApertureSpec& spec, double time) {
  const std::string shape = std::visit(
      [](const auto& a) -> std::string {
        using A = std::remove_cvref_t<decltype(a)>;
        if constexpr (std::is_same_v<A, mpr::glc::DiscAperture>) return "disc";
        if constexpr (std::is_same_v<A, mpr::glc::SquareAperture>) return "square";
        if constexpr (std::is_same_v<A, mpr::glc::GaussianAperture>) return "gaussian";
        if constexpr (std::is_same_v<A, mpr::glc::PolygonAperture>) return "polygon" + std::to_string(a.blades());
        return "disc";
      },
      spec.shape.variant());
  return shape + ":" + number(spec.size.at(time));
}

} // namespace detail

/// The arguments (without the program name) of the mpr-render command that renders frame
/// `time` of `job` as one image of views `view_width` x `view_height` into `output`.
[[nodiscard]] inline std::vector<std::string> render_arguments(const mpr_cli::Job& job, double time, int view_width,
                                                               int view_height, const std::filesystem::path& output) {
  using mpr_cli::Interpolation;
  using mpr_cli::SamplerKind;
  std::vector<std::string> a;
  const auto add = [&](const std::string& option, const std::string& value) {
    a.push_back(option);
    a.push_back(value);
  };
  switch (job.sampler) {
  case SamplerKind::scene:
    break;
  case SamplerKind::obj:
    add("--obj", job.input.string());
    if (job.obj_scale != 1) add("--obj-scale", detail::number(job.obj_scale));
    break;
  case SamplerKind::par:
    add("--par", job.input.string());
    break;
  case SamplerKind::stanford:
    add("--stanford", job.input.string());
    break;
  case SamplerKind::lfca:
    add("--lfca", job.input.string());
    break;
  case SamplerKind::hci:
    add("--hci", job.input.string());
    break;
  case SamplerKind::colmap:
    add("--colmap", job.input.string());
    if (!job.colmap_images.empty()) add("--colmap-images", job.colmap_images.string());
    break;
  }
  const bool light_field = is_light_field(job.sampler);
  if (job.raster) add("--raster", std::to_string(job.raster->first) + "x" + std::to_string(job.raster->second));
  if (job.raster && job.raster_samples > 1) add("--raster-samples", std::to_string(job.raster_samples));
  if (light_field || job.raster) {
    add("--interp", job.interpolation == Interpolation::nearest     ? "nearest"
                    : job.interpolation == Interpolation::synthetic ? "synthetic"
                    : job.interpolation == Interpolation::depth     ? "depth"
                                                                    : "cylinder");
    if (job.interpolation == Interpolation::cylinder || job.interpolation == Interpolation::depth)
      add("--radius", detail::number(job.radius.at(time)));
    // The depth maps and the proxy's settings shape the image under the depth interpolation
    // only (a focus clicked elsewhere is written as --focal-depth; mpr-render refuses depth
    // maps that nothing reads).
    if (job.interpolation == Interpolation::depth && job.has_depth_maps()) {
      add("--depth-maps", job.depth_maps_arg);
      if (!job.sweep_arg.empty()) add("--sweep", job.sweep_arg);
    }
    if (job.interpolation == Interpolation::depth && !job.proxy_arg.empty()) add("--proxy", job.proxy_arg);
    if (job.focal_depth) add("--focal-depth", detail::number(job.focal_depth->at(time)));
  }
  if (light_field) {
    if (job.reference_depth != 1000) add("--reference-depth", detail::number(job.reference_depth));
    if (job.position_scale != 1) add("--position-scale", detail::number(job.position_scale));
    if (job.camera) add("--camera", std::to_string(*job.camera));
    if (job.prefilter) add("--prefilter", std::to_string(*job.prefilter)); // else auto, as in the viewer
  }
  add("--size", std::to_string(view_width) + "x" + std::to_string(view_height));
  if (job.cols * job.rows > 1) {
    add("--layout", std::to_string(job.cols) + "x" + std::to_string(job.rows));
    std::string views;
    for (std::size_t k = 0; k < job.views.size(); ++k) {
      std::string v = job.views[k];
      for (char& c : v)
        if (c == ',') c = ';';
      views += (k == 0 ? "" : ",") + v;
    }
    add("--views", views);
  } else if (job.views[0] != "default") {
    add("--view", job.views[0]);
  }
  if (job.plane_centre) {
    add("--plane-centre", detail::vec3(*job.plane_centre));
    add("--look-at", detail::vec3(*job.look_at));
    add("--plane-size", detail::number(job.plane_size->first) + "," + detail::number(job.plane_size->second));
  }
  if (job.up != mpr::Vec3<double>(0, 1, 0)) add("--up", detail::vec3(job.up));
  if (const double v = job.tilt_x.at(time); v != 0) add("--tilt-x", detail::number(v));
  if (const double v = job.tilt_y.at(time); v != 0) add("--tilt-y", detail::number(v));
  if (job.rectify_to_plane) {
    add("--rectify", "plane");
  } else if (job.rectify) {
    std::string quad;
    for (std::size_t i = 0; i < 4; ++i) quad += (i == 0 ? "" : ";") + detail::vec3((*job.rectify)[i]);
    add("--rectify", quad);
  }
  if (job.scene_centre) add("--scene-centre", detail::vec3(*job.scene_centre));
  if (job.scene_scale) add("--scene-scale", detail::number(*job.scene_scale));
  if (job.morph_to && job.morph.at(time) != 0) {
    add("--morph-to", *job.morph_to);
    add("--morph", detail::number(job.morph.at(time)));
  }
  if (job.spp > 1) {
    add("--spp", std::to_string(job.spp));
    add("--filter", detail::filter_text(job.filter));
  }
  if (job.aperture) {
    add("--aperture", detail::aperture_text(*job.aperture, time));
    if (job.aperture->distance) add("--lens-distance", detail::number(*job.aperture->distance));
    std::string focus;
    for (const double d : job.aperture->focus) focus += (focus.empty() ? "" : ",") + detail::number(d);
    if (!focus.empty()) add("--focus", focus);
  }
  if (job.threads != 0) add("--threads", std::to_string(job.threads));
  if (job.use_double) a.push_back("--double");
  if (job.no_budget) a.push_back("--no-budget");
  add("--output", output.string());
  return a;
}

/// `render_arguments` as one shell line starting with "mpr-render".
[[nodiscard]] inline std::string render_command(const mpr_cli::Job& job, double time, int view_width, int view_height,
                                                const std::filesystem::path& output) {
  std::string line = "mpr-render";
  for (const std::string& arg : render_arguments(job, time, view_width, view_height, output))
    line.append(" ").append(detail::shell_word(arg)); // not operator+: GCC 12's false -Wrestrict
  return line;
}

} // namespace mpr_view
