// mpr-render's Job (tools/mpr-render/job.hpp): command-line combinations that would silently
// render something other than what was asked are refused with one line naming the option.
#include "mpr-render/job.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace {

using mpr_tools_test::job_of;

std::string error_of(std::vector<std::string> args) {
  try {
    (void)job_of(std::move(args));
  } catch (const mpr::error& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST_CASE("mpr-render: an animated value needs --frames", "[tools][job]") {
  // Before: only the start of the animation was rendered, silently.
  CHECK_THAT(error_of({"--tilt-x", "0:30"}),
             Catch::StartsWith("mpr: invalid --tilt-x:") && Catch::Contains("--frames"));
  CHECK_THAT(error_of({"--tilt-y", "0=0,0.5=10,1=0"}), Catch::Contains("--tilt-y") && Catch::Contains("--frames"));
  CHECK_THAT(error_of({"--view", "A", "--morph-to", "G"}),
             Catch::Contains("--morph-to") && Catch::Contains("--frames"));
  CHECK_THAT(error_of({"--raster", "2x2", "--interp", "cylinder", "--radius", "1:2"}), Catch::Contains("--radius"));
  CHECK_THAT(error_of({"--raster", "2x2", "--focal-depth", "5:9"}), Catch::Contains("--focal-depth"));
  // Constant values, written as a number or with equal ends, need no --frames.
  CHECK(error_of({"--tilt-x", "10"}).empty());
  CHECK(error_of({"--tilt-x", "10:10"}).empty());
  CHECK(error_of({"--view", "A", "--morph-to", "G", "--morph", "0.5"}).empty());
  CHECK(job_of({"--tilt-x", "0:30", "--frames", "4"}).frames == 4);
  CHECK(mpr_cli::animated_option(job_of({"--tilt-x", "0:30", "--frames", "4"})) == "--tilt-x");
}

TEST_CASE("mpr-render: --frames needs an animated value", "[tools][job]") {
  // Before: N identical frames.
  CHECK_THAT(error_of({"--frames", "5"}),
             Catch::StartsWith("mpr: invalid --frames:") && Catch::Contains("nothing is animated"));
  CHECK_THAT(error_of({"--frames", "2", "--tilt-x", "10:10"}), Catch::Contains("--frames"));
  CHECK_THAT(error_of({"--frames", "2", "--view", "A", "--morph-to", "G", "--morph", "0.5"}),
             Catch::Contains("--frames"));
  CHECK(mpr_cli::animated_option(job_of({"--tilt-x", "3"})).empty());
}

TEST_CASE("mpr-render: --interp depth and --depth-maps", "[tools][job]") {
  CHECK(job_of({"--raster", "2x2", "--interp", "depth"}).interpolation == mpr_cli::Interpolation::depth);
  const mpr_cli::Job radius = job_of({"--raster", "2x2", "--interp", "depth", "--radius", "2"});
  CHECK(radius.interpolation == mpr_cli::Interpolation::depth);
  CHECK(radius.radius_given);
  CHECK_THAT(error_of({"--raster", "2x2", "--interp", "bogus"}),
             Catch::Contains("nearest, synthetic, cylinder or depth"));
  CHECK_THAT(error_of({"--raster", "2x2", "--interp", "nearest", "--radius", "1"}),
             Catch::Contains("needs --interp cylinder or depth"));
  // Depth maps from files are for light fields; the rasterizer has its own.
  CHECK_THAT(error_of({"--raster", "2x2", "--interp", "depth", "--depth-maps", "."}),
             Catch::Contains("--depth-maps") && Catch::Contains("light fields"));
}

TEST_CASE("mpr-render: --raster-samples", "[tools][job]") {
  CHECK(job_of({"--raster", "2x2"}).raster_samples == 1);
  CHECK(job_of({"--raster", "2x2", "--raster-samples", "5"}).raster_samples == 5);
  CHECK_THAT(error_of({"--raster-samples", "3"}), Catch::Contains("invalid --raster-samples: applies to --raster"));
  CHECK_THAT(error_of({"--raster", "2x2", "--raster-samples", "4"}),
             Catch::Contains("invalid --raster-samples: must be odd"));
  CHECK_THAT(error_of({"--raster", "2x2", "--raster-samples", "17"}),
             Catch::Contains("invalid --raster-samples: 17 is outside [1, 15]"));
  CHECK_THAT(error_of({"--raster", "2x2", "--raster-samples", "three"}), Catch::Contains("--raster-samples"));
}
