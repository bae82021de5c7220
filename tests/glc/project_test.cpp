#include "glc_test_util.hpp"

#include <mpr/glc/cameras.hpp>
#include <mpr/glc/project.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

using mpr::glc::Type;

namespace {
constexpr std::array<Type, 7> kTypes{Type::pinhole, Type::orthographic,         Type::pushbroom, Type::cross_slit,
                                     Type::pencil,  Type::twisted_orthographic, Type::bilinear};
}

// Round trip: project, then ray_at at the returned uv, then the distance from the point to that
// ray's line, relative to the forward-error scale of evaluating the ray (glc_test::roundtrip_error).
// Points away from slits: |D(z)| >= 0.05 (|A| z^2 + |B| |z| + |C|), depths 0.2 .. 30.
TEMPLATE_TEST_CASE("project: round trip through ray_at, away from slits", "[glc][project]", float, double) {
  using T = TestType;
  glc_test::Rng rng(1005);
  // The bound: 1e-12 relative in double (measured: below 1e-14).
  const double bound = sizeof(T) == 4 ? 1e-5 : 1e-12;
  std::ostringstream report;
  for (const Type type : kTypes) {
    double worst = 0;
    int projected = 0;
    for (int i = 0; i < 200; ++i) {
      const auto cam = glc_test::random_camera<T>(type, rng);
      const auto tp = mpr::glc::two_plane(cam.plane, cam.selector);
      const auto ch = mpr::glc::characteristic(tp);
      for (int j = 0; j < 20; ++j) {
        const T z = T(rng.uniform(0.2, 30));
        const mpr::Vec3<T> x = cam.plane.centre() + rng.vec<T>(-1, 1) * (1 + z) + z * tp.normal();
        const double zd = double(tp.to_frame(x).z());
        if (std::abs(ch(zd)) < 0.05 * (std::abs(ch.a) * zd * zd + std::abs(ch.b * zd) + std::abs(ch.c))) continue;
        const auto uv = mpr::glc::project(cam.plane, cam.selector, x);
        REQUIRE(uv.has_value());
        worst = std::max(worst, glc_test::roundtrip_error(cam.plane, cam.selector, x, *uv));
        ++projected;
      }
    }
    INFO(mpr::glc::to_string(type));
    CHECK(projected > 2000);
    CHECK(worst <= bound);
    report << mpr::glc::to_string(type) << " " << worst << "  ";
  }
  WARN((sizeof(T) == 4 ? "float" : "double") << " projection round trip, worst relative distance: " << report.str());
}

// Near a slit the 2x2 system is ill conditioned (its determinant is D(z) ~ delta): a point at
// relative depth distance delta from a slit projects to uv with an error that grows like eps / delta.
TEMPLATE_TEST_CASE("project: round trip near slits", "[glc][project]", float, double) {
  using T = TestType;
  glc_test::Rng rng(77);
  std::ostringstream report;
  bool within = true;
  for (const double delta : {1e-2, 1e-4, 1e-6, 1e-8}) {
    if (sizeof(T) == 4 && delta < 1e-5) continue; // below float's depth resolution
    double worst = 0;
    int projected = 0;
    for (int i = 0; i < 300; ++i) {
      const auto cam = glc_test::random_camera<T>(rng.uniform(0, 1) < 0.5 ? Type::cross_slit : Type::pushbroom, rng);
      const auto cl = mpr::glc::classify(cam.plane, cam.selector);
      const auto tp = mpr::glc::two_plane(cam.plane, cam.selector);
      // A point near the slit line at relative depth distance delta from the slit (the draws in
      // a fixed order: every compiler tests the same points).
      const T across = T(rng.uniform(-0.5, 0.5)), along = T(rng.uniform(-2, 2));
      const mpr::Vec3<T> x = cl.slits[0].point + along * cl.slits[0].direction +
                             T(double(cl.depths[0]) * delta) * tp.normal() +
                             across * tp.normal().cross(cl.slits[0].direction);
      const auto uv = mpr::glc::project(cam.plane, cam.selector, x);
      if (!uv) continue;
      ++projected;
      worst = std::max(worst, glc_test::roundtrip_error(cam.plane, cam.selector, x, *uv));
    }
    report << "delta " << delta << ": " << worst << " (" << projected << " of 300 projected)  ";
    // Off the slit (delta > 0) every such point lies on a ray of the GLC: nearly all project, so
    // the bound below is checked on hundreds of points, never on none.
    CHECK(projected >= 270);
    // Relative to the forward-error scale of the ray evaluation (which grows as uv leaves the
    // image) the error stays at a few eps; relative to |x - c| alone it grows like eps / delta.
    // Not a bound for every point: at delta 1e-8 a point projecting to uv ~ 5e5 (the draws
    // `along` and `across` swapped) reaches about 570 eps in double.
    within = within && worst <= 64 * std::numeric_limits<T>::epsilon();
  }
  WARN((sizeof(T) == 4 ? "float" : "double") << " projection near slits, worst relative distance: " << report.str());
  CHECK(within);
}

