#pragma once
/// \file
/// `mpr::PinholeCamera`: a calibrated pinhole camera (intrinsics K, rotation R, translation t,
/// optional radial distortion), shared by the light-field samplers, the loaders and the
/// software rasterizer.

#include <mpr/core/error.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <cmath>
#include <optional>
#include <string>

namespace mpr {

/// A pinhole camera with the projection `x ~ K [R | t] X` (world to camera `x_cam = R X + t`,
/// camera looking along +z, image x right and y down), as in the Middlebury `_par.txt` files
/// and OpenCV.
///
/// Pixel coordinates: `project` returns continuous coordinates in K's units, where the centre of
/// pixel (i, j) is at (i, j) (OpenCV / Middlebury convention). The image covers
/// [-0.5, width - 0.5) x [-0.5, height - 0.5). Note that mpr's `Region` puts pixel centres at
/// +0.5; `image_plane()` converts between the two exactly.
///
/// Distortion (optional, Brown's radial model): normalized coordinates `p = (x/z, y/z)` are
/// scaled by `1 + k1 r^2 + k2 r^4`, r = |p|, before K is applied.
template <std::floating_point T>
class PinholeCamera {
public:
  using scalar_type = T;

  struct Distortion {
    T k1 = 0;
    T k2 = 0;
  };

  /// Throws `argument_error` naming "K", "R", "t", "width", "height" or "distortion" when a value
  /// is not finite, K is not upper triangular with positive focal lengths, R is not a rotation
  /// (max |R^T R - I| > `rotation_tolerance` or det R < 0), or the image size is not positive.
  PinholeCamera(const Mat3<T>& K, const Mat3<T>& R, const Vec3<T>& t, int width, int height, Distortion distortion = {},
                T rotation_tolerance = default_rotation_tolerance())
      : R_(R), t_(t), width_(width), height_(height), distortion_(distortion) {
    if (!K.allFinite()) throw argument_error("K", "not finite");
    if (!R.allFinite()) throw argument_error("R", "not finite");
    if (!t.allFinite()) throw argument_error("t", "not finite");
    if (width <= 0) throw argument_error("width", "must be positive");
    if (height <= 0) throw argument_error("height", "must be positive");
    if (!std::isfinite(distortion.k1) || !std::isfinite(distortion.k2))
      throw argument_error("distortion", "not finite");
    if (K(2, 0) != 0 || K(2, 1) != 0 || K(1, 0) != 0 || !(K(2, 2) != 0))
      throw argument_error("K", "must be upper triangular with K(2,2) != 0");
    K_ = K / K(2, 2);
    if (!(K_(0, 0) > 0) || !(K_(1, 1) > 0)) throw argument_error("K", "focal lengths must be positive");
    const T orthogonality = (R.transpose() * R - Mat3<T>::Identity()).cwiseAbs().maxCoeff();
    if (!(orthogonality <= rotation_tolerance))
      throw argument_error("R", "not a rotation: max |R^T R - I| = " + std::to_string(orthogonality));
    if (!(R.determinant() > 0)) throw argument_error("R", "a reflection (det R < 0), not a rotation");
    K_inverse_ = K_.inverse();
    centre_ = -(R_.transpose() * t_);
  }

  /// Default tolerance on |R^T R - I|: loose enough for rotations printed to 6 digits.
  [[nodiscard]] static constexpr T default_rotation_tolerance() noexcept { return T(1e-5); }

  /// A camera at `eye` looking at `target` with `up` roughly up in the image, a vertical field
  /// of view of `vertical_fov` radians, square pixels and the principal point at the image centre.
  [[nodiscard]] static PinholeCamera look_at(const Vec3<T>& eye, const Vec3<T>& target, const Vec3<T>& up,
                                             T vertical_fov, int width, int height) {
    if (!eye.allFinite() || !target.allFinite() || !up.allFinite()) throw argument_error("look_at", "not finite");
    if (!(vertical_fov > 0 && vertical_fov < T(3.14159)))
      throw argument_error("vertical_fov", "must be in (0, pi) radians");
    const Vec3<T> forward = target - eye;
    if (!(forward.norm() > 0)) throw argument_error("target", "equals eye");
    const Vec3<T> z = forward.normalized();
    const Vec3<T> x_raw = z.cross(up);
    if (!(x_raw.norm() > T(1e-6) * up.norm())) throw argument_error("up", "parallel to the viewing direction");
    const Vec3<T> x = x_raw.normalized();
    const Vec3<T> y = z.cross(x); // image y points down
    Mat3<T> R;
    R.row(0) = x.transpose();
    R.row(1) = y.transpose();
    R.row(2) = z.transpose();
    const T f = T(0.5) * static_cast<T>(height) / std::tan(T(0.5) * vertical_fov);
    Mat3<T> K = Mat3<T>::Identity();
    K(0, 0) = f;
    K(1, 1) = f;
    K(0, 2) = T(0.5) * static_cast<T>(width) - T(0.5);
    K(1, 2) = T(0.5) * static_cast<T>(height) - T(0.5);
    const Vec3<T> t = -(R * eye);
    return PinholeCamera(K, R, t, width, height);
  }

