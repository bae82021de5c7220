#pragma once
/// \file
/// Closed-form projection of a 3D point into a General Linear Camera (Yu & McMillan,
/// "Multiperspective Projection and Collineation", ICCV 2005): the GLC ray through a point at
/// depth z has the barycentric weights of the point in the generator triangle at that depth, a
/// 2x2 linear solve.

#include <mpr/glc/two_plane.hpp>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <limits>
#include <optional>
#include <type_traits>

namespace mpr::glc {

/// Settings of `project`.
template <std::floating_point T>
struct ProjectConfig {
  /// The point's depth counts as a slit depth when |D(z)| <= `singular * eps(double) * |m1||m2|`
  /// (the 2x2 system's determinant against the size of its columns).
  double singular = 64;
  /// At a slit depth, a point within `slit_tolerance * max(L, |z|)` (world units, L =
  /// `TwoPlane::scale()`) of the slit (or of a pinhole's centre) lies on it.
  T slit_tolerance = sizeof(T) < sizeof(double) ? T(1e-4) : T(1e-9);
};

/// The weights (a, b) of the GLC ray of `glc` through `point` (the ray is `glc.ray(a, b)`), or
/// empty when no ray passes through it.
///
/// Solves (x, y) = P0(z) + a (P1(z) - P0(z)) + b (P2(z) - P0(z)) at the point's depth z, where
/// Pk(z) is where generator k reaches depth z, by Cramer's rule in double precision (float input
/// too). The determinant is D(z), the characteristic polynomial, so the solve is singular exactly
/// at slit depths. There:
/// - a point off the slit (or off a pinhole's centre) is seen by no ray: empty;
/// - a point on a slit is seen by a one-parameter family of rays (a whole image curve); the
///   documented choice is the member whose weights are closest to `preferred`.
/// A point with z < 0 lies behind the image plane: the returned ray's *line* passes through it
/// (at parameter t = z), not the ray itself. Returns empty for a non-finite point.
template <std::floating_point T>
[[nodiscard]] std::optional<Vec2<T>> project(const TwoPlane<T>& glc, const std::type_identity_t<Vec3<T>>& point,
                                             const Vec2<T>& preferred = Vec2<T>(T(1) / 3, T(1) / 3),
                                             const ProjectConfig<T>& config = {}) noexcept {
  if (!point.allFinite()) return std::nullopt;
  const Vec3<double> f = glc.to_frame(point).template cast<double>();
  const double z = f.z();
  const auto& g = glc.generators();
  const auto at = [&](std::size_t k) {
    return Vec2<double>(double(g[k].u) + z * double(g[k].sigma), double(g[k].v) + z * double(g[k].tau));
  };
  const Vec2<double> p0 = at(0);
  const Vec2<double> m1 = at(1) - p0, m2 = at(2) - p0;
  const Vec2<double> rhs = Vec2<double>(f.x(), f.y()) - p0;
  const double d = m1.x() * m2.y() - m1.y() * m2.x();
  const double eps = std::numeric_limits<double>::epsilon();
  if (std::abs(d) > config.singular * eps * m1.norm() * m2.norm()) {
    const double a = (rhs.x() * m2.y() - rhs.y() * m2.x()) / d;
    const double b = (m1.x() * rhs.y() - m1.y() * rhs.x()) / d;
    const Vec2<T> w(static_cast<T>(a), static_cast<T>(b));
    if (!w.allFinite()) return std::nullopt;
    return w;
  }
  // Slit depth: the columns are parallel (slit) or both ~zero (pinhole centre depth).
  const Vec3<double> width = glc.width_vector().template cast<double>();
  const Vec3<double> height = glc.height_vector().template cast<double>();
  const auto world = [&](const Vec2<double>& uv) { return Vec3<double>(uv.x() * width + uv.y() * height).norm(); };
  const double tolerance = double(config.slit_tolerance) * std::max(double(glc.scale()), std::abs(z));
  const Vec2<double>& m = m1.norm() >= m2.norm() ? m1 : m2;
  const double size = world(m);
  const Vec2<double> want = preferred.template cast<double>();
  if (!(size > tolerance)) {
    // Pinhole centre depth: all generators meet at P0(z).
    if (!(world(rhs) <= tolerance)) return std::nullopt;
    return preferred;
  }
  const Vec2<double> t = m / m.norm();
  const Vec2<double> off = rhs - rhs.dot(t) * t; // component of the point off the slit line
  if (!(world(off) <= tolerance)) return std::nullopt;
  // Weights w with w.x (m1 . t) + w.y (m2 . t) = rhs . t, closest to `preferred`.
  const Vec2<double> k(m1.dot(t), m2.dot(t));
  const Vec2<double> w = want + k * ((rhs.dot(t) - k.dot(want)) / k.squaredNorm());
  const Vec2<T> out = w.template cast<T>();
  if (!out.allFinite()) return std::nullopt;
  return out;
}

/// The image uv of `point` in the GLC that `selector` renders on `plane`: the ray
/// `selector.ray_at(px, uv, plane.point_at(uv))` passes through `point` (at t = its depth, see
/// the TwoPlane overload). uv may lie outside [0,1]^2 (the point is outside the image). On a
/// slit the returned uv is the one closest to the image centre (0.5, 0.5). Empty when no ray of
/// the camera passes through the point.
template <std::floating_point T>
[[nodiscard]] std::optional<Vec2<T>> project(const PlanarSurface<T>& plane, const GlcSelector<T>& selector,
                                             const std::type_identity_t<Vec3<T>>& point,
                                             const ProjectConfig<T>& config = {}) {
  return project(two_plane(plane, selector), point, Vec2<T>(T(0.5), T(0.5)), config);
}

} // namespace mpr::glc
