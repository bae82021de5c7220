#pragma once
/// \file
/// Classification of a General Linear Camera into the eight types of Yu & McMillan ("General
/// Linear Cameras", ECCV 2004, Table 1), with its slits, centre or direction in world coordinates.
/// The same taxonomy appears as eigen-structures in Adams & Levoy ("General Linear Cameras with
/// Finite Aperture", EGSR 2007).

#include <mpr/core/error.hpp>
#include <mpr/glc/characteristic.hpp>
#include <mpr/glc/two_plane.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <limits>
#include <string_view>
#include <type_traits>

namespace mpr::glc {

/// The eight GLC types (ECCV 2004, Table 1).
enum class Type {
  pinhole,              ///< all rays through one point (double root, generator triangles homothetic)
  orthographic,         ///< all rays parallel
  pushbroom,            ///< rays through one slit and parallel to one plane (one finite root)
  cross_slit,           ///< rays through two slits at different depths (two real roots)
  pencil,               ///< rays through one slit, in planes containing it (double root, not pinhole)
  twisted_orthographic, ///< rays parallel to one plane, direction rotating (double root at infinity)
  bilinear,             ///< no slit (complex roots): every point lies on exactly one ray
  epi                   ///< all rays lie in one plane (D(z) identically zero)
};

/// The enumerator's name, e.g. "cross_slit".
[[nodiscard]] constexpr std::string_view to_string(Type t) noexcept {
  switch (t) {
  case Type::pinhole:
    return "pinhole";
  case Type::orthographic:
    return "orthographic";
  case Type::pushbroom:
    return "pushbroom";
  case Type::cross_slit:
    return "cross_slit";
  case Type::pencil:
    return "pencil";
  case Type::twisted_orthographic:
    return "twisted_orthographic";
  case Type::bilinear:
    return "bilinear";
  case Type::epi:
    return "epi";
  }
  return "unknown";
}

/// A line `point + s * direction` in world coordinates; `direction` has unit length.
template <std::floating_point T>
struct Line {
  Vec3<T> point = Vec3<T>::Zero();
  Vec3<T> direction = Vec3<T>::Zero();
};

/// Tolerances of `classify`, all relative to the camera's characteristic length L
/// (`TwoPlane::scale()`, the longest edge of the generator triangle on the image plane, i.e. about
/// the image size for a `GlcSelector`) or dimensionless, so the type does not change when the
/// scene is scaled or translated. Defaults depend on the scalar type of the input: a GLC whose
/// generators were rounded to float carries float-sized errors even though `classify` computes in
/// double. The defaults were chosen from the measurements in docs/numerics.md.
template <std::floating_point T>
struct ClassifyConfig {
  static constexpr bool is_float = sizeof(T) < sizeof(double);
  /// The reference length L (world units) of every tolerance below; 0 (default): the camera's
  /// own `TwoPlane::scale()`. Pass the same L to compare cameras whose generator triangles
  /// differ in size (a slit at 500 L1 is finite for L1 but at infinity for L2 = L1 / 10).
  T length = 0;
  /// A slit farther than `far * L` from the image plane is at infinity. Rounding a
  /// pencil-like or twisted camera's generators by eps moves a double root at infinity to about
  /// L / sqrt(eps) (7e7 L in double, 3e3 L in float), so `far` must stay below that.
  T far = is_float ? T(300) : T(1e6);
  /// Two slits closer in depth than `depth_tolerance * L + relative_depth * |depth|` are one
  /// double slit (pinhole or pencil). Rounding splits a pencil's double root by about
  /// sqrt(eps) relative, so `relative_depth` must be much larger than sqrt(eps).
  T depth_tolerance = is_float ? T(1e-4) : T(1e-9);
  T relative_depth = is_float ? T(1e-2) : T(1e-6);
  /// A double slit is a pinhole when the three generators cross its depth within
  /// `lateral_tolerance * max(L, |depth|)` of each other; otherwise it is a pencil.
  T lateral_tolerance = is_float ? T(1e-4) : T(1e-9);
  /// Without finite slits, the camera is orthographic when the generator directions differ by
  /// less than this angle (radians), twisted orthographic otherwise.
  T angular_tolerance = is_float ? T(1e-3) : T(1e-7);
  /// Relative size of the 2x2 minors of [r1 - r0; r2 - r0] below which the generators are
  /// affinely dependent (not a GLC), and of A, B, C below which the camera is an EPI.
  T rank_tolerance = T(1024) * std::numeric_limits<T>::epsilon();
};

/// The result of `classify`. Depths are world lengths from the image plane along the
/// `TwoPlane::normal()` (the side the rays travel to; negative: behind the ray origins).
template <std::floating_point T>
struct Classification {
  Type type = Type::epi;
  /// Number of finite slits: 2 (cross_slit), 1 (pushbroom, pencil), 0 otherwise.
  int slit_count = 0;
  /// Slit depths, nearest first (cross_slit: two; pushbroom, pencil: one), and for a pinhole the
  /// depth of its centre in `depths[0]`.
  std::array<T, 2> depths{};
  /// The slits in world coordinates; each is parallel to the image plane (ECCV 2004, sec. 4).
  std::array<Line<T>, 2> slits{};
  /// Pinhole: the centre of projection.
  Vec3<T> centre = Vec3<T>::Zero();
  /// Orthographic: the common (unit, scene-facing) ray direction.
  Vec3<T> direction = Vec3<T>::Zero();
  /// The characteristic equation (plane uv units) and its roots, for diagnostics.
  Characteristic<double> characteristic{};
  Roots roots{};
};

namespace detail {

template <std::floating_point T>
[[nodiscard]] Line<T> slit_at(const TwoPlane<double>& glc, double z) noexcept {
  // At a slit depth the generator triangle collapses to a segment on the slit: its centroid is a
  // point of the slit and its longest edge the slit's direction.
  std::array<Vec3<double>, 3> p;
  for (std::size_t k = 0; k < 3; ++k) {
    const Generator<double>& g = glc.generators()[k];
    p[k] = glc.in_plane(g.u + z * g.sigma, g.v + z * g.tau);
  }
  const std::array<Vec3<double>, 3> edges{Vec3<double>(p[1] - p[0]), Vec3<double>(p[2] - p[0]),
                                          Vec3<double>(p[2] - p[1])};
  std::size_t longest = 0;
  for (std::size_t k = 1; k < 3; ++k)
    if (edges[k].norm() > edges[longest].norm()) longest = k;
  const Vec3<double> centroid = (p[0] + p[1] + p[2]) / 3.0 + glc.origin() + z * glc.normal();
  const double length = edges[longest].norm();
  const Vec3<double> dir = length > 0 ? Vec3<double>(edges[longest] / length) : Vec3<double>::Zero();
  return {centroid.template cast<T>(), dir.template cast<T>()};
}

} // namespace detail

/// The type of the GLC `glc` and its slits / centre / direction (the robust classifier of the
/// reference note glc-math.md sec. 7.2). Computes in double precision for float input too.
///
/// Decision order: affine dependence (error), EPI (A = B = C = 0 relative to the size of each
/// coefficient's terms), then the roots of the characteristic equation: a root beyond `far * L`
/// is at infinity; none finite: orthographic or twisted orthographic by the direction spread;
/// one: pushbroom; two distinct (farther apart than the depth tolerance): cross-slit; a complex
/// pair closer than the depth tolerance, or two close real roots, is a double root z0 = -B/2A,
/// and then pinhole or pencil by whether the generators meet within the lateral tolerance at z0;
/// a complex pair otherwise: bilinear.
///
/// Throws `argument_error("generators", ...)` when the three generators are affinely dependent
/// (they span a single ray or a one-parameter family: not a GLC, although A = B = C = 0 there too).
template <std::floating_point T>
[[nodiscard]] Classification<T> classify(const TwoPlane<T>& input, const ClassifyConfig<T>& config = {}) {
  const TwoPlane<double> glc = input.template cast<double>();
  const auto& g = glc.generators();
  if (!(config.length >= 0) || !std::isfinite(config.length)) throw argument_error("length", "must be >= 0 and finite");
  const double L = config.length > 0 ? static_cast<double>(config.length) : glc.scale();
  const double rank_tol = static_cast<double>(config.rank_tolerance);

  // Affine independence: rank [r1 - r0; r2 - r0] = 2, measured in comparable units (plane
  // coordinates; slopes times L).
  {
    const std::array<double, 4> a{g[1].u - g[0].u, g[1].v - g[0].v, L * (g[1].sigma - g[0].sigma),
                                  L * (g[1].tau - g[0].tau)};
    const std::array<double, 4> b{g[2].u - g[0].u, g[2].v - g[0].v, L * (g[2].sigma - g[0].sigma),
                                  L * (g[2].tau - g[0].tau)};
    double minors = 0, na = 0, nb = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      na += a[i] * a[i];
      nb += b[i] * b[i];
      for (std::size_t j = i + 1; j < 4; ++j) {
        const double m = detail::cross2(a[i], a[j], b[i], b[j]);
        minors += m * m;
      }
    }
    if (!(std::sqrt(minors) > rank_tol * std::sqrt(na) * std::sqrt(nb)))
      throw argument_error("generators", "affinely dependent: the three rays span fewer than two dimensions of "
                                         "ray space, so they define no GLC");
  }

