#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield.hpp>
#include <mpr/mpr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <random>
#include <span>
#include <utility>
#include <vector>

using mpr_test::constant_colour;

namespace {

template <class T, class Interp>
mpr::CameraFrameSampler<Interp, T, mpr::Color>
make_sampler(const std::vector<mpr::PinholeCamera<T>>& cameras, std::vector<mpr::Image<mpr::Color>> images,
             Interp interp = {}, typename mpr::CameraFrameSampler<Interp, T, mpr::Color>::Config config = {}) {
  auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(cameras, std::move(images));
  return mpr::CameraFrameSampler<Interp, T, mpr::Color>(frames, interp, config);
}

bool close(const mpr::Color& a, const mpr::Color& b, float tolerance) { return ((a - b).abs() <= tolerance).all(); }

// `rays` through the sampler by every path it has -- per ray, batch (`sample_rays`) and tile
// (`sample_tile`, rows of `width`) -- each answer within `tolerance` of `expected[i]`.
template <class S, class T>
void check_every_path(const S& sampler, const std::vector<mpr::Ray<T>>& rays, int width,
                      const std::vector<mpr::Color>& expected, float tolerance) {
  std::vector<mpr::Color> batch(rays.size()), tile(rays.size());
  sampler.sample_rays(rays, batch);
  sampler.sample_tile(rays, width, tile);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    INFO("ray " << i << " expected " << expected[i].transpose());
    CHECK(close(sampler.sample(rays[i]), expected[i], tolerance));
    CHECK(close(batch[i], expected[i], tolerance));
    CHECK(close(tile[i], expected[i], tolerance));
  }
}

// `n` rays along +z whose points (origins) are evenly spaced `step` apart in x from `start`: a
// run the batch and tile paths add by shift-and-add.
template <class T>
std::vector<mpr::Ray<T>> ray_row(const mpr::Vec3<T>& start, T step, std::size_t n) {
  std::vector<mpr::Ray<T>> rays;
  for (std::size_t i = 0; i < n; ++i)
    rays.push_back({mpr::Vec3<T>(start.x() + step * static_cast<T>(i), start.y(), start.z()), mpr::Vec3<T>(0, 0, 1)});
  return rays;
}

} // namespace

TEST_CASE("camera frame samplers satisfy the sampler concepts", "[camera_frame_sampler]") {
  STATIC_REQUIRE(mpr::RaySampler<mpr::CameraFrameSampler<mpr::NearestCamera>>);
  STATIC_REQUIRE(mpr::RaySampler<mpr::CameraFrameSampler<mpr::SyntheticAperture, double>>);
  STATIC_REQUIRE(mpr::RaySampler<mpr::CameraFrameSampler<mpr::CylinderAperture, float, mpr::Color>>);
  STATIC_REQUIRE(mpr::BatchRaySampler<mpr::CameraFrameSampler<mpr::SyntheticAperture>>);
  STATIC_REQUIRE(mpr::BatchRaySampler<mpr::CameraFrameSampler<mpr::NearestCamera, double>>);
  STATIC_REQUIRE_FALSE(mpr::BatchRaySampler<mpr::CheckerboardPlane<float>>);
  STATIC_REQUIRE(mpr::TileRaySampler<mpr::CameraFrameSampler<mpr::SyntheticAperture>>);
  STATIC_REQUIRE(mpr::TileRaySampler<mpr::CameraFrameSampler<mpr::CylinderAperture, double, mpr::Color>>);
  STATIC_REQUIRE_FALSE(mpr::TileRaySampler<mpr::CheckerboardPlane<float>>);
  // The grid path: the three interpolations of a frame set have one; a batch-only one does not.
  STATIC_REQUIRE(mpr::GridRaySampler<mpr::CameraFrameSampler<mpr::NearestCamera, double>>);
  STATIC_REQUIRE(mpr::GridRaySampler<mpr::CameraFrameSampler<mpr::SyntheticAperture>>);
  STATIC_REQUIRE(mpr::GridRaySampler<mpr::CameraFrameSampler<mpr::CylinderAperture, float, mpr::Color>>);
  STATIC_REQUIRE_FALSE(mpr::GridRaySampler<mpr::CameraFrameSampler<mpr::DepthProxy>>);
  STATIC_REQUIRE(mpr::ComposablePolicies<mpr::PlanarSurface<double>, mpr::GlcSelector<double>,
                                         mpr::CameraFrameSampler<mpr::NearestCamera, double>>);
  STATIC_REQUIRE_FALSE(mpr::ComposablePolicies<mpr::PlanarSurface<double>, mpr::GlcSelector<double>,
                                               mpr::CameraFrameSampler<mpr::NearestCamera, float>>);
}

TEMPLATE_TEST_CASE("CameraFrameSampler rejects bad configuration", "[camera_frame_sampler]", float, double) {
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(2, 2, 1.0, 8, 6, 8.0);
  using S = mpr::CameraFrameSampler<mpr::CylinderAperture, T, mpr::Color>;
  CHECK_THROWS_AS(S(nullptr, mpr::CylinderAperture{1.0}), mpr::argument_error);
  CHECK_THROWS_AS(S(std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(), mpr::CylinderAperture{1.0}),
                  mpr::argument_error);
  auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(cams, mpr_test::constant_images(cams));
  CHECK_THROWS_AS(S(frames, mpr::CylinderAperture{0.0}), mpr::argument_error);
  CHECK_THROWS_AS(S(frames, mpr::CylinderAperture{-1.0}), mpr::argument_error);
  CHECK_THROWS_AS(S(frames, mpr::CylinderAperture{std::numeric_limits<double>::quiet_NaN()}), mpr::argument_error);
  typename S::Config bad;
  bad.depth = std::numeric_limits<T>::infinity();
  CHECK_THROWS_AS(S(frames, mpr::CylinderAperture{1.0}, bad), mpr::argument_error);
  CHECK_NOTHROW(S(frames, mpr::CylinderAperture{1.0}));
  // Frame sets check their own consistency.
  CHECK_THROWS_AS((mpr::CameraFrameSet<T, mpr::Color>(cams, {})), mpr::argument_error);
  std::vector<mpr::Image<mpr::Color>> wrong(4, mpr::Image<mpr::Color>(7, 6));
  CHECK_THROWS_AS((mpr::CameraFrameSet<T, mpr::Color>(cams, wrong)), mpr::argument_error);
}

