#pragma once
// Strict command-line parsing for mpr-render: `--name value`, `--name=value` and flags. Every
// malformed value throws mpr::argument_error naming the option, so the tool can print one clear
// line and exit non-zero.

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

/// One documented option.
struct OptionSpec {
  std::string name;  ///< without the leading dashes
  std::string value; ///< placeholder for the value, empty for a flag
  std::string help;  ///< one or two sentences
  std::string example;
};

/// The parsed command line: option name -> every value given (flags store "").
class ParsedArgs {
public:
  [[nodiscard]] bool has(const std::string& name) const { return values_.count(name) != 0; }
  /// The last value given for `name`, if any.
  [[nodiscard]] std::optional<std::string> get(const std::string& name) const {
    const auto it = values_.find(name);
    if (it == values_.end()) return std::nullopt;
    return it->second.back();
  }
  [[nodiscard]] std::vector<std::string> all(const std::string& name) const {
    const auto it = values_.find(name);
    return it == values_.end() ? std::vector<std::string>{} : it->second;
  }
  void add(const std::string& name, std::string value) { values_[name].push_back(std::move(value)); }

private:
  std::map<std::string, std::vector<std::string>> values_;
};

/// The edit distance (insertions, deletions, substitutions, transpositions of neighbours) between
/// `a` and `b`.
[[nodiscard]] inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

/// "; did you mean --NAME?" for the option of `specs` nearest to the unknown `name` (at most 2
/// edits, and fewer than half its letters), else "".
[[nodiscard]] inline std::string did_you_mean(const std::string& name, const std::vector<OptionSpec>& specs) {
  const OptionSpec* best = nullptr;
  std::size_t best_distance = 3;
  for (const OptionSpec& s : specs)
    if (const std::size_t d = edit_distance(name, s.name); d < best_distance && 2 * d < name.size())
      best = &s, best_distance = d;
  return best == nullptr ? std::string() : "; did you mean --" + best->name + "?";
}

/// Parses argv against `specs`. Throws argument_error for unknown options, missing values and
/// stray positional arguments.
inline ParsedArgs parse_args(int argc, const char* const* argv, const std::vector<OptionSpec>& specs) {
  ParsedArgs parsed;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0)
      throw mpr::argument_error(arg, "unexpected argument (options start with --; see --help)");
    std::string name = arg.substr(2), value;
    bool inline_value = false;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      inline_value = true;
    }
    const OptionSpec* spec = nullptr;
    for (const OptionSpec& s : specs)
      if (s.name == name) spec = &s;
    if (spec == nullptr)
      throw mpr::argument_error("--" + name, "unknown option" + did_you_mean(name, specs) + " (see --help)");
    if (spec->value.empty()) {
      if (inline_value) throw mpr::argument_error("--" + name, "is a flag and takes no value");
    } else if (!inline_value) {
      if (i + 1 >= argc) throw mpr::argument_error("--" + name, "needs a value " + spec->value);
      // "--view --output a.png": the value of --view is missing, not a.png misplaced.
      if (const std::string next = argv[i + 1]; next.rfind("--", 0) == 0 && next.size() > 2)
        throw mpr::argument_error("--" + name, "needs a value " + spec->value + " before " + next);
      value = argv[++i];
    }
    parsed.add(name, value);
  }
  return parsed;
}

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