  Classification<T> out;
  out.characteristic = characteristic(glc);
  const Characteristic<double>& ch = out.characteristic;
  const Roots r = roots(ch);
  out.roots = r;

  const auto plane_len = [&](double du, double dv) { return glc.in_plane(du, dv).norm(); };
  const double e2 = std::hypot(g[1].u - g[0].u, g[1].v - g[0].v), e3 = std::hypot(g[2].u - g[0].u, g[2].v - g[0].v);
  const double f2 = std::hypot(g[1].sigma - g[0].sigma, g[1].tau - g[0].tau),
               f3 = std::hypot(g[2].sigma - g[0].sigma, g[2].tau - g[0].tau);
  if (std::abs(ch.a) <= rank_tol * f2 * f3 && std::abs(ch.b) <= rank_tol * (e2 * f3 + f2 * e3) &&
      std::abs(ch.c) <= rank_tol * e2 * e3) {
    out.type = Type::epi;
    return out;
  }

  const double far = static_cast<double>(config.far) * L;
  const double depth_tol = static_cast<double>(config.depth_tolerance) * L;
  const double rel_depth = static_cast<double>(config.relative_depth);

  const auto parallel_type = [&]() {
    const double spread = std::max({plane_len(g[1].sigma - g[0].sigma, g[1].tau - g[0].tau),
                                    plane_len(g[2].sigma - g[0].sigma, g[2].tau - g[0].tau),
                                    plane_len(g[2].sigma - g[1].sigma, g[2].tau - g[1].tau)});
    if (spread <= static_cast<double>(config.angular_tolerance)) {
      out.type = Type::orthographic;
      const Vec3<double> d =
          glc.direction((g[0].sigma + g[1].sigma + g[2].sigma) / 3.0, (g[0].tau + g[1].tau + g[2].tau) / 3.0);
      out.direction = d.normalized().template cast<T>();
    } else {
      out.type = Type::twisted_orthographic;
    }
    return out;
  };

