#include <mpr/sampling/any_filter.hpp>

#include <catch2/catch.hpp>

#include <type_traits>

TEST_CASE("AnyFilter answers as the filter it holds; visit hands over the concrete type", "[sampling]") {
  const mpr::AnyFilter box;
  CHECK(box.radius() == 0.5);
  CHECK(box.evaluate(0.4, 0.4) == 1);
  const mpr::AnyFilter mitchell = mpr::MitchellFilter(3);
  CHECK(mitchell.radius() == 3);
  CHECK(mitchell.evaluate(0.7, -1.9) == mpr::MitchellFilter(3).evaluate(0.7, -1.9));
  const mpr::AnyFilter lanczos = mpr::LanczosFilter();
  CHECK(lanczos.evaluate(0.3, 0.2) == mpr::LanczosFilter().evaluate(0.3, 0.2));
  const bool is_mitchell = mitchell.visit(
      [](const auto& f) { return std::is_same_v<std::remove_cvref_t<decltype(f)>, mpr::MitchellFilter>; });
  CHECK(is_mitchell);
  STATIC_REQUIRE(std::is_constructible_v<mpr::AnyFilter, mpr::GaussianFilter>);
  STATIC_REQUIRE_FALSE(std::is_constructible_v<mpr::AnyFilter, int>);
}
