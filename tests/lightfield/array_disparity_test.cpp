#include <mpr/lightfield/array_disparity.hpp>

#include <catch2/catch.hpp>

#include <limits>

TEST_CASE("array disparity: d = f B / Z - s and back", "[array_disparity]") {
  const mpr::ArrayDisparity a{80, 20};
  CHECK(a.disparity(4.0) == Approx(0).margin(1e-12));
  CHECK(a.disparity(2.0) == Approx(20));
  CHECK(a.disparity(8.0) == Approx(-10));
  CHECK(a.depth(-10.0) == Approx(8));
  CHECK(a.depth(60.0) == Approx(1));
  mpr::Image<float> depth(2, 1);
  depth(0, 0) = 2;
  depth(1, 0) = 8;
  const mpr::Image<float> d = mpr::disparity_from_depth(depth.view(), a);
  CHECK(d(0, 0) == Approx(20));
  CHECK(d(1, 0) == Approx(-10));
  const mpr::Image<float> back = mpr::depth_from_disparity(d.view(), a);
  CHECK(back(0, 0) == Approx(2));
  CHECK(back(1, 0) == Approx(8));
}

TEST_CASE("array disparity: bad maps and arrays name the pixel or field", "[array_disparity]") {
  const mpr::ArrayDisparity a{80, 20};
  mpr::Image<float> depth(2, 1, 1.0f);
  depth(1, 0) = 0;
  CHECK_THROWS_WITH(mpr::disparity_from_depth(depth.view(), a), Catch::Contains("invalid depth: pixel (1, 0)"));
  mpr::Image<float> disparity(2, 1);
  disparity(0, 0) = -20; // the array's infinity
  CHECK_THROWS_WITH(mpr::depth_from_disparity(disparity.view(), a), Catch::Contains("invalid disparity: pixel (0, 0)"));
  disparity(0, 0) = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_WITH(mpr::depth_from_disparity(disparity.view(), a), Catch::Contains("pixel (0, 0)"));
  CHECK_THROWS_WITH(mpr::disparity_from_depth(depth.view(), mpr::ArrayDisparity{0, 1}),
                    Catch::Contains("invalid focal_baseline"));
}
