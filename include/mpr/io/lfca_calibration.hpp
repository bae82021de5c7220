#pragma once
/// \file
/// Loader of the Stanford multi-camera array (LFCA) "plane + parallax" calibration (Vaish,
/// Wilburn, Joshi & Levoy, "Using plane + parallax for calibrating dense camera arrays", CVPR
/// 2004): a positions file with one `camera-id X Y` line per camera (the camera's position on
/// the camera plane, up to scale and offset) and, per camera, a text file with a 3x3 row-major
/// homography H (9 numbers, any whitespace) mapping raw image pixels to the rectified reference
/// plane: `x_rect ~ H x_raw` (pixel centres at integer coordinates).
///
/// The homography is applied at sampling time without resampling the image: the raw camera is
/// the rectified planar-array camera (planar_camera_array.hpp) followed by H^-1, i.e.
/// `P_raw ~ H^-1 K_i [I | -C_i]`; its 3x3 part is split into K' R' (RQ decomposition), which
/// is again a pinhole camera with the same centre.

#include <mpr/camera/planar_camera_array.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/calibration_text.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/load_limits.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <Eigen/LU>
#include <Eigen/QR>
#include <cmath>
#include <filesystem>
#include <string>
#include <unordered_map>
#include <vector>

namespace mpr {

/// File layout and metric choices of an LFCA calibration.
struct LfcaOptions {
  /// The image and homography file of a camera: `{id}` is replaced by the camera id. Relative
  /// to the folder of the positions file.
  std::string image_pattern = "{id}.png";
  std::string homography_pattern = "{id}.homography.txt";
  /// The rectified array's metric model (planar_camera_array.hpp). LFCA positions are taken as
  /// X right and Y down in the image (no negation by default).
  PlanarArrayOptions array = {};
};

namespace detail {
[[nodiscard]] inline std::string replace_id(std::string pattern, const std::string& id) {
  const std::string key = "{id}";
  for (std::size_t p = pattern.find(key); p != std::string::npos; p = pattern.find(key, p + id.size()))
    pattern.replace(p, key.size(), id);
  return pattern;
}
} // namespace detail

/// RQ decomposition of a non-singular 3x3 matrix up to a positive or negative scale:
/// `M ~ K R` with K upper triangular, positive diagonal, K(2,2) = 1, and R a rotation.
template <std::floating_point T>
void rq_decompose(const Mat3<T>& M_in, Mat3<T>& K, Mat3<T>& R) {
  Mat3<T> M = M_in;
  if (M.determinant() < 0) M = -M;
  Mat3<T> flip = Mat3<T>::Zero();
  flip(0, 2) = flip(1, 1) = flip(2, 0) = 1;
  // (flip M)^T = Q U  =>  M = flip U^T Q^T = (flip U^T flip) (flip Q^T).
  const Eigen::HouseholderQR<Mat3<T>> qr((flip * M).transpose());
  const Mat3<T> Q = qr.householderQ();
  const Mat3<T> U = qr.matrixQR().template triangularView<Eigen::Upper>();
  K = flip * U.transpose() * flip;
  R = flip * Q.transpose();
  for (int i = 0; i < 3; ++i)
    if (K(i, i) < 0) {
      K.col(i) = -K.col(i);
      R.row(i) = -R.row(i);
    }
  K /= K(2, 2);
}

/// Reads an LFCA calibration and its images into a `CameraFrameSet` (8-bit frames; names are
/// the camera ids, in file order). Text files are read within `limits` (regular files, bounded
/// size and line length); image headers are read first, and sizes and `limits` (pixels per
/// image, bytes of the whole set) checked before any image is decoded. Throws `io_error` naming
/// the file and line for malformed numbers, a wrong field count, duplicate ids, a position that
/// is not finite once scaled, a homography file without exactly 9 numbers or with a singular
/// matrix (the scale of H does not matter), missing or unreadable images, images above a
/// limit, or images of different sizes.
template <std::floating_point T = double>
[[nodiscard]] CameraFrameSet<T, Rgb8> read_lfca(const std::filesystem::path& positions_file,
                                                const LfcaOptions& options = {}, const LoadLimits& limits = {}) {
  options.array.validate();
  const std::vector<detail::TextLine> lines = detail::read_text_lines(positions_file, limits);
  if (lines.empty()) throw io_error(positions_file.string(), "no `camera-id X Y` lines");
  const std::filesystem::path folder = positions_file.parent_path();
  std::vector<std::string> ids;
  std::vector<Vec2<double>> positions;
  std::unordered_map<std::string, std::size_t> first_line; // id -> line: linear, not quadratic
  for (const detail::TextLine& line : lines) {
    detail::require_fields(positions_file, line, 3, "id X Y");
    const auto [at, inserted] = first_line.emplace(line.fields[0], line.number);
    if (!inserted)
      throw io_error(positions_file.string(),
                     "duplicate camera id " + line.fields[0] + " (first on line " + std::to_string(at->second) + ")",
                     line.number);
    ids.push_back(line.fields[0]);
    positions.emplace_back(detail::parse_number(positions_file, line, 1),
                           detail::parse_number(positions_file, line, 2));
  }
  const std::vector<Vec3<T>> centres = planar_array_centres<T>(positions, options.array);
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (!centres[i].allFinite())
      throw io_error(positions_file.string(), detail::position_overflow_reason<T>(positions[i], options.array),
                     lines[i].number);
  // First every homography and image header (no image decoded yet), in camera order.
  std::vector<std::filesystem::path> image_paths;
  std::vector<ImageInfo> infos;
  std::vector<Mat3<double>> homographies;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const std::filesystem::path h_path = folder / detail::replace_id(options.homography_pattern, ids[i]);
    // The homography: 9 numbers over any number of lines.
    const std::vector<detail::TextLine> h_lines = detail::read_text_lines(h_path, limits);
    std::vector<double> h;
    for (const detail::TextLine& line : h_lines)
      for (std::size_t k = 0; k < line.fields.size(); ++k) {
        if (h.size() == 9)
          throw io_error(h_path.string(), "more than 9 numbers (expected a 3x3 homography)", line.number);
        h.push_back(detail::parse_number(h_path, line, k));
      }
    if (h.size() != 9)
      throw io_error(h_path.string(),
                     "expected 9 numbers (a 3x3 row-major homography), found " + std::to_string(h.size()));
    Mat3<double> H;
    for (int k = 0; k < 9; ++k) H(k / 3, k % 3) = h[static_cast<std::size_t>(k)];
    // H is defined up to scale: normalise it so that tiny or huge (finite) entries do not matter.
    const double scale = H.cwiseAbs().maxCoeff();
    if (!(scale > 0)) throw io_error(h_path.string(), "singular homography (all zero)");
    H /= scale;
    if (!(std::abs(H.determinant()) > 1e-12)) throw io_error(h_path.string(), "singular homography");
    homographies.push_back(H);
    image_paths.push_back(folder / detail::replace_id(options.image_pattern, ids[i]));
    try {
      infos.push_back(read_image_info(image_paths.back(), limits));
    } catch (const io_error& err) {
      throw io_error(positions_file.string(), std::string("image of camera ") + ids[i] + ": " + err.what(),
                     lines[i].number);
    }
    if (infos.back().width != infos[0].width || infos.back().height != infos[0].height)
      throw io_error(image_paths.back().string(), "image is " + std::to_string(infos.back().width) + "x" +
                                                      std::to_string(infos.back().height) + ", the first camera's is " +
                                                      std::to_string(infos[0].width) + "x" +
                                                      std::to_string(infos[0].height));
  }
  check_set_budget(image_paths, infos, limits, CameraFrameSet<T, Rgb8>::holds_linear16());
  std::vector<PinholeCamera<T>> cameras;
  std::vector<Image<Rgb8>> images;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const std::filesystem::path& image_path = image_paths[i];
    const std::filesystem::path h_path = folder / detail::replace_id(options.homography_pattern, ids[i]);
    const Mat3<double>& H = homographies[i];
    Image<Rgb8> image;
    try {
      image = read_rgb8(image_path, limits);
    } catch (const io_error& err) {
      throw io_error(positions_file.string(), std::string("image of camera ") + ids[i] + ": " + err.what(),
                     lines[i].number);
    }
    if (image.width() != infos[0].width || image.height() != infos[0].height)
      throw io_error(image_path.string(), "image changed size while loading");
    const Vec3<double> C = centres[i].template cast<double>();
    const PinholeCamera<double> rectified =
        planar_array_camera<double>(C, image.width(), image.height(), options.array);
    const Mat3<double> M = H.inverse() * rectified.K();
    Mat3<double> K, R;
    rq_decompose(M, K, R);
    const Vec3<double> t = -(R * C);
    try {
      cameras.emplace_back(K.cast<T>(), R.cast<T>(), t.cast<T>(), image.width(), image.height(),
                           typename PinholeCamera<T>::Distortion{},
                           std::is_same_v<T, float> ? T(1e-4) : PinholeCamera<T>::default_rotation_tolerance());
    } catch (const argument_error& err) {
      throw io_error(h_path.string(), std::string("homography gives no valid camera: ") + err.what());
    }
    images.push_back(std::move(image));
    if (limits.progress) limits.progress(i + 1, ids.size());
  }
  // Built on z = 0 (planar_camera_array.hpp): hand the plane over instead of letting the samplers fit it.
  return CameraFrameSet<T, Rgb8>(std::move(cameras), std::move(images), ids)
      .on_plane(Plane<T>{Vec3<T>::Zero(), Vec3<T>::UnitZ()});
}

} // namespace mpr