TEMPLATE_TEST_CASE("project: points on and off a slit, at a pinhole centre, not finite", "[glc][project]", float,
                   double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto plane = glc_test::unit_plane<T>();
  // The cross-slit example: slits x = 0 at z = 2 (along y) and y = 0 at z = 4 (along x).
  const auto xslit = glc_test::from_st<T>(plane, 0, 0, 0.5, 0, 0, 0.75);
  // On the first slit: a family of rays; the one closest to the image centre is returned.
  const auto on = mpr::glc::project(plane, xslit, V(0, 3, 2));
  REQUIRE(on.has_value());
  const mpr::Ray<T> r = xslit.ray_at({0, 0}, *on, plane.point_at(*on));
  CHECK(glc_test::distance_to_line(r, V(0, 3, 2)) <= 1e-6);
  // Off the slit at the slit's depth: no ray.
  CHECK_FALSE(mpr::glc::project(plane, xslit, V(1, 3, 2)).has_value());
  CHECK_FALSE(mpr::glc::project(plane, xslit, V(1, 3, 4)).has_value());
  CHECK(mpr::glc::project(plane, xslit, V(1, 3, 3)).has_value());
  // Pinhole at (0, 0, 2): its centre is seen by every ray; the image centre is returned.
  const auto pinhole = glc_test::from_st<T>(plane, 0, 0, 0.5, 0, 0, 0.5);
  const auto c = mpr::glc::project(plane, pinhole, V(0, 0, 2));
  REQUIRE(c.has_value());
  CHECK(*c == mpr::Vec2<T>(0.5, 0.5));
  CHECK_FALSE(mpr::glc::project(plane, pinhole, V(0.5, 0, 2)).has_value());
  // The pinhole's projection is the perspective division: (x, y, z) -> (x, y) * 2 / (2 - z)... in uv.
  const auto p = mpr::glc::project(plane, pinhole, V(1, 0.5, 4));
  REQUIRE(p.has_value());
  CHECK(p->x() == Approx(-1).epsilon(1e-6));
  CHECK(p->y() == Approx(-0.5).epsilon(1e-6));
  // Behind the plane: the ray's line passes through the point.
  const auto behind = mpr::glc::project(plane, xslit, V(0.3, 0.4, -1));
  REQUIRE(behind.has_value());
  CHECK(glc_test::distance_to_line(xslit.ray_at({0, 0}, *behind, plane.point_at(*behind)), V(0.3, 0.4, -1)) <= 1e-6);
  CHECK_FALSE(mpr::glc::project(plane, xslit, V(T(NAN), 0, 1)).has_value());
  CHECK_FALSE(mpr::glc::project(plane, xslit, V(0, T(INFINITY), 1)).has_value());
}

TEMPLATE_TEST_CASE("project: an EPI sees exactly the points of its ray plane", "[glc][project]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto plane = glc_test::unit_plane<T>();
  const auto epi = mpr::glc::epi(plane, T(0.5), V(0.25, 0.5, 1), T(0.5));
  // The ray plane: through (0, 0.5, 0) with normal (0, 1, -0.5).
  const V in = V(0.4, 0.5, 0) + T(3) * V(0.25, 0.5, 1) + T(0.7) * V(1, 0, 0);
  const auto w = mpr::glc::project(epi, in);
  REQUIRE(w.has_value());
  CHECK(glc_test::distance_to_line(epi.ray(w->x(), w->y()), in) <= 1e-5);
  CHECK_FALSE(mpr::glc::project(epi, V(in + V(0, 0.1, 0))).has_value());
}
