#include "glc_test_util.hpp"

#include <mpr/core/concepts.hpp>
#include <mpr/glc/cameras.hpp>
#include <mpr/glc/classify.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

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

namespace {

// The slope field of a GLC, worked out from its rays alone: with an orthonormal frame (e1, e2)
// on the plane and n its normal, the slope of the ray at a plane point is (d.e1, d.e2) / d.n and
// is affine in the point's plane coordinates (x, y) = ((p - c).e1, (p - c).e2). Returns the
// gradient K (d slope / d (x, y)) and the slope at the plane centre c.
template <class T>
std::pair<Eigen::Matrix2d, Eigen::Vector2d> slope_field(const mpr::PlanarSurface<T>& plane,
                                                        const mpr::GlcSelector<T>& sel) {
  const Eigen::Vector3d n = plane.normal().template cast<double>();
  const Eigen::Vector3d e1 = (plane.point_at({1, 0}) - plane.point_at({0, 0})).template cast<double>().normalized();
  const Eigen::Vector3d e2 = n.cross(e1);
  const Eigen::Vector3d c = plane.centre().template cast<double>();
  const auto at = [&](double u, double v, Eigen::Vector2d& xy) {
    const mpr::Vec2<T> uv(static_cast<T>(u), static_cast<T>(v));
    const Eigen::Vector3d p = plane.point_at(uv).template cast<double>() - c;
    const Eigen::Vector3d d = sel.direction_at(uv).template cast<double>();
    xy = Eigen::Vector2d(p.dot(e1), p.dot(e2));
    return Eigen::Vector2d(d.dot(e1) / d.dot(n), d.dot(e2) / d.dot(n));
  };
  Eigen::Vector2d x0, x1, x2;
  const Eigen::Vector2d s0 = at(0.5, 0.5, x0), s1 = at(1, 0.5, x1), s2 = at(0.5, 1, x2);
  Eigen::Matrix2d dx, ds;
  dx << x1 - x0, x2 - x0;
  ds << s1 - s0, s2 - s0;
  return {ds * dx.inverse(), s0};
}

} // namespace

TEMPLATE_TEST_CASE("cameras: twisted orthographic and bilinear cameras have the slope field of their definition",
                   "[glc][cameras]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const double tol = sizeof(T) == 4 ? 2e-4 : 1e-11;
  // A plane that is not axis-aligned and not square.
  const mpr::PlanarSurface<T> plane(V(T(0.2), T(-0.4), T(1)), V(T(1.6), T(0.3), T(0.2)), V(T(-0.2), T(1.1), T(0.4)));
  const Eigen::Vector3d n = plane.normal().template cast<double>();
  const V direction = plane.normal() + V(T(0.3), T(-0.2), T(0.1));
  // The slope of `direction` in any orthonormal frame has the length of its part along the plane
  // over its normal component.
  const Eigen::Vector3d dd = direction.template cast<double>();
  const double expected_slope = (dd - dd.dot(n) * n).norm() / dd.dot(n);

  // Twisted orthographic: K = twist w w_perp^T (rank 1, trace 0): the rays are parallel along the
  // tilt direction w and turn as one moves across it; |K| = |twist|.
  const T twist = T(0.7);
  const auto [Kt, st] =
      slope_field(plane, mpr::glc::twisted_orthographic(plane, direction, V(T(0.4), T(0.9), T(0.1)), twist));
  CHECK(st.norm() == Approx(expected_slope).epsilon(tol));
  CHECK(std::abs(Kt.trace()) <= tol);
  CHECK(std::abs(Kt.determinant()) <= tol);
  CHECK(Kt.norm() == Approx(0.7).epsilon(tol));
  // The kernel of K is the tilt's in-plane direction w: moving along w keeps the direction.
  Eigen::Vector3d w3 = Eigen::Vector3d(0.4, 0.9, 0.1);
  w3 -= w3.dot(n) * n;
  const Eigen::Vector3d e1 = (plane.point_at({1, 0}) - plane.point_at({0, 0})).template cast<double>().normalized();
  const Eigen::Vector2d w = Eigen::Vector2d(w3.dot(e1), w3.dot(n.cross(e1))).normalized();
  CHECK((Kt * w).norm() <= tol);
  CHECK((Kt.transpose() * w).norm() == Approx(0.7).epsilon(tol)); // the slope changes along w

  // Bilinear: K = [c -t; t c]: trace 2c, determinant c^2 + t^2, rotation part |t|.
  const T convergence = T(-0.35), bi_twist = T(0.6);
  const auto [Kb, sb] = slope_field(plane, mpr::glc::bilinear(plane, direction, convergence, bi_twist));
  CHECK(sb.norm() == Approx(expected_slope).epsilon(tol));
  CHECK(Kb.trace() == Approx(2 * -0.35).epsilon(tol));
  CHECK(Kb.determinant() == Approx(0.35 * 0.35 + 0.6 * 0.6).epsilon(tol));
  CHECK(std::abs(Kb(1, 0) - Kb(0, 1)) / 2 == Approx(0.6).epsilon(tol));
  CHECK(std::abs(Kb(0, 0) - Kb(1, 1)) <= tol);
  CHECK(std::abs(Kb(0, 1) + Kb(1, 0)) <= tol);
}
