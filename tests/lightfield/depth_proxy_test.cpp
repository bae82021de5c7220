#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield.hpp>
#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <utility>
#include <vector>

namespace {

// 3 x 3 cameras (spacing 1, 40 x 30 pixels, focal 30) on z = 0 looking at the textured plane
// z = 5, with exact depth maps (camera z of the plane: 5 everywhere).
template <class T>
std::shared_ptr<const mpr::CameraFrameSet<T, mpr::Color>> plane_set(float depth = 5.0f) {
  const auto cams = mpr_test::grid_cameras<T>(3, 3, 1.0, 40, 30, 30.0);
  std::vector<mpr::Image<float>> maps(cams.size(), mpr::Image<float>(40, 30, depth));
  return std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(
      mpr::CameraFrameSet<T, mpr::Color>(cams, mpr_test::plane_images(cams, 5.0)).with_depth(std::move(maps)));
}

// Cameras at x = -0.5, 0 and 0.5 (40 x 30 pixels, focal 30) see the textured plane z = 5; the
// third one's image is red and its depth map says `third_depth` everywhere (the others: 5).
template <class T>
std::shared_ptr<const mpr::CameraFrameSet<T, mpr::Color>> red_third_set(float third_depth) {
  const auto cams = mpr_test::grid_cameras<T>(3, 1, 0.5, 40, 30, 30.0);
  std::vector<mpr::Image<mpr::Color>> images = mpr_test::plane_images(cams, 5.0);
  images[2] = mpr::Image<mpr::Color>(40, 30, mpr::Color(1, 0, 0));
  std::vector<mpr::Image<float>> maps(3, mpr::Image<float>(40, 30, 5.0f));
  maps[2] = mpr::Image<float>(40, 30, third_depth);
  return std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(
      mpr::CameraFrameSet<T, mpr::Color>(cams, std::move(images)).with_depth(std::move(maps)));
}

// An object on an empty backdrop: the 3 x 3 cameras of `plane_set` with maps that show the
// square |x|, |y| <= 0.5 of the plane z = 5 and nothing (+inf) around it, while their images show
// the plane's texture everywhere (a backdrop the maps call empty, so that a wrong answer shows).
template <class T>
std::shared_ptr<const mpr::CameraFrameSet<T, mpr::Color>> square_set() {
  const auto cams = mpr_test::grid_cameras<T>(3, 3, 1.0, 40, 30, 30.0);
  std::vector<mpr::Image<float>> maps;
  for (const auto& c : cams) {
    mpr::Image<float> m(40, 30, std::numeric_limits<float>::infinity());
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 40; ++x) {
        const mpr::Vec3<T> p = c.ray_through(mpr::Vec2<T>(static_cast<T>(x), static_cast<T>(y))).at(T(5));
        if (std::abs(static_cast<double>(p.x())) <= 0.5 && std::abs(static_cast<double>(p.y())) <= 0.5) m(x, y) = 5.0f;
      }
    maps.push_back(std::move(m));
  }
  return std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(
      mpr::CameraFrameSet<T, mpr::Color>(cams, mpr_test::plane_images(cams, 5.0)).with_depth(std::move(maps)));
}

} // namespace

TEST_CASE("DepthProxy is a frame interpolation with a batch path", "[depth_proxy]") {
  STATIC_REQUIRE(mpr::FrameInterpolation<mpr::DepthProxy, float, mpr::Rgb8>);
  STATIC_REQUIRE(mpr::FrameInterpolation<mpr::DepthProxy, double, mpr::Color>);
  STATIC_REQUIRE(mpr::BatchFrameInterpolation<mpr::DepthProxy, float, mpr::Rgb8>);
  STATIC_REQUIRE(mpr::BatchFrameInterpolation<mpr::DepthProxy, double, mpr::Color>);
  STATIC_REQUIRE_FALSE(mpr::TileFrameInterpolation<mpr::DepthProxy, double, mpr::Rgb8>);
  STATIC_REQUIRE(mpr::RaySampler<mpr::CameraFrameSampler<mpr::DepthProxy, float>>);
  STATIC_REQUIRE(mpr::BatchRaySampler<mpr::CameraFrameSampler<mpr::DepthProxy, float>>);
  STATIC_REQUIRE_FALSE(mpr::TileRaySampler<mpr::CameraFrameSampler<mpr::DepthProxy, float>>);
  STATIC_REQUIRE(mpr::DepthProxy::uses_depth_maps);
}

TEMPLATE_TEST_CASE("DepthProxy refuses bad parameters and frames without depth maps", "[depth_proxy]", float, double) {
  using T = TestType;
  const auto frames = plane_set<T>();
  using Sampler = mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color>;
  CHECK_NOTHROW(Sampler(frames, mpr::DepthProxy{}));
  const auto refuse = [&](mpr::DepthProxy p, const char* parameter) {
    try {
      (void)Sampler(frames, p);
      FAIL("no exception for " << parameter);
    } catch (const mpr::argument_error& e) {
      CHECK(e.parameter() == parameter);
    }
  };
  refuse({0.0}, "radius");
  refuse({std::nan("")}, "radius");
  refuse({1.0, 0}, "k");
  refuse({1.0, 4, 0.0}, "tolerance");
  refuse({1.0, 4, 1.0}, "tolerance");
  refuse({1.0, 4, 0.01, 0}, "march_cameras");
  for (const double v : {0.0, 1.0, std::nan("")}) {
    mpr::DepthProxy p;
    p.visibility_tolerance = v;
    refuse(p, "visibility_tolerance");
  }
  const auto cams = mpr_test::grid_cameras<T>(2, 1, 1.0, 8, 6, 8.0);
  const auto bare = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(
      cams, mpr_test::plane_images(cams, 5.0), std::vector<std::string>{"left", "right"});
  CHECK_THROWS_WITH(Sampler(bare), Catch::Contains("depth maps") && Catch::Contains("left"));
}