  [[nodiscard]] const Mat3<T>& K() const noexcept { return K_; }
  [[nodiscard]] const Mat3<T>& R() const noexcept { return R_; }
  [[nodiscard]] const Vec3<T>& t() const noexcept { return t_; }
  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] const Distortion& distortion() const noexcept { return distortion_; }
  [[nodiscard]] bool has_distortion() const noexcept { return distortion_.k1 != 0 || distortion_.k2 != 0; }

  /// Camera centre in world coordinates, `-R^T t`.
  [[nodiscard]] const Vec3<T>& centre() const noexcept { return centre_; }
  /// The viewing direction (camera +z) in world coordinates.
  [[nodiscard]] Vec3<T> forward() const noexcept { return R_.row(2).transpose(); }

  /// `R X + t`.
  [[nodiscard]] Vec3<T> camera_from_world(const Vec3<T>& X) const noexcept { return R_ * X + t_; }

  /// Continuous pixel coordinates of `X` without the image-bounds check; empty when X is not
  /// strictly in front of the camera.
  [[nodiscard]] std::optional<Vec2<T>> project_unbounded(const Vec3<T>& X) const noexcept {
    const Vec3<T> c = camera_from_world(X);
    if (!(c.z() > 0)) return std::nullopt;
    Vec2<T> p(c.x() / c.z(), c.y() / c.z());
    if (has_distortion()) {
      const T r2 = p.squaredNorm();
      p *= T(1) + r2 * (distortion_.k1 + r2 * distortion_.k2);
    }
    return Vec2<T>(K_(0, 0) * p.x() + K_(0, 1) * p.y() + K_(0, 2), K_(1, 1) * p.y() + K_(1, 2));
  }

  /// Continuous pixel coordinates of `X` (pixel centres at integers); empty when X is behind the
  /// camera or projects outside [-0.5, width - 0.5) x [-0.5, height - 0.5).
  [[nodiscard]] std::optional<Vec2<T>> project(const Vec3<T>& X) const noexcept {
    const std::optional<Vec2<T>> p = project_unbounded(X);
    if (!p || !in_image(*p)) return std::nullopt;
    return p;
  }

  /// True when continuous pixel coordinates `p` lie in the image.
  [[nodiscard]] bool in_image(const Vec2<T>& p) const noexcept {
    return p.x() >= T(-0.5) && p.x() < static_cast<T>(width_) - T(0.5) && p.y() >= T(-0.5) &&
           p.y() < static_cast<T>(height_) - T(0.5);
  }

  /// The ray from the centre through continuous pixel coordinates `pixel`; its direction has
  /// unit camera-z component (so `at(depth)` is at that depth in front of the camera).
  /// Distortion is inverted by fixed-point iteration (converges for |k1 r^2 + k2 r^4| < 1).
  [[nodiscard]] Ray<T> ray_through(const Vec2<T>& pixel) const noexcept {
    const Vec3<T> h = K_inverse_ * Vec3<T>(pixel.x(), pixel.y(), T(1));
    Vec2<T> distorted(h.x() / h.z(), h.y() / h.z());
    Vec2<T> p = distorted;
    if (has_distortion()) {
      for (int i = 0; i < 20; ++i) {
        const T r2 = p.squaredNorm();
        p = distorted / (T(1) + r2 * (distortion_.k1 + r2 * distortion_.k2));
      }
    }
    return {centre_, R_.transpose() * Vec3<T>(p.x(), p.y(), T(1))};
  }

  /// The image plane at `depth` in front of the camera whose region uv maps exactly onto this
  /// camera's pixels: uv (0, 0) is the corner (-0.5, -0.5) and uv (1, 1) the corner
  /// (width - 0.5, height - 0.5), so an output of width x height pixels puts every pixel centre on
  /// the matching camera pixel centre. Ignores distortion. Precondition: depth > 0.
  [[nodiscard]] PlanarSurface<T> image_plane(T depth) const {
    if (!(depth > 0) || !std::isfinite(depth)) throw argument_error("depth", "must be positive and finite");
    const auto at = [&](T x, T y) {
      const Vec3<T> h = K_inverse_ * Vec3<T>(x, y, T(1));
      return Vec3<T>(centre_ + R_.transpose() * (h / h.z() * depth));
    };
    const T w = static_cast<T>(width_) - T(0.5), hgt = static_cast<T>(height_) - T(0.5);
    const Vec3<T> origin = at(T(-0.5), T(-0.5));
    return PlanarSurface<T>(origin, Vec3<T>(at(w, T(-0.5)) - origin), Vec3<T>(at(T(-0.5), hgt) - origin));
  }

private:
  Mat3<T> K_;
  Mat3<T> R_;
  Vec3<T> t_;
  int width_;
  int height_;
  Distortion distortion_;
  Mat3<T> K_inverse_;
  Vec3<T> centre_;
};

} // namespace mpr
