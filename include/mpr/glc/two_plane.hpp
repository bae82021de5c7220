#pragma once
/// \file
/// `mpr::glc::TwoPlane`: the two-plane form of a General Linear Camera in the frame of its image
/// plane (Yu & McMillan, "General Linear Cameras", ECCV 2004, sec. 3).

#include <mpr/core/error.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/selector/glc_selector.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <limits>

namespace mpr::glc {

/// One generator ray in two-plane coordinates (sigma, tau, u, v) (ECCV 2004, eq. 1).
///
/// (u, v) is where the ray crosses the image plane, in the plane's affine coordinates:
/// the world point `origin + u * width_vector + v * height_vector` (so uv in [0,1]^2 is the
/// image of a `PlanarSurface`). (sigma, tau) is the change of (u, v) per unit of *depth* along the
/// frame normal, i.e. the ray's direction is `sigma * width_vector + tau * height_vector + normal`
/// (dimension: uv units per world length). The st plane of the papers is at depth 1:
/// s = u + sigma, t = v + tau.
template <std::floating_point T>
struct Generator {
  T sigma = 0;
  T tau = 0;
  T u = 0;
  T v = 0;
  friend bool operator==(const Generator&, const Generator&) = default;
};

/// Three generator rays of a GLC and the image-plane frame they are written in.
///
/// The frame is `origin`, `width_vector` W, `height_vector` H (world units) and the unit
/// `normal()` n = side * normalize(W x H), where `side` (+1 or -1) is the side of the plane the
/// rays travel to. The world point at plane coordinates (u, v) and depth z is
/// `origin + u W + v H + z n`; depths are world lengths along n, so a ray of `ray()` reaches depth
/// z at parameter t = z. The GLC is the set of affine combinations
/// `a * g1 + b * g2 + (1 - a - b) * g0` of the generators (componentwise in (sigma, tau, u, v)).
template <std::floating_point T>
class TwoPlane {
public:
  using scalar_type = T;

  /// Throws `argument_error` for a non-finite or degenerate frame ("origin", "width_vector",
  /// "height_vector"), a `side` other than +-1 ("side") or a non-finite generator ("generators").
  TwoPlane(const Vec3<T>& origin, const Vec3<T>& width_vector, const Vec3<T>& height_vector, int side,
           const std::array<Generator<T>, 3>& generators)
      : origin_(origin), width_(width_vector), height_(height_vector), generators_(generators) {
    if (!origin.allFinite()) throw argument_error("origin", "not finite");
    if (!width_vector.allFinite() || !(width_vector.norm() > 0))
      throw argument_error("width_vector", "zero or not finite");
    if (!height_vector.allFinite() || !(height_vector.norm() > 0))
      throw argument_error("height_vector", "zero or not finite");
    if (side != 1 && side != -1) throw argument_error("side", "must be +1 or -1");
    const Vec3<T> cross = width_vector.cross(height_vector);
    if (!(cross.norm() > 16 * std::numeric_limits<T>::epsilon() * width_vector.norm() * height_vector.norm()))
      throw argument_error("height_vector", "parallel to width_vector: the plane is degenerate");
    normal_ = T(side) * cross.normalized();
    for (const Generator<T>& g : generators)
      if (!std::isfinite(g.sigma) || !std::isfinite(g.tau) || !std::isfinite(g.u) || !std::isfinite(g.v))
        throw argument_error("generators", "not finite");
    // Dual basis of (W, H) within the plane: u = p . dual_u, v = p . dual_v for in-plane p.
    const T det = cross.dot(normal_);
    dual_u_ = height_.cross(normal_) / det;
    dual_v_ = normal_.cross(width_) / det;
  }