TEMPLATE_TEST_CASE("DepthProxy finds the surface from the depth maps whatever the focal depth", "[depth_proxy]", float,
                   double) {
  using T = TestType;
  const auto frames = plane_set<T>();
  // The configured focal plane (z = 2) is wrong: the cylinder aperture blends the wrong pixels,
  // the depth proxy finds z = 5 and reads the texture there.
  mpr::FrameSamplerConfig<T> config;
  config.depth = T(2);
  const auto table = std::make_shared<const mpr::FrameTable<T, mpr::Color>>(frames, config);
  const auto proxy = mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color>::sharing(table, mpr::DepthProxy{2.0});
  const auto cylinder =
      mpr::CameraFrameSampler<mpr::CylinderAperture, T, mpr::Color>::sharing(table, mpr::CylinderAperture{1.5});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.8, 0.8), slope(-0.25, 0.25);
  double worst_proxy = 0, worst_cylinder = 0, worst_depth = 0;
  for (int n = 0; n < 200; ++n) {
    const mpr::Ray<T> ray{mpr::Vec3<T>(static_cast<T>(u(rng)), static_cast<T>(u(rng)), T(0)),
                          mpr::Vec3<T>(static_cast<T>(slope(rng)), static_cast<T>(slope(rng)), T(1))};
    const std::optional<T> t = proxy.interpolation().surface(proxy.table(), ray);
    REQUIRE(t.has_value());
    const mpr::Vec3<T> hit = ray.at(*t);
    worst_depth = std::max(worst_depth, std::abs(static_cast<double>(hit.z()) - 5.0));
    const mpr::Color truth = mpr_test::plane_texture(static_cast<double>(hit.x()), static_cast<double>(hit.y()));
    worst_proxy = std::max(worst_proxy, static_cast<double>((proxy.sample(ray) - truth).abs().maxCoeff()));
    worst_cylinder = std::max(worst_cylinder, static_cast<double>((cylinder.sample(ray) - truth).abs().maxCoeff()));
  }
  INFO("worst depth error " << worst_depth << ", colour error proxy " << worst_proxy << ", cylinder "
                            << worst_cylinder);
  CHECK(worst_depth < 1e-3);
  CHECK(worst_proxy < 2e-3); // the texture is linear: bilinear reconstruction is exact
  CHECK(worst_cylinder > 10 * worst_proxy);
  // A ray running back toward the cameras finds nothing (the walk goes along the ray, away from
  // the cameras), on the line or the half-line (which misses the maps' box altogether).
  const mpr::Ray<T> away{mpr::Vec3<T>(0, 0, 0), mpr::Vec3<T>(0, 0, -1)};
  CHECK_FALSE(proxy.interpolation().surface(proxy.table(), away).has_value());
  mpr::DepthProxy half{2.0};
  half.whole_line = false;
  CHECK_FALSE(half.surface(proxy.table(), away).has_value());
  // A ray that starts beyond the surface finds it behind its origin (a focal plane inside the
  // scene), or nothing on its half-line.
  const mpr::Ray<T> beyond{mpr::Vec3<T>(T(0.2), T(0.1), T(8)), mpr::Vec3<T>(0, 0, 1)};
  const std::optional<T> back = proxy.interpolation().surface(proxy.table(), beyond);
  REQUIRE(back.has_value());
  CHECK(std::abs(static_cast<double>(*back) + 3.0) < 1e-3);
  CHECK_FALSE(half.surface(proxy.table(), beyond).has_value());
}

TEMPLATE_TEST_CASE("DepthProxy on a tilted plane: the crossing in closed form", "[depth_proxy]", float, double) {
  using T = TestType;
  // The 3 x 3 cameras of `plane_set` see the plane z = 5 + 0.3 x - 0.2 y (depth 3.3 to 6.7 over
  // the images, about 0.05 per pixel): exact depth maps that vary inside every pixel, so a
  // lookup that reads the nearest pixel instead of interpolating misses the crossing by up to
  // 0.025, and a ray's crossing t* = (z0 + a ox + b oy - oz) / (dz - a dx - b dy) is the oracle.
  const mpr_test::TiltedPlane plane;
  const auto cams = mpr_test::grid_cameras<T>(3, 3, 1.0, 40, 30, 30.0);
  std::vector<mpr::Image<float>> maps;
  auto images = mpr_test::tilted_plane_images(cams, plane, &maps);
  const auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(
      mpr::CameraFrameSet<T, mpr::Color>(cams, std::move(images)).with_depth(std::move(maps)));
  mpr::FrameSamplerConfig<T> config;
  config.depth = T(2); // a wrong focal plane: only the maps lead to the surface
  const mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color> proxy(frames, mpr::DepthProxy{2.0}, config);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.8, 0.8), slope(-0.25, 0.25);
  std::vector<mpr::Ray<T>> rays;
  for (int n = 0; n < 64; ++n)
    rays.push_back(mpr::Ray<T>{mpr::Vec3<T>(static_cast<T>(u(rng)), static_cast<T>(u(rng)), T(0)),
                               mpr::Vec3<T>(static_cast<T>(slope(rng)), static_cast<T>(slope(rng)), T(1))});
  std::vector<mpr::Color> batch(rays.size());
  proxy.sample_rays(rays, batch);
  std::vector<std::optional<T>> batch_t(rays.size()); // sixteen-lane walks (float, x86 with Highway)
  proxy.interpolation().surface_rays(proxy.table(), std::span<const mpr::Ray<T>>(rays),
                                     std::span<std::optional<T>>(batch_t));
  double worst_t = 0, worst_batch_t = 0, worst_colour = 0, worst_batch = 0, deepest = 0, shallowest = 1e9;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const mpr::Vec3<double> o = rays[i].origin.template cast<double>(), d = rays[i].direction.template cast<double>();
    const double t_exact = plane.hit_t(o, d);
    const mpr::Vec3<double> x = o + t_exact * d;
    deepest = std::max(deepest, x.z());
    shallowest = std::min(shallowest, x.z());
    const std::optional<T> t = proxy.interpolation().surface(proxy.table(), rays[i]);
    REQUIRE(t.has_value());
    worst_t = std::max(worst_t, std::abs(static_cast<double>(*t) - t_exact));
    REQUIRE(batch_t[i].has_value());
    worst_batch_t = std::max(worst_batch_t, std::abs(static_cast<double>(*batch_t[i]) - t_exact));
    const mpr::Color truth = mpr_test::plane_texture(x.x(), x.y());
    worst_colour = std::max(worst_colour, static_cast<double>((proxy.sample(rays[i]) - truth).abs().maxCoeff()));
    worst_batch = std::max(worst_batch, static_cast<double>((batch[i] - truth).abs().maxCoeff()));
  }
  INFO("worst |t - t*| per ray " << worst_t << ", batch " << worst_batch_t << "; colour error per ray " << worst_colour
                                 << ", batch " << worst_batch);
  CHECK(deepest - shallowest > 0.3); // the rays meet the plane at depths that differ
  CHECK(worst_t < 1e-3);
  CHECK(worst_batch_t < 1e-3);
  CHECK(worst_colour < 1e-4);
  CHECK(worst_batch < 1e-4);
}