TEMPLATE_TEST_CASE("NearestCamera answers with the camera nearest the ray line", "[camera_frame_sampler]", float,
                   double) {
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(5, 4, 1.0, 16, 12, 16.0);
  const auto sampler = make_sampler<T>(cams, mpr_test::constant_images(cams), mpr::NearestCamera{});
  const mpr::Vec3<T> X(T(0.1), T(-0.2), T(10)); // on the axis of the array, seen by every camera
  for (std::size_t k = 0; k < cams.size(); ++k) {
    // A ray through X whose line passes 0.1 from camera k's centre.
    const mpr::Vec3<T> near_k = cams[k].centre() + mpr::Vec3<T>(T(0.1), T(0.05), T(0));
    const mpr::Ray<T> ray{X, X - near_k};
    CHECK(close(sampler.sample(ray), constant_colour(k, cams.size()), 1e-6f));
  }
  // A point behind every camera: background (black by default), not NaN.
  const mpr::Color behind = sampler.sample({mpr::Vec3<T>(0, 0, -5), mpr::Vec3<T>(0, 0, 1)});
  CHECK(close(behind, mpr::Color::Zero(), 0));
  // Degenerate direction: background, never NaN.
  const mpr::Color zero_dir = sampler.sample({X, mpr::Vec3<T>::Zero()});
  CHECK(zero_dir.allFinite());
}

TEMPLATE_TEST_CASE("SyntheticAperture averages the cameras that see the point", "[camera_frame_sampler]", float,
                   double) {
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(3, 3, 1.0, 16, 12, 16.0);
  typename mpr::CameraFrameSampler<mpr::SyntheticAperture, T, mpr::Color>::Config config;
  config.background = mpr::Color(0.5f, 0.25f, 0.125f);
  const auto sampler = make_sampler<T>(cams, mpr_test::constant_images(cams), mpr::SyntheticAperture{}, config);
  // The fixture's colours are asymmetric: leaving out any one or two cameras changes the mean.
  REQUIRE(mpr_test::constant_colour_is_asymmetric(9, 1e-3f));
  // Seen by all nine cameras: the mean of the nine colours, (11/24, 4/9, 19/48) worked out by
  // hand from the fixture's table, whatever the ray direction.
  const mpr::Color mean(11.0f / 24.0f, 4.0f / 9.0f, 19.0f / 48.0f);
  CHECK(close(sampler.sample({mpr::Vec3<T>(0, 0, 20), mpr::Vec3<T>(0, 0, 1)}), mean, 1e-6f));
  CHECK(close(sampler.sample({mpr::Vec3<T>(0, 0, 20), mpr::Vec3<T>(T(0.3), 0, 1)}), mean, 1e-6f));
  // The batch and tile paths too: 24 evenly spaced points (shift-and-add), two tile rows of 12.
  check_every_path(sampler, ray_row<T>(mpr::Vec3<T>(T(-0.2), T(0.1), T(20)), T(0.02), 24), 12,
                   std::vector<mpr::Color>(24, mean), 1e-5f);
  // Field of view: x pixel 7.5 + 16 dx / z must lie in [-0.5, 15.5), y pixel 5.5 + 16 dy / z in
  // [-0.5, 11.5). At X = (1, 0, 2.5) a camera one unit away is 6.4 px off centre: seen across x
  // (cameras 4 and 5 of the middle row), not across y, and the camera two units away in x not
  // at all -- so exactly cameras 4 and 5, mean (8/16 + 5/16, 4/16 + 5/16, 7/16 + 7/16) / 2.
  const mpr::Vec3<T> X(T(1.0), T(0), T(2.5));
  int seen = 0;
  for (std::size_t k = 0; k < 9; ++k) seen += cams[k].project(X) ? 1 : 0;
  CHECK(seen == 2);
  const mpr::Color pair_mean(13.0f / 32.0f, 9.0f / 32.0f, 7.0f / 16.0f);
  CHECK(close(sampler.sample({X, mpr::Vec3<T>(0, 0, 1)}), pair_mean, 1e-6f));
  check_every_path(sampler, ray_row<T>(mpr::Vec3<T>(T(0.99), 0, T(2.5)), T(0.001), 16), 8,
                   std::vector<mpr::Color>(16, pair_mean), 1e-5f);
  // Nobody sees it: the background, by every path (a row of points behind the cameras).
  CHECK(close(sampler.sample({mpr::Vec3<T>(0, 0, -1), mpr::Vec3<T>(0, 0, 1)}), config.background, 0));
  check_every_path(sampler, ray_row<T>(mpr::Vec3<T>(T(-0.2), 0, T(-1)), T(0.02), 16), 8,
                   std::vector<mpr::Color>(16, config.background), 0);
}

