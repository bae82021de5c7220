#pragma once
// Shared helpers of the GLC tests: the exact canonical examples of the reference note
// (glc-math.md sec. 5), written on the plane z = 0 with unit axes.
#include <mpr/glc.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <utility>

namespace glc_test {

template <class T>
mpr::PlanarSurface<T> unit_plane() {
  return mpr::PlanarSurface<T>(mpr::Vec3<T>::Zero(), mpr::Vec3<T>::UnitX(), mpr::Vec3<T>::UnitY());
}

/// The GLC whose generator at uv (0,0), (1,0), (0,1) goes to st points s0, s1, s2 on z = 1.
template <class T>
mpr::GlcSelector<T> from_st(const mpr::PlanarSurface<T>& plane, T s0x, T s0y, T s1x, T s1y, T s2x, T s2y) {
  return mpr::GlcSelector<T>(plane, mpr::Vec3<T>(s0x, s0y, 1), mpr::Vec3<T>(s1x - 1, s1y, 1),
                             mpr::Vec3<T>(s2x, s2y - 1, 1));
}

/// Three world rays from uv points to st points on z = 1.
template <class T>
std::array<mpr::Ray<T>, 3> rays(const std::array<std::array<T, 4>, 3>& uvst) {
  std::array<mpr::Ray<T>, 3> out;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& r = uvst[k];
    out[k] = {mpr::Vec3<T>(r[0], r[1], 0), mpr::Vec3<T>(r[2] - r[0], r[3] - r[1], 1)};
  }
  return out;
}

struct Rng {
  std::mt19937_64 engine;
  explicit Rng(unsigned long long seed) : engine(seed) {}
  double uniform(double lo, double hi) {
    // 53 random bits: the same sequence on every standard library.
    const double x = static_cast<double>(engine() >> 11) * (1.0 / 9007199254740992.0);
    return lo + (hi - lo) * x;
  }
  template <class T>
  mpr::Vec3<T> vec(double lo, double hi) {
    // The draws in statements of their own: the order of a call's arguments is unspecified and
    // differs between compilers (GCC: last first), which would give each compiler other samples.
    const double z = uniform(lo, hi), y = uniform(lo, hi), x = uniform(lo, hi);
    return mpr::Vec3<T>(T(x), T(y), T(z));
  }
};

/// A random camera of `type` built with the factories of cameras.hpp on a random plane of size
/// about 1, with its construction parameters (slit depths etc.) for error measurements.
template <class T>
struct Camera {
  mpr::PlanarSurface<T> plane;
  mpr::GlcSelector<T> selector;
  mpr::Vec3<T> centre = mpr::Vec3<T>::Zero();    // pinhole
  mpr::Vec3<T> direction = mpr::Vec3<T>::Zero(); // orthographic
  std::array<mpr::glc::Line<T>, 2> slits{};      // pushbroom, cross_slit, pencil
};

template <class T>
mpr::PlanarSurface<T> random_plane(Rng& rng) {
  for (;;) {
    const mpr::Vec3<T> o = rng.vec<T>(-1, 1), w = rng.vec<T>(-1, 1), h = rng.vec<T>(-1, 1);
    if (w.cross(h).norm() > T(0.3) * w.norm() * h.norm() && w.norm() > T(0.3) && h.norm() > T(0.3))
      return mpr::PlanarSurface<T>(o, w, h);
  }
}

