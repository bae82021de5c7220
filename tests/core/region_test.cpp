#include <mpr/core/region.hpp>

#include <catch2/catch.hpp>

TEMPLATE_TEST_CASE("pixel_to_uv maps pixel centres into the region", "[region]", float, double) {
  const mpr::Region region(10, 20, 4, 2);
  const mpr::Vec2<TestType> first = region.pixel_to_uv<TestType>({10, 20});
  CHECK(first.x() == TestType(0.125));
  CHECK(first.y() == TestType(0.25));
  const mpr::Vec2<TestType> last = region.pixel_to_uv<TestType>({13, 21});
  CHECK(last.x() == TestType(0.875));
  CHECK(last.y() == TestType(0.75));
  // Centre of the region: between pixels, uv (0.5, 0.5) is the shared corner of four pixels.
  CHECK(region.pixel_to_uv<TestType>({12, 21}).x() == TestType(0.625));
  CHECK(region.contains({13, 21}));
  CHECK_FALSE(region.contains({14, 21}));
  CHECK_FALSE(region.contains({9, 20}));
}

TEST_CASE("Region rejects empty sizes", "[region]") {
  CHECK_THROWS_AS(mpr::Region(0, 0, 0, 5), mpr::argument_error);
  CHECK_THROWS_WITH(mpr::Region(0, 0, 5, -1), Catch::Contains("region height"));
}