  [[nodiscard]] const Vec3<T>& origin() const noexcept { return origin_; }
  [[nodiscard]] const Vec3<T>& width_vector() const noexcept { return width_; }
  [[nodiscard]] const Vec3<T>& height_vector() const noexcept { return height_; }
  /// Unit normal pointing to the side the rays travel to (depth grows along it).
  [[nodiscard]] const Vec3<T>& normal() const noexcept { return normal_; }
  [[nodiscard]] const std::array<Generator<T>, 3>& generators() const noexcept { return generators_; }
  [[nodiscard]] const Generator<T>& operator[](int k) const noexcept {
    return generators_[static_cast<std::size_t>(k)];
  }

  /// World vector of a plane-coordinate offset (du, dv) (no origin added).
  [[nodiscard]] Vec3<T> in_plane(T du, T dv) const noexcept { return du * width_ + dv * height_; }
  /// World point at plane coordinates (u, v) and depth z.
  [[nodiscard]] Vec3<T> point(T u, T v, T z) const noexcept { return origin_ + in_plane(u, v) + z * normal_; }
  /// World direction of slopes (sigma, tau): unit component along `normal()`.
  [[nodiscard]] Vec3<T> direction(T sigma, T tau) const noexcept { return in_plane(sigma, tau) + normal_; }

  /// Plane coordinates (u, v) and depth z of a world point: `x = point(u, v, z)`.
  [[nodiscard]] Vec3<T> to_frame(const Vec3<T>& x) const noexcept {
    const Vec3<T> p = x - origin_;
    return {p.dot(dual_u_), p.dot(dual_v_), p.dot(normal_)};
  }

  /// The GLC ray with weights a on generator 1, b on generator 2 and 1 - a - b on generator 0,
  /// starting on the image plane; its direction has unit component along `normal()`.
  [[nodiscard]] Ray<T> ray(T a, T b) const noexcept {
    const Generator<T>& g0 = generators_[0];
    const Generator<T>& g1 = generators_[1];
    const Generator<T>& g2 = generators_[2];
    const T u = g0.u + a * (g1.u - g0.u) + b * (g2.u - g0.u);
    const T v = g0.v + a * (g1.v - g0.v) + b * (g2.v - g0.v);
    const T s = g0.sigma + a * (g1.sigma - g0.sigma) + b * (g2.sigma - g0.sigma);
    const T t = g0.tau + a * (g1.tau - g0.tau) + b * (g2.tau - g0.tau);
    return {point(u, v, T(0)), direction(s, t)};
  }

  /// The characteristic length L of the camera (world units): the longest edge of the generator
  /// triangle on the image plane, or 1 when the three generators cross the plane at one point.
  /// Every tolerance of `classify` is relative to L, so classification is scale invariant.
  [[nodiscard]] T scale() const noexcept {
    const Generator<T>& g0 = generators_[0];
    const Generator<T>& g1 = generators_[1];
    const Generator<T>& g2 = generators_[2];
    const T l = std::max({in_plane(g1.u - g0.u, g1.v - g0.v).norm(), in_plane(g2.u - g0.u, g2.v - g0.v).norm(),
                          in_plane(g2.u - g1.u, g2.v - g1.v).norm()});
    return l > 0 ? l : T(1);
  }

