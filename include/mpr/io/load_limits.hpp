#pragma once
/// \file
/// Bounds on what mpr's loaders accept, so that a hostile or broken input fails with an
/// `io_error` naming the file instead of exhausting memory or never finishing: only regular
/// files are read (not `/dev/zero`, FIFOs or folders), text files have a bounded size and line
/// length, and images a bounded pixel count (checked from the header, before decoding) and, for
/// a whole frame set, a bounded total of decoded texels. Every loader takes a `LoadLimits`
/// (defaults below); raise a limit by passing your own. See docs/reliability.md.

#include <mpr/core/error.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <system_error>

namespace mpr {

/// Limits applied while loading files. The defaults fit every real data set mpr is tested with
/// (the largest, Stanford "chess", is 289 images of 1400x800 pixels, 1.94 GB loaded).
struct LoadLimits {
  /// Pixels (width x height) of one image; larger images are refused before decoding.
  /// Default 2^26 (e.g. 8192 x 8192; 192 MiB as 8-bit RGB).
  std::uint64_t max_image_pixels = std::uint64_t(1) << 26;
  /// Bytes all images of one frame set take once loaded (6 a pixel: the decoded 8-bit RGB image
  /// and the set's texel copy; `kSetBytesPerPixel`), checked from the image headers before any
  /// image is decoded. Default 4 GiB.
  std::uint64_t max_set_bytes = std::uint64_t(4) << 30;
  /// Size in bytes of one text file (calibration, OBJ, MTL). Default 1 GiB.
  std::uint64_t max_text_bytes = std::uint64_t(1) << 30;
  /// Length in bytes of one line of a text file. Default 1 MiB.
  std::uint64_t max_line_bytes = std::uint64_t(1) << 20;
  /// Size in bytes of one (encoded) image file. Default 1 GiB.
  std::uint64_t max_image_file_bytes = std::uint64_t(1) << 30;
  /// Not a limit: called by the frame-set loaders (read_par_file, read_stanford_light_field,
  /// read_lfca) after each image is decoded, with the images decoded so far and the total, so a
  /// program can show the progress of a long load (a 289-image Stanford set takes tens of
  /// seconds). Empty by default (nothing is called). It lives here because every loader takes
  /// a LoadLimits; an exception it throws ends the load.
  std::function<void(std::size_t loaded, std::size_t total)> progress;
};

namespace detail {

/// Throws `io_error` naming `path` unless it is an existing regular file (after following
/// symbolic links) of at most `max_bytes` bytes; returns its size. `what` names the kind of
/// file in the message ("OBJ file", "image"). Never throws `std::filesystem::filesystem_error`
/// (a symbolic-link loop is an `io_error` too).
inline std::uint64_t require_regular_file(const std::filesystem::path& path, std::uint64_t max_bytes,
                                          const char* what) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw io_error(path.string(),
                   std::string("cannot open ") + what + ": " + (ec ? ec.message() : std::string("no such file")));
  if (!std::filesystem::is_regular_file(status))
    throw io_error(path.string(), std::string("not a regular file (") + what + " expected)");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw io_error(path.string(), std::string("cannot read ") + what + ": " + ec.message());
  if (size > max_bytes)
    throw io_error(path.string(), std::string(what) + " of " + std::to_string(size) + " bytes is above the limit of " +
                                      std::to_string(max_bytes) + " bytes (LoadLimits)");
  return size;
}

/// Reads the whole text file `path` (a regular file within `limits.max_text_bytes`) and throws
/// `io_error` naming the file and line when a line is longer than `limits.max_line_bytes`
/// (lines end at `\n`, `\r\n` or a bare `\r`, as in tinyobjloader).
[[nodiscard]] inline std::string read_text_file(const std::filesystem::path& path, const LoadLimits& limits,
                                                const char* what = "text file") {
  const std::uint64_t size = require_regular_file(path, limits.max_text_bytes, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io_error(path.string(), std::string("cannot open ") + what);
  std::string text;
  text.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  std::uint64_t line_length = 0;
  std::size_t line = 1;
  while (in) {
    in.read(buffer, sizeof buffer);
    const std::streamsize n = in.gcount();
    for (std::streamsize i = 0; i < n; ++i) {
      const char c = buffer[i];
      if (c == '\n' || c == '\r') {
        // "\r\n" is one line end: the '\n' after a '\r' does not start another line.
        if (!(c == '\n' && !text.empty() && text.back() == '\r')) ++line;
        line_length = 0;
      } else if (++line_length > limits.max_line_bytes) {
        throw io_error(path.string(),
                       "line longer than " + std::to_string(limits.max_line_bytes) + " bytes (LoadLimits)", line);
      }
      text.push_back(c);
    }
    if (text.size() > limits.max_text_bytes)
      throw io_error(path.string(), std::string(what) + " grew above the limit of " +
                                        std::to_string(limits.max_text_bytes) + " bytes (LoadLimits)");
  }
  if (in.bad()) throw io_error(path.string(), "read error");
  return text;
}

} // namespace detail

} // namespace mpr
