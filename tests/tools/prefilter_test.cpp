// mpr-render's --prefilter (tools/mpr-render/prefilter.hpp): the option's values, the factor
// `auto` picks from the output pixels' footprint on the frames, and the frames a render samples.
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <vector>

namespace {

using mpr_tools_test::job_of;

/// The prefilter factor of `args` (after the array defaults, as mpr-render computes it).
int factor_of(const std::vector<std::string>& args) {
  const mpr_cli::Job given = job_of(args);
  const mpr_cli::Loaded<float> l = mpr_cli::load<float>(given);
  const mpr_cli::Job job = mpr_cli::with_array_defaults(given, l);
  const auto [w, h] = mpr_cli::view_size(job, l);
  return mpr_cli::prefilter_factor(job, l, w, h);
}

} // namespace

TEST_CASE("--prefilter takes auto or a factor 1..8, for light fields only", "[prefilter]") {
  const std::filesystem::path dir = mpr_tools_test::plane_light_field("prefilter_parse", 2.0f);
  const std::string par = (dir / "tiny_par.txt").string();
  CHECK_FALSE(job_of({"--par", par}).prefilter.has_value());
  CHECK_FALSE(job_of({"--par", par, "--prefilter", "auto"}).prefilter.has_value());
  CHECK(job_of({"--par", par, "--prefilter", "3"}).prefilter == 3);
  for (const char* bad : {"0", "9", "two", "-1"})
    CHECK_THROWS_WITH(job_of({"--par", par, "--prefilter", bad}), Catch::Contains("--prefilter"));
  CHECK_THROWS_WITH(job_of({"--scene", "classroom", "--prefilter", "2"}),
                    Catch::Contains("--prefilter") && Catch::Contains("light fields"));
  CHECK_THROWS_WITH(job_of({"--scene", "classroom", "--raster", "4x3", "--prefilter", "2"}),
                    Catch::Contains("--prefilter"));
}

TEST_CASE("--prefilter auto is the whole camera pixels an output pixel spans", "[prefilter]") {
  // Three 8 x 6 cameras of random codes (focal length 8) with depth maps of the plane z = 2.
  const std::filesystem::path dir = mpr_tools_test::plane_light_field("prefilter_auto", 2.0f);
  const std::string par = (dir / "tiny_par.txt").string();
  CHECK(factor_of({"--par", par, "--focal-depth", "2"}) == 1);                  // the cameras' own size
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "4x3"}) == 2); // half
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "5x4"}) == 1); // 1.6 camera pixels
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "2x2"}) == 3); // the 6-pixel height
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "4x3", "--zoom", "2"}) == 1);
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "4x3", "--prefilter", "1"}) == 1);
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "8x6", "--prefilter", "2"}) == 2);
  // The depth proxy samples where its depth maps put the surface: auto leaves its frames alone;
  // so does supersampling, which integrates each pixel itself.
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "4x3", "--interp", "depth", "--depth-maps",
                   dir.string()}) == 1);
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "4x3", "--spp", "4"}) == 1);
  // Every frame of an animation counts: a keyframe between the first, middle and last frame that
  // tilts the plane 60 degrees about its horizontal axis halves the vertical footprint there.
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "4x3", "--tilt-x", "0=0,0.25=60,0.5=0,1=0", "--frames",
                   "9"}) == 1);
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "4x3", "--tilt-x", "0=0,0.25=20,0.5=0,1=0", "--frames",
                   "9"}) == 1); // cos 20 deg x 2 = 1.88
  // A layout of several views: the smallest footprint of any (view A is the reference view here).
  CHECK(factor_of({"--par", par, "--focal-depth", "2", "--size", "4x3", "--layout", "2x1", "--views",
                   "default,default"}) == 2);
}

