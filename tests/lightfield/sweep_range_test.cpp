#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/sweep_range.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using namespace mpr_test;

namespace {

// Bright band-limited texture on the plane z = depth (periods of 1.3 to 4 world units).
mpr::Rgb8 texture(double x, double y) {
  const auto channel = [&](double a, double b, double c, double d) {
    const double v = 0.55 + 0.2 * std::sin(a * x + b * y) + 0.15 * std::sin(c * x - d * y + 1.0);
    return static_cast<std::uint8_t>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
  };
  return mpr::Rgb8{channel(3.1, 1.3, 1.7, 4.7), channel(2.3, -3.7, 4.1, 1.9), channel(-1.9, 2.9, 3.3, -2.2)};
}

// Cameras with R = I see the plane z = depth: pixel (x, y) of a camera at centre C shows the
// plane point C + depth ((x - cx) / f, (y - cy) / f).
template <class T>
std::vector<mpr::Image<mpr::Rgb8>> plane_views(const std::vector<mpr::PinholeCamera<T>>& cameras, double depth) {
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (const auto& c : cameras) {
    mpr::Image<mpr::Rgb8> image(c.width(), c.height());
    const double f = static_cast<double>(c.K()(0, 0)), cx = static_cast<double>(c.K()(0, 2)),
                 cy = static_cast<double>(c.K()(1, 2));
    for (int y = 0; y < c.height(); ++y)
      for (int x = 0; x < c.width(); ++x)
        image(x, y) = texture(static_cast<double>(c.centre().x()) + depth * (x - cx) / f,
                              static_cast<double>(c.centre().y()) + depth * (y - cy) / f);
    images.push_back(std::move(image));
  }
  return images;
}

} // namespace

TEMPLATE_TEST_CASE("the common frustum of two parallel cameras, and its range without texture", "[sweep_range]", float,
                   double) {
  using T = TestType;
  // Focal 40, 32 pixels wide, one unit apart along x. The right camera sees the reference
  // pixel x at depth z at u = x - 40 / z, inside the image while u >= -0.5: z >= 40 / (x + 0.5),
  // nearest for the last column x = 31: z = 40 / 31.5. The left camera, symmetrically, from
  // x = 0. Both see together out to infinity.
  const std::vector<mpr::PinholeCamera<T>> cams{camera_at<T>({T(0), T(0), T(0)}, 32, 24, 40),
                                                camera_at<T>({T(1), T(0), T(0)}, 32, 24, 40)};
  std::vector<mpr::Image<mpr::Rgb8>> flat(2, mpr::Image<mpr::Rgb8>(32, 24, mpr::Rgb8{90, 90, 90}));
  const mpr::CameraFrameSet<T, mpr::Rgb8> frames(cams, flat);
  const mpr::SweepRange r = mpr::sweep_range(frames);
  CHECK(r.frustum_near == Approx(40.0 / 31.5).epsilon(1e-5));
  CHECK(r.frustum_far == std::numeric_limits<double>::infinity());
  // A flat grey has nothing to match: the frustum's range, its far end 100 times its near.
  CHECK(r.source == mpr::SweepRangeSource::frustum);
  CHECK(r.matches == 0);
  CHECK(r.near == Approx(40.0 / 31.5).epsilon(1e-5));
  CHECK(r.far == Approx(4000.0 / 31.5).epsilon(1e-5));
}

