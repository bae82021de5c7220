#include "glc_test_util.hpp"

#include <mpr/core/concepts.hpp>
#include <mpr/glc/cameras.hpp>
#include <mpr/glc/classify.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

using mpr::glc::Type;

namespace {
constexpr std::array<Type, 7> kSelectorTypes{Type::pinhole,    Type::orthographic, Type::pushbroom,
                                             Type::cross_slit, Type::pencil,       Type::twisted_orthographic,
                                             Type::bilinear};
}

// Each factory builds a camera of its type, and the classifier recovers its geometry. The worst
// errors (relative to the plane size ~1 and depths 1..5) are printed for docs/numerics.md.
TEMPLATE_TEST_CASE("cameras: every factory builds its type and classify recovers the geometry", "[glc][cameras]", float,
                   double) {
  using T = TestType;
  glc_test::Rng rng(2004);
  const double tol = sizeof(T) == 4 ? 1e-3 : 1e-10;
  std::ostringstream report;
  for (const Type type : kSelectorTypes) {
    int wrong = 0;
    double worst = 0;
    for (int i = 0; i < 1000; ++i) {
      const auto cam = glc_test::random_camera<T>(type, rng);
      const auto cl = mpr::glc::classify(cam.plane, cam.selector);
      if (cl.type != type) {
        ++wrong;
        continue;
      }
      double err = 0;
      if (type == Type::pinhole) err = (cl.centre - cam.centre).template cast<double>().norm();
      if (type == Type::orthographic) err = (cl.direction - cam.direction).template cast<double>().norm();
      if (type == Type::pushbroom || type == Type::pencil) err = glc_test::line_distance(cl.slits[0], cam.slits[0]);
      if (type == Type::cross_slit) {
        // Slits are reported nearest first.
        const double d0 = std::abs(double((cam.slits[0].point - cam.plane.centre()).dot(cam.plane.normal())));
        const double d1 = std::abs(double((cam.slits[1].point - cam.plane.centre()).dot(cam.plane.normal())));
        const auto& near = d0 <= d1 ? cam.slits[0] : cam.slits[1];
        const auto& far = d0 <= d1 ? cam.slits[1] : cam.slits[0];
        err = std::max(glc_test::line_distance(cl.slits[0], near), glc_test::line_distance(cl.slits[1], far));
      }
      worst = std::max(worst, err);
    }
    INFO(mpr::glc::to_string(type));
    CHECK(wrong == 0);
    CHECK(worst <= tol);
    report << mpr::glc::to_string(type) << " " << worst << "  ";
  }
  WARN((sizeof(T) == 4 ? "float" : "double")
       << " worst geometry error (centre / direction / slit line): " << report.str());
}

