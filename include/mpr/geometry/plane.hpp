#pragma once
/// \file
/// `mpr::Plane<T>`: a plane in space -- a point and a normal -- with the one ray crossing every
/// module uses (checkerboard, light-field array plane, mpr-render's rectification), and
/// `mpr::PlaneBasis<T>`, the affine coordinates (a, b) of points on it along two edge vectors
/// (the dual basis), which `PlanarSurface::uv_of` and the checkerboard's cells use. The
/// structure-of-arrays crossing of a whole row of rays is `detail::plane_rays`
/// (geometry/detail/plane_kernels.hpp).

#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>

#include <cmath>

namespace mpr {

/// The plane through `point` with normal `normal` (any non-zero length; world frame).
template <std::floating_point T>
struct Plane {
  Vec3<T> point = Vec3<T>::Zero();
  Vec3<T> normal = Vec3<T>::UnitZ();

  /// The ray parameter t at which `ray.at(t)` lies on the plane: (point - o) . n / (d . n).
  /// Infinite or NaN when the ray runs parallel to the plane (d . n = 0).
  [[nodiscard]] T crossing_parameter(const Ray<T>& ray) const noexcept {
    return (point - ray.origin).dot(normal) / ray.direction.dot(normal);
  }

  /// Where the ray's line crosses the plane, `ray.at(crossing_parameter(ray))` (not finite when
  /// parallel).
  [[nodiscard]] Vec3<T> crossing(const Ray<T>& ray) const noexcept { return ray.at(crossing_parameter(ray)); }
};

/// Affine coordinates on a plane spanned by `origin` and two non-parallel edge vectors:
/// `coordinates(origin + a edge_a + b edge_b) = (a, b)`, exactly up to rounding, through the
/// dual basis (edge_b x n, n x edge_a) / |n|^2 with n = edge_a x edge_b. Points off the plane
/// are projected along n.
template <std::floating_point T>
class PlaneBasis {
public:
  PlaneBasis() = default;
  /// Precondition: the edges are finite and not parallel (callers validate them).
  PlaneBasis(const Vec3<T>& origin, const Vec3<T>& edge_a, const Vec3<T>& edge_b) : origin_(origin) {
    const Vec3<T> n = edge_a.cross(edge_b);
    const T nn = n.squaredNorm();
    dual_a_ = edge_b.cross(n) / nn;
    dual_b_ = n.cross(edge_a) / nn;
  }

  /// (a, b) of the point x (see the class comment).
  [[nodiscard]] Vec2<T> coordinates(const Vec3<T>& x) const noexcept {
    const Vec3<T> offset = x - origin_;
    return Vec2<T>(offset.dot(dual_a_), offset.dot(dual_b_));
  }

private:
  Vec3<T> origin_ = Vec3<T>::Zero();
  Vec3<T> dual_a_ = Vec3<T>::UnitX();
  Vec3<T> dual_b_ = Vec3<T>::UnitY();
};

} // namespace mpr
