// mpr-render's --spp and --filter (tools/mpr-render/pixel_sampling.hpp).
#include "mpr-render/pixel_sampling.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <type_traits>
#include <variant>

using mpr_tools_test::job_of;

TEST_CASE("--spp: 1 to 4096, the pixel centre at 1 and scrambled Sobol points above", "[cli][sampling]") {
  CHECK(job_of({}).spp == 1);
  CHECK(job_of({"--spp", "16"}).spp == 16);
  CHECK(std::holds_alternative<mpr::PixelCentre>(mpr_cli::make_pixel_sampling(1, mpr::AnyFilter())));
  const mpr_cli::PixelSamplingVariant s = mpr_cli::make_pixel_sampling(16, mpr::MitchellFilter(1.5));
  const auto* super = std::get_if<mpr::Supersample<mpr::OwenSobol, mpr::AnyFilter>>(&s);
  REQUIRE(super != nullptr);
  CHECK(super->pattern().count() == 16);
  CHECK(super->filter().radius() == 1.5);
  for (const char* bad : {"0", "-3", "4097", "100000", "two", "1.5", ""})
    CHECK_THROWS_WITH(job_of({"--spp", bad}), Catch::StartsWith("mpr: invalid --spp: "));
}

TEST_CASE("--filter NAME[:RADIUS]: pbrt-v4 defaults, explicit radii, one clear error each", "[cli][sampling]") {
  const auto radius = [](const char* text) { return mpr_cli::parse_filter(text).radius(); };
  CHECK(radius("box") == 0.5);
  CHECK(radius("tent") == 2);
  CHECK(radius("triangle") == 2);
  CHECK(radius("gaussian") == 1.5);
  CHECK(radius("mitchell") == 2);
  CHECK(radius("lanczos") == 4);
  CHECK(radius("mitchell:1.5") == 1.5);
  CHECK(radius("box:64") == 64);
  const bool is_gaussian = mpr_cli::parse_filter("gaussian:2").visit([](const auto& f) {
    return std::is_same_v<std::remove_cvref_t<decltype(f)>, mpr::GaussianFilter>;
  });
  CHECK(is_gaussian);
  CHECK(job_of({"--spp", "4", "--filter", "tent:1"}).filter.radius() == 1);
  CHECK_THROWS_WITH(mpr_cli::parse_filter("tent:-1"), Catch::Contains("--filter") && Catch::Contains("radius -1"));
  CHECK_THROWS_WITH(mpr_cli::parse_filter("tent:0"), Catch::Contains("radius 0"));
  CHECK_THROWS_WITH(mpr_cli::parse_filter("box:65"), Catch::Contains("(0, 64]"));
  CHECK_THROWS_WITH(mpr_cli::parse_filter("box:nan"), Catch::Contains("--filter"));
  CHECK_THROWS_WITH(mpr_cli::parse_filter("sinc"), Catch::Contains("'sinc' is not box, tent"));
  CHECK_THROWS_WITH(mpr_cli::parse_filter("sinc:-1"), Catch::Contains("'sinc' is not"));
  CHECK_THROWS_WITH(mpr_cli::parse_filter("box:1:2"), Catch::Contains("NAME:RADIUS"));
  CHECK_THROWS_WITH(job_of({"--filter", "box"}), Catch::Contains("--filter") && Catch::Contains("needs --spp"));
}