  double z0 = 0; // a double root, when the code below falls through
  if (r.complex) {
    const double modulus = std::hypot(r.real, r.imag);
    if (modulus > far) return parallel_type();
    if (2 * r.imag > depth_tol + rel_depth * std::abs(r.real)) {
      out.type = Type::bilinear;
      return out;
    }
    z0 = r.real;
  } else {
    const bool first_finite = std::abs(r.first) <= far, second_finite = std::abs(r.second) <= far;
    if (!first_finite) return parallel_type(); // |first| <= |second|
    if (!second_finite) {
      out.type = Type::pushbroom;
      out.slit_count = 1;
      out.depths[0] = static_cast<T>(r.first);
      out.slits[0] = detail::slit_at<T>(glc, r.first);
      return out;
    }
    if (std::abs(r.first - r.second) > depth_tol + rel_depth * std::max(std::abs(r.first), std::abs(r.second))) {
      out.type = Type::cross_slit;
      out.slit_count = 2;
      const double near = std::abs(r.first) <= std::abs(r.second) ? r.first : r.second;
      const double farther = near == r.first ? r.second : r.first;
      out.depths = {static_cast<T>(near), static_cast<T>(farther)};
      out.slits = {detail::slit_at<T>(glc, near), detail::slit_at<T>(glc, farther)};
      return out;
    }
    z0 = ch.a != 0 ? -ch.b / (2 * ch.a) : 0.5 * (r.first + r.second);
  }

  // Double root at z0: pinhole when the generators meet in one point there, else pencil.
  std::array<Vec3<double>, 3> p;
  for (std::size_t k = 0; k < 3; ++k) p[k] = glc.in_plane(g[k].u + z0 * g[k].sigma, g[k].v + z0 * g[k].tau);
  const double spread = std::max({(p[1] - p[0]).norm(), (p[2] - p[0]).norm(), (p[2] - p[1]).norm()});
  out.depths[0] = static_cast<T>(z0);
  if (spread <= static_cast<double>(config.lateral_tolerance) * std::max(L, std::abs(z0))) {
    out.type = Type::pinhole;
    const Vec3<double> c = (p[0] + p[1] + p[2]) / 3.0 + glc.origin() + z0 * glc.normal();
    out.centre = c.template cast<T>();
  } else {
    out.type = Type::pencil;
    out.slit_count = 1;
    out.slits[0] = detail::slit_at<T>(glc, z0);
  }
  return out;
}

/// The type of the GLC that `selector` renders on `plane` (see `two_plane`). A `GlcSelector` is
/// never an EPI (its generators cross the plane at three non-collinear points).
template <std::floating_point T>
[[nodiscard]] Classification<T> classify(const PlanarSurface<T>& plane, const GlcSelector<T>& selector,
                                         const ClassifyConfig<T>& config = {}) {
  return classify(two_plane(plane, selector), config);
}

} // namespace mpr::glc
