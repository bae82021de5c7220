#include <mpr/sampling/stratified.hpp>

#include <catch2/catch.hpp>

#include <set>
#include <utility>

TEST_CASE("stratified: one point in each of the n x n strata, jittered per pixel", "[sampling]") {
  for (const int n : {1, 2, 3, 4, 7}) {
    const mpr::Stratified pattern(n);
    REQUIRE(pattern.count() == n * n);
    for (const mpr::Pixel px : {mpr::Pixel{0, 0}, mpr::Pixel{5, 2}, mpr::Pixel{639, 479}}) {
      std::set<std::pair<int, int>> strata;
      for (int i = 0; i < pattern.count(); ++i) {
        const mpr::SamplePoint p = pattern.point(px, i);
        REQUIRE(p.x >= 0);
        REQUIRE(p.x < 1);
        REQUIRE(p.y >= 0);
        REQUIRE(p.y < 1);
        const int sx = static_cast<int>(p.x * n), sy = static_cast<int>(p.y * n);
        CHECK(sx == i % n);
        CHECK(sy == i / n);
        strata.insert({sx, sy});
        CHECK(p == pattern.point(px, i)); // deterministic
      }
      CHECK(static_cast<int>(strata.size()) == n * n);
    }
  }
  const mpr::Stratified s(4);
  CHECK_FALSE(s.point({0, 0}, 5) == s.point({1, 0}, 5));
  CHECK_FALSE(s.point({0, 0}, 5) == mpr::Stratified(4, 7).point({0, 0}, 5));
}

TEST_CASE("stratified: n outside [1, 64] throws naming the parameter", "[sampling]") {
  CHECK_THROWS_AS(mpr::Stratified(0), mpr::argument_error);
  CHECK_THROWS_AS(mpr::Stratified(-3), mpr::argument_error);
  CHECK_THROWS_AS(mpr::Stratified(65), mpr::argument_error);
  CHECK_NOTHROW(mpr::Stratified(64));
  try {
    (void)mpr::Stratified(0);
  } catch (const mpr::argument_error& e) {
    CHECK(e.parameter() == "stratified n");
  }
}

TEST_CASE("stratified lens points use every stratum once, in a shuffled order", "[sampling]") {
  STATIC_REQUIRE(mpr::LensSamplePattern<mpr::Stratified>);
  const mpr::Stratified pattern(5);
  std::set<std::pair<int, int>> strata;
  int aligned = 0;
  for (int i = 0; i < 25; ++i) {
    const mpr::SamplePoint p = pattern.lens_point({3, 1}, i);
    REQUIRE(p.x >= 0);
    REQUIRE(p.x < 1);
    strata.insert({static_cast<int>(p.x * 5), static_cast<int>(p.y * 5)});
    aligned += static_cast<int>(p.x * 5) == i % 5 && static_cast<int>(p.y * 5) == i / 5 ? 1 : 0;
  }
  CHECK(strata.size() == 25);
  CHECK(aligned < 25);
}
