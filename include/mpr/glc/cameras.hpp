#pragma once
/// \file
/// Canonical General Linear Cameras on a given image plane: one factory per type of Yu &
/// McMillan ("General Linear Cameras", ECCV 2004, sec. 4-5). Each returns the `GlcSelector` whose
/// corner rays generate the camera, so it renders with any sampler.
///
/// Conventions shared by every factory: `plane.normal()` points into the scene and every ray
/// travels along it (positive component); slits are `Line`s in world coordinates, which must be
/// parallel to the image plane (a GLC's slits always are, ECCV 2004 sec. 4) and off it. The
/// gradient-form factories (pencil, twisted orthographic, bilinear) use the plane's orthonormal
/// frame: e1 = unit width direction, e2 = normal x e1 (towards the height vector), positions
/// q = ((p - c) . e1, (p - c) . e2) measured from the plane centre c, and ray slopes
/// (d . e1, d . e2) / (d . n) = K q + k0 with a 2x2 gradient K (1 / world length) (glc-math.md
/// sec. 5; Adams & Levoy, EGSR 2007, use P = (I + K)^-1).

#include <mpr/core/error.hpp>
#include <mpr/glc/classify.hpp>
#include <mpr/glc/two_plane.hpp>
#include <mpr/selector/glc_selector.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <array>
#include <cmath>
#include <concepts>
#include <limits>
#include <type_traits>

