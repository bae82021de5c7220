#include "glc_test_util.hpp"

#include <mpr/core/concepts.hpp>
#include <mpr/glc/cameras.hpp>
#include <mpr/glc/rectify.hpp>
#include <mpr/scene/checkerboard_plane.hpp>

#include <catch2/catch.hpp>

TEMPLATE_TEST_CASE("rectify: the rectified selector evaluates the GLC at the warped uv", "[glc][rectify]", float,
                   double) {
  using T = TestType;
  using V2 = mpr::Vec2<T>;
  STATIC_REQUIRE(mpr::RaySelector<mpr::glc::RectifiedSelector<T>>);
  STATIC_REQUIRE(
      (mpr::ComposablePolicies<mpr::HomographySurface<T>, mpr::glc::RectifiedSelector<T>, mpr::CheckerboardPlane<T>>));
  const auto plane = glc_test::unit_plane<T>();
  const auto sel = mpr::glc::oblique_orthographic(plane, T(0.6), T(0.2));
  const auto r = mpr::glc::rectify(plane, sel, {V2(-0.5, 0.1), V2(0.4, 0.0), V2(0.5, 0.9), V2(-0.4, 1.0)});
  for (const V2& uv : {V2(0, 0), V2(0.3, 0.7), V2(1, 1)}) {
    const V2 w = r.surface.warp(uv);
    const mpr::Ray<T> got = r.selector.ray_at({0, 0}, uv, r.surface.point_at(uv));
    const mpr::Ray<T> want = sel.ray_at({0, 0}, w, plane.point_at(w));
    CHECK((got.origin - want.origin).norm() <= 16 * std::numeric_limits<T>::epsilon());
    CHECK((got.direction - want.direction).norm() <= 16 * std::numeric_limits<T>::epsilon());
  }
  CHECK_THROWS_WITH(mpr::glc::rectify(plane, sel, {V2(0, 0), V2(1, 1), V2(1, 0), V2(0, 1)}), Catch::Contains("quad"));
}

TEMPLATE_TEST_CASE("rectify: target_region finds where the camera shows a scene quadrilateral", "[glc][rectify]", float,
                   double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto plane = glc_test::unit_plane<T>();
  // Orthographic rays along (1, 0, 1): the square at depth 4 appears shifted by -4 in u.
  const auto sel = mpr::glc::orthographic(plane, V(1, 0, 1));
  const auto quad = mpr::glc::target_region(plane, sel, {V(4, 0, 4), V(5, 0, 4), V(5, 1, 4), V(4, 1, 4)});
  CHECK((quad[0] - mpr::Vec2<T>(0, 0)).norm() <= 1e-5);
  CHECK((quad[2] - mpr::Vec2<T>(1, 1)).norm() <= 1e-5);
  CHECK_THROWS_WITH(mpr::glc::target_region(plane, sel, {V(4, 0, -4), V(5, 0, 4), V(5, 1, 4), V(4, 1, 4)}),
                    Catch::Contains("behind"));
  // The cross-slit example cannot see points off its slit at the slit's depth.
  const auto xslit = glc_test::from_st<T>(plane, 0, 0, 0.5, 0, 0, 0.75);
  CHECK_THROWS_WITH(mpr::glc::target_region(plane, xslit, {V(1, 3, 2), V(5, 0, 3), V(5, 1, 3), V(4, 1, 3)}),
                    Catch::Contains("no ray"));
}