  /// The same camera in another scalar type.
  template <std::floating_point U>
  [[nodiscard]] TwoPlane<U> cast() const {
    std::array<Generator<U>, 3> g;
    for (std::size_t k = 0; k < 3; ++k)
      g[k] = {static_cast<U>(generators_[k].sigma), static_cast<U>(generators_[k].tau),
              static_cast<U>(generators_[k].u), static_cast<U>(generators_[k].v)};
    const int side = width_.cross(height_).dot(normal_) > 0 ? 1 : -1;
    return TwoPlane<U>(origin_.template cast<U>(), width_.template cast<U>(), height_.template cast<U>(), side, g);
  }

private:
  Vec3<T> origin_;
  Vec3<T> width_;
  Vec3<T> height_;
  std::array<Generator<T>, 3> generators_;
  Vec3<T> normal_;
  Vec3<T> dual_u_;
  Vec3<T> dual_v_;
};

/// The two-plane form of the GLC that `selector` renders on `plane`: generators at uv (0,0),
/// (1,0), (0,1) (so the weights (a, b) of `TwoPlane::ray` are the image uv), frame = the plane,
/// normal on the side the selector's rays travel to.
///
/// Throws `argument_error("selector", ...)` when the selector was built for a plane with another
/// normal (its corner directions would then not describe rays of this plane).
template <std::floating_point T>
[[nodiscard]] TwoPlane<T> two_plane(const PlanarSurface<T>& plane, const GlcSelector<T>& selector) {
  const Vec3<T>& n = plane.normal();
  if (!((selector.normal() - n).norm() <= 64 * std::numeric_limits<T>::epsilon()))
    throw argument_error("selector", "was built for a plane with a different normal");
  const int side = selector.d00().dot(n) > 0 ? 1 : -1;
  const Vec3<T> normal = T(side) * n;
  const Vec3<T> cross = plane.width_vector().cross(plane.height_vector());
  const T det = cross.dot(normal);
  const Vec3<T> dual_u = plane.height_vector().cross(normal) / det;
  const Vec3<T> dual_v = normal.cross(plane.width_vector()) / det;
  const auto slopes = [&](const Vec3<T>& d, T u, T v) {
    // d has component +-1 along n (GlcSelector's scaling); normalise exactly to +1 along `normal`.
    const Vec3<T> scaled = d / d.dot(normal);
    return Generator<T>{scaled.dot(dual_u), scaled.dot(dual_v), u, v};
  };
  return TwoPlane<T>(plane.origin(), plane.width_vector(), plane.height_vector(), side,
                     {slopes(selector.d00(), 0, 0), slopes(selector.d10(), 1, 0), slopes(selector.d01(), 0, 1)});
}

/// The two-plane form of the GLC spanned by three world rays, written in the frame of `plane`
/// (each ray is extended as a line to meet the plane). Use it for cameras a `GlcSelector` cannot
/// express (an EPI, whose generators cross the plane on one line).
///
/// Throws `argument_error("rays", ...)` for a non-finite ray, a zero direction or one parallel
/// to the plane, or rays travelling to different sides of it.
template <std::floating_point T>
[[nodiscard]] TwoPlane<T> two_plane(const PlanarSurface<T>& plane, const std::array<Ray<T>, 3>& rays) {
  const Vec3<T>& n = plane.normal();
  int side = 0;
  for (const Ray<T>& r : rays) {
    if (!r.origin.allFinite() || !r.direction.allFinite()) throw argument_error("rays", "not finite");
    const T along = r.direction.dot(n);
    if (!(std::abs(along) > 64 * std::numeric_limits<T>::epsilon() * r.direction.norm()))
      throw argument_error("rays", "zero direction or parallel to the image plane");
    const int s = along > 0 ? 1 : -1;
    if (side != 0 && s != side) throw argument_error("rays", "rays travel to different sides of the image plane");
    side = s;
  }
  const Vec3<T> normal = T(side) * n;
  const Vec3<T> cross = plane.width_vector().cross(plane.height_vector());
  const T det = cross.dot(normal);
  const Vec3<T> dual_u = plane.height_vector().cross(normal) / det;
  const Vec3<T> dual_v = normal.cross(plane.width_vector()) / det;
  std::array<Generator<T>, 3> g;
  for (std::size_t k = 0; k < 3; ++k) {
    const Vec3<T> d = rays[k].direction / rays[k].direction.dot(normal);
    const Vec3<T> p = rays[k].origin - plane.origin();
    const Vec3<T> hit = p - p.dot(normal) * d; // the ray's line at depth 0
    g[k] = {d.dot(dual_u), d.dot(dual_v), hit.dot(dual_u), hit.dot(dual_v)};
  }
  return TwoPlane<T>(plane.origin(), plane.width_vector(), plane.height_vector(), side, g);
}

} // namespace mpr::glc
