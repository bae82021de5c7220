#pragma once
// mpr-render's output files: the image format from the file name (PNG or JPEG), the numbered
// frames of an animation, stale frames of an earlier, longer run of the same name, and the
// ffmpeg command that turns the frames into an MP4.

#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/image_io.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace mpr_cli {

enum class ImageFormat { png, jpeg };

/// JPEG quality of mpr-render's .jpg output (stb_image_write, 1..100).
inline constexpr int jpeg_quality = 95;

namespace detail {
inline std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
} // namespace detail

/// The format of an output file from its extension (any case): .png -> PNG, .jpg or .jpeg ->
/// JPEG, no extension (e.g. /dev/stdout) -> PNG. Throws argument_error("--output") for any other
/// extension, so a file is never written in a format its name does not say.
[[nodiscard]] inline ImageFormat image_format(const std::filesystem::path& path) {
  const std::string ext = detail::lower(path.extension().string());
  if (ext.empty() || ext == ".png") return ImageFormat::png;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::jpeg;
  throw mpr::argument_error("--output", "'" + path.string() + "': mpr-render writes .png, .jpg or .jpeg, not '" +
                                            path.extension().string() + "'");
}

/// Writes `image` as PNG or JPEG (quality `jpeg_quality`) by the extension of `path`, atomically
/// (no partial file on failure; mpr::write_png / mpr::write_jpeg).
inline void write_image(const std::filesystem::path& path, const mpr::Image<mpr::Rgb8>& image) {
  if (image_format(path) == ImageFormat::jpeg)
    mpr::write_jpeg(path, image, jpeg_quality);
  else
    mpr::write_png(path, image);
}

/// The extension of an animation's frames: the output's for JPEG (".jpg", ".JPEG", ...), else ".png".
[[nodiscard]] inline std::string frame_extension(const std::filesystem::path& output) {
  return image_format(output) == ImageFormat::jpeg ? output.extension().string() : std::string(".png");
}

/// Frames `<stem>_NNNN<ext>` (four or more digits, NNNN > `frames`) next to `output`: left by an
/// earlier run of the same output name with more frames. Sorted.
[[nodiscard]] inline std::vector<std::filesystem::path> stale_frames(const std::filesystem::path& output, int frames) {
  std::vector<std::filesystem::path> stale;
  const std::filesystem::path folder = output.parent_path().empty() ? std::filesystem::path(".") : output.parent_path();
  const std::string prefix = output.stem().string() + "_", ext = frame_extension(output);
  std::error_code ec;
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() < prefix.size() + 4 + ext.size() || name.compare(0, prefix.size(), prefix) != 0 ||
        name.compare(name.size() - ext.size(), ext.size(), ext) != 0)
      continue;
    const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - ext.size());
    if (digits.size() > 9 || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    if (std::stol(digits) > frames) stale.push_back(it->path());
  }
  std::sort(stale.begin(), stale.end());
  return stale;
}

/// Removes `stale_frames(output, frames)`; returns how many were removed.
inline int remove_stale_frames(const std::filesystem::path& output, int frames) {
  int removed = 0;
  for (const std::filesystem::path& p : stale_frames(output, frames)) {
    std::error_code ec;
    removed += std::filesystem::remove(p, ec) ? 1 : 0;
  }
  return removed;
}

/// `s` in single quotes for /bin/sh.
[[nodiscard]] inline std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// The MP4 next to `output` (out.png -> out.mp4).
[[nodiscard]] inline std::filesystem::path video_path(const std::filesystem::path& output) {
  std::filesystem::path mp4 = output;
  mp4.replace_extension(".mp4");
  return mp4;
}

/// The ffmpeg command that encodes frames 1..`frames` of `output` at `fps` frames per second
/// into video_path(output) (H.264, yuv420p, sizes padded to even). `-frames:v` bounds the input,
/// so frames of another run with the same name never enter the video.
[[nodiscard]] inline std::string ffmpeg_command(const std::filesystem::path& output, int frames, double fps) {
  std::filesystem::path pattern = output;
  pattern.replace_filename(output.stem().string() + "_%04d" + frame_extension(output));
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", fps);
  return "ffmpeg -loglevel error -y -framerate " + std::string(rate) + " -start_number 1 -i " +
         shell_quoted(pattern.string()) + " -frames:v " + std::to_string(frames) +
         " -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' " + shell_quoted(video_path(output).string());
}

/// True when `ffmpeg` is on PATH.
[[nodiscard]] inline bool ffmpeg_available() { return std::system("command -v ffmpeg >/dev/null 2>&1") == 0; }

} // namespace mpr_cli
