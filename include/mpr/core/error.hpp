#pragma once
/// \file
/// The exception types thrown by mpr's I/O and configuration code. The render path never
/// throws: everything that can fail is checked when a policy is constructed or loaded.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace mpr {

/// Base of every exception mpr throws.
class error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// A bad argument or configuration value. `parameter()` names it (e.g. "d10", "width_vector"),
/// `reason()` says what is wrong with it; `what()` is "mpr: invalid PARAMETER: REASON". A program
/// that maps configuration fields to its own option names (mpr-render's `--sweep KEY`) rethrows
/// with its name and the same reason.
class argument_error : public error {
public:
  argument_error(std::string parameter, std::string reason)
      : error("mpr: invalid " + parameter + ": " + reason), parameter_(std::move(parameter)),
        reason_(std::move(reason)) {}
  [[nodiscard]] const std::string& parameter() const noexcept { return parameter_; }
  [[nodiscard]] const std::string& reason() const noexcept { return reason_; }

private:
  std::string parameter_, reason_;
};

/// A file that cannot be read, written or parsed. `path()` names the file; `line()` is the
/// 1-based line of a text file where parsing failed, or 0 when no line applies.
class io_error : public error {
public:
  io_error(std::string path, const std::string& reason, std::size_t line = 0)
      : error(format(path, reason, line)), path_(std::move(path)), line_(line) {}
  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  [[nodiscard]] std::size_t line() const noexcept { return line_; }

private:
  static std::string format(const std::string& path, const std::string& reason, std::size_t line) {
    // append() rather than operator+ chains: GCC 12 raises a false -Wrestrict on the latter.
    std::string text("mpr: ");
    text.append(path);
    if (line != 0) text.append(":").append(std::to_string(line));
    text.append(": ").append(reason);
    return text;
  }
  std::string path_;
  std::size_t line_;
};

} // namespace mpr