TEMPLATE_TEST_CASE("DepthProxy blends only the cameras whose depth maps see the point", "[depth_proxy]", float,
                   double) {
  using T = TestType;
  // The third camera's map claims an occluder at z = 2 (`red_third_set`). Rays nearer the other
  // two find z = 5 from their maps, and the third camera, which would see the point only behind
  // its occluder, must not contribute.
  const mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color> proxy(red_third_set<T>(2.0f), mpr::DepthProxy{2.0, 4});
  for (const double x : {-0.5, -0.3, 0.0, 0.2}) {
    const mpr::Ray<T> ray{mpr::Vec3<T>(static_cast<T>(x), 0, 0), mpr::Vec3<T>(0, T(0.05), 1)};
    const std::optional<T> t = proxy.interpolation().surface(proxy.table(), ray);
    REQUIRE(t.has_value());
    const mpr::Vec3<T> hit = ray.at(*t);
    const mpr::Color c = proxy.sample(ray);
    INFO("ray from x = " << x);
    CHECK(std::abs(static_cast<double>(hit.z()) - 5.0) < 1e-3);
    CHECK((c - mpr_test::plane_texture(static_cast<double>(hit.x()), static_cast<double>(hit.y()))).abs().maxCoeff() <
          2e-3f);
  }
}

TEMPLATE_TEST_CASE("DepthProxy's visibility test forgives the maps' error by its own tolerance", "[depth_proxy]", float,
                   double) {
  using T = TestType;
  // The third camera's map is 2% nearer than the plane (an estimated map's error, not an
  // occluder; `red_third_set`). The surface search (tolerance 1%) runs in the middle camera and
  // finds z = 5; the blend counts the third camera as seeing the point with the default
  // visibility tolerance (3%), and as occluded with 1%: the red shows only in the first case,
  // per ray and in the batch path alike.
  const auto frames = red_third_set<T>(4.9f);
  mpr::DepthProxy strict{2.0, 4};
  strict.visibility_tolerance = 0.01;
  REQUIRE(mpr::DepthProxy{}.visibility_tolerance == 0.03);
  const mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color> loose(frames, mpr::DepthProxy{2.0, 4}),
      occluded(frames, strict);
  std::vector<mpr::Ray<T>> rays;
  for (const double x : {-0.2, -0.1, 0.1, 0.2}) // off the cameras' centres, which would take all the weight
    rays.push_back(mpr::Ray<T>{mpr::Vec3<T>(static_cast<T>(x), 0, 0), mpr::Vec3<T>(0, T(0.05), 1)});
  std::vector<mpr::Color> loose_batch(rays.size()), occluded_batch(rays.size());
  loose.sample_rays(rays, loose_batch);
  occluded.sample_rays(rays, occluded_batch);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const std::optional<T> t = loose.interpolation().surface(loose.table(), rays[i]);
    REQUIRE(t.has_value());
    const mpr::Vec3<T> hit = rays[i].at(*t);
    INFO("ray from x = " << rays[i].origin.x());
    CHECK(std::abs(static_cast<double>(hit.z()) - 5.0) < 1e-3);
    const mpr::Color truth = mpr_test::plane_texture(static_cast<double>(hit.x()), static_cast<double>(hit.y()));
    for (const mpr::Color& c : {occluded.sample(rays[i]), occluded_batch[i]})
      CHECK((c - truth).abs().maxCoeff() < 2e-3f);
    for (const mpr::Color& c : {loose.sample(rays[i]), loose_batch[i]}) {
      CHECK(c.x() - truth.x() > 0.02f); // the red camera's share
      CHECK((c - loose.sample(rays[i])).abs().maxCoeff() < 1e-5f);
    }
  }
}

