#pragma once
/// \file
/// The metric pinhole calibration format `<name>_par.txt` of the Middlebury multi-view data
/// (Seitz et al., CVPR 2006; captured on the Stanford spherical gantry): reader and writer.
///
/// Format: the first line is the image count N; then N lines
///   `imgname k11 k12 k13 k21 k22 k23 k31 k32 k33 r11 r12 r13 r21 r22 r23 r31 r32 r33 t1 t2 t3`
/// with K and R row-major, projection `x ~ K [R | t] X` (world to camera `R X + t`), pixel
/// centres at integer coordinates, image origin top-left. Image names are relative to the
/// folder of the calibration file.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/calibration_text.hpp>
#include <mpr/io/file_write.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/load_limits.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace mpr {

/// One line of a `_par.txt` file.
template <std::floating_point T>
struct ParEntry {
  std::string image_name;
  Mat3<T> K;
  Mat3<T> R;
  Vec3<T> t;
  /// 1-based line in the file (0 for entries not read from a file).
  std::size_t line = 0;
};

/// Reads the calibration lines of a `_par.txt` file without loading images. Throws `io_error`
/// naming the file and line for a missing or malformed count, a wrong number of fields, a
/// malformed or non-finite number, or fewer/more lines than the count says.
template <std::floating_point T = double>
[[nodiscard]] std::vector<ParEntry<T>> read_par_entries(const std::filesystem::path& par_file,
                                                        const LoadLimits& limits = {}) {
  const std::vector<detail::TextLine> lines = detail::read_text_lines(par_file, limits);
  if (lines.empty()) throw io_error(par_file.string(), "empty file: expected the image count on line 1");
  constexpr const char* layout = "image name, K (9 numbers), R (9), t (3)";
  if (lines[0].fields.size() != 1)
    throw io_error(par_file.string(),
                   "expected the image count alone on the first line, found " +
                       detail::count_of_fields(lines[0].fields.size()) +
                       ": is this a _par.txt file? (the image count, then one line per image: " + layout + ")",
                   lines[0].number);
  const long count = detail::parse_count(par_file, lines[0], 0);
  if (static_cast<std::size_t>(count) != lines.size() - 1)
    throw io_error(par_file.string(),
                   "the count says " + std::to_string(count) + " images but " + std::to_string(lines.size() - 1) +
                       " calibration lines follow",
                   lines[0].number);
  std::vector<ParEntry<T>> entries;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const detail::TextLine& line = lines[i];
    detail::require_fields(par_file, line, 22, layout);
    ParEntry<T> e;
    e.image_name = line.fields[0];
    e.line = line.number;
    for (int k = 0; k < 9; ++k) e.K(k / 3, k % 3) = static_cast<T>(detail::parse_number(par_file, line, 1 + k));
    for (int k = 0; k < 9; ++k) e.R(k / 3, k % 3) = static_cast<T>(detail::parse_number(par_file, line, 10 + k));
    for (int k = 0; k < 3; ++k) e.t[k] = static_cast<T>(detail::parse_number(par_file, line, 19 + k));
    entries.push_back(std::move(e));
  }
  return entries;
}

/// The pinhole camera of a `_par.txt` entry for an image of `width` x `height`; a bad K or R
/// becomes an `io_error` naming the file and line ("singular K", "R is not a rotation").
template <std::floating_point T>
[[nodiscard]] PinholeCamera<T> par_camera(const std::filesystem::path& par_file, const ParEntry<T>& e, int width,
                                          int height) {
  if (!(std::abs(e.K.determinant()) > 0)) throw io_error(par_file.string(), "singular K", e.line);
  try {
    return PinholeCamera<T>(e.K, e.R, e.t, width, height);
  } catch (const argument_error& err) {
    throw io_error(par_file.string(), err.what(), e.line);
  }
}