TEST_CASE("--write-depth reads the full frames' depth maps whatever --prefilter does", "[prefilter]") {
  // Depth maps of a checkerboard of depths 2 and 3: the nearest of a 2x2 block is 2 everywhere.
  const std::filesystem::path dir = mpr_tools_test::plane_light_field("prefilter_depth", 2.0f);
  for (int i = 0; i < 3; ++i) {
    mpr::Image<float> depth(8, 6);
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 8; ++x) depth(x, y) = (x + y) % 2 == 0 ? 2.0f : 3.0f;
    mpr::write_pfm(dir / ("view" + std::to_string(i) + ".pfm"), depth);
  }
  const std::string par = (dir / "tiny_par.txt").string();
  const auto depth_of = [&](const char* prefilter, const char* name) {
    const std::filesystem::path pfm = dir / name;
    (void)mpr_cli::render_frames(job_of({"--par", par, "--focal-depth", "2.5", "--size", "4x3", "--depth-maps",
                                         dir.string(), "--write-depth", pfm.string(), "--prefilter", prefilter}));
    return mpr::read_pfm(pfm);
  };
  const mpr::Image<float> full = depth_of("1", "full.pfm"), automatic = depth_of("auto", "auto.pfm");
  REQUIRE(automatic.width() == full.width());
  int differ = 0;
  for (int y = 0; y < full.height(); ++y)
    for (int x = 0; x < full.width(); ++x) differ += automatic(x, y) == full(x, y) ? 0 : 1;
  CHECK(differ == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a prefiltered render samples the frames at the output's scale and says so", "[prefilter]") {
  const std::filesystem::path dir = mpr_tools_test::plane_light_field("prefilter_render", 2.0f);
  const std::string par = (dir / "tiny_par.txt").string();
  const auto render = [&](const std::vector<std::string>& extra, std::string& said) {
    std::vector<std::string> args{"--par", par, "--focal-depth", "2", "--size", "4x3"};
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<mpr::Image<mpr::Rgb8>> frames;
    std::ostringstream info, warnings;
    mpr_cli::run(
        job_of(args), [&](int, int, const mpr::Image<mpr::Rgb8>& image) { frames.push_back(image); }, &info, &warnings);
    said = info.str();
    REQUIRE(frames.size() == 1);
    return frames[0];
  };
  std::string auto_said, full_said;
  const mpr::Image<mpr::Rgb8> prefiltered = render({"--interp", "nearest"}, auto_said);
  const mpr::Image<mpr::Rgb8> full = render({"--interp", "nearest", "--prefilter", "1"}, full_said);
  CHECK_THAT(auto_said, Catch::Contains("prefiltered the frames to 1/2 of their scale (4x3)") &&
                            Catch::Contains("2.00 camera pixels"));
  CHECK(full_said.find("prefiltered") == std::string::npos);
  // The nearest camera (the middle one, centred on the view) at the prefiltered scale: each output
  // pixel is the linear-light mean of its 2x2 block of the middle image; on the full frames a
  // bilinear sample between the block's four texels at their common corner -- the same mean, up to
  // the prefiltered image's rounding to 8 bits.
  const mpr::Image<mpr::Rgb8> middle = mpr::read_rgb8(dir / "view1.png");
  int worst = 0, worst_full = 0;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      const mpr::Color mean = (mpr::to_color(middle(2 * x, 2 * y)) + mpr::to_color(middle(2 * x + 1, 2 * y)) +
                               mpr::to_color(middle(2 * x, 2 * y + 1)) + mpr::to_color(middle(2 * x + 1, 2 * y + 1))) *
                              0.25f;
      const mpr::Rgb8 want = mpr::to_rgb8(mean), got = prefiltered(x, y), got_full = full(x, y);
      worst = std::max({worst, std::abs(want.r - got.r), std::abs(want.g - got.g), std::abs(want.b - got.b)});
      worst_full = std::max(
          {worst_full, std::abs(want.r - got_full.r), std::abs(want.g - got_full.g), std::abs(want.b - got_full.b)});
    }
  CHECK(worst <= 1);
  CHECK(worst_full <= 1);
  // Under the synthetic aperture the side cameras' texels lie 0.4 pixel off the middle one's: box
  // then tent (prefiltered) and tent alone (full frames) give different images.
  std::string said;
  CHECK_FALSE(render({"--interp", "synthetic"}, said) == render({"--interp", "synthetic", "--prefilter", "1"}, said));
  // A factor the cameras cannot hold is refused, naming the option and the camera.
  CHECK_THROWS_WITH(mpr_cli::render_frames(job_of({"--par", par, "--focal-depth", "2", "--prefilter", "7"})),
                    Catch::Contains("--prefilter") && Catch::Contains("view0.png") && Catch::Contains("8x6") &&
                        !Catch::Contains("invalid factor")); // one line, not a message inside a message
}