TEMPLATE_TEST_CASE("the common frustum of two converging cameras is bounded on both sides", "[sweep_range]", float,
                   double) {
  using T = TestType;
  // Two cameras 2 apart, each turned 45 degrees towards the other, axes crossing at (1, 0, 1),
  // focal 40 and 33 pixels wide (half field atan(16.5 / 40) = 22.4 degrees). Every ray of one
  // leaves the other's field far away (their directions lie at least 90 - 2 x 22.4 degrees
  // apart), so the common frustum is finite at both ends, and contains the crossing of the
  // axes, which both see at their image centres.
  const auto turned = [](T x, T angle) {
    mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
    K(0, 0) = K(1, 1) = T(40);
    K(0, 2) = T(16);
    K(1, 2) = T(12);
    const T c = std::cos(angle), s = std::sin(angle);
    mpr::Mat3<T> R;
    R << c, 0, -s, 0, 1, 0, s, 0, c; // world -> camera: the camera's axis is (sin, 0, cos) in the world
    const mpr::Vec3<T> centre(x, 0, 0);
    return mpr::PinholeCamera<T>(K, R, mpr::Vec3<T>(-(R * centre)), 33, 25);
  };
  const T quarter = T(0.7853981633974483);
  const std::vector<mpr::PinholeCamera<T>> cams{turned(0, quarter), turned(2, -quarter)};
  std::vector<mpr::Image<mpr::Rgb8>> flat(2, mpr::Image<mpr::Rgb8>(33, 25, mpr::Rgb8{90, 90, 90}));
  const mpr::SweepRange r = mpr::sweep_range(mpr::CameraFrameSet<T, mpr::Rgb8>(cams, flat));
  CHECK(r.frustum_near > 0);
  CHECK(std::isfinite(r.frustum_far));
  // The axes cross at depth sqrt(2) along each: the frustum contains it.
  CHECK(r.frustum_near < 1.4142);
  CHECK(r.frustum_far > 1.4143);
}

TEMPLATE_TEST_CASE("sparse matches bound the range of a textured plane", "[sweep_range]", float, double) {
  using T = TestType;
  // 3 x 3 cameras 0.5 apart, focal 40, 64 x 48, looking at the plane z = 5: parallax 4 pixels
  // between neighbours, 11.3 between diagonal corners (the longer partner). Every match lies at
  // w = 1 / 5 within a quarter of a step (about 0.06 and 0.02 in w's share for the two
  // partners), the range is that widened by 2% of 1 / 5 on each side.
  const auto cams = grid_cameras<T>(3, 3, 0.5, 64, 48, 40);
  const mpr::CameraFrameSet<T, mpr::Rgb8> frames(cams, plane_views(cams, 5.0));
  const mpr::SweepRange r = mpr::sweep_range(frames);
  CHECK(r.source == mpr::SweepRangeSource::matches);
  CHECK(r.matches >= 16);
  CHECK(r.near > 4.5);
  CHECK(r.near < 4.95);
  CHECK(r.far > 5.05);
  CHECK(r.far < 5.6);
  CHECK(r.frustum_far == std::numeric_limits<double>::infinity());
}

TEST_CASE("sweep range settings are checked, naming the field", "[sweep_range]") {
  const auto refuse = [](mpr::SweepRangeConfig c, const char* parameter) {
    try {
      mpr::validate(c);
      FAIL("no exception for " << parameter);
    } catch (const mpr::argument_error& e) {
      CHECK(e.parameter() == parameter);
    }
  };
  CHECK_NOTHROW(mpr::validate(mpr::SweepRangeConfig{}));
  mpr::SweepRangeConfig c;
  c.reference_cameras = 0;
  refuse(c, "reference_cameras");
  c = {};
  c.coarse_width = 8;
  refuse(c, "coarse_width");
  c = {};
  c.min_score = 0;
  refuse(c, "min_score");
  c = {};
  c.quantile = 0.5;
  refuse(c, "quantile");
  c = {};
  c.margin = -1;
  refuse(c, "margin");
  c = {};
  c.min_matches = 0;
  refuse(c, "min_matches");
  // One camera has no partner.
  const std::vector<mpr::PinholeCamera<double>> one{camera_at<double>({0, 0, 0}, 8, 8, 10)};
  CHECK_THROWS_AS(mpr::sweep_range(mpr::CameraFrameSet<double, mpr::Rgb8>(one, {mpr::Image<mpr::Rgb8>(8, 8)})),
                  mpr::argument_error);
}
