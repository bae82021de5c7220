#pragma once
/// \file
/// `mpr::GlcSelector`: the General Linear Camera ray field (Yu & McMillan, "General Linear
/// Cameras", ECCV 2004).

#include <mpr/core/error.hpp>
#include <mpr/core/pixel.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/ray_grid.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <cmath>
#include <limits>
#include <string>

namespace mpr {

/// The GLC given by an image plane and the ray directions at its corners uv (0,0), (1,0), (0,1).
///
/// Two-plane parametrisation (ECCV 2004, sec. 3): the uv plane is the image plane and the st plane
/// lies at unit distance along the plane normal n. Each corner direction is scaled to unit
/// component along n (keeping its side), so it reaches the st plane after one unit; the scaled
/// direction is then interpolated *affinely* over uv:
///   d(u, v) = d00 + u (d10 - d00) + v (d01 - d00),
/// i.e. (sigma, tau) are affine in (u, v) and the rays form the GLC spanned by the three corner
/// rays. The ray starts at the surface point passed in and its direction's component along n
/// is +-1 everywhere, so no ray is ever parallel to the plane and `ray.at(t)` lies at depth `t`
/// from the plane. Any image surface can be combined with it (the selector reads only `uv` and
/// the point); the GLC itself is defined with respect to the plane given here.
template <std::floating_point T>
class GlcSelector {
public:
  using scalar_type = T;

  /// Throws `argument_error` naming "d00", "d10" or "d01" when a direction is not finite, is
  /// zero, is parallel to the plane (|d.n| <= 64 eps |d|), or lies on the other side of the plane
  /// than d00.
  GlcSelector(const PlanarSurface<T>& plane, const Vec3<T>& d00, const Vec3<T>& d10, const Vec3<T>& d01)
      : normal_(plane.normal()) {
    const Vec3<T> s00 = scaled(d00, "d00");
    const Vec3<T> s10 = scaled(d10, "d10");
    const Vec3<T> s01 = scaled(d01, "d01");
    const T side = s00.dot(normal_);
    if (s10.dot(normal_) * side < 0) throw argument_error("d10", "on the other side of the image plane than d00");
    if (s01.dot(normal_) * side < 0) throw argument_error("d01", "on the other side of the image plane than d00");
    d00_ = s00;
    du_ = s10 - s00;
    dv_ = s01 - s00;
  }

  /// The ray of the GLC at `uv`, starting at `point` (the surface point of `uv`).
  [[nodiscard]] Ray<T> ray_at(Pixel, const Vec2<T>& uv, const Vec3<T>& point) const noexcept {
    return {point, direction_at(uv)};
  }

  /// The rays `ray_at` returns over a surface whose points are `points` (`AffineSelector`): they
  /// start at the points and their directions are `direction_at`.
  [[nodiscard]] AffineRays<T> affine_rays(const AffineField3<T>& points) const noexcept {
    return {points, {d00_, du_, dv_}};
  }

  /// The scaled direction at `uv` (component +-1 along the plane normal).
  [[nodiscard]] Vec3<T> direction_at(const Vec2<T>& uv) const noexcept {
    // Per component, as `PlanarSurface::point_at`: keeps the per-pixel path free of calls.
    const T u = uv.x(), v = uv.y();
    return Vec3<T>(d00_.x() + u * du_.x() + v * dv_.x(), d00_.y() + u * du_.y() + v * dv_.y(),
                   d00_.z() + u * du_.z() + v * dv_.z());
  }

  /// The scaled corner directions at uv (0,0), (1,0) and (0,1).
  [[nodiscard]] Vec3<T> d00() const noexcept { return d00_; }
  [[nodiscard]] Vec3<T> d10() const noexcept { return d00_ + du_; }
  [[nodiscard]] Vec3<T> d01() const noexcept { return d00_ + dv_; }
  /// Unit normal of the plane the GLC was defined on.
  [[nodiscard]] const Vec3<T>& normal() const noexcept { return normal_; }

private:
  Vec3<T> scaled(const Vec3<T>& d, const char* name) const {
    if (!d.allFinite()) throw argument_error(name, "not finite");
    const T length = d.norm();
    if (!(length > 0)) throw argument_error(name, "zero direction");
    const T along = d.dot(normal_);
    if (!(std::abs(along) > 64 * std::numeric_limits<T>::epsilon() * length))
      throw argument_error(name, "parallel to the image plane");
    return d / std::abs(along);
  }

  Vec3<T> normal_;
  Vec3<T> d00_;
  Vec3<T> du_;
  Vec3<T> dv_;
};

} // namespace mpr
