#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/depth_estimation.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace {

// A smooth texture on the plane z = depth: sums of sinusoids with periods of 1.3 to 4 units
// (10 to 32 pixels at z = 5 with focal 40), so that the images are band-limited (a hard-edged
// texture point-sampled per pixel biases every matcher towards whole-pixel disparities).
mpr::Rgb8 smooth_texture(double x, double y) {
  const auto channel = [&](double a, double b, double c, double d) {
    const double v = 0.5 + 0.25 * std::sin(a * x + b * y) + 0.2 * std::sin(c * x - d * y + 1.0);
    return static_cast<std::uint8_t>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
  };
  return mpr::Rgb8{channel(3.1, 1.3, 1.7, 4.7), channel(2.3, -3.7, 4.1, 1.9), channel(-1.9, 2.9, 3.3, -2.2)};
}

template <class T>
std::vector<mpr::Image<mpr::Rgb8>> smooth_images(const std::vector<mpr::PinholeCamera<T>>& cameras, double depth) {
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (const auto& cam : cameras) {
    mpr::Image<mpr::Rgb8> img(cam.width(), cam.height());
    const mpr::PinholeCamera<double> c(cam.K().template cast<double>(), cam.R().template cast<double>(),
                                       cam.t().template cast<double>(), cam.width(), cam.height());
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) {
        const mpr::Ray<double> r = c.ray_through({x, y});
        const mpr::Vec3<double> p = r.at((depth - r.origin.z()) / r.direction.z());
        img(x, y) = smooth_texture(p.x(), p.y());
      }
    images.push_back(std::move(img));
  }
  return images;
}

} // namespace

TEST_CASE("plane sweep settings are checked, naming the field", "[depth_estimation]") {
  const auto refuse = [](mpr::PlaneSweepConfig c, const char* parameter) {
    try {
      mpr::validate(c);
      FAIL("no exception for " << parameter);
    } catch (const mpr::argument_error& e) {
      CHECK(e.parameter() == parameter);
    }
  };
  CHECK_NOTHROW(mpr::validate(mpr::PlaneSweepConfig{}));
  mpr::PlaneSweepConfig c;
  c.near = 0;
  refuse(c, "near");
  c = {};
  c.far = c.near;
  refuse(c, "far");
  c = {};
  c.planes = 1;
  refuse(c, "planes");
  c = {};
  c.neighbours = 0;
  refuse(c, "neighbours");
  c = {};
  c.best = c.neighbours + 1;
  refuse(c, "best");
  c = {};
  c.truncation = 0;
  refuse(c, "truncation");
  c = {};
  c.spatial = -1;
  refuse(c, "spatial");
  c = {};
  c.range = std::nan("");
  refuse(c, "range");
}

TEMPLATE_TEST_CASE("a plane sweep recovers the depth of a textured plane", "[depth_estimation]", float, double) {
  using T = TestType;
  // 3 x 3 cameras 0.3 apart, 48 x 36 pixels, focal 40, facing a textured plane at z = 5.
  const auto cams = mpr_test::grid_cameras<T>(3, 3, 0.3, 48, 36, 40.0);
  const mpr::CameraFrameSet<T> frames(cams, smooth_images(cams, 5.0));
  mpr::PlaneSweepConfig config;
  config.near = 2;
  config.far = 20;
  config.planes = 48;
  config.threads = 2;
  const mpr::DepthEstimate e = mpr::estimate_depth(frames, 4, config);
  REQUIRE(e.depth.width() == 48);
  REQUIRE(e.confidence.height() == 36);
  std::vector<double> errors;
  for (int y = 4; y < 32; ++y)
    for (int x = 4; x < 44; ++x) {
      errors.push_back(std::abs(static_cast<double>(e.depth(x, y)) - 5.0) / 5.0);
      CHECK(e.confidence(x, y) >= 0.0f);
      CHECK(e.confidence(x, y) <= 1.0f);
    }
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2), errors.end());
  const double median = errors[errors.size() / 2];
  INFO("median relative depth error " << median);
  // One plane step is about 2.5% of the depth at z = 5; the parabola refines below it.
  CHECK(median < 0.01);
  // Every camera's map, ready for with_depth (positive, finite).
  config.planes = 16;
  const std::vector<mpr::Image<float>> maps = mpr::estimate_depth_maps(frames, config);
  REQUIRE(maps.size() == 9);
  CHECK(mpr::CameraFrameSet<T>(frames).with_depth(maps).has_depth());
  // A flat grey set has no texture: the confidence is zero where every neighbour sees the pixel
  // at every plane (without aggregation, which would spread the image border's costs inward).
  config.spatial = 0;
  const std::vector<mpr::Image<mpr::Rgb8>> grey(9, mpr::Image<mpr::Rgb8>(48, 36, mpr::Rgb8{128, 128, 128}));
  const mpr::DepthEstimate flat = mpr::estimate_depth(mpr::CameraFrameSet<T>(cams, grey), 4, config);
  CHECK(flat.confidence(24, 18) < 0.05f);
  CHECK(e.confidence(24, 18) > 0.3f);
}

TEST_CASE("a plane sweep refuses a bad camera index, a single camera and lens distortion", "[depth_estimation]") {
  using T = double;
  const auto cams = mpr_test::grid_cameras<T>(2, 1, 0.3, 16, 12, 16.0);
  const mpr::CameraFrameSet<T> frames(cams, smooth_images(cams, 5.0));
  mpr::PlaneSweepConfig config;
  CHECK_THROWS_AS(mpr::estimate_depth(frames, 2, config), mpr::argument_error);
  CHECK_THROWS_AS(mpr::estimate_depth(frames.without(1), 0, config), mpr::argument_error);
  std::vector<mpr::PinholeCamera<T>> distorted = cams;
  distorted[1] =
      mpr::PinholeCamera<T>(cams[1].K(), cams[1].R(), cams[1].t(), 16, 12, mpr::PinholeCamera<T>::Distortion{0.1, 0});
  const mpr::CameraFrameSet<T> bad(distorted, smooth_images(cams, 5.0), {"a", "b"});
  CHECK_THROWS_WITH(mpr::estimate_depth(bad, 0, config), Catch::Contains("b: lens distortion"));
}