template <class T>
Camera<T> random_camera(mpr::glc::Type type, Rng& rng) {
  using mpr::glc::Type;
  using V = mpr::Vec3<T>;
  const mpr::PlanarSurface<T> plane = random_plane<T>(rng);
  const V n = plane.normal(), c = plane.centre();
  const auto in_plane = [&]() {
    const V r = rng.vec<T>(-1, 1);
    return V(r - r.dot(n) * n);
  };
  const auto depth = [&]() {
    const double magnitude = rng.uniform(1, 5);
    return T(magnitude) * (rng.uniform(0, 1) < 0.3 ? 1 : -1);
  };
  const auto slit = [&](T z) { return mpr::glc::Line<T>{V(c + in_plane() + z * n), in_plane().normalized()}; };
  switch (type) {
  case Type::pinhole: {
    const T z = depth();
    const V centre = c + in_plane() + z * n;
    return {plane, mpr::glc::perspective(plane, centre), centre};
  }
  case Type::orthographic: {
    const V d = (in_plane() + n).normalized();
    return {plane, mpr::glc::orthographic(plane, d), V::Zero(), d};
  }
  case Type::pushbroom: {
    const auto s = slit(depth());
    const V fan = (s.direction + T(0.3) * in_plane().normalized() + T(0.3) * n).normalized();
    return {plane, mpr::glc::pushbroom(plane, s, fan), V::Zero(), V::Zero(), {s, {}}};
  }
  case Type::cross_slit: {
    const T z1 = depth();
    T z2 = depth();
    while (std::abs(z2 - z1) < T(0.5)) z2 = depth();
    auto s1 = slit(z1), s2 = slit(z2);
    while (s1.direction.cross(s2.direction).norm() < T(0.3)) s2 = slit(z2);
    return {plane, mpr::glc::cross_slit(plane, s1, s2), V::Zero(), V::Zero(), {s1, s2}};
  }
  case Type::pencil: {
    const T z = depth();
    const auto s = slit(z);
    return {plane, mpr::glc::pencil(plane, s, T(rng.uniform(0.3, 1)) / std::abs(z)), V::Zero(), V::Zero(), {s, {}}};
  }
  case Type::twisted_orthographic: {
    const T twist = T(rng.uniform(0.3, 1));
    const V axis = in_plane(), tilt = in_plane();
    return {plane, mpr::glc::twisted_orthographic(plane, V(n + T(0.5) * tilt), axis, twist)};
  }
  case Type::bilinear: {
    const T b = T(rng.uniform(0.3, 1)), a = T(rng.uniform(-1, 1));
    const V tilt = in_plane();
    return {plane, mpr::glc::bilinear(plane, V(n + T(0.5) * tilt), a, b)};
  }
  case Type::epi:
    break;
  }
  throw std::logic_error("random_camera: no GlcSelector for an EPI");
}

/// Distance from `x` to the line of `ray`.
template <class T>
double distance_to_line(const mpr::Ray<T>& ray, const mpr::Vec3<T>& x) {
  const mpr::Vec3<double> d = ray.direction.template cast<double>();
  const mpr::Vec3<double> p = (x - ray.origin).template cast<double>();
  return p.cross(d).norm() / d.norm();
}

/// Round-trip error of a projection: the distance from `x` to the ray that `selector` shows at
/// `uv`, relative to the magnitude of the terms of evaluating that ray at x's depth z:
/// |x - c| + |u||W| + |v||H| + |z|(|d00| + |u||d10 - d00| + |v||d01 - d00|) (the forward-error scale
/// of `point_at(uv) + z * direction_at(uv)`; it grows where uv leaves the image or rays turn fast).
template <class T>
double roundtrip_error(const mpr::PlanarSurface<T>& plane, const mpr::GlcSelector<T>& selector, const mpr::Vec3<T>& x,
                       const mpr::Vec2<T>& uv) {
  const mpr::Ray<T> ray = selector.ray_at({0, 0}, uv, plane.point_at(uv));
  const double u = std::abs(double(uv.x())), v = std::abs(double(uv.y()));
  const double z = std::abs(double((x - plane.point_at(uv)).dot(plane.normal())));
  const double scale = double((x - plane.centre()).norm()) + u * double(plane.width_vector().norm()) +
                       v * double(plane.height_vector().norm()) +
                       z * (double(selector.d00().norm()) + u * double((selector.d10() - selector.d00()).norm()) +
                            v * double((selector.d01() - selector.d00()).norm()));
  return distance_to_line(ray, x) / std::max(scale, 1e-300);
}

/// Distance between two lines (point + direction).
template <class T>
double line_distance(const mpr::glc::Line<T>& a, const mpr::glc::Line<T>& b) {
  const mpr::Vec3<double> da = a.direction.template cast<double>().normalized(),
                          db = b.direction.template cast<double>().normalized();
  const mpr::Vec3<double> w = (b.point - a.point).template cast<double>();
  const mpr::Vec3<double> n = da.cross(db);
  if (n.norm() < 1e-2)
    return std::max(w.cross(da).norm(), 0.0) + (1 - std::abs(da.dot(db))); // parallel: distance + angle
  return 1e9;                                                              // not parallel: not the same line
}

} // namespace glc_test
