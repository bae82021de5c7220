#include <mpr/core/concepts.hpp>
#include <mpr/surface/homography_surface.hpp>

#include <catch2/catch.hpp>

#include <array>
#include <limits>

namespace {
template <class T>
mpr::PlanarSurface<T> plane() {
  return mpr::PlanarSurface<T>(mpr::Vec3<T>(1, 2, 3), mpr::Vec3<T>(4, 0, 0), mpr::Vec3<T>(0, 2, 0));
}
} // namespace

TEMPLATE_TEST_CASE("HomographySurface is an image surface, and not a selector", "[surface][homography]", float,
                   double) {
  STATIC_REQUIRE(mpr::ImageSurface<mpr::HomographySurface<TestType>>);
  STATIC_REQUIRE_FALSE(mpr::RaySelector<mpr::HomographySurface<TestType>>);
  STATIC_REQUIRE(std::is_same_v<typename mpr::HomographySurface<TestType>::scalar_type, TestType>);
}

TEMPLATE_TEST_CASE("homography_from_unit_square maps the corners to the quadrilateral", "[surface][homography]", float,
                   double) {
  using T = TestType;
  using V2 = mpr::Vec2<T>;
  const std::array<V2, 4> quad{V2(0.1, 0.2), V2(0.9, 0.1), V2(1.2, 0.8), V2(-0.1, 0.7)};
  const mpr::HomographySurface<T> s(plane<T>(), mpr::homography_from_unit_square(quad));
  const std::array<V2, 4> square{V2(0, 0), V2(1, 0), V2(1, 1), V2(0, 1)};
  const T tol = 16 * std::numeric_limits<T>::epsilon();
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK((s.warp(square[k]) - quad[k]).norm() <= tol);
    CHECK((s.point_at(square[k]) - plane<T>().point_at(quad[k])).norm() <= 8 * tol);
  }
  // Straight lines stay straight: the midpoint of the top edge lies on the quad's top edge.
  const V2 mid = s.warp(V2(0.5, 0));
  const V2 a = quad[1] - quad[0], b = mid - quad[0];
  CHECK(std::abs(a.x() * b.y() - a.y() * b.x()) <= tol);
  // An axis-aligned target is an affine map (scale and shift).
  const auto affine = mpr::homography_from_unit_square<T>({V2(0.25, 0.5), V2(0.75, 0.5), V2(0.75, 1), V2(0.25, 1)});
  CHECK(affine(2, 0) == 0);
  CHECK(affine(2, 1) == 0);
  const mpr::HomographySurface<T> shifted(plane<T>(), affine);
  CHECK((shifted.warp(V2(0.5, 0.5)) - V2(0.5, 0.75)).norm() <= tol);
  // The identity.
  const mpr::HomographySurface<T> same(plane<T>(), mpr::Mat3<T>::Identity());
  CHECK(same.point_at(V2(0.3, 0.6)) == plane<T>().point_at(V2(0.3, 0.6)));
}

TEMPLATE_TEST_CASE("homographies that are degenerate or reach infinity are rejected", "[surface][homography]", float,
                   double) {
  using T = TestType;
  using V2 = mpr::Vec2<T>;
  CHECK_THROWS_WITH(mpr::homography_from_unit_square<T>({V2(0, 0), V2(1, 0), V2(2, 0), V2(0, 1)}),
                    Catch::Contains("quad"));
  CHECK_THROWS_WITH(mpr::homography_from_unit_square<T>({V2(0, 0), V2(1, 1), V2(1, 0), V2(0, 1)}),
                    Catch::Contains("quad"));
  CHECK_THROWS_WITH(mpr::homography_from_unit_square<T>({V2(0, 0), V2(1, 0), V2(T(NAN), 1), V2(0, 1)}),
                    Catch::Contains("not finite"));
  mpr::Mat3<T> singular = mpr::Mat3<T>::Identity();
  singular(1, 1) = 0;
  CHECK_THROWS_WITH(mpr::HomographySurface<T>(plane<T>(), singular), Catch::Contains("singular"));
  mpr::Mat3<T> horizon = mpr::Mat3<T>::Identity();
  horizon(2, 0) = -2; // w = 1 - 2u changes sign at u = 1/2
  CHECK_THROWS_WITH(mpr::HomographySurface<T>(plane<T>(), horizon), Catch::Contains("infinity"));
  mpr::Mat3<T> bad = mpr::Mat3<T>::Identity();
  bad(0, 1) = T(INFINITY);
  CHECK_THROWS_WITH(mpr::HomographySurface<T>(plane<T>(), bad), Catch::Contains("not finite"));
}
