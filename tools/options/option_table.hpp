#pragma once
// The one declared option table of mpr-render and mpr-view: every option once, with its name,
// value placeholder, help, default, value kind, validation (range or choices), the tools that
// take it, and how the viewer's "save command" writes it back from a Job. The parser
// (parse.hpp, CLI11), the --help text (help.hpp), the Job (make_job.hpp) and the save command
// (save_command.hpp) all read this table; no other file spells an option's name for them.

#include "mpr-render/job.hpp"

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace mpr_cli {

/// What an option's value is; the kind decides how OptionValues parses and checks it.
enum class ValueKind {
  flag,    ///< no value
  integer, ///< an integer in [lo, hi] (lo_open / hi_open ignored)
  number,  ///< a finite number within the bounds, else `bound_text`
  size,    ///< WxH, both in [1, 16384]
  vec3,    ///< x,y,z
  track,   ///< an animatable number (animation.hpp), every key within the bounds, else `bound_text`
  choice,  ///< one of `choices`
  text,    ///< anything; checked by the option's own parser (named in its help)
};

/// The tools that take an option (a bit mask).
enum class Tools : std::uint8_t { render = 1, view = 2, both = 3 };

/// Whether `tools` includes `tool`.
[[nodiscard]] constexpr bool takes(Tools tools, Tools tool) noexcept {
  return (static_cast<unsigned>(tools) & static_cast<unsigned>(tool)) != 0;
}

/// The sections of --help, in the order printed (and the order the save command writes them).
enum class Group { input, light_field, image, surface, animation, run, viewer };

/// The heading of `group` in --help.
[[nodiscard]] std::string_view group_title(Group group) noexcept;

/// What the save command knows when it writes an option: the job on screen at animation time
/// `time` (0..1), one view's size in pixels and the file to write.
struct SaveContext {
  const Job& job;
  double time = 0;
  int view_width = 0, view_height = 0;
  const std::filesystem::path& output;
};

/// How the save command writes an option: nullopt to leave it out (its default, or not part of
/// the picture), "" for a flag that is given, else the value.
using SaveFn = std::optional<std::string> (*)(const SaveContext&);

inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

/// One option. Defaults are those of `Job` (job.hpp) and of the viewer's settings;
/// `default_text` states them for --help.
struct Option {
  std::string_view name{};         ///< without the leading dashes
  std::string_view value{};        ///< placeholder of the value, empty for a flag
  std::string_view help{};         ///< one or a few sentences
  std::string_view default_text{}; ///< the default as --help prints it ("" when there is none to state)
  std::string_view example{};      ///< arguments that run (the suite runs every example)
  ValueKind kind = ValueKind::text;
  Group group = Group::run;
  Tools tools = Tools::both;
  double lo = -kUnbounded, hi = kUnbounded; ///< integer, number, track: the accepted range
  bool lo_open = false, hi_open = false;    ///< number, track: whether lo / hi are excluded
  std::string_view bound_text{}; ///< number, track: the reason given for a value outside; choice: instead of the list
  std::span<const std::string_view> choices{}; ///< choice: the accepted values
  bool in_view_help = true;                    ///< listed by mpr-view --help (when the viewer takes it)
  SaveFn save = nullptr;                       ///< the save command's writer; nullptr: never written
};

/// Every option of both tools, in --help order.
[[nodiscard]] std::span<const Option> option_table() noexcept;

/// The option called `name` (without dashes) that `tool` takes, or nullptr.
[[nodiscard]] const Option* find_option(std::string_view name, Tools tool) noexcept;

} // namespace mpr_cli