TEMPLATE_TEST_CASE("CylinderAperture weights cameras by 1 - d/r and falls back to the nearest",
                   "[camera_frame_sampler]", float, double) {
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(4, 1, 1.0, 16, 12, 16.0); // x = -1.5, -0.5, 0.5, 1.5
  const auto images = mpr_test::constant_images(cams);
  const auto sampler = make_sampler<T>(cams, images, mpr::CylinderAperture{1.0});
  // Ray line along z through x = 0.2: distances 1.7, 0.7, 0.3, 1.3 -> cameras 1 and 2 qualify,
  // weights 0.3 and 0.7.
  const mpr::Ray<T> ray{mpr::Vec3<T>(T(0.2), 0, 30), mpr::Vec3<T>(0, 0, 2)};
  const mpr::Color expected = (0.3f * constant_colour(1, 4) + 0.7f * constant_colour(2, 4)) / 1.0f;
  CHECK(close(sampler.sample(ray), expected, 1e-5f));
  // By hand: 0.3 (9/16, 10/16, 8/16) + 0.7 (10/16, 5/16, 2/16); swapped weights would give
  // (0.58125, 0.53125, 0.3875).
  const mpr::Color by_hand(0.60625f, 0.40625f, 0.2375f);
  CHECK(close(sampler.sample(ray), by_hand, 1e-5f));
  // Every path, on a row of lines x = 0.2 + 0.001 i (weights change slowly along it).
  std::vector<mpr::Color> along;
  for (int i = 0; i < 16; ++i) {
    const float x = 0.2f + 0.001f * static_cast<float>(i);
    along.push_back((0.5f - x) * constant_colour(1) + (0.5f + x) * constant_colour(2)); // weights sum to 1
  }
  check_every_path(sampler, ray_row<T>(mpr::Vec3<T>(T(0.2), 0, 30), T(0.001), 16), 8, along, 1e-4f);
  // Nobody within the radius: the nearest camera (camera 3 at x = 1.5 for a line at x = 4).
  const auto narrow = make_sampler<T>(cams, images, mpr::CylinderAperture{0.1});
  const mpr::Ray<T> far{mpr::Vec3<T>(T(1.55), 0, 30), mpr::Vec3<T>(0, 0, 1)};
  CHECK(close(narrow.sample(far), constant_colour(3, 4), 1e-6f));
  const mpr::Ray<T> outside{mpr::Vec3<T>(T(4), 0, 300), mpr::Vec3<T>(0, 0, 1)};
  const mpr::Color c = narrow.sample(outside);
  CHECK(c.allFinite());
  CHECK(close(c, constant_colour(3, 4), 1e-6f));
  // A wide cylinder equals the weighted mean over all cameras.
  const auto wide = make_sampler<T>(cams, images, mpr::CylinderAperture{100.0});
  mpr::Color acc = mpr::Color::Zero();
  float wsum = 0;
  for (int k = 0; k < 4; ++k) {
    const float w = 1.0f - static_cast<float>(std::abs(cams[static_cast<std::size_t>(k)].centre().x() - 0.2)) / 100.0f;
    acc += w * constant_colour(static_cast<std::size_t>(k), 4);
    wsum += w;
  }
  CHECK(close(wide.sample(ray), acc / wsum, 1e-5f));
}

TEMPLATE_TEST_CASE("pixel reconstruction: bilinear by default, nearest on request; depth option",
                   "[camera_frame_sampler]", float, double) {
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(1, 1, 1.0, 4, 4, 4.0); // principal point (1.5, 1.5)
  mpr::Image<mpr::Color> img(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) img(x, y) = mpr::Color(static_cast<float>(x), static_cast<float>(y), 0.0f);
  const std::vector<mpr::Image<mpr::Color>> images{img};
  const auto bilinear = make_sampler<T>(cams, images, mpr::SyntheticAperture{});
  typename mpr::CameraFrameSampler<mpr::SyntheticAperture, T, mpr::Color>::Config nearest_config;
  nearest_config.filter = mpr::PixelFilter::nearest;
  const auto nearest = make_sampler<T>(cams, images, mpr::SyntheticAperture{}, nearest_config);
  // Pixel (1.25, 2.75): X = ((1.25 - 1.5) z / 4, (2.75 - 1.5) z / 4, z).
  const T z = 8;
  const mpr::Vec3<T> X(T(-0.25) * z / 4, T(1.25) * z / 4, z);
  const mpr::Ray<T> ray{X, mpr::Vec3<T>(0, 0, 1)};
  CHECK(close(bilinear.sample(ray), mpr::Color(1.25f, 2.75f, 0), 1e-5f));
  CHECK(close(nearest.sample(ray), mpr::Color(1, 3, 0), 0));
  // Border: between the last pixel centre and the image edge the edge pixel repeats.
  const mpr::Vec3<T> edge(T(1.8) * z / 4, T(0), z); // pixel x = 3.3
  CHECK(close(bilinear.sample({edge, mpr::Vec3<T>(0, 0, 1)}), mpr::Color(3, 1.5f, 0), 1e-5f));
  // Outside the image (x = 3.6 >= 3.5): no contribution -> background.
  const mpr::Vec3<T> out(T(2.1) * z / 4, T(0), z);
  CHECK(close(bilinear.sample({out, mpr::Vec3<T>(0, 0, 1)}), mpr::Color::Zero(), 0));
  // depth: the colour is taken at ray.at(depth).
  typename mpr::CameraFrameSampler<mpr::SyntheticAperture, T, mpr::Color>::Config depth_config;
  depth_config.depth = T(2);
  const auto at_depth = make_sampler<T>(cams, images, mpr::SyntheticAperture{}, depth_config);
  const mpr::Ray<T> shifted{mpr::Vec3<T>(X.x(), X.y(), X.z() - 4), mpr::Vec3<T>(0, 0, 2)};
  CHECK(close(at_depth.sample(shifted), mpr::Color(1.25f, 2.75f, 0), 1e-5f));
}