TEMPLATE_TEST_CASE("cameras: bad parameters are rejected with the parameter's name", "[glc][cameras]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto plane = glc_test::unit_plane<T>();
  CHECK_THROWS_WITH(mpr::glc::perspective(plane, V(0.3, 0.2, 0)), Catch::Contains("centre"));
  CHECK_THROWS_WITH(mpr::glc::perspective(plane, V(0, T(NAN), -1)), Catch::Contains("centre"));
  CHECK_THROWS_WITH(mpr::glc::orthographic(plane, V(1, 0, 0)), Catch::Contains("direction"));
  CHECK_THROWS_WITH(mpr::glc::oblique_orthographic(plane, T(1.5707963267948966), T(0)), Catch::Contains("angle_u"));
  const mpr::glc::Line<T> tilted{V(0, 0, -1), V(1, 0, 1)}, flat{V(0, 0, -1), V(1, 0, 0)}, on{V(0, 0, 0), V(1, 0, 0)};
  CHECK_THROWS_WITH(mpr::glc::pushbroom(plane, tilted), Catch::Contains("slit") && Catch::Contains("parallel"));
  CHECK_THROWS_WITH(mpr::glc::pushbroom(plane, on), Catch::Contains("image plane"));
  CHECK_THROWS_WITH(mpr::glc::pushbroom(plane, flat, V(0, 1, 0)), Catch::Contains("fan_normal"));
  CHECK_THROWS_WITH(mpr::glc::cross_slit(plane, flat, mpr::glc::Line<T>{V(0, 0, -1), V(0, 1, 0)}),
                    Catch::Contains("same depth"));
  CHECK_THROWS_WITH(mpr::glc::cross_slit(plane, flat, mpr::glc::Line<T>{V(0, 0, -3), V(1, 0, 0)}),
                    Catch::Contains("parallel"));
  CHECK_THROWS_WITH(mpr::glc::pencil(plane, flat, T(0)), Catch::Contains("twist"));
  CHECK_THROWS_WITH(mpr::glc::twisted_orthographic(plane, V(0, 0, 1), V(0, 0, 1), T(1)), Catch::Contains("tilt"));
  CHECK_THROWS_WITH(mpr::glc::bilinear(plane, V(0, 0, 1), T(1), T(0)), Catch::Contains("twist"));
  CHECK_THROWS_WITH(mpr::glc::epi(plane, T(0.5), V(0, 0, 1), T(0)), Catch::Contains("spread"));
  // A valid call of each, so that the checks above are not vacuous.
  CHECK_NOTHROW(mpr::glc::pushbroom(plane, flat));
  CHECK_NOTHROW(mpr::glc::cross_slit(plane, flat, mpr::glc::Line<T>{V(0, 0, -3), V(0, 1, 0)}));
}

TEMPLATE_TEST_CASE("cameras: every ray travels into the scene (along the plane normal)", "[glc][cameras]", float,
                   double) {
  using T = TestType;
  const auto plane = glc_test::unit_plane<T>();
  // Centre in front of the plane: the rays pass through it at t = its depth.
  const auto front = mpr::glc::perspective(plane, mpr::Vec3<T>(0.5, 0.5, 2));
  for (const auto& uv : {mpr::Vec2<T>(0, 0), mpr::Vec2<T>(1, 0.5), mpr::Vec2<T>(0.25, 1)}) {
    const mpr::Ray<T> r = front.ray_at({0, 0}, uv, plane.point_at(uv));
    CHECK(r.direction.z() == T(1));
    CHECK((r.at(2) - mpr::Vec3<T>(0.5, 0.5, 2)).norm() <= 8 * std::numeric_limits<T>::epsilon());
  }
}

TEMPLATE_TEST_CASE("cameras: the EPI camera is one plane of rays, rendered by TwoPlaneSelector", "[glc][cameras]",
                   float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto plane = glc_test::unit_plane<T>();
  const auto epi = mpr::glc::epi(plane, T(0.5), V(0.25, 0.5, 1), T(0.5));
  CHECK(mpr::glc::classify(epi).type == Type::epi);
  STATIC_REQUIRE(mpr::RaySelector<mpr::glc::TwoPlaneSelector<T>>);
  const mpr::glc::TwoPlaneSelector<T> sel(epi);
  // The ray plane contains the row y = 0.5 (direction x) and (0.25, 0.5, 1): normal (0, 1, -0.5).
  const V normal = V(1, 0, 0).cross(V(0.25, 0.5, 1)).normalized();
  for (const T u : {T(0), T(0.3), T(1)})
    for (const T v : {T(0), T(0.7), T(1)}) {
      const mpr::Ray<T> r = sel.ray_at({0, 0}, {u, v}, V::Zero());
      CHECK(std::abs((r.origin - V(0, 0.5, 0)).dot(normal)) <= 8 * std::numeric_limits<T>::epsilon());
      CHECK(std::abs(r.direction.dot(normal)) <= 8 * std::numeric_limits<T>::epsilon());
      CHECK(r.origin.x() == Approx(u).margin(1e-6));
    }
}
