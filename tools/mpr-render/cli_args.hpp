#pragma once
// Strict parsers of option values (numbers, integers, WxH, x,y,z). Every malformed value throws
// mpr::argument_error naming the option, so the tool can print one clear line and exit non-zero.
// The options themselves are declared in tools/options/option_table.hpp.

#include <mpr/core/error.hpp>
#include <mpr/core/vec.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace mpr_cli {

/// A finite number, the whole string. Throws argument_error naming `option`.
inline double parse_number(std::string_view text, const std::string& option) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc{} || ptr != end || text.empty())
    throw mpr::argument_error(option, "'" + std::string(text) + "' is not a number");
  if (!std::isfinite(value)) throw mpr::argument_error(option, "'" + std::string(text) + "' is not finite");
  return value;
}

/// An integer in [lo, hi], the whole string.
inline int parse_int(std::string_view text, const std::string& option, int lo, int hi) {
  int value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc{} || ptr != end || text.empty())
    throw mpr::argument_error(option, "'" + std::string(text) + "' is not an integer");
  if (value < lo || value > hi)
    throw mpr::argument_error(option, std::to_string(value) + " is outside [" + std::to_string(lo) + ", " +
                                          std::to_string(hi) + "]");
  return value;
}

/// Splits on `separator` (empty fields kept, so "1,,2" fails as a number).
inline std::vector<std::string> split(std::string_view text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = text.find(separator, start);
    parts.emplace_back(text.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
    if (at == std::string_view::npos) break;
    start = at + 1;
  }
  return parts;
}

/// "x,y,z".
inline mpr::Vec3<double> parse_vec3(std::string_view text, const std::string& option) {
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() != 3) throw mpr::argument_error(option, "'" + std::string(text) + "' is not x,y,z");
  return {parse_number(parts[0], option), parse_number(parts[1], option), parse_number(parts[2], option)};
}

/// "WxH" with both in [1, 16384].
inline std::pair<int, int> parse_size(std::string_view text, const std::string& option) {
  const std::vector<std::string> parts = split(text, 'x');
  if (parts.size() != 2) throw mpr::argument_error(option, "'" + std::string(text) + "' is not WIDTHxHEIGHT");
  return {parse_int(parts[0], option, 1, 16384), parse_int(parts[1], option, 1, 16384)};
}

} // namespace mpr_cli