TEST_CASE("8-bit frames are decoded to linear colour with the exact sRGB table", "[camera_frame_sampler]") {
  const auto cams = mpr_test::grid_cameras<float>(1, 1, 1.0, 4, 4, 4.0);
  std::vector<mpr::Image<mpr::Rgb8>> images{mpr::Image<mpr::Rgb8>(4, 4, mpr::Rgb8{128, 7, 255})};
  auto frames = std::make_shared<const mpr::CameraFrameSet<float>>(cams, images);
  const mpr::CameraFrameSampler<mpr::NearestCamera> sampler(frames);
  const mpr::Color c = sampler.sample({mpr::Vec3<float>(0, 0, 3), mpr::Vec3<float>(0, 0, 1)});
  // Decoded through the 16-bit linear table (`Srgb8Texel`): within 1/131070 of the exact values.
  CHECK(std::abs(c[0] - mpr::srgb8_to_linear(128)) <= 8e-6f);
  CHECK(std::abs(c[1] - mpr::srgb8_to_linear(7)) <= 8e-6f);
  CHECK(c[2] == 1.0f);
  CHECK(mpr::to_rgb8(c) == mpr::Rgb8{128, 7, 255});
}

TEMPLATE_TEST_CASE("refocusing on the scene plane reproduces a held-out view", "[camera_frame_sampler]", float,
                   double) {
  using T = TestType;
  const double depth = 20;
  auto cams = mpr_test::grid_cameras<T>(4, 4, 1.0, 40, 30, 40.0);
  auto images = mpr_test::plane_images(cams, depth);
  // Hold out camera 5 (an inner one).
  const mpr::PinholeCamera<T> held = cams[5];
  const mpr::Image<mpr::Color> truth = images[5];
  auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(cams, images)->without(5);
  auto shared = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(std::move(frames));
  const mpr::PlanarSurface<T> plane = held.image_plane(static_cast<T>(depth));
  const mpr::GlcSelector<T> glc = mpr::pinhole_glc(held, plane);
  const mpr::Region region(0, 0, held.width(), held.height());
  const auto check_policy = [&](const auto& sampler, float tolerance) {
    const mpr::Renderer renderer(plane, glc, sampler);
    mpr::Image<mpr::Color> out(held.width(), held.height());
    renderer.render(out.view(), region, mpr::RenderOptions{1});
    float worst = 0;
    for (int y = 2; y < held.height() - 2; ++y)
      for (int x = 2; x < held.width() - 2; ++x) worst = std::max(worst, (out(x, y) - truth(x, y)).abs().maxCoeff());
    CHECK(worst <= tolerance);
  };
  check_policy(mpr::CameraFrameSampler<mpr::NearestCamera, T, mpr::Color>(shared), 1e-4f);
  check_policy(mpr::CameraFrameSampler<mpr::SyntheticAperture, T, mpr::Color>(shared), 1e-4f);
  check_policy(mpr::CameraFrameSampler<mpr::CylinderAperture, T, mpr::Color>(shared, mpr::CylinderAperture{1.5}),
               1e-4f);
}

namespace {

// An independent answer for the light-field samplers, written from their definitions with no
// library code: cameras with R = I and centres `centres`, focal length f, principal point at
// the image centre, images `images`. A camera sees X when X is in front of it and its pixel
// (x, y) lies in [-0.5, w - 0.5) x [-0.5, h - 0.5); its colour there is bilinear between pixel
// centres with edge pixels repeated. `near_edge` is set when some camera's pixel, a cylinder
// distance or a nearest-camera tie lies within 1e-3 of a decision boundary (such pixels are
// not compared: float and double may decide differently).
struct Oracle {
  std::vector<mpr::Vec3<double>> centres;
  const std::vector<mpr::Image<mpr::Color>>* images = nullptr;
  double f = 0;

  bool seen(std::size_t k, const mpr::Vec3<double>& X, mpr::Color& colour, bool& near_edge) const {
    const mpr::Image<mpr::Color>& img = (*images)[k];
    const mpr::Vec3<double> d = X - centres[k];
    if (d.z() <= 0) return false;
    const double x = f * d.x() / d.z() + 0.5 * (img.width() - 1), y = f * d.y() / d.z() + 0.5 * (img.height() - 1);
    for (const double e : {x + 0.5, y + 0.5, img.width() - 0.5 - x, img.height() - 0.5 - y})
      near_edge = near_edge || std::abs(e) < 1e-3;
    if (x < -0.5 || y < -0.5 || x >= img.width() - 0.5 || y >= img.height() - 0.5) return false;
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const double ax = x - x0, ay = y - y0;
    const auto px = [&](int i, int j) -> Eigen::Array3d {
      return img(std::clamp(i, 0, img.width() - 1), std::clamp(j, 0, img.height() - 1)).cast<double>();
    };
    const Eigen::Array3d c = (1 - ax) * (1 - ay) * px(x0, y0) + ax * (1 - ay) * px(x0 + 1, y0) +
                             (1 - ax) * ay * px(x0, y0 + 1) + ax * ay * px(x0 + 1, y0 + 1);
    colour = c.cast<float>();
    return true;
  }

  double distance(std::size_t k, const mpr::Vec3<double>& X, const mpr::Vec3<double>& dir) const {
    return (centres[k] - X).cross(dir).norm() / dir.norm();
  }

  // Synthetic aperture: the plain mean over the cameras that see X.
  mpr::Color mean(const mpr::Vec3<double>& X, bool& near_edge) const {
    Eigen::Array3d acc = Eigen::Array3d::Zero();
    int n = 0;
    for (std::size_t k = 0; k < centres.size(); ++k) {
      mpr::Color c;
      if (seen(k, X, c, near_edge)) {
        acc += c.cast<double>();
        ++n;
      }
    }
    return n > 0 ? mpr::Color((acc / n).cast<float>()) : mpr::Color::Zero();
  }

