#include "mpr-render/animation.hpp"

#include <catch2/catch.hpp>

TEST_CASE("linear and keyframed tracks", "[cli]") {
  const mpr_cli::Track linear = mpr_cli::Track::parse("10:30", "--tilt");
  CHECK(linear.at(0) == 10);
  CHECK(linear.at(0.25) == Approx(15));
  CHECK(linear.at(1) == 30);
  CHECK(linear.at(2) == 30); // clamped

  const mpr_cli::Track keys = mpr_cli::Track::parse("0=0,0.5=10,1=0", "--radius");
  CHECK(keys.at(0.25) == Approx(5));
  CHECK(keys.at(0.5) == Approx(10));
  CHECK(keys.at(0.75) == Approx(5));

  CHECK(mpr_cli::frame_time(0, 3) == 0);
  CHECK(mpr_cli::frame_time(1, 3) == 0.5);
  CHECK(mpr_cli::frame_time(2, 3) == 1);
  CHECK(mpr_cli::frame_time(0, 1) == 0);
}

TEST_CASE("malformed tracks are rejected", "[cli]") {
  CHECK_THROWS_WITH(mpr_cli::Track::parse("1:2:3", "--tilt"), Catch::Contains("--tilt"));
  CHECK_THROWS_WITH(mpr_cli::Track::parse("0=1,0.5=2", "--tilt"), Catch::Contains("end at time 1"));
  CHECK_THROWS_WITH(mpr_cli::Track::parse("0=1,0.7=2,0.5=3,1=0", "--tilt"), Catch::Contains("increase"));
  CHECK_THROWS_WITH(mpr_cli::Track::parse("0=a,1=2", "--tilt"), Catch::Contains("not a number"));
}