TEMPLATE_TEST_CASE("DepthProxy: a ray that runs to its vanishing point where the maps show nothing is background",
                   "[depth_proxy]", float, double) {
  using T = TestType;
  // The cameras' images show the plane z = 5, but their maps say they saw nothing (+inf): sky.
  const auto frames = plane_set<T>(std::numeric_limits<float>::infinity());
  mpr::FrameSamplerConfig<T> config;
  config.depth = T(5);
  config.background = mpr::Color(0.1f, 0.2f, 0.3f);
  const auto table = std::make_shared<const mpr::FrameTable<T, mpr::Color>>(frames, config);
  const auto proxy = mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color>::sharing(table, mpr::DepthProxy{2.0});
  // 27 degrees off the axis: its vanishing point lies inside the cameras' images (half field of
  // view 34 degrees), where the maps are +inf: the ray escapes, the background answers.
  const mpr::Ray<T> up{mpr::Vec3<T>(T(0.1), T(0.2), 0), mpr::Vec3<T>(T(0.5), 0, 1)};
  CHECK((proxy.sample(up) - config.background).abs().maxCoeff() < 1e-6f);
  CHECK_FALSE(proxy.interpolation().surface(proxy.table(), up).has_value());
  // 35 degrees: its vanishing point lies outside every image, but the maps show no surface at
  // all (their box is empty), so none lies on this ray either: background too.
  const mpr::Ray<T> side{mpr::Vec3<T>(T(0.1), T(0.2), 0), mpr::Vec3<T>(T(0.7), 0, 1)};
  CHECK((proxy.sample(side) - config.background).abs().maxCoeff() < 1e-6f);
  CHECK_FALSE(proxy.interpolation().surface(proxy.table(), side).has_value());
}

TEMPLATE_TEST_CASE("DepthProxy: a ray seen free through everything the maps show is background", "[depth_proxy]", float,
                   double) {
  using T = TestType;
  const auto frames = square_set<T>(); // the square |x|, |y| <= 0.5 of z = 5 on an empty backdrop
  mpr::FrameSamplerConfig<T> config;
  config.depth = T(5);
  config.background = mpr::Color(0.1f, 0.2f, 0.3f);
  const auto table = std::make_shared<const mpr::FrameTable<T, mpr::Color>>(frames, config);
  // 39 degrees off the axis (the cameras see 34 degrees to each side): its vanishing point lies
  // outside every image, so only the walks through the box of the square's points (z within
  // 1/3 of 5) tell that it passes beside the square: at z = 5 it is at x = 0.7. Before that rule
  // it took the cameras' colour at its focal point, the backdrop's texture there.
  const mpr::Ray<T> beside{mpr::Vec3<T>(T(-3.3), T(0.1), 0), mpr::Vec3<T>(T(0.8), 0, 1)};
  // Far beside the square it misses the box altogether; through the square it finds it.
  const mpr::Ray<T> outside{mpr::Vec3<T>(T(-2), T(0.1), 0), mpr::Vec3<T>(T(0.8), 0, 1)};
  const mpr::Ray<T> through{mpr::Vec3<T>(T(-3.8), T(0.1), 0), mpr::Vec3<T>(T(0.8), 0, 1)};
  for (const bool whole_line : {true, false}) {
    mpr::DepthProxy policy{3.0};
    policy.whole_line = whole_line;
    const auto s = mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color>::sharing(table, policy);
    INFO("whole_line " << whole_line);
    const std::vector<mpr::Ray<T>> rays{beside, outside, through};
    std::vector<mpr::Color> batch(rays.size());
    s.sample_rays(rays, batch);
    for (std::size_t i = 0; i < 2; ++i) {
      CHECK_FALSE(s.interpolation().surface(s.table(), rays[i]).has_value());
      CHECK((s.sample(rays[i]) - config.background).abs().maxCoeff() < 1e-6f);
      CHECK((batch[i] - config.background).abs().maxCoeff() < 1e-6f);
    }
    const std::optional<T> t = s.interpolation().surface(s.table(), through);
    REQUIRE(t.has_value());
    CHECK(static_cast<double>(*t) == Approx(5.0).epsilon(1e-3));
    const mpr::Color texture = mpr_test::plane_texture(0.2, 0.1);
    CHECK((s.sample(through) - texture).abs().maxCoeff() < 2e-3f);
    CHECK((batch[2] - texture).abs().maxCoeff() < 2e-3f);
  }
  // Behind the square (z = 5.2, running along x) the cameras see the square in front of the ray:
  // that stretch is occluded, not seen free, so the ray is not background; with no surface found
  // it takes the cameras' colour at its focal point, as without depth.
  const auto s = mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color>::sharing(table, mpr::DepthProxy{3.0});
  const mpr::Ray<T> behind{mpr::Vec3<T>(T(-4), T(0.1), T(5.2)), mpr::Vec3<T>(1, 0, 0)};
  CHECK_FALSE(s.interpolation().surface(s.table(), behind).has_value());
  const mpr::Color c = s.sample(behind);
  CHECK((c - config.background).abs().maxCoeff() > 0.05f);
  CHECK((c - s.table().camera_color(s.table().index().nearest(behind.origin, behind.direction), behind.at(T(5))))
            .abs()
            .maxCoeff() < 1e-6f);
}

TEMPLATE_TEST_CASE("DepthProxy searches what the nearest camera does not see with the next camera", "[depth_proxy]",
                   float, double) {
  using T = TestType;
  // Camera A (40 x 30, focal 30: it sees |y / z| <= 0.5) lies nearest to the ray, camera B (200
  // x 200, 2.5 below it) farther; both show the plane z = 5. The ray meets the plane at
  // y = -2.75, outside A's image but inside B's, and enters A's view only at z = 10, behind the
  // plane. A's walk knows nothing of the ray before z = 10, so B must search from the ray's
  // start: the surface is at t = 5 (it was lost when B went on from where A stopped).
  const std::vector<mpr::PinholeCamera<T>> cams{mpr_test::camera_at<T>(mpr::Vec3<T>(0, 0, 0), 40, 30, 30.0),
                                                mpr_test::camera_at<T>(mpr::Vec3<T>(0, T(-2.5), 0), 200, 200, 30.0)};
  std::vector<mpr::Image<float>> maps{mpr::Image<float>(40, 30, 5.0f), mpr::Image<float>(200, 200, 5.0f)};
  const auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(
      mpr::CameraFrameSet<T, mpr::Color>(cams, mpr_test::plane_images(cams, 5.0)).with_depth(std::move(maps)));
  mpr::FrameSamplerConfig<T> config;
  config.depth = T(2); // the fallback point, off the surface
  const auto table = std::make_shared<const mpr::FrameTable<T, mpr::Color>>(frames, config);
  for (const bool whole_line : {true, false}) {
    mpr::DepthProxy policy{2.0};
    policy.whole_line = whole_line;
    const auto sampler = mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color>::sharing(table, policy);
    const mpr::Ray<T> ray{mpr::Vec3<T>(0, T(-0.5), 0), mpr::Vec3<T>(0, T(-0.45), 1)};
    const std::optional<T> t = sampler.interpolation().surface(sampler.table(), ray);
    INFO("whole_line " << whole_line);
    REQUIRE(t.has_value());
    CHECK(static_cast<double>(*t) == Approx(5.0).epsilon(1e-3));
    CHECK((sampler.sample(ray) - mpr_test::plane_texture(0.0, -2.75)).abs().maxCoeff() < 2e-3f);
  }
}

