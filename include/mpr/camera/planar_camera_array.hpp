#pragma once
/// \file
/// The camera model of a rectified planar camera array (Stanford Light Field Archive, Stanford
/// multi-camera array after plane + parallax calibration; Vaish et al., CVPR 2004), shared by
/// the Stanford and LFCA loaders.
///
/// World frame: the cameras lie on the plane z = 0, look along +z, image x to the right and
/// image y down (the world x and y axes), all with R = I. The images are rectified onto the
/// reference plane z = `reference_depth`: a point on that plane has the same pixel in every
/// view (zero disparity). Camera i at centre (cx_i, cy_i, 0) then has
///   K_i = [[f, 0, (w-1)/2 + f cx_i / z0], [0, f, (h-1)/2 + f cy_i / z0], [0, 0, 1]],
/// and a point at depth z moves by f * c_i * (1/z0 - 1/z) pixels between views: the disparity
/// of the archive. Only the product (metric scale of the positions) x f x (1/z0 - 1/z) is
/// observable, so scale, focal length and reference depth are free choices; the defaults make
/// positions (whatever their unit) world units, put the reference plane 1000 units away and use
/// a focal length equal to the image width.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/vec.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace mpr {

/// Metric choices of a rectified planar array (see the file comment).
struct PlanarArrayOptions {
  /// World units per unit of the stored camera positions.
  double scale = 1.0;
  /// Depth of the rectified reference plane (world units, > 0).
  double reference_depth = 1000.0;
  /// Focal length in pixels; 0 means the image width.
  double focal_length = 0.0;
  /// Negate the stored X (Y) position. The defaults fit the Stanford gantry data, where X grows
  /// with the camera moving right (image x) and Y with it moving down (image y; Y falls as the
  /// grid row grows and the camera moves up). Measured on Chess: between grid columns 05 and 11
  /// near pieces shift 18 px left and far ones 3 px; between rows 05 and 11 near pieces shift
  /// 17 px down and far ones 2 px.
  bool negate_x = false;
  bool negate_y = false;
  /// Subtract the mean position, so the world origin is the centre of the array.
  bool centre = true;

  /// Throws `argument_error` naming the bad option.
  void validate() const {
    if (!(scale > 0) || !std::isfinite(scale)) throw argument_error("scale", "must be positive and finite");
    if (!(reference_depth > 0) || !std::isfinite(reference_depth))
      throw argument_error("reference_depth", "must be positive and finite");
    if (!(focal_length >= 0) || !std::isfinite(focal_length))
      throw argument_error("focal_length", "must be finite and >= 0 (0: image width)");
  }
};

/// World camera centres (z = 0) for stored positions (X, Y) under `options`.
template <std::floating_point T>
[[nodiscard]] std::vector<Vec3<T>> planar_array_centres(std::span<const Vec2<double>> positions,
                                                        const PlanarArrayOptions& options) {
  options.validate();
  Vec2<double> mean = Vec2<double>::Zero();
  if (options.centre && !positions.empty()) {
    for (const Vec2<double>& p : positions) mean += p;
    mean /= static_cast<double>(positions.size());
  }
  std::vector<Vec3<T>> centres;
  for (const Vec2<double>& p : positions) {
    const double x = (p.x() - mean.x()) * options.scale * (options.negate_x ? -1 : 1);
    const double y = (p.y() - mean.y()) * options.scale * (options.negate_y ? -1 : 1);
    // Out of T's range (or not finite): infinity, without an undefined float conversion; the
    // loaders report such a centre with the file it came from.
    const auto to_t = [](double v) {
      return std::abs(v) <= static_cast<double>(std::numeric_limits<T>::max()) ? static_cast<T>(v)
                                                                               : std::numeric_limits<T>::infinity();
    };
    centres.emplace_back(to_t(x), to_t(y), T(0));
  }
  return centres;
}

namespace detail {
/// Why a stored position gives a non-finite camera centre in T (for the loaders' messages).
template <std::floating_point T>
[[nodiscard]] std::string position_overflow_reason(const Vec2<double>& position, const PlanarArrayOptions& options) {
  char text[160];
  std::snprintf(text, sizeof text, "camera position (%.6g, %.6g) times the position scale %.6g is not finite in %s",
                position.x(), position.y(), options.scale, std::is_same_v<T, float> ? "float" : "double");
  return text;
}
} // namespace detail

/// The rectified camera at `centre` (z = 0) for `width` x `height` images (see the file comment).
template <std::floating_point T>
[[nodiscard]] PinholeCamera<T> planar_array_camera(const Vec3<T>& centre, int width, int height,
                                                   const PlanarArrayOptions& options) {
  options.validate();
  const double f = options.focal_length > 0 ? options.focal_length : static_cast<double>(width);
  const double z0 = options.reference_depth;
  Mat3<T> K = Mat3<T>::Identity();
  K(0, 0) = static_cast<T>(f);
  K(1, 1) = static_cast<T>(f);
  K(0, 2) = static_cast<T>(0.5 * (width - 1) + f * static_cast<double>(centre.x()) / z0);
  K(1, 2) = static_cast<T>(0.5 * (height - 1) + f * static_cast<double>(centre.y()) / z0);
  return PinholeCamera<T>(K, Mat3<T>::Identity(), Vec3<T>(-centre), width, height);
}

/// A virtual camera of a rectified planar array at `centre` (R = I, looking along +z) with the
/// intrinsics of the array camera `like` but the principal point at the image centre: the
/// reference view of the array, e.g. at its middle (the mean centre).
template <std::floating_point T>
[[nodiscard]] PinholeCamera<T> planar_array_reference_camera(const PinholeCamera<T>& like, const Vec3<T>& centre) {
  Mat3<T> K = like.K();
  K(0, 2) = T(0.5) * static_cast<T>(like.width() - 1);
  K(1, 2) = T(0.5) * static_cast<T>(like.height() - 1);
  return PinholeCamera<T>(K, Mat3<T>::Identity(), Vec3<T>(-centre), like.width(), like.height());
}

} // namespace mpr
