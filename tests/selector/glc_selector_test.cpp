#include <mpr/selector/glc_selector.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

namespace {

template <class T>
constexpr T relative_tolerance() {
  return std::is_same_v<T, float> ? T(1e-5) : T(1e-12);
}

/// Distance from `p` to the line of `ray`, computed in double.
template <class T>
double distance_to_line(const mpr::Ray<T>& ray, const mpr::Vec3<double>& p) {
  const mpr::Vec3<double> o = ray.origin.template cast<double>(), d = ray.direction.template cast<double>();
  return (p - o).cross(d).norm() / d.norm();
}

} // namespace

TEMPLATE_TEST_CASE("pinhole GLC: every ray passes through the eye", "[selector]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-3, 3);
  for (int trial = 0; trial < 50; ++trial) {
    const V origin(T(coord(rng)), T(coord(rng)), T(coord(rng)));
    const V width(T(2 + coord(rng)), T(0.3 * coord(rng)), T(0.2 * coord(rng)));
    const V height(T(0.2 * coord(rng)), T(2 + coord(rng)), T(0.3 * coord(rng)));
    const mpr::PlanarSurface<T> plane(origin, width, height);
    // Eye 1..4 units behind (or in front of) the plane's centre.
    const double distance = (trial % 2 ? 1 : -1) * (1 + std::abs(coord(rng)));
    const V eye = V(plane.centre() - T(distance) * plane.normal());
    const mpr::GlcSelector<T> pinhole(plane, V(plane.point_at({0, 0}) - eye), V(plane.point_at({1, 0}) - eye),
                                      V(plane.point_at({0, 1}) - eye));
    const double scale = (plane.centre() - eye).norm() + width.norm() + height.norm();
    for (int i = 0; i <= 10; ++i)
      for (int j = 0; j <= 10; ++j) {
        const mpr::Vec2<T> uv(T(i / 10.0), T(j / 10.0));
        const mpr::Ray<T> ray = pinhole.ray_at({}, uv, plane.point_at(uv));
        REQUIRE(distance_to_line(ray, eye.template cast<double>()) <= relative_tolerance<T>() * scale);
        // Unit component along the normal, pointing away from the eye.
        REQUIRE(std::abs(std::abs(ray.direction.dot(plane.normal())) - 1) <= 4 * relative_tolerance<T>());
      }
  }
}

TEMPLATE_TEST_CASE("orthographic GLC: all rays are parallel", "[selector]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const mpr::PlanarSurface<T> plane(V(5, -2, 1), V(3, 1, 0), V(0, 1, 2));
  const V d(T(0.3), T(-0.7), T(1.9)); // oblique, any length: the selector rescales it
  const mpr::GlcSelector<T> ortho(plane, d, T(2) * d, T(0.5) * d);
  const V expected = ortho.direction_at({0, 0});
  for (int i = 0; i <= 16; ++i)
    for (int j = 0; j <= 16; ++j) {
      const V dir = ortho.direction_at({T(i / 16.0), T(j / 16.0)});
      REQUIRE(dir.cross(expected).norm() <= relative_tolerance<T>() * dir.norm() * expected.norm());
    }
  CHECK(expected.dot(plane.normal()) == Approx(1).epsilon(relative_tolerance<T>()));
}

TEMPLATE_TEST_CASE("directions are interpolated affinely in the two-plane parametrisation", "[selector]", float,
                   double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const mpr::PlanarSurface<T> plane(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)); // normal +z
  const mpr::GlcSelector<T> glc(plane, V(0, 0, 2), V(1, 0, 1), V(0, -3, 3));
  // Scaled corners: (0,0,1), (1,0,1), (0,-1,1); at uv (0.5, 0.5): (0.5, -0.5, 1).
  CHECK((glc.d10() - V(1, 0, 1)).norm() < relative_tolerance<T>());
  CHECK((glc.d01() - V(0, -1, 1)).norm() < relative_tolerance<T>());
  CHECK((glc.direction_at({T(0.5), T(0.5)}) - V(0.5, -0.5, 1)).norm() < relative_tolerance<T>());
  // The ray starts at the point passed in, whatever it is.
  const mpr::Ray<T> ray = glc.ray_at({3, 4}, {T(0.5), T(0.5)}, V(7, 8, 9));
  CHECK(ray.origin == V(7, 8, 9));
  // Directions pointing to the -normal side are kept on that side.
  const mpr::GlcSelector<T> back(plane, V(0, 0, -2), V(1, 0, -1), V(0, 0, -5));
  CHECK((back.d00() - V(0, 0, -1)).norm() < relative_tolerance<T>());
}

TEMPLATE_TEST_CASE("GlcSelector rejects bad corner directions", "[selector]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const mpr::PlanarSurface<T> plane(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0));
  const V ok(0, 0, 1);
  CHECK_THROWS_WITH(mpr::GlcSelector<T>(plane, V(0, 0, 0), ok, ok), Catch::Contains("d00") && Catch::Contains("zero"));
  CHECK_THROWS_WITH(mpr::GlcSelector<T>(plane, ok, V(nan, 0, 1), ok), Catch::Contains("d10"));
  CHECK_THROWS_WITH(mpr::GlcSelector<T>(plane, ok, ok, V(1, 1, 0)),
                    Catch::Contains("d01") && Catch::Contains("parallel"));
  CHECK_THROWS_WITH(mpr::GlcSelector<T>(plane, ok, V(0, 0, -1), ok),
                    Catch::Contains("d10") && Catch::Contains("other side"));
  CHECK_THROWS_AS(mpr::GlcSelector<T>(plane, ok, ok, V(0, 0, -std::numeric_limits<T>::infinity())),
                  mpr::argument_error);
}

TEST_CASE("grazing corner directions give finite rays everywhere", "[selector]") {
  using V = mpr::Vec3<double>;
  const mpr::PlanarSurface<double> plane(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0));
  const mpr::GlcSelector<double> grazing(plane, V(1, 0, 1e-9), V(1, 0, 1e-9), V(0, 1, 1e-9));
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j) {
      const V d = grazing.direction_at({i / 8.0, j / 8.0});
      REQUIRE(d.allFinite());
      REQUIRE(d.z() == Approx(1.0));
    }
}
