#pragma once
// mpr-render's output files: the image format from the file name (PNG, JPEG, or the linear-light
// PFM and OpenEXR), the numbered frames of an animation, stale frames of an earlier, longer run
// of the same name, and the ffmpeg command that turns the frames into an MP4. The encoders of
// the linear formats are in encode_output.hpp.

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

enum class ImageFormat { png, jpeg, pfm, exr };

/// JPEG quality of mpr-render's .jpg output (stb_image_write, 1..100).
inline constexpr int jpeg_quality = 95;

/// The sample type of an OpenEXR output: 16-bit half floats (the default; about 3 decimal
/// digits, up to 65504) or 32-bit floats (the render's values exactly).
enum class ExrPixel { half, full };

/// How the linear render is written, by format: the PNG's bits per channel (8 or 16, sRGB-encoded
/// either way) and the OpenEXR sample type. PFM is always 32-bit float, JPEG 8-bit.
struct OutputEncoding {
  int png_bits = 8;                    ///< --bit-depth: 8 or 16
  ExrPixel exr_pixel = ExrPixel::half; ///< --exr-pixel: half or float
};

/// Whether this build writes OpenEXR (OpenEXR found at configure time: MPR_HAVE_OPENEXR).
[[nodiscard]] constexpr bool exr_available() noexcept {
#if defined(MPR_HAVE_OPENEXR)
  return true;
#else
  return false;
#endif
}

/// Whether `format` stores the linear render (PFM, OpenEXR) rather than sRGB codes.
[[nodiscard]] constexpr bool is_linear(ImageFormat format) noexcept {
  return format == ImageFormat::pfm || format == ImageFormat::exr;
}

namespace detail {
inline std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
} // namespace detail

/// The format of an output file from its extension (any case): .png -> PNG, .jpg or .jpeg ->
/// JPEG, .pfm -> RGB PFM, .exr -> OpenEXR, no extension (e.g. /dev/stdout) -> PNG. Throws
/// argument_error("--output") for any other extension, so a file is never written in a format
/// its name does not say, and for .exr in a build without OpenEXR.
[[nodiscard]] inline ImageFormat image_format(const std::filesystem::path& path) {
  const std::string ext = detail::lower(path.extension().string());
  if (ext.empty() || ext == ".png") return ImageFormat::png;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::jpeg;
  if (ext == ".pfm") return ImageFormat::pfm;
  if (ext == ".exr") {
    if (!exr_available())
      throw mpr::argument_error("--output", "'" + path.string() +
                                                "': this mpr-render was built without OpenEXR (install libopenexr-dev "
                                                "and rebuild); .pfm also writes the linear render");
    return ImageFormat::exr;
  }
  throw mpr::argument_error("--output", "'" + path.string() +
                                            "': mpr-render writes .png, .jpg, .jpeg, .pfm or .exr, not '" +
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

/// `image` encoded as PNG or JPEG (quality `jpeg_quality`) by the extension of `path`.
[[nodiscard]] inline std::vector<unsigned char> encode_image(const std::filesystem::path& path,
                                                             const mpr::Image<mpr::Rgb8>& image) {
  if (image_format(path) == ImageFormat::jpeg) return mpr::encode_jpeg(image.view(), jpeg_quality);
  return mpr::encode_png(image.view());
}

/// The extension of an animation's frames: the output's (".jpg", ".JPEG", ".pfm", ...), and ".png"
/// for an output without one.
[[nodiscard]] inline std::string frame_extension(const std::filesystem::path& output) {
  return image_format(output) == ImageFormat::png ? std::string(".png") : output.extension().string();
}

/// Frames left next to `output` by an earlier, longer run of the same output name: an animation
/// of M frames writes `<stem>_0001<ext>` ... `<stem>_M<ext>` (four or more digits), so the stale
/// frames of a run of `frames` frames are `<stem>_N<ext>` for N = frames + 1, frames + 2, ... as
/// long as each exists. Any other file (a camera's IMG_0042.png beside --output IMG.png) is never
/// counted. In order.
[[nodiscard]] inline std::vector<std::filesystem::path> stale_frames(const std::filesystem::path& output, int frames) {
  std::vector<std::filesystem::path> stale;
  std::error_code ec;
  for (long n = static_cast<long>(frames) + 1; n <= 999'999'999; ++n) {
    char number[16];
    std::snprintf(number, sizeof number, "_%04ld", n);
    std::filesystem::path p = output;
    p.replace_filename(output.stem().string() + number + frame_extension(output));
    if (!std::filesystem::is_regular_file(p, ec)) break;
    stale.push_back(p);
  }
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