TEMPLATE_TEST_CASE("DepthProxy finds a surface near a vanishing point at a tight tolerance", "[depth_proxy]", float,
                   double) {
  using T = TestType;
  // A ray 0.15 beside the middle camera's axis and parallel to it: in that camera it moves 4.5
  // pixels per unit of 1 / depth, so a one-pixel step from z = 5 reaches z = 10.6 and 1/256 of
  // it still spans 0.4% of the depth. At a tolerance of 0.1% the crossing is narrowed further
  // (to ray depths within half the tolerance) and found; only that camera lies within the
  // radius.
  const auto frames = plane_set<T>();
  mpr::FrameSamplerConfig<T> config;
  config.depth = T(3); // the fallback point, off the surface
  const auto table = std::make_shared<const mpr::FrameTable<T, mpr::Color>>(frames, config);
  for (const double tolerance : {0.001, 0.0002, 0.01}) {
    mpr::DepthProxy policy;
    policy.radius = 0.5;
    policy.tolerance = tolerance;
    const auto proxy = mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color>::sharing(table, policy);
    for (const T x : {T(0.15), T(-0.3), T(0.1)}) {
      INFO("tolerance " << tolerance << ", ray at x = " << x);
      const mpr::Ray<T> ray{mpr::Vec3<T>(x, T(0.05), 0), mpr::Vec3<T>(0, 0, 1)};
      const std::optional<T> t = proxy.interpolation().surface(proxy.table(), ray);
      REQUIRE(t.has_value());
      CHECK(static_cast<double>(*t) == Approx(5.0).epsilon(tolerance));
    }
  }
}

TEST_CASE("DepthProxy on a rasterized classroom array is far closer to the ray cast than a focal plane",
          "[depth_proxy]") {
  using T = float;
  using Scene = mpr::scene::Scene<T>;
  const auto scene = std::make_shared<const Scene>(mpr::scene::classroom<T>());
  const mpr::PinholeCamera<T> view = mpr::PinholeCamera<T>::look_at(
      mpr::Vec3<T>(0.3f, 2.2f, 4.5f), mpr::Vec3<T>(0, 1.3f, -8), mpr::Vec3<T>(0, 1, 0), T(1.0), 96, 72);
  const mpr::PlanarSurface<T> plane = view.image_plane(T(1));
  const auto render = [&](const auto& sampler) {
    const mpr::Renderer renderer(plane, mpr::pinhole_glc(view, plane), sampler);
    mpr::Image<mpr::Rgb8> image(96, 72);
    renderer.render(image.view(), mpr::Region(0, 0, 96, 72), {2});
    return image;
  };
  const mpr::Image<mpr::Rgb8> truth = render(mpr::SceneSampler<Scene, mpr::RayCast>(scene));
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = 4;
  config.rows = 3;
  config.width = 192;
  config.height = 144;
  config.raster.threads = 2;
  config.depth_maps = true;
  const auto array = mpr::scene::rasterize_virtual_array(*scene, plane, config);
  const T spacing = plane.width_vector().norm() / 4;
  const auto psnr = [&](const auto& sampler) { return mpr::compare_images(render(sampler).view(), truth.view()).psnr; };
  const double cylinder = psnr(mpr::SceneSampler<Scene, mpr::Rasterized<mpr::CylinderAperture>>(
      array, scene->background(), mpr::PixelFilter::bilinear,
      mpr::Rasterized<mpr::CylinderAperture>{mpr::CylinderAperture{spacing}}));
  const double proxy = psnr(mpr::SceneSampler<Scene, mpr::Rasterized<mpr::DepthProxy>>(
      array, scene->background(), mpr::PixelFilter::bilinear, {mpr::DepthProxy{2 * spacing}}));
  // Measured: 17.6 and 21.1 dB (the rest is edge pixels resampled twice: frames, then view).
  std::printf("classroom 4x3 array of 192x144 vs ray cast: cylinder %.1f dB, depth proxy %.1f dB\n", cylinder, proxy);
  CHECK(proxy > cylinder + 3);
}

namespace {

// The classroom as the default 8 x 6 array of 80 x 60 cameras with exact depth (z-buffers),
// looking into the room from the back.
mpr::scene::VirtualArray<float, mpr::Rgb8> classroom_array() {
  using T = float;
  const auto scene = mpr::scene::classroom<T>();
  const mpr::Vec3<T> eye(0, 3.1f, 3.0f), target(0, 1.6f, -8);
  const mpr::Vec3<T> forward = (target - eye).normalized();
  const mpr::Vec3<T> right = forward.cross(mpr::Vec3<T>::UnitY()).normalized();
  const mpr::Vec3<T> down = forward.cross(right);
  mpr::scene::VirtualArrayConfig<T> config;
  config.width = 80;
  config.height = 60;
  config.raster.threads = 2;
  config.depth_maps = true;
  return mpr::scene::rasterize_virtual_array(scene, mpr::PlanarSurface<T>::centred(eye, T(8) * right, T(6) * down),
                                             config);
}

} // namespace

