#pragma once
// mpr-view's `S` key: the mpr-render command line that renders the view on screen (one frame:
// animated values are written at the time of the frame shown). Written from the option table
// (tools/options/save_command.hpp), so no option name is spelled here.

#include "mpr-render/job.hpp"
#include "options/save_command.hpp"

#include <filesystem>
#include <string>
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
  return mpr_cli::save_arguments(job, time, view_width, view_height, output);
}

/// `render_arguments` as one shell line starting with "mpr-render".
[[nodiscard]] inline std::string render_command(const mpr_cli::Job& job, double time, int view_width, int view_height,
                                                const std::filesystem::path& output) {
  return mpr_cli::save_command(job, time, view_width, view_height, output);
}

} // namespace mpr_view