  // Nearest camera to the line (X, dir): its colour, or black when it does not see X.
  mpr::Color nearest(const mpr::Vec3<double>& X, const mpr::Vec3<double>& dir, bool& near_edge) const {
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t k = 0; k < centres.size(); ++k) order.emplace_back(distance(k, X, dir), k);
    std::sort(order.begin(), order.end());
    near_edge = near_edge || order[1].first - order[0].first < 1e-3;
    mpr::Color c;
    return seen(order[0].second, X, c, near_edge) ? c : mpr::Color(mpr::Color::Zero());
  }

  // Cylinder of radius r: weights 1 - d / r over cameras strictly within r that see X,
  // renormalised; the nearest camera when none does.
  mpr::Color cylinder(const mpr::Vec3<double>& X, const mpr::Vec3<double>& dir, double r, bool& near_edge) const {
    Eigen::Array3d acc = Eigen::Array3d::Zero();
    double wsum = 0;
    for (std::size_t k = 0; k < centres.size(); ++k) {
      const double d = distance(k, X, dir);
      near_edge = near_edge || std::abs(d - r) < 1e-3;
      mpr::Color c;
      if (d < r && seen(k, X, c, near_edge)) {
        acc += (1 - d / r) * c.cast<double>();
        wsum += 1 - d / r;
      }
    }
    return wsum > 0 ? mpr::Color((acc / wsum).cast<float>()) : nearest(X, dir, near_edge);
  }
};

} // namespace

TEMPLATE_TEST_CASE("refocusing off the scene plane gives the independently computed per-camera blend",
                   "[camera_frame_sampler]", float, double) {
  using T = TestType;
  // 4 x 4 cameras looking at the plane z = 20 with per-pixel noise on its texture (so neighbouring
  // cameras see different colours and no blend is linear in the camera position), viewed by a
  // pinhole between the cameras focused at z = 12: every camera sees a different scene point
  // through each focal point, so which cameras are used and their weights all show in the result.
  const auto cams = mpr_test::grid_cameras<T>(4, 4, 1.0, 40, 30, 40.0);
  auto images = mpr_test::plane_images(cams, 20.0);
  std::mt19937 rng(19);
  for (auto& img : images)
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x)
        img(x, y) += mpr::Color(1, 2, 3) * (static_cast<float>(rng() % 64) / 512.0f);
  auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(cams, images);
  Oracle oracle;
  oracle.images = &images;
  oracle.f = 40;
  for (const auto& c : cams) oracle.centres.push_back(c.centre().template cast<double>());

  const mpr::Vec3<double> eye(-0.3, -0.15, 0);
  const double focus = 12, f = 40;
  const mpr::PinholeCamera<T> view = mpr_test::camera_at<T>(mpr::Vec3<T>(eye.cast<T>()), 40, 30, f);
  const mpr::PlanarSurface<T> plane = view.image_plane(static_cast<T>(focus));
  const mpr::GlcSelector<T> glc = mpr::pinhole_glc(view, plane);
  const mpr::Region region(0, 0, 40, 30);
  const double radius = 1.3;
  const auto check = [&](const auto& sampler, int kind) {
    const mpr::Renderer renderer(plane, glc, sampler);
    for (const int threads : {1, 2}) {
      mpr::Image<mpr::Color> out(40, 30);
      renderer.render(out.view(), region, mpr::RenderOptions{threads});
      float worst = 0, worst_pixel = 0;
      int compared = 0;
      for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
          // Pixel (x, y) of the view sees the focal point X on z = 12 along the line from the eye.
          const mpr::Vec3<double> dir((x - 19.5) / f, (y - 14.5) / f, 1);
          const mpr::Vec3<double> X = eye + focus * dir;
          bool near_edge = false;
          const mpr::Color expected = kind == 0   ? oracle.mean(X, near_edge)
                                      : kind == 1 ? oracle.nearest(X, dir, near_edge)
                                                  : oracle.cylinder(X, dir, radius, near_edge);
          if (near_edge) continue;
          ++compared;
          worst = std::max(worst, (out(x, y) - expected).abs().maxCoeff());
          worst_pixel = std::max(worst_pixel, (renderer.shade({x, y}, region) - expected).abs().maxCoeff());
        }
      INFO("interpolation " << kind << ", " << threads << " threads, " << compared << " pixels compared");
      CHECK(compared >= 40 * 30 * 9 / 10);
      // Bilinear of noise 0.37 per pixel at most, shift-and-add within 1e-3 pixel.
      CHECK(worst <= 1e-3f);
      CHECK(worst_pixel <= 1e-4f);
    }
  };
  check(mpr::CameraFrameSampler<mpr::SyntheticAperture, T, mpr::Color>(frames), 0);
  check(mpr::CameraFrameSampler<mpr::NearestCamera, T, mpr::Color>(frames), 1);
  check(mpr::CameraFrameSampler<mpr::CylinderAperture, T, mpr::Color>(frames, mpr::CylinderAperture{radius}), 2);
}

