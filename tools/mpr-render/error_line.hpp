#pragma once
// The one line a tool prints for an error: "mpr-render: invalid --size: ...". The message of an
// exception may quote a file's bytes (a PNG given to --par) or a huge value (a 20 MB word of an
// mpr-view script): control bytes and invalid UTF-8 become '?', and the line is cut to
// kMaxErrorLine bytes with " ...".

#include <cstddef>
#include <string>

namespace mpr_cli {

/// Longest error line printed, bytes (without the tool's name).
inline constexpr std::size_t kMaxErrorLine = 480;

/// The length of the valid UTF-8 sequence at `s[i]` (0: not one).
[[nodiscard]] inline std::size_t utf8_length(const std::string& s, std::size_t i) noexcept {
  const auto c = static_cast<unsigned char>(s[i]);
  const std::size_t n = c >= 0xF0 && c <= 0xF4 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 && c <= 0xDF ? 2 : 0;
  if (n == 0 || c >= 0xF5 || i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 0;
  return n;
}

/// `what` as one printable line (see the file comment), without a leading "mpr: ".
[[nodiscard]] inline std::string error_line(std::string what) {
  if (what.rfind("mpr: ", 0) == 0) what.erase(0, 5);
  std::string line;
  for (std::size_t i = 0; i < what.size() && line.size() < kMaxErrorLine;) {
    const auto c = static_cast<unsigned char>(what[i]);
    if (c == '\n' || c == '\t') {
      line += ' ';
      ++i;
    } else if (c < 0x20 || c == 0x7F) {
      line += '?';
      ++i;
    } else if (c < 0x80) {
      line += what[i++];
    } else if (const std::size_t n = utf8_length(what, i); n > 0) {
      line.append(what, i, n);
      i += n;
    } else {
      line += '?';
      ++i;
    }
  }
  if (line.size() >= kMaxErrorLine) line += " ...";
  return line;
}

} // namespace mpr_cli
