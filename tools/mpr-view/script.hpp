#pragma once
// mpr-view's --script FILE: timed input events that drive the window through the same code paths
// as a user, one command per line ('#' starts a comment):
//   wait MS                    let MS milliseconds of real time pass (events keep being handled)
//   key NAME                   press and release a key, by SDL key name (G, Escape, Left, F1, [)
//   drag X0,Y0 X1,Y1 [BUTTON]  press BUTTON (left, right or middle; default left) at X0,Y0, move to X1,Y1, release
//   wheel N                    turn the wheel N notches (negative: towards the user)
//   click X,Y                  press and release the left button at X,Y
//   resize WxH                 resize the window to W x H pixels (as a user dragging its border)
//   screenshot PATH            wait until the view is rendered at full resolution, then write the
//                              window's content (picture, HUD, overlay) as a PNG
// Parsing is independent of SDL except for the key-name check, which takes a function.

#include <mpr/core/error.hpp>

#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace mpr_view {

/// One script command; which fields are used depends on `kind`.
struct ScriptCommand {
  enum class Kind { wait, key, drag, wheel, click, resize, screenshot };
  Kind kind = Kind::wait;
  int line = 0;                       ///< 1-based line in the file
  int milliseconds = 0;               ///< wait
  std::string key;                    ///< key: the SDL key name as written
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0; ///< drag (from, to), click (x0, y0), resize (x1 x y1); window pixels
  std::string button = "left";        ///< drag
  int notches = 0;                    ///< wheel
  std::filesystem::path path;         ///< screenshot
};

namespace detail {

inline bool parse_int_text(std::string_view text, int& value) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc{} && ptr == end && !text.empty();
}

inline std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

} // namespace detail

/// Parses a script's text. `valid_key(name)` says whether a key name exists. Throws
/// mpr::io_error naming `source` and the line for the first bad command.
/// Largest --script file accepted, bytes (a script of 20,000 commands is about 300 KB).
inline constexpr std::uintmax_t kMaxScriptBytes = 1u << 20;
/// Longest script line accepted, bytes.
inline constexpr std::size_t kMaxScriptLine = 1024;

[[nodiscard]] inline std::vector<ScriptCommand> parse_script(std::istream& in, const std::string& source,
                                                             const std::function<bool(const std::string&)>& valid_key,
                                                             int max_window = 16384) {
  std::vector<ScriptCommand> commands;
  std::string text;
  int line_number = 0;
  while (std::getline(in, text)) {
    ++line_number;
    if (text.size() > kMaxScriptLine)
      throw mpr::io_error(source, "line longer than " + std::to_string(kMaxScriptLine) + " bytes",
                          static_cast<std::size_t>(line_number));
    if (const auto hash = text.find('#'); hash != std::string::npos) text.erase(hash);
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const std::vector<std::string> w = detail::words(text);
    if (w.empty()) continue;
    const auto fail = [&](const std::string& why) {
      throw mpr::io_error(source, why, static_cast<std::size_t>(line_number));
    };
    const auto point = [&](const std::string& s, int& x, int& y) {
      const auto comma = s.find(',');
      if (comma == std::string::npos || !detail::parse_int_text(std::string_view(s).substr(0, comma), x) ||
          !detail::parse_int_text(std::string_view(s).substr(comma + 1), y))
        fail("'" + s + "' is not a window position X,Y");
      if (x < 0 || y < 0 || x >= max_window || y >= max_window) fail("'" + s + "' lies outside any window");
    };
    ScriptCommand c;
    c.line = line_number;
    const std::string& verb = w[0];
    const auto arguments = [&](std::size_t lo, std::size_t hi, const char* form) {
      if (w.size() - 1 < lo || w.size() - 1 > hi) fail("expected '" + std::string(form) + "'");
    };
    if (verb == "wait") {
      arguments(1, 1, "wait MS");
      if (!detail::parse_int_text(w[1], c.milliseconds) || c.milliseconds < 0 || c.milliseconds > 3600000)
        fail("'" + w[1] + "' is not a time in milliseconds (0 to 3600000)");
      c.kind = ScriptCommand::Kind::wait;
    } else if (verb == "key") {
      arguments(1, 1, "key NAME");
      if (!valid_key(w[1])) fail("'" + w[1] + "' is not an SDL key name (e.g. G, Escape, Left, F1)");
      c.kind = ScriptCommand::Kind::key;
      c.key = w[1];
    } else if (verb == "drag") {
      arguments(2, 3, "drag X0,Y0 X1,Y1 [left|right|middle]");
      point(w[1], c.x0, c.y0);
      point(w[2], c.x1, c.y1);
      if (w.size() == 4) {
        if (w[3] != "left" && w[3] != "right" && w[3] != "middle")
          fail("'" + w[3] + "' is not a mouse button (left, right, middle)");
        c.button = w[3];
      }
      c.kind = ScriptCommand::Kind::drag;
    } else if (verb == "wheel") {
      arguments(1, 1, "wheel N");
      if (!detail::parse_int_text(w[1], c.notches) || c.notches < -1000 || c.notches > 1000)
        fail("'" + w[1] + "' is not a number of notches (-1000 to 1000)");
      c.kind = ScriptCommand::Kind::wheel;
    } else if (verb == "click") {
      arguments(1, 1, "click X,Y");
      point(w[1], c.x0, c.y0);
      c.kind = ScriptCommand::Kind::click;
    } else if (verb == "resize") {
      arguments(1, 1, "resize WxH");
      const auto x = w[1].find('x');
      if (x == std::string::npos || !detail::parse_int_text(std::string_view(w[1]).substr(0, x), c.x1) ||
          !detail::parse_int_text(std::string_view(w[1]).substr(x + 1), c.y1) || c.x1 < 16 || c.y1 < 16 ||
          c.x1 > max_window || c.y1 > max_window)
        fail("'" + w[1] + "' is not a window size WxH (16 to " + std::to_string(max_window) + " pixels each)");
      c.kind = ScriptCommand::Kind::resize;
    } else if (verb == "screenshot") {
      arguments(1, 1, "screenshot PATH");
      c.kind = ScriptCommand::Kind::screenshot;
      c.path = w[1];
    } else {
      fail("unknown command '" + verb + "' (wait, key, drag, wheel, click, resize, screenshot)");
    }
    commands.push_back(std::move(c));
  }
  return commands;
}

/// Reads and parses a script file; throws mpr::io_error when it cannot be read.
[[nodiscard]] inline std::vector<ScriptCommand> read_script(const std::filesystem::path& path,
                                                            const std::function<bool(const std::string&)>& valid_key) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw mpr::io_error(path.string(), std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
  if (const std::uintmax_t size = std::filesystem::file_size(path, ec); !ec && size > kMaxScriptBytes)
    throw mpr::io_error(path.string(), std::to_string(size) + " bytes: scripts are limited to " +
                                           std::to_string(kMaxScriptBytes) + " bytes");
  std::ifstream in(path);
  if (!in) throw mpr::io_error(path.string(), std::strerror(errno));
  return parse_script(in, path.string(), valid_key);
}

} // namespace mpr_view
