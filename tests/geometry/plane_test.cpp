// Plane crossings and in-plane coordinates against hand-computed and long-double answers.
#include <mpr/geometry/plane.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <type_traits>

TEMPLATE_TEST_CASE("Plane::crossing by hand", "[geometry][plane]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  // The plane z = 2 (normal of length 3, pointing down): a ray from (1, 1, 0) along (1, 0, 1)
  // meets it at t = 2, at (3, 1, 2).
  const mpr::Plane<T> plane{V(5, -7, 2), V(0, 0, -3)};
  const mpr::Ray<T> ray{V(1, 1, 0), V(1, 0, 1)};
  CHECK(plane.crossing_parameter(ray) == T(2));
  CHECK(plane.crossing(ray) == V(3, 1, 2));
  // Behind the origin: negative parameter, still the line's crossing.
  const mpr::Ray<T> back{V(1, 1, 4), V(1, 0, 1)};
  CHECK(plane.crossing_parameter(back) == T(-2));
  // Parallel: not finite (a division by zero, never a silent point).
  const mpr::Ray<T> parallel{V(1, 1, 0), V(1, 1, 0)};
  CHECK_FALSE(std::isfinite(plane.crossing_parameter(parallel)));
  CHECK_FALSE(plane.crossing(parallel).allFinite());
}

TEMPLATE_TEST_CASE("PlaneBasis recovers affine coordinates on skewed edges", "[geometry][plane]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const T tol = std::is_same_v<T, float> ? T(2e-5) : T(1e-13);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3, 3);
  int checked = 0;
  for (int k = 0; k < 500; ++k) {
    const mpr::Vec3<long double> o(u(rng), u(rng), u(rng)), a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    // Skip nearly parallel edges (the basis is ill-conditioned there by nature).
    if (a.cross(b).norm() < 0.3L * a.norm() * b.norm()) continue;
    const mpr::PlaneBasis<T> basis(o.template cast<T>(), a.template cast<T>(), b.template cast<T>());
    const long double s = u(rng), t = u(rng);
    const mpr::Vec3<long double> x = o + s * a + t * b;
    const mpr::Vec2<T> st = basis.coordinates(x.template cast<T>());
    const T scale = T(1) + static_cast<T>(std::abs(s) + std::abs(t));
    REQUIRE(std::abs(st.x() - static_cast<T>(s)) < tol * scale * 10);
    REQUIRE(std::abs(st.y() - static_cast<T>(t)) < tol * scale * 10);
    // A point off the plane along the normal has the same coordinates.
    const mpr::Vec3<long double> off = x + 0.75L * a.cross(b);
    const mpr::Vec2<T> st2 = basis.coordinates(off.template cast<T>());
    REQUIRE(std::abs(st2.x() - static_cast<T>(s)) < tol * scale * 100);
    REQUIRE(std::abs(st2.y() - static_cast<T>(t)) < tol * scale * 100);
    ++checked;
  }
  CHECK(checked > 300);
  // By hand: origin (1, 0, 0), edges (2, 0, 0) and (1, 1, 0); (4, 1, 0) = o + 1 a + 1 b.
  const mpr::PlaneBasis<T> hand(V(1, 0, 0), V(2, 0, 0), V(1, 1, 0));
  CHECK(hand.coordinates(V(4, 1, 0)) == mpr::Vec2<T>(1, 1));
  CHECK(hand.coordinates(V(2, 1, 5)) == mpr::Vec2<T>(0, 1));
}

TEMPLATE_TEST_CASE("PlanarSurface::uv_of inverts point_at", "[geometry][plane]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const T tol = std::is_same_v<T, float> ? T(1e-5) : T(1e-13);
  const auto plane = mpr::PlanarSurface<T>::centred(V(0, 3, -10), V(8, 0, 1), V(0.5, -6, 0)).tilted(T(0.3), T(-0.4));
  for (int i = -2; i <= 12; ++i)
    for (int j = -2; j <= 12; ++j) {
      const mpr::Vec2<T> uv(T(i) / 10, T(j) / 10);
      const mpr::Vec2<T> back = plane.uv_of(plane.point_at(uv));
      REQUIRE(std::abs(back.x() - uv.x()) < tol);
      REQUIRE(std::abs(back.y() - uv.y()) < tol);
    }
  // Far from the origin with small edges: the error is the rounding of the point's coordinates
  // (1e6 has a spacing of 1.2e-10 in double, 0.06 in float) over the edge length 1e-2.
  const auto far = mpr::PlanarSurface<T>(V(1e6, -1e6, 1e6), V(T(1e-2), 0, 0), V(0, T(1e-2), 0));
  const mpr::Vec2<T> back = far.uv_of(far.point_at({T(0.25), T(0.75)}));
  const T far_tol = std::is_same_v<T, float> ? T(0.0625 / 1e-2) : T(2.5e-8);
  CHECK(std::abs(back.x() - T(0.25)) <= far_tol);
  CHECK(std::abs(back.y() - T(0.75)) <= far_tol);
}