TEMPLATE_TEST_CASE("the batch path renders the same image as the per-pixel path", "[camera_frame_sampler]", float,
                   double) {
  using T = TestType;
  // A 6x5 array of 8-bit frames with texture, viewed off-axis through a tilted focal plane.
  auto cams = mpr_test::grid_cameras<T>(6, 5, 0.7, 48, 36, 40.0);
  const auto linear = mpr_test::plane_images(cams, 15.0);
  const auto images = mpr_test::with_detail(linear, 5, 31, 0, 0); // high-frequency detail
  auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(cams, images);
  const mpr::PinholeCamera<T> view = mpr::PinholeCamera<T>::look_at(
      mpr::Vec3<T>(T(0.3), T(-0.2), T(-1)), mpr::Vec3<T>(0, 0, 15), mpr::Vec3<T>(0, -1, 0), T(0.9), 64, 48);
  const mpr::Region region(0, 0, 64, 48);
  // Tilted focal plane (general path) and, from a camera of the array's own intrinsics, a
  // plane parallel to the array at the cameras' pixel scale (the shift-and-add path), seen by a
  // GLC whose rays sweep across the array.
  const mpr::PlanarSurface<T> tilted = view.image_plane(T(14)).tilted(T(0.3), T(0.2));
  mpr::Mat3<T> K = cams[0].K();
  K(0, 2) = T(31.5);
  K(1, 2) = T(23.5);
  const mpr::PinholeCamera<T> straight(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>(T(-0.1), T(0.2), 0), 64, 48);
  const mpr::PlanarSurface<T> parallel = straight.image_plane(T(15));
  const auto sweep = [&](const mpr::PlanarSurface<T>& p) {
    const auto d = [&](T u, T v) {
      return mpr::Vec3<T>(p.point_at({u, v}) - mpr::Vec3<T>(-1 + 2 * u, T(-0.5) + v, 0));
    };
    return mpr::GlcSelector<T>(p, d(0, 0), d(1, 0), d(0, 1));
  };
  for (const auto& setup : {std::pair{tilted, mpr::pinhole_glc(view, tilted)}, std::pair{parallel, sweep(parallel)}}) {
    // Named references, not a structured binding: lambdas capture those from C++20 on, but
    // Clang before 16 rejects it.
    const auto& plane = setup.first;
    const auto& glc = setup.second;
    const auto compare = [&](const auto& sampler) {
      const mpr::Renderer renderer(plane, glc, sampler);
      mpr::Image<mpr::Rgb8> batch(64, 48);
      renderer.render(batch.view(), region, mpr::RenderOptions{2});
      int worst = 0;
      for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
          const mpr::Rgb8 one = mpr::to_rgb8(renderer.shade({x, y}, region));
          const mpr::Rgb8 b = batch(x, y);
          worst = std::max({worst, std::abs(one.r - b.r), std::abs(one.g - b.g), std::abs(one.b - b.b)});
        }
      CHECK(worst <= 1);
    };
    compare(mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(frames));
    compare(mpr::CameraFrameSampler<mpr::NearestCamera, T>(frames));
    compare(mpr::CameraFrameSampler<mpr::CylinderAperture, T>(frames, mpr::CylinderAperture{1.2}));
  }
}