TEST_CASE("DepthProxy finds a held-out camera's own depth from the other cameras of a rasterized array",
          "[depth_proxy]") {
  // The classroom as an 8 x 6 array of 80 x 60 cameras with exact depth; camera 28 is held out
  // and the surface is searched along each of its pixels' rays from the other 47 (whose walks
  // start where each camera first sees the ray, and pass over stretches others saw free). The
  // depth found is the held-out camera's own z-buffer at nearly every pixel, the view's corners
  // included (the floor there lies outside the nearest cameras' images: it was lost before
  // walks that entered the view late stopped moving the search on).
  using T = float;
  const auto array = classroom_array();
  const std::size_t held = 28;
  const auto others = std::make_shared<const mpr::CameraFrameSet<T, mpr::Rgb8>>(array.frames.without(held));
  const auto sampler = mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Rgb8>(others, mpr::DepthProxy{2.0});
  const mpr::PinholeCamera<T>& cam = array.frames.camera(held);
  int agree = 0, corners = 0, corners_agree = 0;
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 80; ++x) {
      const mpr::Ray<T> ray = cam.ray_through({x, y});
      const std::optional<T> t = sampler.interpolation().surface(sampler.table(), ray);
      const float exact = array.frames.depth(held)(x, y);
      const bool ok =
          t.has_value() ? std::abs(cam.forward().dot(ray.direction) * *t - exact) <= 0.02f * exact : std::isinf(exact);
      agree += ok;
      if (y >= 50 && (x < 10 || x >= 70)) {
        ++corners;
        corners_agree += ok;
      }
    }
  INFO(agree << " of 4800 pixels, " << corners_agree << " of " << corners << " in the bottom corners");
  CHECK(agree >= 0.93 * 4800);            // measured 4576 (before: 4034); 220 of the 224 others on depth edges
  CHECK(corners_agree >= 0.95 * corners); // measured 200 of 200 (before: 101)
}

TEMPLATE_TEST_CASE("DepthProxy answers alike whether a linear scan or the ball tree finds its cameras", "[depth_proxy]",
                   float, double) {
  using T = TestType;
  // A 9 x 8 array (72 cameras: the ball tree finds the candidates) and the same array without its
  // last column (64: a linear scan). Rays near the middle have the same candidates in both (the
  // dropped column is 4 spacings away, the radius 2.4), so they must get the same depth and
  // colour; each camera's image is tinted by its own colour and k = 30 blends every candidate, so a changed set
  // of candidates changes the colour.
  const auto make = [](int columns) {
    const auto all = mpr_test::grid_cameras<T>(9, 8, 0.25, 40, 30, 30.0);
    std::vector<mpr::PinholeCamera<T>> cams;
    for (std::size_t i = 0; i < all.size(); ++i)
      if (static_cast<int>(i % 9) < columns) cams.push_back(all[i]);
    std::vector<mpr::Image<mpr::Color>> images = mpr_test::plane_images(cams, 5.0);
    for (std::size_t i = 0; i < images.size(); ++i) {
      const int grid = static_cast<int>(i) / columns * 9 + static_cast<int>(i) % columns; // index in the 9 x 8 grid
      const mpr::Color tint = mpr_test::constant_colour(static_cast<std::size_t>(grid));
      for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) images[i](x, y) = (images[i](x, y) + tint).eval();
    }
    std::vector<mpr::Image<float>> maps(cams.size(), mpr::Image<float>(40, 30, 5.0f));
    return std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(
        mpr::CameraFrameSet<T, mpr::Color>(cams, std::move(images)).with_depth(std::move(maps)));
  };
  const mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color> tree(make(9), mpr::DepthProxy{0.6, 30});
  const mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color> scan(make(8), mpr::DepthProxy{0.6, 30});
  REQUIRE(tree.frames().size() == 72);
  REQUIRE(scan.frames().size() == 64);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.2, 0.2), slope(-0.03, 0.03);
  for (int n = 0; n < 100; ++n) {
    // Around the middle of the 8-column block (x = -0.125 in the 9-column grid's frame).
    const mpr::Ray<T> ray{mpr::Vec3<T>(static_cast<T>(u(rng) - 0.125), static_cast<T>(u(rng)), T(0)),
                          mpr::Vec3<T>(static_cast<T>(slope(rng)), static_cast<T>(slope(rng)), T(1))};
    const std::optional<T> a = tree.interpolation().surface(tree.table(), ray);
    const std::optional<T> b = scan.interpolation().surface(scan.table(), ray);
    REQUIRE(a.has_value());
    REQUIRE(b.has_value());
    CHECK(std::abs(static_cast<double>(*a - *b)) < 1e-4);
    INFO("ray " << n);
    CHECK((tree.sample(ray) - scan.sample(ray)).abs().maxCoeff() < 1e-4f);
  }
}

namespace {

// The rays of every pixel of `cam`, then rays no camera answers: a zero and a NaN direction, one
// pointing away from the scene (background), one from far outside the array.
template <class T>
std::vector<mpr::Ray<T>> batch_rays(const mpr::PinholeCamera<T>& cam) {
  std::vector<mpr::Ray<T>> rays;
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) rays.push_back(cam.ray_through({x, y}));
  const mpr::Vec3<T> o = cam.centre();
  rays.push_back({o, mpr::Vec3<T>::Zero()});
  rays.push_back({o, mpr::Vec3<T>(std::numeric_limits<T>::quiet_NaN(), 0, 1)});
  rays.push_back({o, -cam.forward()});
  rays.push_back({o + mpr::Vec3<T>(T(1e4), 0, 0), cam.forward()});
  return rays;
}

