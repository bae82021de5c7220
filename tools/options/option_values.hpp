#pragma once
// The values a command line gave, by option name, and their typed reading: each getter parses
// the value as the option's declared kind (option_table.hpp) and applies its declared range or
// choices, throwing mpr::argument_error naming the option ("invalid --spp: 0 is outside [1, 4096]").

#include "option_table.hpp"

#include "mpr-render/animation.hpp"
#include "mpr-render/cli_args.hpp"

#include <mpr/core/vec.hpp>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mpr_cli {

/// The parsed command line: option name -> every value given, in order (flags store "").
class OptionValues {
public:
  [[nodiscard]] bool has(std::string_view name) const { return values_.count(std::string(name)) != 0; }
  /// The last value given for `name` (the last one wins), if any.
  [[nodiscard]] std::optional<std::string> get(std::string_view name) const {
    const auto it = values_.find(std::string(name));
    if (it == values_.end()) return std::nullopt;
    return it->second.back();
  }
  [[nodiscard]] std::vector<std::string> all(std::string_view name) const {
    const auto it = values_.find(std::string(name));
    return it == values_.end() ? std::vector<std::string>{} : it->second;
  }
  void add(std::string_view name, std::string value) { values_[std::string(name)].push_back(std::move(value)); }

  /// The value of an integer option, within its declared [lo, hi].
  [[nodiscard]] std::optional<int> integer(std::string_view name) const;
  /// The value of a number option, within its declared bounds.
  [[nodiscard]] std::optional<double> number(std::string_view name) const;
  /// The value of a WxH option.
  [[nodiscard]] std::optional<std::pair<int, int>> size(std::string_view name) const;
  /// The value of an x,y,z option.
  [[nodiscard]] std::optional<mpr::Vec3<double>> vec3(std::string_view name) const;
  /// The value of an animatable option, every key within its declared bounds.
  [[nodiscard]] std::optional<Track> track(std::string_view name) const;
  /// The index in the option's declared choices of its value.
  [[nodiscard]] std::optional<std::size_t> choice(std::string_view name) const;

private:
  std::map<std::string, std::vector<std::string>> values_;
};

/// Whether `value` lies within `option`'s declared bounds.
[[nodiscard]] constexpr bool within_bounds(const Option& option, double value) noexcept {
  return (option.lo_open ? value > option.lo : value >= option.lo) &&
         (option.hi_open ? value < option.hi : value <= option.hi);
}

} // namespace mpr_cli