TEMPLATE_TEST_CASE("tiles of rows wider than one batch give the per-pixel image, for any thread count",
                   "[camera_frame_sampler]", float, double) {
  using T = TestType;
  // 3x2 cameras with rows of 320 pixels (wider than the 256-ray batches), a plane parallel to
  // the array at their pixel scale (whole-row shift-and-add), rendered into an image region
  // that starts at an odd row and column so tiles and regions do not line up.
  auto cams = mpr_test::grid_cameras<T>(3, 2, 0.5, 320, 21, 320.0);
  const auto linear = mpr_test::plane_images(cams, 12.0);
  const std::vector<mpr::Image<mpr::Rgb8>> images = mpr_test::with_detail(linear, 9, 0, 63, 0);
  auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(cams, images);
  mpr::Mat3<T> K = cams[0].K();
  const mpr::PinholeCamera<T> straight(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>(T(0.05), T(-0.1), 0), 300, 19);
  const mpr::PlanarSurface<T> plane = straight.image_plane(T(12));
  const mpr::GlcSelector<T> glc = mpr::pinhole_glc(straight, plane);
  const mpr::Region region(3, 1, 300, 19);
  // And a GLC whose rays sweep across the array (origins from u = -0.8 to 0.8 along a row, v =
  // -0.4 to 0.4 down the image): a narrow cylinder then weighs each camera on a stretch of each
  // row that changes from row to row and from 64-ray segment to segment.
  const auto d = [&](T u, T v) {
    return mpr::Vec3<T>(plane.point_at({u, v}) - mpr::Vec3<T>(T(-0.8) + T(1.6) * u, T(-0.4) + T(0.8) * v, 0));
  };
  const mpr::GlcSelector<T> sweep(plane, d(0, 0), d(1, 0), d(0, 1));
  // On `plane` unless another surface is given.
  const auto compare = [&](const auto& sampler, const mpr::GlcSelector<T>& selector,
                           const mpr::PlanarSurface<T>* on = nullptr) {
    const mpr::Renderer renderer(on != nullptr ? *on : plane, selector, sampler);
    mpr::Image<mpr::Rgb8> one(305, 22, mpr::Rgb8{1, 2, 3}), two(305, 22, mpr::Rgb8{1, 2, 3});
    renderer.render(one.view(), region, mpr::RenderOptions{1});
    renderer.render(two.view(), region, mpr::RenderOptions{2});
    CHECK(one == two);
    int worst = 0, untouched = 0;
    for (int y = 0; y < 22; ++y)
      for (int x = 0; x < 305; ++x) {
        const bool inside = x >= 3 && y >= 1 && y < 20 && x < 303;
        const mpr::Rgb8 b = one(x, y);
        if (!inside) {
          untouched += b == mpr::Rgb8{1, 2, 3} ? 1 : 0;
          continue;
        }
        const mpr::Rgb8 p = mpr::to_rgb8(renderer.shade({x, y}, region));
        worst = std::max({worst, std::abs(p.r - b.r), std::abs(p.g - b.g), std::abs(p.b - b.b)});
      }
    CHECK(worst <= 1);
    CHECK(untouched == 305 * 22 - 300 * 19);
  };
  compare(mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(frames), glc);
  compare(mpr::CameraFrameSampler<mpr::NearestCamera, T>(frames), glc);
  compare(mpr::CameraFrameSampler<mpr::CylinderAperture, T>(frames, mpr::CylinderAperture{0.6}), glc);
  compare(mpr::CameraFrameSampler<mpr::CylinderAperture, T>(frames, mpr::CylinderAperture{0.35}), sweep);
  compare(mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(frames), sweep);
  compare(mpr::CameraFrameSampler<mpr::NearestCamera, T>(frames), sweep);
  // At z = 16 every camera sees the plane's points at whole-pixel shifts (20 pixels per unit of
  // the centres' offsets from the view's): each run reads one camera row, and the cylinder adds
  // its short rows rows outer, each camera on the stretch it weighs, padded to 8 rays. Rays whose
  // origins sweep 1.6 or 8 units along a row: a narrow cylinder then weighs 4 to 40 rays of one.
  const mpr::PlanarSurface<T> whole = straight.image_plane(T(16));
  for (const T spread : {T(1.6), T(8)}) {
    const auto d16 = [&](T u, T v) {
      return mpr::Vec3<T>(whole.point_at({u, v}) - mpr::Vec3<T>(spread * (u - T(0.5)), T(-0.4) + T(0.8) * v, 0));
    };
    const mpr::GlcSelector<T> sweep16(whole, d16(0, 0), d16(1, 0), d16(0, 1));
    for (const double r : {0.06, 0.1, 0.2, 0.35, 0.6})
      compare(mpr::CameraFrameSampler<mpr::CylinderAperture, T>(frames, mpr::CylinderAperture{r}), sweep16, &whole);
  }

  // Each interpolation's grid path (what the renderer takes under a plane and a GLC) against its
  // tile path on the same tile's rays; on a non-planar array the nearest camera and the cylinder
  // decline the grid, the synthetic aperture (which needs no plane) takes it there too.
  const mpr::AffineRays<T> field = sweep.affine_rays(plane.affine_points());
  const T u0 = region.column_to_u<T>(3), v0 = region.row_to_v<T>(9), su = T(1) / 300, sv = T(1) / 19;
  const mpr::Renderer rays_of(plane, sweep, mpr::CameraFrameSampler<mpr::NearestCamera, T>(frames));
  const auto exact = [&](int i, int j) noexcept { return rays_of.ray_at({3 + i, 9 + j}, region); };
  const mpr::RayGrid<T, decltype(exact)> grid{300,
                                              8,
                                              field.origin.value(u0, v0),
                                              mpr::Vec3<T>(su * field.origin.du),
                                              mpr::Vec3<T>(sv * field.origin.dv),
                                              field.direction.value(u0, v0),
                                              mpr::Vec3<T>(su * field.direction.du),
                                              mpr::Vec3<T>(sv * field.direction.dv),
                                              field.origin.rounding(),
                                              field.direction.rounding(),
                                              exact};
  std::vector<mpr::Ray<T>> rays;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 300; ++i) rays.push_back(exact(i, j));
  const auto grid_against_tile = [&](const auto& sampler, bool declines) {
    std::vector<mpr::Color> by_grid(rays.size(), mpr::Color(-1, -1, -1)), by_tile(rays.size());
    if (declines) {
      CHECK_FALSE(sampler.sample_grid(grid, by_grid));
      CHECK(std::all_of(by_grid.begin(), by_grid.end(), [](const mpr::Color& c) { return (c == -1).all(); }));
      return;
    }
    REQUIRE(sampler.sample_grid(grid, by_grid));
    sampler.sample_tile(rays, 300, by_tile);
    int worst = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const mpr::Rgb8 g = mpr::to_rgb8(by_grid[i]), t = mpr::to_rgb8(by_tile[i]);
      worst = std::max({worst, std::abs(g.r - t.r), std::abs(g.g - t.g), std::abs(g.b - t.b)});
    }
    CHECK(worst <= 1);
  };
  grid_against_tile(mpr::CameraFrameSampler<mpr::NearestCamera, T>(frames), false);
  grid_against_tile(mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(frames), false);
  grid_against_tile(mpr::CameraFrameSampler<mpr::CylinderAperture, T>(frames, mpr::CylinderAperture{0.35}), false);
  std::vector<mpr::PinholeCamera<T>> ring;
  for (int c = 0; c < 6; ++c) {
    const T angle = T(0.3) * static_cast<T>(c - 3);
    ring.push_back(mpr::PinholeCamera<T>::look_at(
        mpr::Vec3<T>(12 * std::sin(angle), T(0.4) * static_cast<T>(c % 2), 12 - 12 * std::cos(angle)),
        mpr::Vec3<T>(0, 0, 12), mpr::Vec3<T>(0, -1, 0), T(1), 320, 21));
  }
  const auto ring_frames = std::make_shared<const mpr::CameraFrameSet<T>>(ring, images);
  REQUIRE_FALSE(mpr::CameraFrameSampler<mpr::NearestCamera, T>(ring_frames).planar_array());
  grid_against_tile(mpr::CameraFrameSampler<mpr::NearestCamera, T>(ring_frames), true);
  grid_against_tile(mpr::CameraFrameSampler<mpr::CylinderAperture, T>(ring_frames, mpr::CylinderAperture{3}), true);
  grid_against_tile(mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(ring_frames), false);
}

