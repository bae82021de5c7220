#pragma once
/// \file
/// Reading whitespace-separated calibration text files line by line, with errors that name the
/// file and the 1-based line (`io_error`). Shared by the light-field loaders.

#include <mpr/core/error.hpp>

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
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

/// Reads `path` and splits every line at whitespace. Lines that are empty or start with `#`
/// (after leading whitespace) are skipped. Throws `io_error` if the file cannot be opened or read.
[[nodiscard]] inline std::vector<TextLine> read_text_lines(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io_error(path.string(), "cannot open file");
  std::vector<TextLine> lines;
  std::string text;
  for (std::size_t number = 1; std::getline(in, text); ++number) {
    TextLine line{number, {}};
    std::size_t i = 0;
    while (i < text.size()) {
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      std::size_t j = i;
      while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j]))) ++j;
      if (j > i) line.fields.emplace_back(text.substr(i, j - i));
      i = j;
    }
    if (line.fields.empty() || line.fields.front()[0] == '#') continue;
    lines.push_back(std::move(line));
  }
  if (in.bad()) throw io_error(path.string(), "read error");
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

/// Throws `io_error` unless `line` has exactly `count` fields.
inline void require_fields(const std::filesystem::path& path, const TextLine& line, std::size_t count) {
  if (line.fields.size() != count)
    throw io_error(path.string(),
                   "expected " + std::to_string(count) + " fields, found " + std::to_string(line.fields.size()),
                   line.number);
}

} // namespace mpr::detail
