#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/scene_depth.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

using namespace mpr_test;

namespace {

// Bright band-limited texture (every channel at least 64 codes).
mpr::Rgb8 bright(double x, double y) {
  const auto channel = [&](double a, double b, double c, double d) {
    const double v = 0.6 + 0.2 * std::sin(a * x + b * y) + 0.15 * std::sin(c * x - d * y + 1.0);
    return static_cast<std::uint8_t>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
  };
  return mpr::Rgb8{channel(3.1, 1.3, 1.7, 4.7), channel(2.3, -3.7, 4.1, 1.9), channel(-1.9, 2.9, 3.3, -2.2)};
}

// Cameras with R = I see a textured disc of radius `radius` on the plane z = depth, centred on
// the z axis, against black: pixel (x, y) of a camera at C shows the plane point
// C + depth ((x - cx) / f, (y - cy) / f).
template <class T>
std::vector<mpr::Image<mpr::Rgb8>> disc_views(const std::vector<mpr::PinholeCamera<T>>& cameras, double depth,
                                              double radius) {
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (const auto& c : cameras) {
    mpr::Image<mpr::Rgb8> image(c.width(), c.height(), mpr::Rgb8{0, 0, 0});
    const double f = static_cast<double>(c.K()(0, 0)), cx = static_cast<double>(c.K()(0, 2)),
                 cy = static_cast<double>(c.K()(1, 2));
    for (int y = 0; y < c.height(); ++y)
      for (int x = 0; x < c.width(); ++x) {
        const double px = static_cast<double>(c.centre().x()) + depth * (x - cx) / f,
                     py = static_cast<double>(c.centre().y()) + depth * (y - cy) / f;
        if (px * px + py * py <= radius * radius) image(x, y) = bright(px, py);
      }
    images.push_back(std::move(image));
  }
  return images;
}

} // namespace

TEST_CASE("the depth proxy's radius is twice the median camera spacing", "[scene_depth]") {
  // Centres at x = 0, 1, 3, 3: nearest distinct neighbours 1, 1, 2, 2 (the two at 3 share a
  // place and do not count for each other); the median (the upper of the middle two) is 2.
  std::vector<mpr::PinholeCamera<double>> cams;
  for (const double x : {0.0, 1.0, 3.0, 3.0}) cams.push_back(camera_at<double>({x, 0, 0}, 8, 8, 10));
  const mpr::CameraFrameSet<double, mpr::Rgb8> frames(
      cams, std::vector<mpr::Image<mpr::Rgb8>>(4, mpr::Image<mpr::Rgb8>(8, 8)));
  CHECK(mpr::depth_proxy_radius(frames) == 4.0);
  // A grid 0.5 apart: 1.
  const auto grid = grid_cameras<double>(3, 3, 0.5, 8, 8, 10);
  CHECK(mpr::depth_proxy_radius(mpr::CameraFrameSet<double, mpr::Rgb8>(
            grid, std::vector<mpr::Image<mpr::Rgb8>>(9, mpr::Image<mpr::Rgb8>(8, 8)))) == Approx(1.0));
}

TEMPLATE_TEST_CASE("a textured disc on black: range from matches, backdrop found, hull applied", "[scene_depth]", float,
                   double) {
  using T = TestType;
  // 3 x 3 cameras 0.5 apart, focal 40, 64 x 48, a disc of radius 1.5 at z = 5 (12 pixels across
  // its radius): about 85 % of each image is black.
  const auto cams = grid_cameras<T>(3, 3, 0.5, 64, 48, 40);
  const mpr::CameraFrameSet<T, mpr::Rgb8> frames(cams, disc_views(cams, 5.0, 1.5));
  mpr::SceneDepthConfig config;
  config.sweep.threads = 2;
  std::vector<std::string> stages;
  config.sweep.progress = [&](const mpr::DepthProgress& p) {
    if (p.done == p.total) stages.emplace_back(p.stage);
    CHECK(p.done <= p.total);
    CHECK(p.seconds >= 0);
  };
  const mpr::SceneDepth d = mpr::estimate_scene_depth(frames, config);
  CHECK(d.range.source == mpr::SweepRangeSource::matches);
  CHECK(d.range.near < 5.0);
  CHECK(d.range.far > 5.0);
  REQUIRE(d.backdrop.has_value());
  CHECK(d.backdrop->colour.r == 0);
  CHECK(d.backdrop->colour.g == 0);
  CHECK(d.backdrop->colour.b == 0);
  CHECK(stages == std::vector<std::string>{"range", "backdrop", "sweep", "hull"});
  REQUIRE(d.maps.size() == 9);
  // The middle camera: its corner sees the backdrop (+inf), its centre the disc at 5.
  const mpr::Image<float>& m = d.maps[4];
  CHECK(std::isinf(m(0, 0)));
  CHECK(std::isinf(m(63, 47)));
  CHECK(m(32, 24) == Approx(5.0).epsilon(0.05));
  CHECK(m(28, 20) == Approx(5.0).epsilon(0.05));
}

TEMPLATE_TEST_CASE("a given range is kept, and no backdrop is looked for when told not to", "[scene_depth]", float,
                   double) {
  using T = TestType;
  const auto cams = grid_cameras<T>(3, 3, 0.5, 64, 48, 40);
  const mpr::CameraFrameSet<T, mpr::Rgb8> frames(cams, disc_views(cams, 5.0, 1.5));
  mpr::SceneDepthConfig config;
  config.sweep.near = 4;
  config.sweep.far = 7;
  config.sweep.planes = 16;
  config.use_backdrop = false;
  const mpr::SceneDepth d = mpr::estimate_scene_depth(frames, config);
  CHECK(d.range.source == mpr::SweepRangeSource::given);
  CHECK(d.range.near == 4.0);
  CHECK(d.range.far == 7.0);
  CHECK_FALSE(d.backdrop.has_value());
  // No hull: the black corner gets some depth of the sweep, not +inf.
  CHECK(std::isfinite(d.maps[4](0, 0)));
  config.hull_planes = 1;
  CHECK_THROWS_AS(mpr::estimate_scene_depth(frames, config), mpr::argument_error);
}
