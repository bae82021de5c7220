#pragma once
/// \file
/// Finite-aperture GLCs (Adams and Levoy, "General Linear Cameras with Finite Aperture", EGSR
/// 2007; encoding of docs/glc.md and the reference notes, section 6): a pixel integrates the
/// light field over a 2-D aperture, I(x) = integral of w(a) L(ray(x, a)) da.
///
/// Two planes: the image plane (where the rays of the wrapped pinhole selector start; the
/// "z = 1" plane of the encoding) and the lens plane parallel to it at distance `lens_distance`
/// behind it, on the side away from the scene ("z = 0"). Aperture coordinates a are world units
/// along the image plane's unit axes (width and height directions). The ray of pixel x and
/// aperture point a crosses the lens plane at P(x) + a, where P(x) is the crossing of the
/// pinhole ray of x (the GLC, "perspective" part), and the image plane at X + F a, where X is the
/// pixel's surface point and F the 2x2 focus matrix: the block map [[I, F], [P, I]].
/// - F = 0: all rays of a pixel pass through its point on the image plane: a thin lens focused on
///   the image plane, circle of confusion 2 r |D - h| / D for an object at distance D from the
///   lens plane (aperture radius r, h = lens_distance; tested against this thin-lens formula).
/// - F = f I: the rays of a pixel meet at depth z = 1 / (1 - f) (lens plane 0, image plane 1), a
///   refocused thin lens (anastigmatic); `focus_at_depth` builds it for a distance in front of the
///   image plane.
/// - distinct eigenvalues: astigmatic, two focal lines (glc::classify_focus).
/// Under `PixelCentre` a finite-aperture selector renders its pinhole (a = 0) image; under a
/// `Supersample` policy whose pattern has lens points, each sample gets its own aperture point.

#include <mpr/core/concepts.hpp>
#include <mpr/core/error.hpp>
#include <mpr/glc/aperture.hpp>
#include <mpr/sampling/pixel_sampling.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <Eigen/Core>

#include <cmath>
#include <utility>

namespace mpr::glc {

template <std::floating_point T>
using Mat2 = Eigen::Matrix<T, 2, 2>;

/// The focus matrix f I that focuses a finite-aperture GLC at `depth` in front of the image plane
/// (world units; depth 0: on the image plane, F = 0), with the lens plane `lens_distance` behind
/// it: f = depth / (lens_distance + depth). Throws `argument_error` naming "focus depth" unless
/// depth > -lens_distance and finite.
template <std::floating_point T>
[[nodiscard]] Mat2<T> focus_at_depth(T lens_distance, T depth) {
  if (!std::isfinite(depth) || !(depth + lens_distance > 0))
    throw argument_error("focus depth", "must be finite and in front of the lens plane");
  return Mat2<T>(Mat2<T>::Identity() * (depth / (lens_distance + depth)));
}

/// Astigmatic focus: focal distance `depth_u` for the aperture's u direction and `depth_v` for
/// its v direction (F = diag(f_u, f_v)); the focal lines lie along the other axis.
template <std::floating_point T>
[[nodiscard]] Mat2<T> astigmatic_focus(T lens_distance, T depth_u, T depth_v) {
  Mat2<T> f = Mat2<T>::Zero();
  f(0, 0) = focus_at_depth(lens_distance, depth_u)(0, 0);
  f(1, 1) = focus_at_depth(lens_distance, depth_v)(1, 1);
  return f;
}

/// A finite aperture around the pinhole selector `Inner` (e.g. `GlcSelector<T>`) on `plane`.
template <RaySelector Inner, ApertureShape Shape>
class FiniteAperture {
public:
  using scalar_type = typename Inner::scalar_type;
  using T = scalar_type;

  /// `size`: aperture radius (disc, polygon), half side (square) or sigma (Gaussian), world
  /// units, >= 0 (0: the pinhole). `lens_distance` > 0: the lens plane's distance behind the
  /// image plane. Throws `argument_error` naming "aperture size", "aperture distance" or
  /// "focus matrix" for bad values, and "focus" when a corner or the centre ray of the view is
  /// (nearly) parallel to the image plane, where the lens plane has no crossing.
  FiniteAperture(const PlanarSurface<T>& plane, Inner inner, Shape shape, T size, T lens_distance,
                 const Mat2<T>& focus = Mat2<T>::Zero())
      : inner_(std::move(inner)), shape_(std::move(shape)), size_(size), h_(lens_distance), focus_(focus) {
    if (!std::isfinite(size) || size < 0) throw argument_error("aperture size", "must be finite and >= 0");
    if (!std::isfinite(lens_distance) || !(lens_distance > 0))
      throw argument_error("aperture distance", "must be finite and > 0");
    if (!focus.allFinite()) throw argument_error("focus matrix", "not finite");
    axis_u_ = plane.width_vector().normalized();
    axis_v_ = plane.height_vector().normalized();
    normal_ = plane.normal();
    const Vec3<T>& n = normal_;
    for (const Vec2<T>& uv : {Vec2<T>(0, 0), Vec2<T>(1, 0), Vec2<T>(0, 1), Vec2<T>(1, 1), Vec2<T>(0.5, 0.5)}) {
      const Ray<T> r = inner_.ray_at(Pixel{}, uv, plane.point_at(uv));
      if (!(std::fabs(r.direction.dot(n)) > T(1e-6) * r.direction.norm()))
        throw argument_error("focus", "the rays are parallel to the image plane (no focal plane crossing)");
    }
  }

  [[nodiscard]] const Inner& inner() const noexcept { return inner_; }
  [[nodiscard]] const Shape& shape() const noexcept { return shape_; }
  [[nodiscard]] T size() const noexcept { return size_; }
  [[nodiscard]] T lens_distance() const noexcept { return h_; }
  [[nodiscard]] const Mat2<T>& focus() const noexcept { return focus_; }

  /// The pinhole (central, a = 0) ray.
  [[nodiscard]] Ray<T> ray_at(Pixel px, const Vec2<T>& uv, const Vec3<T>& point) const noexcept {
    return inner_.ray_at(px, uv, point);
  }

  /// The ray of aperture point `size * shape.at(lens)` (see the file comment): it starts on the
  /// image plane at X + F a and comes from P(x) + a on the lens plane.
  [[nodiscard]] Ray<T> ray_at(Pixel px, const Vec2<T>& uv, const Vec3<T>& point, SamplePoint lens) const noexcept {
    const Ray<T> c = inner_.ray_at(px, uv, point);
    const Vec2<double> s = shape_.at(lens);
    const Vec2<T> a(static_cast<T>(s.x()) * size_, static_cast<T>(s.y()) * size_);
    const Vec2<T> fa = focus_ * a;
    const Vec3<T> on_image = fa.x() * axis_u_ + fa.y() * axis_v_;
    const Vec3<T> on_lens = a.x() * axis_u_ + a.y() * axis_v_;
    // c.direction / |d.n| * h reaches from the lens plane to the image plane along the pinhole
    // ray; the aperture ray's direction is that plus (F a - a), rescaled by |d.n| / h.
    const T scale = std::fabs(c.direction.dot(normal_)) / h_;
    return {Vec3<T>(c.origin + on_image), Vec3<T>(c.direction + scale * (on_image - on_lens))};
  }

private:
  Inner inner_;
  Shape shape_;
  T size_, h_;
  Mat2<T> focus_;
  Vec3<T> axis_u_ = Vec3<T>::UnitX(), axis_v_ = Vec3<T>::UnitY(), normal_ = Vec3<T>::UnitZ();
};

} // namespace mpr::glc
