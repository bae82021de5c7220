#pragma once
// The parts of the option table (option_table.hpp) and what they share: each section of --help
// is declared in its own file (table_inputs.cpp: the sampler and the light-field options;
// table_image.cpp: the image and its plane; table_run.cpp: animation, output and run, and the
// viewer's own), joined in --help order by option_table(). Included by those files only.

#include "option_table.hpp"

#include <charconv>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace mpr_cli::table {

/// The options of the INPUT and LIGHT FIELDS sections, in --help order.
[[nodiscard]] std::span<const Option> input_options() noexcept;
/// The options of the IMAGE and IMAGE PLANE sections.
[[nodiscard]] std::span<const Option> image_options() noexcept;
/// The options of the ANIMATION, OUTPUT AND RUN and VIEWER sections.
[[nodiscard]] std::span<const Option> run_options() noexcept;

// --- How the save command writes values back (shortest text that reads back the same double).

/// What a save writer returns; kOmit leaves the option out.
using Saved = std::optional<std::string>;
inline constexpr Saved kOmit = std::nullopt;

[[nodiscard]] inline std::string num(double v) {
  char text[32];
  const std::to_chars_result r = std::to_chars(text, text + sizeof text, v);
  return std::string(text, r.ptr);
}
[[nodiscard]] inline std::string vec3(const mpr::Vec3<double>& v) {
  return num(v.x()) + "," + num(v.y()) + "," + num(v.z());
}
[[nodiscard]] inline std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

/// Light fields and --raster: the interpolation's options apply.
[[nodiscard]] inline bool interpolated(const Job& j) { return is_light_field(j.sampler) || j.raster.has_value(); }
/// The depth interpolation's own options (depth maps, proxy) shape the picture.
[[nodiscard]] inline bool depth_interpolated(const Job& j) {
  return interpolated(j) && j.interpolation == Interpolation::depth;
}
/// One view (no --layout).
[[nodiscard]] inline bool single_view(const Job& j) { return j.cols * j.rows == 1; }

// Shorthands of the declarations.
inline constexpr Group input = Group::input, lf = Group::light_field, image = Group::image, surface = Group::surface,
                       anim = Group::animation, run = Group::run, viewer = Group::viewer;
inline constexpr ValueKind flag = ValueKind::flag, integer = ValueKind::integer, number = ValueKind::number,
                           size = ValueKind::size, vec = ValueKind::vec3, track = ValueKind::track,
                           choice = ValueKind::choice;
inline constexpr std::string_view kPositive = "must be positive";

} // namespace mpr_cli::table
