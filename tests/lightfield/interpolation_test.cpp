// A new light-field interpolation written entirely in this file -- a Gaussian-weighted aperture
// -- plugs into CameraFrameSampler, the renderer and the batch path without touching any mpr
// header. It uses only the public toolkit of FrameTable / frame_runs.hpp.
#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield.hpp>
#include <mpr/mpr.hpp>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

namespace {

// Every camera within 3 sigma of the ray line, weighted by exp(-d^2 / (2 sigma^2)).
struct GaussianAperture {
  double sigma = 1.0;

  void validate() const {
    if (!(sigma > 0) || !std::isfinite(sigma)) throw mpr::argument_error("sigma", "must be positive and finite");
  }
  template <class T>
  [[nodiscard]] float weight(T d2) const noexcept {
    return d2 < T(9 * sigma * sigma) ? static_cast<float>(std::exp(-static_cast<double>(d2) / (2 * sigma * sigma))) : 0;
  }
  template <class T, class Px>
  [[nodiscard]] mpr::Color sample(const mpr::FrameTable<T, Px>& table, const mpr::Ray<T>& ray) const noexcept {
    const mpr::Vec3<T> X = table.point_of(ray);
    const T inv = T(1) / ray.direction.squaredNorm();
    float acc[3] = {0, 0, 0}, total = 0;
    for (const auto& c : table.cameras())
      table.add_seen(c, X, weight(mpr::line_distance2(c.centre, ray.origin, ray.direction, inv)), acc, total);
    return table.finish(acc, total);
  }
  // Batch path: cameras outer, each adding its weighted pixels to the whole run.
  template <class T, class Px>
  void sample_rays(const mpr::FrameTable<T, Px>& table, std::span<const mpr::Ray<T>> rays,
                   std::span<mpr::Color> out) const noexcept {
    std::vector<mpr::Vec3<T>> points(rays.size());
    std::vector<float> acc(3 * rays.size(), 0.0f), total(rays.size(), 0.0f), w(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) points[i] = table.point_of(rays[i]);
    for (const auto& c : table.cameras()) {
      for (std::size_t i = 0; i < rays.size(); ++i)
        w[i] = weight(
            mpr::line_distance2(c.centre, rays[i].origin, rays[i].direction, T(1) / rays[i].direction.squaredNorm()));
      table.add_per_ray(c, points.data(), rays.size(), acc.data(), total.data(), w.data());
    }
    for (std::size_t i = 0; i < rays.size(); ++i) out[i] = table.finish(acc.data() + 3 * i, total[i]);
  }
};

} // namespace

TEST_CASE("an interpolation defined in a test models the interpolation concepts", "[interpolation]") {
  STATIC_REQUIRE(mpr::FrameInterpolation<GaussianAperture, float, mpr::Rgb8>);
  STATIC_REQUIRE(mpr::BatchFrameInterpolation<GaussianAperture, double, mpr::Color>);
  STATIC_REQUIRE_FALSE(mpr::TileFrameInterpolation<GaussianAperture, double, mpr::Color>);
  using S = mpr::CameraFrameSampler<GaussianAperture, double, mpr::Color>;
  STATIC_REQUIRE(mpr::RaySampler<S>);
  STATIC_REQUIRE(mpr::BatchRaySampler<S>);
  STATIC_REQUIRE_FALSE(mpr::TileRaySampler<S>); // no tile path: the renderer takes rows
  STATIC_REQUIRE(mpr::TileRaySampler<mpr::CameraFrameSampler<mpr::NearestCamera, double, mpr::Color>>);
  STATIC_REQUIRE_FALSE(mpr::FrameInterpolation<int, float, mpr::Rgb8>);
  STATIC_REQUIRE_FALSE(mpr::FrameInterpolation<mpr::CheckerboardPlane<float>, float, mpr::Rgb8>);
}

TEMPLATE_TEST_CASE("a test-defined Gaussian aperture renders the exact weighted average", "[interpolation]", float,
                   double) {
  using T = TestType;
  // 4 x 3 cameras, each showing one constant colour drawn at random (not linear in the index).
  const auto cameras = mpr_test::grid_cameras<T>(4, 3, 1.0, 16, 12, 16.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<mpr::Color> colours;
  std::vector<mpr::Image<mpr::Color>> images;
  for (const auto& c : cameras) {
    colours.emplace_back(u(rng), u(rng), u(rng));
    images.emplace_back(c.width(), c.height(), colours.back());
  }
  const auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(cameras, std::move(images));
  const double sigma = 0.8;
  mpr::FrameSamplerConfig<T> config;
  config.depth = T(10); // every camera sees the points the test rays ask for
  const mpr::CameraFrameSampler<GaussianAperture, T, mpr::Color> sampler(frames, GaussianAperture{sigma}, config);
  CHECK_THROWS_AS((mpr::CameraFrameSampler<GaussianAperture, T, mpr::Color>(frames, GaussianAperture{0})),
                  mpr::argument_error);

  // A view through the array: a fronto-parallel image plane at z = 0 covering it, rays along +z
  // tilted slightly so that every ray has its own set of distances.
  const auto plane = mpr::PlanarSurface<T>::centred({T(0.1), T(-0.05), 0}, {T(3.5), 0, 0}, {0, T(2.5), 0});
  const mpr::GlcSelector<T> selector(plane, {T(-0.1), T(-0.05), 1}, {T(0.1), T(-0.05), 1}, {T(-0.1), T(0.08), 1});
  const mpr::Renderer renderer(plane, selector, sampler);
  const int W = 24, H = 16;
  mpr::Image<mpr::Color> batch(W, H), single(W, H);
  renderer.render(batch.view(), mpr::Region(0, 0, W, H), mpr::RenderOptions{2});
  const mpr::Region region(0, 0, W, H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      single(x, y) = renderer.shade({x, y}, region);
      // Independent expectation in long double: sum_i w_i c_i / sum_i w_i.
      const mpr::Ray<T> ray = renderer.ray_at({x, y}, region);
      long double acc[3] = {0, 0, 0}, total = 0;
      for (std::size_t i = 0; i < cameras.size(); ++i) {
        const mpr::Vec3<long double> o = ray.origin.template cast<long double>();
        const mpr::Vec3<long double> d = ray.direction.template cast<long double>();
        const mpr::Vec3<long double> e = cameras[i].centre().template cast<long double>() - o;
        const long double d2 = e.cross(d).squaredNorm() / d.squaredNorm();
        if (d2 >= 9 * sigma * sigma) continue;
        const long double w = std::exp(-d2 / (2 * sigma * sigma));
        for (int k = 0; k < 3; ++k) acc[k] += w * colours[i][k];
        total += w;
      }
      REQUIRE(total > 0);
      for (int k = 0; k < 3; ++k) {
        CHECK(std::abs(single(x, y)[k] - static_cast<float>(acc[k] / total)) < 2e-5f);
        CHECK(std::abs(batch(x, y)[k] - single(x, y)[k]) < 2e-6f);
      }
    }
}
