// Typed reading of option values with each option's declared range or choices (option_values.hpp).
#include "option_values.hpp"

#include <mpr/core/error.hpp>

#include <cmath>
#include <limits>

namespace mpr_cli {

namespace {

/// The declared option `name` (of either tool); a name missing from the table is a bug of the caller.
const Option& declared(std::string_view name) {
  for (const Option& o : option_table())
    if (o.name == name) return o;
  throw mpr::argument_error("--" + std::string(name), "is not in the option table");
}

std::string flag_of(const Option& o) { return "--" + std::string(o.name); }

/// The closed range of an integer option, clamped to int.
int int_bound(double v) {
  constexpr double lo = std::numeric_limits<int>::min(), hi = std::numeric_limits<int>::max();
  return static_cast<int>(v < lo ? lo : v > hi ? hi : v);
}

} // namespace

std::optional<int> OptionValues::integer(std::string_view name) const {
  const auto v = get(name);
  if (!v) return std::nullopt;
  const Option& o = declared(name);
  return parse_int(*v, flag_of(o), int_bound(o.lo), int_bound(o.hi));
}

std::optional<double> OptionValues::number(std::string_view name) const {
  const auto v = get(name);
  if (!v) return std::nullopt;
  const Option& o = declared(name);
  const double x = parse_number(*v, flag_of(o));
  if (!within_bounds(o, x)) throw mpr::argument_error(flag_of(o), std::string(o.bound_text));
  return x;
}

std::optional<std::pair<int, int>> OptionValues::size(std::string_view name) const {
  const auto v = get(name);
  if (!v) return std::nullopt;
  return parse_size(*v, flag_of(declared(name)));
}

std::optional<mpr::Vec3<double>> OptionValues::vec3(std::string_view name) const {
  const auto v = get(name);
  if (!v) return std::nullopt;
  return parse_vec3(*v, flag_of(declared(name)));
}

std::optional<Track> OptionValues::track(std::string_view name) const {
  const auto v = get(name);
  if (!v) return std::nullopt;
  const Option& o = declared(name);
  Track t = parse_track(*v, flag_of(o));
  for (const Track::Key& k : t.keys())
    if (!within_bounds(o, k.value)) throw mpr::argument_error(flag_of(o), std::string(o.bound_text));
  return t;
}

std::optional<std::size_t> OptionValues::choice(std::string_view name) const {
  const auto v = get(name);
  if (!v) return std::nullopt;
  const Option& o = declared(name);
  std::string list;
  for (std::size_t k = 0; k < o.choices.size(); ++k) {
    if (o.choices[k] == *v) return k;
    list += std::string(k == 0 ? "" : k + 1 == o.choices.size() ? " or " : ", ") + std::string(o.choices[k]);
  }
  throw mpr::argument_error(flag_of(o),
                            "'" + *v + "' " + (o.bound_text.empty() ? "is not " + list : std::string(o.bound_text)));
}

} // namespace mpr_cli
