#pragma once
/// \file
/// `mpr::PlanarSurface`: an image plane, the most common image surface.

#include <mpr/core/error.hpp>
#include <mpr/core/ray_grid.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/geometry/plane.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace mpr {

/// A parallelogram in space onto which the output region is mapped:
/// `point_at(uv) = origin + u * width_vector + v * height_vector`, uv in [0, 1]^2.
///
/// `origin` is the point shown at the region's top-left corner, `width_vector` runs along the
/// top edge (u to the right) and `height_vector` down the left edge (v down), all in world units.
/// `normal()` is `normalize(width_vector x height_vector)`: with u right and v down, it points
/// *away* from a viewer who sees the image upright, i.e. into the scene.
template <std::floating_point T>
class PlanarSurface {
public:
  using scalar_type = T;

  /// Throws `argument_error` naming the parameter if a vector is not finite, `width_vector` or
  /// `height_vector` is zero, or the two are parallel.
  PlanarSurface(const Vec3<T>& origin, const Vec3<T>& width_vector, const Vec3<T>& height_vector)
      : origin_(origin), width_(width_vector), height_(height_vector) {
    if (!origin.allFinite()) throw argument_error("origin", "not finite");
    if (!width_vector.allFinite()) throw argument_error("width_vector", "not finite");
    if (!height_vector.allFinite()) throw argument_error("height_vector", "not finite");
    const T wn = width_vector.norm(), hn = height_vector.norm();
    if (!(wn > 0)) throw argument_error("width_vector", "zero length");
    if (!(hn > 0)) throw argument_error("height_vector", "zero length");
    // Scale-free test on the unit edge directions (no underflow for tiny planes): |sin(angle)|
    // below a few ulps leaves the plane without a normal.
    const Vec3<T> cross = Vec3<T>(width_vector / wn).cross(Vec3<T>(height_vector / hn));
    if (!(cross.norm() > 16 * std::numeric_limits<T>::epsilon()))
      throw argument_error("height_vector", "parallel to width_vector: the plane is degenerate");
    normal_ = cross.normalized();
  }

  /// The plane centred on `centre` with the given edge vectors.
  [[nodiscard]] static PlanarSurface centred(const Vec3<T>& centre, const Vec3<T>& width_vector,
                                             const Vec3<T>& height_vector) {
    const Vec3<T> origin = centre - T(0.5) * (width_vector + height_vector);
    return PlanarSurface(origin, width_vector, height_vector);
  }

  /// The surface point shown at normalized region coordinates `uv`.
  [[nodiscard]] Vec3<T> point_at(const Vec2<T>& uv) const noexcept {
    // Written per component: GCC does not always inline Eigen's assignment loop for this
    // expression, and a call per pixel costs more than the arithmetic (renderer benchmarks).
    const T u = uv.x(), v = uv.y();
    return Vec3<T>(origin_.x() + u * width_.x() + v * height_.x(), origin_.y() + u * width_.y() + v * height_.y(),
                   origin_.z() + u * width_.z() + v * height_.z());
  }

  /// `point_at` as an affine field (`AffineSurface`).
  [[nodiscard]] AffineField3<T> affine_points() const noexcept { return {origin_, width_, height_}; }

  /// The inverse of `point_at`: the uv of a point on the plane (a point off the plane is
  /// projected along the normal), uv outside [0, 1]^2 for points outside the rectangle. Solved
  /// through the 2x2 normal equations of the edges (Gram matrix [a.a a.b; a.b b.b]), which for
  /// the usual rectangle (a.b = 0) reduce to (x.a / a.a, x.b / b.b): fewer roundings than the
  /// cross-product dual basis of `PlaneBasis`, and the arithmetic mpr-render's `--rectify plane`
  /// has always used (its images stay byte-identical).
  [[nodiscard]] Vec2<T> uv_of(const Vec3<T>& point) const noexcept {
    const Vec3<T> x = point - origin_;
    const T aa = width_.dot(width_), ab = width_.dot(height_), bb = height_.dot(height_);
    const T det = aa * bb - ab * ab;
    return Vec2<T>((bb * width_.dot(x) - ab * height_.dot(x)) / det, (aa * height_.dot(x) - ab * width_.dot(x)) / det);
  }

  /// The plane as a point and unit normal (for ray crossings).
  [[nodiscard]] Plane<T> plane() const noexcept { return Plane<T>{origin_, normal_}; }

  [[nodiscard]] const Vec3<T>& origin() const noexcept { return origin_; }
  [[nodiscard]] const Vec3<T>& width_vector() const noexcept { return width_; }
  [[nodiscard]] const Vec3<T>& height_vector() const noexcept { return height_; }
  /// Unit normal, `normalize(width_vector x height_vector)`.
  [[nodiscard]] const Vec3<T>& normal() const noexcept { return normal_; }
  /// The point at uv = (0.5, 0.5).
  [[nodiscard]] Vec3<T> centre() const noexcept { return point_at(Vec2<T>(T(0.5), T(0.5))); }

  /// This plane rotated by `angle` radians (right-handed) about the line through `pivot` along
  /// `axis`. Used to tilt the image (focal) plane. Throws `argument_error` for a zero or
  /// non-finite axis, a non-finite angle or pivot.
  [[nodiscard]] PlanarSurface rotated(T angle, const Vec3<T>& axis, const Vec3<T>& pivot) const {
    if (!std::isfinite(angle)) throw argument_error("angle", "not finite");
    if (!axis.allFinite() || !(axis.norm() > 0)) throw argument_error("axis", "zero or not finite");
    if (!pivot.allFinite()) throw argument_error("pivot", "not finite");
    const Mat3<T> rotation = Eigen::AngleAxis<T>(angle, axis.normalized()).toRotationMatrix();
    const Vec3<T> origin = pivot + rotation * (origin_ - pivot);
    const Vec3<T> width = rotation * width_;
    const Vec3<T> height = rotation * height_;
    return PlanarSurface(origin, width, height);
  }

  /// This plane tilted about its own centre: first by `about_horizontal` radians about the
  /// width direction (top edge moves along the normal), then by `about_vertical` about the
  /// height direction.
  [[nodiscard]] PlanarSurface tilted(T about_horizontal, T about_vertical) const {
    const Vec3<T> c = centre();
    const PlanarSurface first = rotated(about_horizontal, width_, c);
    return first.rotated(about_vertical, first.height_vector(), c);
  }

private:
  Vec3<T> origin_;
  Vec3<T> width_;
  Vec3<T> height_;
  Vec3<T> normal_;
};

} // namespace mpr