// `sample_rays` over `rays` in spans of 1, 2, ..., 40 rays (partial groups of sixteen), against
// `sample` per ray: equal, or (where the per-ray code may have fused multiply-adds, whose
// rounding moves a decision at a threshold) differing in at most `allowed` of the rays.
template <class Sampler, class T>
void check_batch(const Sampler& sampler, const std::vector<mpr::Ray<T>>& rays) {
  std::vector<mpr::Color> batch(rays.size());
  std::size_t at = 0;
  for (std::size_t length = 1; at < rays.size(); length = length % 40 + 1) {
    const std::size_t n = std::min(length, rays.size() - at);
    sampler.sample_rays(std::span<const mpr::Ray<T>>(rays).subspan(at, n), std::span<mpr::Color>(batch).subspan(at, n));
    at += n;
  }
  std::size_t differ = 0;
  float worst = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const mpr::Color one = sampler.sample(rays[i]);
    REQUIRE(batch[i].allFinite());
    if ((one != batch[i]).any()) {
      ++differ;
      worst = std::max(worst, (one - batch[i]).abs().maxCoeff());
    }
  }
  INFO(differ << " of " << rays.size() << " rays differ, by at most " << worst << "; SIMD level "
              << mpr::detail::simd_level_name());
#if defined(__FMA__) || defined(__FP_FAST_FMAF)
  CHECK(differ <= rays.size() / 500);
#else
  CHECK(differ == 0);
#endif
}

} // namespace

TEST_CASE("DepthProxy's batch path answers as sample(ray) on a rasterized classroom array", "[depth_proxy]") {
  // The classroom as an 8 x 6 array of 80 x 60 cameras with exact depth, camera 28 held out:
  // every pixel's ray (occlusions, depth edges, the floor at the corners, rays that leave the
  // room) through the 47 others, for several k (k + 1 = 8 is the most the sixteen-lane path
  // keeps; k = 8 takes the per-ray path inside `sample_rays`).
  using T = float;
  const auto array = classroom_array();
  const std::size_t held = 28;
  const auto others = std::make_shared<const mpr::CameraFrameSet<T, mpr::Rgb8>>(array.frames.without(held));
  const std::vector<mpr::Ray<T>> rays = batch_rays(array.frames.camera(held));
  mpr::FrameSamplerConfig<T> frames_config;
  frames_config.background = mpr::Color(0.2f, 0.4f, 0.6f);
  const auto table = std::make_shared<const mpr::FrameTable<T, mpr::Rgb8>>(others, frames_config);
  for (const int k : {1, 4, 7, 8}) {
    for (const double radius : {0.6, 2.0}) {
      INFO("k = " << k << ", radius " << radius);
      mpr::DepthProxy proxy{radius, k};
      check_batch(mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Rgb8>::sharing(table, proxy), rays);
    }
  }
  // The rays of a camera of the set itself: they pass through its centre, so its cosine
  // rounds to about 1, above 1 for some rays.
  const auto all = std::make_shared<const mpr::CameraFrameSet<T, mpr::Rgb8>>(array.frames);
  check_batch(mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Rgb8>(all, mpr::DepthProxy{2.0}), rays);
  // The half-line search and the nearest-pixel filter.
  mpr::DepthProxy half{2.0};
  half.whole_line = false;
  check_batch(mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Rgb8>::sharing(table, half), rays);
  frames_config.filter = mpr::PixelFilter::nearest;
  check_batch(mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Rgb8>(others, mpr::DepthProxy{2.0}, frames_config),
              rays);
}

TEMPLATE_TEST_CASE("DepthProxy's batch path answers as sample(ray) on float frames", "[depth_proxy]", float, double) {
  // The 3 x 3 plane set (linear float texels), one map with a step and a hole of +inf, random
  // rays across it; double takes the per-ray path.
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(3, 3, 1.0, 40, 30, 30.0);
  std::vector<mpr::Image<float>> maps(cams.size(), mpr::Image<float>(40, 30, 5.0f));
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      if (x > 25) maps[4](x, y) = 3.0f;
      if (x < 6 && y < 6) maps[4](x, y) = std::numeric_limits<float>::infinity();
    }
  const auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(
      mpr::CameraFrameSet<T, mpr::Color>(cams, mpr_test::plane_images(cams, 5.0)).with_depth(std::move(maps)));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.5, 1.5), slope(-0.3, 0.3);
  std::vector<mpr::Ray<T>> rays;
  for (int n = 0; n < 600; ++n)
    rays.push_back({mpr::Vec3<T>(static_cast<T>(u(rng)), static_cast<T>(u(rng)), T(0)),
                    mpr::Vec3<T>(static_cast<T>(slope(rng)), static_cast<T>(slope(rng)), T(1))});
  check_batch(mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color>(frames, mpr::DepthProxy{1.5}), rays);
}

