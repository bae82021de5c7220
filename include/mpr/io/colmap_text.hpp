#pragma once
/// \file
/// The text form of a COLMAP sparse model (Schoenberger and Frahm, "Structure-from-Motion
/// Revisited", CVPR 2016; file layout of COLMAP 3.x): `cameras.txt` and `images.txt`, parsed into
/// plain entries without loading any image. `colmap.hpp` turns them into a frame set.
///
/// `cameras.txt`: one line per camera, `CAMERA_ID MODEL WIDTH HEIGHT PARAMS...`. Accepted models
/// and their parameters (focal lengths and principal point in pixels, distortion dimensionless):
///   SIMPLE_PINHOLE f cx cy | PINHOLE fx fy cx cy | SIMPLE_RADIAL f cx cy k |
///   RADIAL f cx cy k1 k2 | OPENCV fx fy cx cy k1 k2 p1 p2 (only with p1 = p2 = 0).
/// Every other model is refused by name. COLMAP puts the centre of the upper-left pixel at
/// (0.5, 0.5); mpr at (0, 0) (see PinholeCamera), so the principal point is shifted by -0.5.
///
/// `images.txt`: two lines per image, `IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME`, then the
/// image's 2D points (ignored; the line may be empty). (QW, QX, QY, QZ) is the Hamilton unit
/// quaternion of the world-to-camera rotation R and T = t, so `x_cam = R X + t` as in mpr.
/// Lines starting with `#` are comments.

#include <mpr/core/error.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/io/calibration_text.hpp>
#include <mpr/io/load_limits.hpp>

#include <Eigen/Geometry>

#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace mpr {

/// One camera of `cameras.txt`, converted to mpr's conventions.
template <std::floating_point T>
struct ColmapCamera {
  long id = 0;
  /// The COLMAP model name as written (e.g. "PINHOLE").
  std::string model;
  int width = 0;
  int height = 0;
  /// Intrinsics, upper triangular, K(2,2) = 1, principal point with pixel centres at integers
  /// (COLMAP's cx - 0.5, cy - 0.5).
  Mat3<T> K = Mat3<T>::Identity();
  /// Radial distortion `1 + k1 r^2 + k2 r^4` (PinholeCamera::Distortion); zero for the pinholes.
  T k1 = 0;
  T k2 = 0;
  /// 1-based line in cameras.txt.
  std::size_t line = 0;
};

/// One image of `images.txt`.
template <std::floating_point T>
struct ColmapImage {
  long id = 0;
  long camera_id = 0;
  std::string name;
  /// World-to-camera rotation (from the normalised quaternion) and translation.
  Mat3<T> R = Mat3<T>::Identity();
  Vec3<T> t = Vec3<T>::Zero();
  /// 1-based line in images.txt.
  std::size_t line = 0;
};

namespace detail {

/// The lines of a COLMAP text file, keeping empty lines (an image's 2D-point line may be empty)
/// but dropping comment lines. Each line is split at whitespace.
[[nodiscard]] inline std::vector<TextLine> read_colmap_lines(const std::filesystem::path& path,
                                                             const LoadLimits& limits) {
  const std::string text = read_text_file(path, limits, "COLMAP text file");
  std::vector<TextLine> lines;
  std::size_t number = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    std::size_t stop = text.find_first_of("\r\n", begin);
    if (stop == std::string::npos) stop = text.size();
    const std::string_view row(text.data() + begin, stop - begin);
    begin = stop + (stop + 1 < text.size() && text[stop] == '\r' && text[stop + 1] == '\n' ? 2 : 1);
    TextLine line{++number, {}};
    for (std::size_t i = 0; i < row.size();) {
      while (i < row.size() && std::isspace(static_cast<unsigned char>(row[i]))) ++i;
      std::size_t j = i;
      while (j < row.size() && !std::isspace(static_cast<unsigned char>(row[j]))) ++j;
      if (j > i) line.fields.emplace_back(row.substr(i, j - i));
      i = j;
    }
    if (!line.fields.empty() && line.fields.front()[0] == '#') continue;
    lines.push_back(std::move(line));
  }
  return lines;
}

/// Parameter count of a supported COLMAP camera model; 0 when mpr does not support it.
[[nodiscard]] inline std::size_t colmap_parameter_count(const std::string& model) noexcept {
  if (model == "SIMPLE_PINHOLE") return 3;
  if (model == "PINHOLE" || model == "SIMPLE_RADIAL") return 4;
  if (model == "RADIAL") return 5;
  if (model == "OPENCV") return 8;
  return 0;
}

/// Parses a positive image dimension (field `field`).
[[nodiscard]] inline int parse_dimension(const std::filesystem::path& path, const TextLine& line, std::size_t field) {
  const long v = parse_count(path, line, field);
  if (v <= 0 || v > (1L << 20))
    throw io_error(path.string(), "field " + std::to_string(field + 1) + " (image size) must be in [1, 2^20]",
                   line.number);
  return static_cast<int>(v);
}

} // namespace detail

