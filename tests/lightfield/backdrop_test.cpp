#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/backdrop.hpp>

#include <vector>

using namespace mpr_test;

namespace {

// `n` cameras of 32 x 32 pixels (their placement does not matter here).
std::vector<mpr::PinholeCamera<double>> cameras(int n) {
  std::vector<mpr::PinholeCamera<double>> c;
  for (int i = 0; i < n; ++i) c.push_back(camera_at<double>({double(i), 0, 0}, 32, 32, 30));
  return c;
}

// A 32 x 32 image of `back` with the square [8, 24) x [8, 24) of `object` (a quarter).
mpr::Image<mpr::Rgb8> square_on(mpr::Rgb8 back, mpr::Rgb8 object) {
  mpr::Image<mpr::Rgb8> image(32, 32, back);
  for (int y = 8; y < 24; ++y)
    for (int x = 8; x < 24; ++x) image(x, y) = object;
  return image;
}

} // namespace

TEST_CASE("an object on a plain backdrop is found with the backdrop's colour", "[backdrop]") {
  const mpr::Rgb8 back{10, 20, 30}, object{200, 150, 100};
  const mpr::CameraFrameSet<double, mpr::Rgb8> frames(cameras(4),
                                                      std::vector<mpr::Image<mpr::Rgb8>>(4, square_on(back, object)));
  const std::optional<mpr::Backdrop> b = mpr::detect_backdrop(frames);
  REQUIRE(b.has_value());
  // The border band is 2 pixels (3% of 32 is under 2), all backdrop: its colour exactly, every
  // border within the least tolerance (12), three quarters of each image.
  CHECK(b->colour.r == 10);
  CHECK(b->colour.g == 20);
  CHECK(b->colour.b == 30);
  CHECK(b->tolerance == 12);
  CHECK(b->views == 4);
  CHECK(b->total == 4);
  CHECK(b->uniform_share == 1.0);
  CHECK(b->border_share == 1.0);
  CHECK(b->image_share == 0.75);
}

TEST_CASE("views with no plain backdrop are not taken for one", "[backdrop]") {
  // A ramp: the borders hold every colour from 0 to 248 in steps of 8.
  mpr::Image<mpr::Rgb8> ramp(32, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      ramp(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(8 * x), static_cast<std::uint8_t>(8 * y), 60};
  const mpr::CameraFrameSet<double, mpr::Rgb8> ramps(cameras(3), std::vector<mpr::Image<mpr::Rgb8>>(3, ramp));
  CHECK_FALSE(mpr::detect_backdrop(ramps).has_value());
  CHECK(mpr::measure_backdrop(ramps).uniform_share < 0.7);
  // One colour everywhere: a backdrop with no object (all of every image) is not an object on a
  // backdrop.
  const mpr::CameraFrameSet<double, mpr::Rgb8> blank(
      cameras(3), std::vector<mpr::Image<mpr::Rgb8>>(3, mpr::Image<mpr::Rgb8>(32, 32, mpr::Rgb8{5, 5, 5})));
  CHECK_FALSE(mpr::detect_backdrop(blank).has_value());
  CHECK(mpr::measure_backdrop(blank).image_share == 1.0);
  // Three of four views on black, one on a ramp: 3/4 of the views meets min_views 0.75.
  std::vector<mpr::Image<mpr::Rgb8>> mixed(3, square_on({0, 0, 0}, {180, 180, 180}));
  mixed.push_back(ramp);
  const mpr::CameraFrameSet<double, mpr::Rgb8> most(cameras(4), mixed);
  const mpr::Backdrop m = mpr::measure_backdrop(most);
  CHECK(m.views == 3);
  mpr::BackdropConfig strict;
  strict.min_views = 0.8;
  CHECK_FALSE(mpr::detect_backdrop(most, strict).has_value());
}

TEST_CASE("the backdrop silhouette is foreground beyond the tolerance in any channel", "[backdrop]") {
  const mpr::BackdropSilhouette s{mpr::Rgb8{10, 20, 30}, 12};
  CHECK_FALSE(s.foreground({10, 20, 30}));
  CHECK_FALSE(s.foreground({22, 8, 42}));
  CHECK(s.foreground({23, 20, 30}));
  CHECK(s.foreground({10, 7, 30}));
  CHECK(s.foreground({10, 20, 43}));
}

TEST_CASE("backdrop settings are checked, naming the field", "[backdrop]") {
  const auto refuse = [](mpr::BackdropConfig c, const char* parameter) {
    try {
      mpr::validate(c);
      FAIL("no exception for " << parameter);
    } catch (const mpr::argument_error& e) {
      CHECK(e.parameter() == parameter);
    }
  };
  mpr::BackdropConfig c;
  c.border = 0.5;
  refuse(c, "border");
  c = {};
  c.min_uniform_share = 0;
  refuse(c, "min_uniform_share");
  c = {};
  c.tolerance_share = 1.5;
  refuse(c, "tolerance_share");
  c = {};
  c.min_image_share = 0.9;
  c.max_image_share = 0.5;
  refuse(c, "min_image_share");
  CHECK_THROWS_AS(mpr::detect_backdrop(mpr::CameraFrameSet<double, mpr::Rgb8>{}), mpr::argument_error);
}