/// Reads a `_par.txt` file and every image it names into a `CameraFrameSet` (8-bit frames;
/// names are the image names). Every image must exist, decode, and have the size of the first.
/// Image headers are read first: sizes and `limits` (pixels per image, bytes of the whole set)
/// are checked before any image is decoded. Throws `io_error` naming the file (and line) on any
/// failure.
template <std::floating_point T = double>
[[nodiscard]] CameraFrameSet<T, Rgb8> read_par_file(const std::filesystem::path& par_file,
                                                    const LoadLimits& limits = {}) {
  const std::vector<ParEntry<T>> entries = read_par_entries<T>(par_file, limits);
  if (entries.empty()) throw io_error(par_file.string(), "no images", 1);
  const std::filesystem::path folder = par_file.parent_path();
  std::vector<std::filesystem::path> paths;
  std::vector<ImageInfo> infos;
  for (const ParEntry<T>& e : entries) {
    paths.push_back(folder / e.image_name);
    try {
      infos.push_back(read_image_info(paths.back(), limits));
    } catch (const io_error& err) {
      throw io_error(par_file.string(), std::string("image of this line: ") + err.what(), e.line);
    }
    if (infos.back().width != infos[0].width || infos.back().height != infos[0].height)
      throw io_error(paths.back().string(), "image is " + std::to_string(infos.back().width) + "x" +
                                                std::to_string(infos.back().height) + ", the first image is " +
                                                std::to_string(infos[0].width) + "x" + std::to_string(infos[0].height));
  }
  check_set_budget(paths, infos, limits, CameraFrameSet<T, Rgb8>::holds_linear16());
  std::vector<PinholeCamera<T>> cameras;
  std::vector<Image<Rgb8>> images;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const ParEntry<T>& e = entries[i];
    Image<Rgb8> image;
    try {
      image = read_rgb8(paths[i], limits);
    } catch (const io_error& err) {
      throw io_error(par_file.string(), std::string("image of this line: ") + err.what(), e.line);
    }
    if (image.width() != infos[0].width || image.height() != infos[0].height)
      throw io_error(paths[i].string(), "image changed size while loading");
    cameras.push_back(par_camera(par_file, e, image.width(), image.height()));
    images.push_back(std::move(image));
    names.push_back(e.image_name);
    if (limits.progress) limits.progress(i + 1, entries.size());
  }
  return CameraFrameSet<T, Rgb8>(std::move(cameras), std::move(images), std::move(names));
}

/// Writes cameras in the `_par.txt` format (K normalised to K(2,2) = 1; 17 significant digits,
/// so doubles read back exactly). Throws `argument_error` ("cameras") when the lists differ in
/// length or a camera has lens distortion (the format has none), `io_error` when the file
/// cannot be written (`write_file_atomically`: no partial file is left).
template <std::floating_point T>
void write_par_file(const std::filesystem::path& par_file, std::span<const std::string> image_names,
                    std::span<const PinholeCamera<T>> cameras) {
  if (image_names.size() != cameras.size()) throw argument_error("cameras", "names and cameras differ in number");
  for (const PinholeCamera<T>& c : cameras)
    if (c.has_distortion()) throw argument_error("cameras", "the _par.txt format has no lens distortion");
  for (const std::string& n : image_names)
    if (n.empty() || n.find_first_of(" \t\r\n") != std::string::npos)
      throw argument_error("image_names", "empty or containing whitespace: '" + n + "'");
  std::string text = std::to_string(cameras.size()) + "\n";
  const auto number = [&text](double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, " %.17g", v);
    text += buffer;
  };
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const PinholeCamera<T>& c = cameras[i];
    text += image_names[i];
    for (int k = 0; k < 9; ++k) number(static_cast<double>(c.K()(k / 3, k % 3)));
    for (int k = 0; k < 9; ++k) number(static_cast<double>(c.R()(k / 3, k % 3)));
    for (int k = 0; k < 3; ++k) number(static_cast<double>(c.t()[k]));
    text += "\n";
  }
  write_file_atomically(
      par_file, std::span<const unsigned char>(reinterpret_cast<const unsigned char*>(text.data()), text.size()));
}

/// Writes the cameras of a frame set (with its names) in the `_par.txt` format.
template <std::floating_point T, class Px>
void write_par_file(const std::filesystem::path& par_file, const CameraFrameSet<T, Px>& frames) {
  write_par_file<T>(par_file, std::span<const std::string>(frames.names()),
                    std::span<const PinholeCamera<T>>(frames.cameras()));
}

/// Writes a frame set as `<folder>/<stem>_par.txt` plus one PNG per frame under its name (the
/// folder is created), e.g. a rasterized virtual array (`scene::rasterize_virtual_array`), so a
/// synthetic data set with a known ground truth can be shared. Returns the path of the
/// `_par.txt` file, which `read_par_file` reads back. Throws `argument_error` naming "stem"
/// (empty, or with a path separator or whitespace) or as `write_par_file` (distorted cameras,
/// names with whitespace), `io_error` when a folder or file cannot be written.
template <std::floating_point T, class Px>
std::filesystem::path write_frame_set(const std::filesystem::path& folder, const std::string& stem,
                                      const CameraFrameSet<T, Px>& frames) {
  if (stem.empty() || stem.find_first_of("/\\ \t\r\n") != std::string::npos)
    throw argument_error("stem", "empty or containing a path separator or whitespace: '" + stem + "'");
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw io_error(folder.string(), "cannot create folder: " + ec.message());
  for (std::size_t i = 0; i < frames.size(); ++i) write_png(folder / frames.name(i), frames.image(i));
  const std::filesystem::path par = folder / (stem + "_par.txt");
  write_par_file(par, frames);
  return par;
}

} // namespace mpr