TEMPLATE_TEST_CASE("far from the world origin the grid paths still give the per-pixel image", "[camera_frame_sampler]",
                   float, double) {
  using T = TestType;
  // The set-up of the test above (3x2 cameras of 320x21, a GLC sweeping across the array),
  // moved as a whole by D: the images stay the same, only the coordinates grow. In float at D =
  // 1000 the renderer's rays carry rounding of 1e-4 units (a tenth of the proof's margin): a row
  // evaluated from the affine grid chose other cameras than the per-pixel path near their
  // boundaries (44 levels apart). At D = 1e5 the rounding is a fifth of a pixel and the rows go
  // through the exact rays (the tile path's image, which the per-pixel path itself no longer
  // matches to one level there).
  auto base = mpr_test::grid_cameras<T>(3, 2, 0.5, 320, 21, 320.0);
  const auto linear = mpr_test::plane_images(base, 12.0);
  const std::vector<mpr::Image<mpr::Rgb8>> images = mpr_test::with_detail(linear, 9, 0, 63, 0);
  for (const double D : {1e3, 1e5}) {
    INFO("moved by " << D);
    const mpr::Vec3<T> off(static_cast<T>(D), static_cast<T>(0.7 * D), static_cast<T>(0.3 * D));
    std::vector<mpr::PinholeCamera<T>> cams;
    for (const auto& c : base) cams.emplace_back(c.K(), c.R(), mpr::Vec3<T>(c.t() - c.R() * off), 320, 21);
    auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(cams, images);
    const mpr::PinholeCamera<T> view(base[0].K(), mpr::Mat3<T>::Identity(),
                                     mpr::Vec3<T>(mpr::Vec3<T>(T(0.05), T(-0.1), 0) - off), 300, 19);
    const mpr::PlanarSurface<T> plane = view.image_plane(T(12));
    const auto d = [&](T u, T v) {
      return mpr::Vec3<T>(plane.point_at({u, v}) - (mpr::Vec3<T>(T(-0.8) + T(1.6) * u, T(-0.4) + T(0.8) * v, 0) + off));
    };
    const mpr::GlcSelector<T> sweep(plane, d(0, 0), d(1, 0), d(0, 1));
    const mpr::Region region(0, 0, 300, 19);
    const auto compare = [&](const auto& sampler) {
      const mpr::Renderer renderer(plane, sweep, sampler);
      mpr::Image<mpr::Rgb8> image(300, 19);
      renderer.render(image.view(), region, mpr::RenderOptions{1});
      std::vector<mpr::Ray<T>> rays;
      for (int y = 0; y < 19; ++y)
        for (int x = 0; x < 300; ++x) rays.push_back(renderer.ray_at({x, y}, region));
      std::vector<mpr::Color> tile(rays.size());
      for (std::size_t t = 0; t < rays.size(); t += 8 * 300) {
        const std::size_t n = std::min<std::size_t>(8 * 300, rays.size() - t);
        sampler.sample_tile(std::span<const mpr::Ray<T>>(rays.data() + t, n), 300,
                            std::span<mpr::Color>(tile.data() + t, n));
      }
      int worst = 0;
      for (int y = 0; y < 19; ++y)
        for (int x = 0; x < 300; ++x) {
          const mpr::Rgb8 p = D < 1e4 ? mpr::to_rgb8(renderer.shade({x, y}, region))
                                      : mpr::to_rgb8(tile[static_cast<std::size_t>(y * 300 + x)]);
          const mpr::Rgb8 b = image(x, y);
          worst = std::max({worst, std::abs(p.r - b.r), std::abs(p.g - b.g), std::abs(p.b - b.b)});
        }
      CHECK(worst <= 1);
    };
    compare(mpr::CameraFrameSampler<mpr::NearestCamera, T>(frames));
    compare(mpr::CameraFrameSampler<mpr::CylinderAperture, T>(frames, mpr::CylinderAperture{0.35}));
    compare(mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(frames));
  }
}

TEMPLATE_TEST_CASE("output at any scale of the cameras' gives the per-pixel image", "[camera_frame_sampler]", float,
                   double) {
  using T = TestType;
  // Rows that step 2 or 3 camera pixels per output pixel (the strided shift-and-add), 0.5, 2/3,
  // 0.75, 1.5 and 2.4 (resampled rows), on a plane parallel to the array; 8-bit frames with fine
  // detail. On the plane z = 10 every camera's shift is a whole pixel (16 per 0.5 apart): there
  // the synthetic aperture's resampled blocks share their weights (`SharedWeightsBatch`).
  auto cams = mpr_test::grid_cameras<T>(3, 2, 0.5, 320, 40, 320.0);
  const auto linear = mpr_test::plane_images(cams, 12.0);
  const auto images = mpr_test::with_detail(linear, 11, 0, 0, 63);
  auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(cams, images);
  for (const T depth : {T(12), T(10)})
    for (const T step : {T(2), T(3), T(0.5), T(2) / 3, T(0.75), T(1.5), T(2.4)}) {
      INFO("camera pixels per output pixel: " << step << ", plane z = " << depth);
      mpr::Mat3<T> K = cams[0].K();
      K(0, 0) /= step;
      K(1, 1) /= step;
      const int w = static_cast<int>(300 / step), h = static_cast<int>(36 / step);
      K(0, 2) = T(0.5) * static_cast<T>(w - 1);
      K(1, 2) = T(0.5) * static_cast<T>(h - 1);
      const mpr::PinholeCamera<T> view(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>(T(0.05), T(-0.1), 0), w, h);
      const mpr::PlanarSurface<T> plane = view.image_plane(depth);
      const mpr::Region region(0, 0, w, h);
      const auto compare = [&](const auto& sampler) {
        const mpr::Renderer renderer(plane, mpr::pinhole_glc(view, plane), sampler);
        mpr::Image<mpr::Rgb8> batch(w, h);
        renderer.render(batch.view(), region, mpr::RenderOptions{2});
        int worst = 0;
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const mpr::Rgb8 p = mpr::to_rgb8(renderer.shade({x, y}, region));
            const mpr::Rgb8 b = batch(x, y);
            worst = std::max({worst, std::abs(p.r - b.r), std::abs(p.g - b.g), std::abs(p.b - b.b)});
          }
        CHECK(worst <= 1);
      };
      compare(mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(frames));
      compare(mpr::CameraFrameSampler<mpr::NearestCamera, T>(frames));
      compare(mpr::CameraFrameSampler<mpr::CylinderAperture, T>(frames, mpr::CylinderAperture{0.6}));
    }
}
