#pragma once
/// \file
/// Reading whitespace-separated calibration text files line by line, with errors that name the
/// file and the 1-based line (`io_error`). Shared by the light-field loaders.

#include <mpr/core/error.hpp>
#include <mpr/io/load_limits.hpp>

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace mpr::detail {

/// One non-empty line of a text file split into fields, with its 1-based line number.
struct TextLine {
  std::size_t number = 0;
  std::vector<std::string> fields;
};

/// Reads `path` (a regular file within `limits`: size and line length, see load_limits.hpp)
/// and splits every line at whitespace. Lines end at `\n`, `\r\n` or a bare `\r`. Lines that
/// are empty or start with `#` (after leading whitespace) are skipped. Throws `io_error` if the
/// file is not a regular file, cannot be read, or exceeds a limit (naming the line).
[[nodiscard]] inline std::vector<TextLine> read_text_lines(const std::filesystem::path& path,
                                                           const LoadLimits& limits = {}) {
  const std::string text = read_text_file(path, limits);
  std::vector<TextLine> lines;
  std::size_t number = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    std::size_t stop = text.find_first_of("\r\n", begin);
    if (stop == std::string::npos) stop = text.size();
    const std::string_view line_text(text.data() + begin, stop - begin);
    begin = stop + (stop + 1 < text.size() && text[stop] == '\r' && text[stop + 1] == '\n' ? 2 : 1);
    TextLine line{++number, {}};
    std::size_t i = 0;
    while (i < line_text.size()) {
      while (i < line_text.size() && std::isspace(static_cast<unsigned char>(line_text[i]))) ++i;
      std::size_t j = i;
      while (j < line_text.size() && !std::isspace(static_cast<unsigned char>(line_text[j]))) ++j;
      if (j > i) line.fields.emplace_back(line_text.substr(i, j - i));
      i = j;
    }
    if (line.fields.empty() || line.fields.front()[0] == '#') continue;
    lines.push_back(std::move(line));
  }
  return lines;
}

/// Parses a whole field as a finite floating-point number; throws `io_error` naming the file,
/// line and field otherwise.
[[nodiscard]] inline double parse_number(const std::filesystem::path& path, const TextLine& line, std::size_t field) {
  const std::string& s = line.fields[field];
  double value = 0;
  const char* first = s.data();
  if (!s.empty() && s[0] == '+') ++first;
  const auto [end, ec] = std::from_chars(first, s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(value))
    throw io_error(path.string(), "field " + std::to_string(field + 1) + " ('" + s + "') is not a finite number",
                   line.number);
  return value;
}

/// Parses a whole field as a non-negative integer.
[[nodiscard]] inline long parse_count(const std::filesystem::path& path, const TextLine& line, std::size_t field) {
  const std::string& s = line.fields[field];
  long value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size() || value < 0)
    throw io_error(path.string(), "field " + std::to_string(field + 1) + " ('" + s + "') is not a count", line.number);
  return value;
}

/// "1 field", "10 fields".
[[nodiscard]] inline std::string count_of_fields(std::size_t n) {
  return std::to_string(n) + (n == 1 ? " field" : " fields");
}

/// Throws `io_error` unless `line` has exactly `count` fields; `layout` (if not empty) says what
/// they are, e.g. "id X Y".
inline void require_fields(const std::filesystem::path& path, const TextLine& line, std::size_t count,
                           const std::string& layout = {}) {
  if (line.fields.size() != count)
    throw io_error(path.string(),
                   "expected " + count_of_fields(count) + (layout.empty() ? "" : " (" + layout + ")") + ", found " +
                       std::to_string(line.fields.size()),
                   line.number);
}

} // namespace mpr::detail