/// Reads `cameras.txt`. Throws `io_error` naming the file and line for a malformed line, a
/// non-finite or non-positive focal length, a duplicate id, or a model mpr does not support
/// (named in the message, e.g. "camera model OPENCV_FISHEYE is not supported").
template <std::floating_point T = double>
[[nodiscard]] std::vector<ColmapCamera<T>> read_colmap_cameras(const std::filesystem::path& cameras_txt,
                                                               const LoadLimits& limits = {}) {
  std::vector<ColmapCamera<T>> cameras;
  std::map<long, std::size_t> seen;
  for (const detail::TextLine& line : detail::read_colmap_lines(cameras_txt, limits)) {
    if (line.fields.empty()) continue;
    if (line.fields.size() < 4)
      throw io_error(cameras_txt.string(),
                     "expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS..., found " +
                         detail::count_of_fields(line.fields.size()),
                     line.number);
    ColmapCamera<T> c;
    c.id = detail::parse_count(cameras_txt, line, 0);
    c.model = line.fields[1];
    c.line = line.number;
    const std::size_t n = detail::colmap_parameter_count(c.model);
    if (n == 0)
      throw io_error(cameras_txt.string(),
                     "camera model " + c.model +
                         " is not supported (supported: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV)",
                     line.number);
    detail::require_fields(cameras_txt, line, 4 + n, "CAMERA_ID " + c.model + " WIDTH HEIGHT and its parameters");
    c.width = detail::parse_dimension(cameras_txt, line, 2);
    c.height = detail::parse_dimension(cameras_txt, line, 3);
    std::array<double, 8> p{};
    for (std::size_t k = 0; k < n; ++k) p[k] = detail::parse_number(cameras_txt, line, 4 + k);
    const bool one_focal = c.model == "SIMPLE_PINHOLE" || c.model == "SIMPLE_RADIAL" || c.model == "RADIAL";
    const double fx = p[0], fy = one_focal ? p[0] : p[1];
    const double cx = one_focal ? p[1] : p[2], cy = one_focal ? p[2] : p[3];
    if (!(fx > 0) || !(fy > 0)) throw io_error(cameras_txt.string(), "focal length must be positive", line.number);
    if (c.model == "SIMPLE_RADIAL") c.k1 = static_cast<T>(p[3]);
    if (c.model == "RADIAL") c.k1 = static_cast<T>(p[3]), c.k2 = static_cast<T>(p[4]);
    if (c.model == "OPENCV") {
      if (p[6] != 0 || p[7] != 0)
        throw io_error(cameras_txt.string(),
                       "camera model OPENCV with tangential distortion (p1, p2 not 0) is not supported", line.number);
      c.k1 = static_cast<T>(p[4]);
      c.k2 = static_cast<T>(p[5]);
    }
    c.K(0, 0) = static_cast<T>(fx);
    c.K(1, 1) = static_cast<T>(fy);
    c.K(0, 2) = static_cast<T>(cx - 0.5);
    c.K(1, 2) = static_cast<T>(cy - 0.5);
    if (!seen.emplace(c.id, cameras.size()).second)
      throw io_error(cameras_txt.string(), "camera id " + std::to_string(c.id) + " appears twice", line.number);
    cameras.push_back(std::move(c));
  }
  return cameras;
}

/// Reads `images.txt` (the pose lines; the 2D-point lines are skipped unread). Throws `io_error`
/// naming the file and line for a malformed line, a non-finite number, a zero quaternion or a
/// duplicate image id. Images are returned in file order.
template <std::floating_point T = double>
[[nodiscard]] std::vector<ColmapImage<T>> read_colmap_images(const std::filesystem::path& images_txt,
                                                             const LoadLimits& limits = {}) {
  const std::vector<detail::TextLine> lines = detail::read_colmap_lines(images_txt, limits);
  std::vector<ColmapImage<T>> images;
  std::map<long, std::size_t> seen;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const detail::TextLine& line = lines[i];
    if (line.fields.empty()) continue; // blank lines between images
    detail::require_fields(images_txt, line, 10, "IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
    ColmapImage<T> im;
    im.id = detail::parse_count(images_txt, line, 0);
    std::array<double, 7> v{};
    for (std::size_t k = 0; k < 7; ++k) v[k] = detail::parse_number(images_txt, line, 1 + k);
    im.camera_id = detail::parse_count(images_txt, line, 8);
    im.name = line.fields[9];
    im.line = line.number;
    const Eigen::Quaternion<double> q(v[0], v[1], v[2], v[3]);
    if (!(q.norm() > 1e-12)) throw io_error(images_txt.string(), "the quaternion is zero", line.number);
    im.R = q.normalized().toRotationMatrix().template cast<T>();
    im.t = Vec3<double>(v[4], v[5], v[6]).template cast<T>();
    if (!seen.emplace(im.id, images.size()).second)
      throw io_error(images_txt.string(), "image id " + std::to_string(im.id) + " appears twice", line.number);
    images.push_back(std::move(im));
    ++i; // the next line holds the image's 2D points (possibly empty, possibly absent at the end)
  }
  return images;
}

} // namespace mpr