namespace mpr::glc {

namespace detail {

template <std::floating_point T>
struct PlaneFrame {
  Vec3<T> c, e1, e2, n;
  explicit PlaneFrame(const PlanarSurface<T>& plane)
      : c(plane.centre()), e1(plane.width_vector().normalized()), e2(plane.normal().cross(e1)), n(plane.normal()) {}
  [[nodiscard]] Vec2<T> local(const Vec3<T>& p) const { return {(p - c).dot(e1), (p - c).dot(e2)}; }
  [[nodiscard]] T depth(const Vec3<T>& p) const { return (p - c).dot(n); }
  [[nodiscard]] Vec3<T> direction(const Vec2<T>& slope) const { return n + slope.x() * e1 + slope.y() * e2; }
  [[nodiscard]] Vec2<T> slope(const Vec3<T>& d) const { return Vec2<T>(d.dot(e1), d.dot(e2)) / d.dot(n); }
};

template <std::floating_point T, class F>
[[nodiscard]] GlcSelector<T> from_directions(const PlanarSurface<T>& plane, F&& f) {
  return GlcSelector<T>(plane, f(plane.point_at({T(0), T(0)})), f(plane.point_at({T(1), T(0)})),
                        f(plane.point_at({T(0), T(1)})));
}

/// Slopes K q + k0 at the corners.
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> from_gradient(const PlanarSurface<T>& plane, const Eigen::Matrix<T, 2, 2>& K,
                                           const Vec2<T>& k0) {
  const PlaneFrame<T> fr(plane);
  return from_directions(plane, [&](const Vec3<T>& p) {
    const Vec2<T> s = K * fr.local(p) + k0;
    return fr.direction(s);
  });
}

template <std::floating_point T>
[[nodiscard]] Vec3<T> forward(const Vec3<T>& d, const Vec3<T>& n) {
  return d.dot(n) < 0 ? Vec3<T>(-d) : d;
}

template <std::floating_point T>
void check_direction(const Vec3<T>& d, const Vec3<T>& n, const char* name) {
  if (!d.allFinite() || !(d.norm() > 0)) throw argument_error(name, "zero or not finite");
  if (!(std::abs(d.normalized().dot(n)) > 64 * std::numeric_limits<T>::epsilon()))
    throw argument_error(name, "parallel to the image plane");
}

/// Validates a slit and returns its depth in front of the plane (negative: behind).
template <std::floating_point T>
T check_slit(const PlanarSurface<T>& plane, const Line<T>& slit, const char* name) {
  if (!slit.point.allFinite() || !slit.direction.allFinite() || !(slit.direction.norm() > 0))
    throw argument_error(name, "zero or not finite");
  const Vec3<T> w = slit.direction.normalized();
  if (!(std::abs(w.dot(plane.normal())) <= T(1e-4)))
    throw argument_error(name, "not parallel to the image plane (a GLC slit always is)");
  const T depth = (slit.point - plane.centre()).dot(plane.normal());
  const T size = std::max(plane.width_vector().norm(), plane.height_vector().norm());
  if (!(std::abs(depth) > 64 * std::numeric_limits<T>::epsilon() * size))
    throw argument_error(name, "lies in the image plane");
  return depth;
}

} // namespace detail

/// Pinhole camera with centre of projection `centre` (off the plane). The rays are the lines
/// through the centre, oriented into the scene (through the centre when it lies in front).
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> perspective(const PlanarSurface<T>& plane, const std::type_identity_t<Vec3<T>>& centre) {
  if (!centre.allFinite()) throw argument_error("centre", "not finite");
  const T depth = (centre - plane.centre()).dot(plane.normal());
  const T size = std::max(plane.width_vector().norm(), plane.height_vector().norm());
  if (!(std::abs(depth) > 64 * std::numeric_limits<T>::epsilon() * size))
    throw argument_error("centre", "lies in the image plane");
  return detail::from_directions(
      plane, [&](const Vec3<T>& p) { return detail::forward(Vec3<T>(p - centre), plane.normal()); });
}

/// Orthographic camera: every ray has `direction` (oriented into the scene; may be oblique).
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> orthographic(const PlanarSurface<T>& plane,
                                          const std::type_identity_t<Vec3<T>>& direction) {
  detail::check_direction(direction, plane.normal(), "direction");
  const Vec3<T> d = detail::forward(direction, plane.normal());
  return GlcSelector<T>(plane, d, d, d);
}

/// Oblique orthographic camera: parallel rays tilted from the plane normal by `angle_u` towards
/// the width direction and `angle_v` towards the height direction (radians, |angle| < pi/2):
/// direction = n + tan(angle_u) e1 + tan(angle_v) e2.
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> oblique_orthographic(const PlanarSurface<T>& plane, std::type_identity_t<T> angle_u,
                                                  std::type_identity_t<T> angle_v) {
  const T limit = T(1.5707963267948966) * (1 - 64 * std::numeric_limits<T>::epsilon());
  if (!(std::abs(angle_u) < limit)) throw argument_error("angle_u", "must be finite with |angle| < pi/2");
  if (!(std::abs(angle_v) < limit)) throw argument_error("angle_v", "must be finite with |angle| < pi/2");
  const detail::PlaneFrame<T> fr(plane);
  return orthographic(plane, fr.direction(Vec2<T>(std::tan(angle_u), std::tan(angle_v))));
}

/// Pushbroom camera: a linear sensor swept along `slit` (the path of its centre, parallel to
/// the plane); every ray meets the slit and is perpendicular to `fan_normal` (the rays of one
/// sensor position form a fan in a plane with that normal). `fan_normal` must not be
/// perpendicular to the slit; by default it is the slit direction (fans across the slit).
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> pushbroom(const PlanarSurface<T>& plane, const std::type_identity_t<Line<T>>& slit,
                                       const std::type_identity_t<Vec3<T>>& fan_normal) {
  detail::check_slit(plane, slit, "slit");
  const Vec3<T> w = slit.direction.normalized();
  if (!fan_normal.allFinite() || !(fan_normal.norm() > 0)) throw argument_error("fan_normal", "zero or not finite");
  const Vec3<T> m = fan_normal.normalized();
  if (!(std::abs(m.dot(w)) > T(1e-3))) throw argument_error("fan_normal", "perpendicular to the slit");
  return detail::from_directions(plane, [&](const Vec3<T>& p) {
    // In the plane through p and the slit, and perpendicular to m.
    const Vec3<T> to = p - slit.point;
    const Vec3<T> d = m.dot(w) * to - m.dot(to) * w;
    return detail::forward(d, plane.normal());
  });
}

template <std::floating_point T>
[[nodiscard]] GlcSelector<T> pushbroom(const PlanarSurface<T>& plane, const std::type_identity_t<Line<T>>& slit) {
  return pushbroom(plane, slit, slit.direction);
}

/// Cross-slit camera: every ray meets both slits (parallel to the plane, at different depths,
/// not parallel to each other) (Zomet et al. 2003; ECCV 2004 sec. 4).
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> cross_slit(const PlanarSurface<T>& plane, const std::type_identity_t<Line<T>>& slit1,
                                        const std::type_identity_t<Line<T>>& slit2) {
  const T z1 = detail::check_slit(plane, slit1, "slit1");
  const T z2 = detail::check_slit(plane, slit2, "slit2");
  const T size = std::max({plane.width_vector().norm(), plane.height_vector().norm(), std::abs(z1), std::abs(z2)});
  if (!(std::abs(z1 - z2) > T(1e-6) * size)) throw argument_error("slit2", "at the same depth as slit1");
  const Vec3<T> w1 = slit1.direction.normalized(), w2 = slit2.direction.normalized();
  if (!(w1.cross(w2).norm() > T(1e-6))) throw argument_error("slit2", "parallel to slit1");
  return detail::from_directions(plane, [&](const Vec3<T>& p) {
    // The intersection of the planes (p, slit1) and (p, slit2).
    const Vec3<T> n1 = w1.cross(Vec3<T>(p - slit1.point));
    const Vec3<T> n2 = w2.cross(Vec3<T>(p - slit2.point));
    return detail::forward(Vec3<T>(n1.cross(n2)), plane.normal());
  });
}

/// Pencil camera: every ray meets `slit`; the rays through one slit point form a plane
/// containing the slit, and that plane turns as the point moves along the slit. `twist`
/// (1 / world length, non-zero) is the rate: gradient K = -(1/z) I + twist w w_perp^T, where z is
/// the slit's depth and w its in-plane direction (glc-math.md sec. 5).
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> pencil(const PlanarSurface<T>& plane, const std::type_identity_t<Line<T>>& slit,
                                    std::type_identity_t<T> twist) {
  const T z = detail::check_slit(plane, slit, "slit");
  if (!std::isfinite(twist) || twist == 0) throw argument_error("twist", "must be finite and non-zero (0: a pinhole)");
  const detail::PlaneFrame<T> fr(plane);
  const Vec2<T> w = Vec2<T>(slit.direction.dot(fr.e1), slit.direction.dot(fr.e2)).normalized();
  const Vec2<T> w_perp(-w.y(), w.x());
  Eigen::Matrix<T, 2, 2> K = (-1 / z) * Eigen::Matrix<T, 2, 2>::Identity();
  K += twist * w * w_perp.transpose();
  const Vec2<T> k0 = fr.local(slit.point) / z;
  return detail::from_gradient(plane, K, k0);
}

/// Twisted orthographic camera: rays parallel to planes containing `tilt` (an in-plane
/// direction); along `tilt` their slope changes by `twist` (1 / world length, non-zero) per
/// unit of distance across it, starting from `direction` at the plane centre: gradient
/// K = twist w w_perp^T, nilpotent (ECCV 2004 sec. 5).
template <std::floating_point T>
[[nodiscard]] GlcSelector<T>
twisted_orthographic(const PlanarSurface<T>& plane, const std::type_identity_t<Vec3<T>>& direction,
                     const std::type_identity_t<Vec3<T>>& tilt, std::type_identity_t<T> twist) {
  detail::check_direction(direction, plane.normal(), "direction");
  if (!std::isfinite(twist) || twist == 0)
    throw argument_error("twist", "must be finite and non-zero (0: orthographic)");
  const detail::PlaneFrame<T> fr(plane);
  const Vec2<T> w2(tilt.dot(fr.e1), tilt.dot(fr.e2));
  if (!tilt.allFinite() || !(w2.norm() > T(1e-3) * tilt.norm()))
    throw argument_error("tilt", "zero, not finite or along the normal");
  const Vec2<T> w = w2.normalized();
  const Vec2<T> w_perp(-w.y(), w.x());
  const Eigen::Matrix<T, 2, 2> K = twist * w * w_perp.transpose();
  return detail::from_gradient(plane, K, fr.slope(detail::forward(direction, plane.normal())));
}

/// Bilinear camera: gradient K = convergence I + twist J, J = rotation by +90 degrees, so the
/// st triangle is a rotated and scaled copy of the uv triangle (ECCV 2004 sec. 5). No two rays
/// meet and no slit exists for non-zero `twist` (1 / world length). `convergence`
/// (1 / world length) spreads the rays like a pinhole at depth -1 / convergence; `direction` is
/// the ray at the plane centre.
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> bilinear(const PlanarSurface<T>& plane, const std::type_identity_t<Vec3<T>>& direction,
                                      std::type_identity_t<T> convergence, std::type_identity_t<T> twist) {
  detail::check_direction(direction, plane.normal(), "direction");
  if (!std::isfinite(convergence)) throw argument_error("convergence", "not finite");
  if (!std::isfinite(twist) || twist == 0) throw argument_error("twist", "must be finite and non-zero");
  const detail::PlaneFrame<T> fr(plane);
  Eigen::Matrix<T, 2, 2> K;
  K << convergence, -twist, twist, convergence;
  return detail::from_gradient(plane, K, fr.slope(detail::forward(direction, plane.normal())));
}

/// EPI camera: the rays that cross the image row v = `row` (in [0,1]) and whose directions lie in
/// the plane spanned by the row and `direction`, i.e. one plane of rays, a 2D slice of an
/// epipolar-plane image (ECCV 2004 sec. 4). A `GlcSelector` cannot express it (its generators
/// cross the plane at three non-collinear points), so this returns the two-plane form; render it
/// with `TwoPlaneSelector`: image u runs along the row, image v turns the ray by `spread` in
/// slope (v = 0: `direction`).
template <std::floating_point T>
[[nodiscard]] TwoPlane<T> epi(const PlanarSurface<T>& plane, std::type_identity_t<T> row,
                              const std::type_identity_t<Vec3<T>>& direction, std::type_identity_t<T> spread) {
  if (!std::isfinite(row)) throw argument_error("row", "not finite");
  detail::check_direction(direction, plane.normal(), "direction");
  if (!std::isfinite(spread) || spread == 0) throw argument_error("spread", "must be finite and non-zero");
  const Vec3<T> d = detail::forward(direction, plane.normal());
  const Vec3<T> along = plane.width_vector().normalized();
  const Vec3<T> p0 = plane.point_at({T(0), row}), p1 = plane.point_at({T(1), row});
  const Ray<T> r0{p0, d}, r1{p1, d}, r2{p0, Vec3<T>(d / d.dot(plane.normal()) + spread * along)};
  return two_plane(plane, std::array<Ray<T>, 3>{r0, r1, r2});
}

/// A ray selector for any two-plane GLC (including an EPI): image uv are the weights (a, b) of
/// `TwoPlane::ray`; it ignores the surface point (use any surface of the same scalar type).
template <std::floating_point T>
class TwoPlaneSelector {
public:
  using scalar_type = T;
  explicit TwoPlaneSelector(const TwoPlane<T>& glc) : glc_(glc) {}
  [[nodiscard]] Ray<T> ray_at(Pixel, const Vec2<T>& uv, const Vec3<T>&) const noexcept {
    return glc_.ray(uv.x(), uv.y());
  }
  [[nodiscard]] const TwoPlane<T>& glc() const noexcept { return glc_; }

private:
  TwoPlane<T> glc_;
};

} // namespace mpr::glc