TEMPLATE_TEST_CASE("DepthProxy's batch path answers as sample(ray) past an object on an empty backdrop",
                   "[depth_proxy]", float, double) {
  // `square_set`: random rays from the camera plane and from inside the maps' box, steep enough
  // that some vanishing points leave the images; they hit the square, pass beside it (seen free
  // through the box), miss the box, or run behind the square (occluded: the focal point). Radii
  // with no camera, one and all nine in reach; the line and the half-line.
  using T = TestType;
  const auto frames = square_set<T>();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3, 3), slope(-0.9, 0.9), inside(4.8, 5.2);
  std::vector<mpr::Ray<T>> rays;
  for (int n = 0; n < 900; ++n) {
    const double z = n % 3 == 0 ? inside(rng) : 0.0;
    rays.push_back({mpr::Vec3<T>(static_cast<T>(u(rng) / (z > 0 ? 3 : 1)), static_cast<T>(u(rng) / (z > 0 ? 3 : 1)),
                                 static_cast<T>(z)),
                    mpr::Vec3<T>(static_cast<T>(slope(rng)), static_cast<T>(slope(rng)), T(n % 5 == 0 ? -1 : 1))});
  }
  mpr::FrameSamplerConfig<T> config;
  config.depth = T(5);
  config.background = mpr::Color(0.1f, 0.2f, 0.3f);
  const auto table = std::make_shared<const mpr::FrameTable<T, mpr::Color>>(frames, config);
  std::size_t background = 0;
  for (const double radius : {0.05, 1.5, 4.0})
    for (const bool whole_line : {true, false}) {
      mpr::DepthProxy p{radius};
      p.whole_line = whole_line;
      const auto sampler = mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color>::sharing(table, p);
      INFO("radius " << radius << ", whole_line " << whole_line);
      check_batch(sampler, rays);
      for (const auto& r : rays) background += (sampler.sample(r) == config.background).all() ? 1 : 0;
    }
  CHECK(background > rays.size()); // the rules that answer the background are exercised
}

TEST_CASE("DepthProxy's batch path answers as sample(ray) with cameras one pixel tall or wide", "[depth_proxy]") {
  // Two cameras of 40 x 1 and two of 1 x 30 pixels side by side, a plane at depth 5: the walks,
  // the lookups and the reads ahead stay inside such images (found by review: the read-ahead
  // clamped to height - 2, below 0 for one row).
  using T = float;
  std::vector<mpr::PinholeCamera<T>> cams;
  std::vector<mpr::Image<float>> maps;
  for (const auto& [w, h] : {std::pair{40, 1}, std::pair{40, 1}, std::pair{1, 30}, std::pair{1, 30}}) {
    mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
    K(0, 0) = K(1, 1) = 30;
    K(0, 2) = 0.5f * static_cast<T>(w - 1);
    K(1, 2) = 0.5f * static_cast<T>(h - 1);
    const T x = 0.1f * static_cast<T>(cams.size());
    cams.emplace_back(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>(-x, 0, 0), w, h);
    maps.emplace_back(w, h, 5.0f);
  }
  const auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(
      mpr::CameraFrameSet<T, mpr::Color>(cams, mpr_test::plane_images(cams, 5.0)).with_depth(std::move(maps)));
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.2, 0.5), slope(-0.1, 0.1);
  std::vector<mpr::Ray<T>> rays;
  for (int n = 0; n < 200; ++n)
    rays.push_back({mpr::Vec3<T>(static_cast<T>(u(rng)), static_cast<T>(0.1 * u(rng)), T(0)),
                    mpr::Vec3<T>(static_cast<T>(slope(rng)), static_cast<T>(slope(rng)), T(1))});
  check_batch(mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color>(frames, mpr::DepthProxy{0.5}), rays);
}

TEMPLATE_TEST_CASE("DepthProxy's k-best weights, hand-worked: (1 - p / p_k) / (p + 1e-6) over the k best",
                   "[depth_proxy][oracle]", float, double) {
  using T = TestType;
  // Five cameras at x = -1, -0.5, 0, 0.5, 1 on z = 0, each showing one constant colour
  // (`constant_colour(i)`), all maps at depth 5. A ray from (0.1, 0, 0) along +z meets the plane at
  // X = (0.1, 0, 5); camera i sees X at the angle p_i = atan(|x_i - 0.1| / 5) from the ray:
  // offsets 1.1, 0.6, 0.1, 0.4, 0.9, so by increasing penalty the cameras are 2, 3, 1, 4, 0.
  const auto cams = mpr_test::grid_cameras<T>(5, 1, 0.5, 40, 30, 30.0);
  std::vector<mpr::Image<float>> maps(5, mpr::Image<float>(40, 30, 5.0f));
  const auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(
      mpr::CameraFrameSet<T, mpr::Color>(cams, mpr_test::constant_images(cams)).with_depth(std::move(maps)));
  const double offset[5] = {1.1, 0.6, 0.1, 0.4, 0.9};
  const int by_penalty[5] = {2, 3, 1, 4, 0};
  const auto p = [&](int i) { return std::atan(offset[i] / 5.0); };
  const mpr::Ray<T> ray{mpr::Vec3<T>(T(0.1), 0, 0), mpr::Vec3<T>(0, 0, 1)};
  for (const int k : {1, 2, 3, 4, 5, 8}) {
    // p_k: the (k+1)-th smallest penalty, or twice the largest (+1e-6) when k >= 5 cameras.
    const double pk = k < 5 ? p(by_penalty[k]) : 2 * p(by_penalty[4]) + 1e-6;
    mpr::Color expected = mpr::Color::Zero();
    double total = 0;
    for (int j = 0; j < std::min(k, 5); ++j) {
      const int i = by_penalty[j];
      const double w = (1 - p(i) / pk) / (p(i) + 1e-6);
      expected += static_cast<float>(w) * mpr_test::constant_colour(static_cast<std::size_t>(i));
      total += w;
    }
    expected /= static_cast<float>(total);
    mpr::DepthProxy rule{2.0, k};
    const mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Color> proxy(frames, rule);
    const mpr::Color single = proxy.sample(ray);
    std::vector<mpr::Ray<T>> rays(21, ray);
    std::vector<mpr::Color> batch(rays.size());
    proxy.sample_rays(rays, batch);
    INFO("k = " << k << ": expected " << expected.transpose() << ", per ray " << single.transpose() << ", batch "
                << batch[20].transpose());
    CHECK((single - expected).abs().maxCoeff() < 2e-4f);
    for (const mpr::Color& c : batch) CHECK((c - expected).abs().maxCoeff() < 2e-4f);
  }
}
