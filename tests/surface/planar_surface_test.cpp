#include <mpr/surface/planar_surface.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

TEMPLATE_TEST_CASE("PlanarSurface maps uv affinely onto the parallelogram", "[surface]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const mpr::PlanarSurface<T> plane(V(1, 2, 3), V(4, 0, 0), V(0, -2, 0));
  CHECK(plane.point_at({0, 0}) == V(1, 2, 3));
  CHECK(plane.point_at({1, 0}) == V(5, 2, 3));
  CHECK(plane.point_at({0, 1}) == V(1, 0, 3));
  CHECK(plane.point_at({0.5, 0.25}) == V(3, 1.5, 3));
  CHECK(plane.centre() == V(3, 1, 3));
  // u right (x), v down (-y): the normal x cross -y = -z.
  CHECK(plane.normal() == V(0, 0, -1));
  const auto centred = mpr::PlanarSurface<T>::centred(V(0, 0, 5), V(2, 0, 0), V(0, 2, 0));
  CHECK(centred.origin() == V(-1, -1, 5));
}

TEMPLATE_TEST_CASE("PlanarSurface rejects degenerate planes", "[surface]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  CHECK_THROWS_WITH(mpr::PlanarSurface<T>(V(0, 0, 0), V(0, 0, 0), V(0, 1, 0)), Catch::Contains("width_vector"));
  CHECK_THROWS_WITH(mpr::PlanarSurface<T>(V(0, 0, 0), V(1, 0, 0), V(2, 0, 0)), Catch::Contains("parallel"));
  CHECK_THROWS_WITH(mpr::PlanarSurface<T>(V(nan, 0, 0), V(1, 0, 0), V(0, 1, 0)), Catch::Contains("origin"));
  CHECK_THROWS_AS(mpr::PlanarSurface<T>(V(0, 0, 0), V(1, 0, 0), V(0, nan, 0)), mpr::argument_error);
  // Tiny but well-shaped planes are fine: the test is scale-free.
  CHECK_NOTHROW(mpr::PlanarSurface<T>(V(0, 0, 0), V(T(1e-20), 0, 0), V(0, T(1e-20), 0)));
}

TEMPLATE_TEST_CASE("rotated and tilted planes", "[surface]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const T tol = std::is_same_v<T, float> ? T(1e-6) : T(1e-14);
  const mpr::PlanarSurface<T> plane(V(-1, -1, 2), V(2, 0, 0), V(0, 2, 0));
  const T quarter = T(std::acos(-1.0) / 2);
  // A quarter turn about the y axis through the plane's centre (0, 0, 2).
  const mpr::PlanarSurface<T> turned = plane.rotated(quarter, V(0, 1, 0), V(0, 0, 2));
  CHECK((turned.centre() - V(0, 0, 2)).norm() < tol);
  CHECK((turned.width_vector() - V(0, 0, -2)).norm() < 2 * tol);
  CHECK((turned.normal() - V(1, 0, 0)).norm() < tol); // R_y(90) z = x
  // Tilting about the horizontal axis keeps the centre and the width vector.
  const mpr::PlanarSurface<T> tilted = plane.tilted(T(0.3), T(0));
  CHECK((tilted.centre() - plane.centre()).norm() < 4 * tol);
  CHECK((tilted.width_vector() - plane.width_vector()).norm() < 4 * tol);
  CHECK(std::abs(tilted.normal().dot(plane.normal()) - std::cos(T(0.3))) < tol);
  CHECK_THROWS_WITH(plane.rotated(T(1), V(0, 0, 0), V(0, 0, 0)), Catch::Contains("axis"));
  CHECK_THROWS_WITH(plane.rotated(std::numeric_limits<T>::infinity(), V(0, 1, 0), V(0, 0, 0)),
                    Catch::Contains("angle"));
}
