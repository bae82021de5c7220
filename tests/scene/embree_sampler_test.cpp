// Built and run only when Embree 3 was found at configure time (tests/CMakeLists.txt defines
// MPR_HAVE_EMBREE and links it); otherwise this file compiles to nothing.
#if MPR_HAVE_EMBREE
#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>
#include <mpr/scene/embree_sampler.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <memory>
#include <span>
#include <vector>

namespace {

std::vector<mpr::Ray<float>> classroom_rays(int w, int h) {
  const auto camera = mpr::PinholeCamera<float>::look_at(
      mpr::Vec3<float>(0.3f, 2.2f, 3.5f), mpr::Vec3<float>(0, 1.3f, -8), mpr::Vec3<float>(0, 1, 0), 1.0f, w, h);
  std::vector<mpr::Ray<float>> rays;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) rays.push_back(camera.ray_through(mpr::Vec2<float>(x + 0.5f, y + 0.5f)));
  return rays;
}

} // namespace

TEST_CASE("Embree policy: the same depths and colours as mpr's ray cast, to rounding", "[scene][embree]") {
  using Embree = mpr::SceneSampler<mpr::scene::Scene<float>, mpr::EmbreeRayCast>;
  using EmbreeDepth = mpr::SceneSampler<mpr::scene::Scene<float>, mpr::EmbreeRayCast, mpr::HitDepth>;
  using Mpr = mpr::SceneSampler<mpr::scene::Scene<float>, mpr::RayCast>;
  using MprDepth = mpr::SceneSampler<mpr::scene::Scene<float>, mpr::RayCast, mpr::HitDepth>;
  STATIC_REQUIRE(mpr::TileRaySampler<Embree>);
  STATIC_REQUIRE(mpr::BatchRaySampler<EmbreeDepth>);
  STATIC_REQUIRE_FALSE(mpr::RaySampler<mpr::EmbreeRayCast>); // the tag is no sampler
  const auto scene = std::make_shared<const mpr::scene::Scene<float>>(mpr::scene::classroom<float>());
  const Embree embree(scene);
  const EmbreeDepth embree_depth(scene);
  const Mpr ours(scene);
  const MprDepth ours_depth(scene);
  const int w = 120, h = 90;
  const auto rays = classroom_rays(w, h);
  std::vector<mpr::Color> c(rays.size());
  std::vector<float> d(rays.size()), d_rays(rays.size());
  embree.sample_tile(rays, w, std::span<mpr::Color>(c));
  embree_depth.sample_tile(rays, w, std::span<float>(d));
  embree_depth.sample_rays(rays, std::span<float>(d_rays));
  int hit_miss = 0, far_depth = 0, far_colour = 0, hits = 0, packet_vs_single = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const float want = ours_depth.sample(rays[i]);
    const float one = embree_depth.sample(rays[i]);
    packet_vs_single += !(one == d[i] || std::abs(one - d[i]) <= 1e-5f * std::abs(one));
    packet_vs_single += !(d_rays[i] == d[i] || std::abs(d_rays[i] - d[i]) <= 1e-5f * std::abs(d[i]));
    if (std::isinf(want) != std::isinf(d[i])) {
      ++hit_miss;
      continue;
    }
    if (std::isinf(want)) continue;
    ++hits;
    far_depth += std::abs(want - d[i]) > 1e-4f * want;
    far_colour += (ours.sample(rays[i]) - c[i]).abs().maxCoeff() > 0.02f;
  }
  INFO(hits << " hits; " << hit_miss << " hit/miss disagreements, " << far_depth << " depths and " << far_colour
            << " colours off; " << packet_vs_single << " packet/single differences");
  CHECK(hits > 7000);
  CHECK(hit_miss <= 2);
  CHECK(far_depth <= 10); // a different triangle at a silhouette, at most a few pixels
  CHECK(far_colour <= 10);
  CHECK(packet_vs_single == 0);
}

TEST_CASE("Embree policy: empty scenes, degenerate rays and bad arguments", "[scene][embree][bad_input]") {
  using Embree = mpr::SceneSampler<mpr::scene::Scene<float>, mpr::EmbreeRayCast>;
  using EmbreeDepth = mpr::SceneSampler<mpr::scene::Scene<float>, mpr::EmbreeRayCast, mpr::HitDepth>;
  CHECK_THROWS_AS(Embree(std::shared_ptr<const mpr::scene::Scene<float>>()), mpr::argument_error);
  const mpr::scene::Scene<float> empty;
  const Embree none(empty);
  const EmbreeDepth none_depth(empty);
  const mpr::Ray<float> ray{mpr::Vec3<float>(0, 0, 0), mpr::Vec3<float>(0, 0, -1)};
  CHECK((none.sample(ray) == empty.background()).all());
  CHECK(std::isinf(none_depth.sample(ray)));
  const EmbreeDepth depth(mpr::scene::classroom<float>(), RTC_BUILD_QUALITY_MEDIUM);
  CHECK(std::isinf(depth.sample({mpr::Vec3<float>(0, 1, 0), mpr::Vec3<float>(0, 0, 0)}))); // zero direction
  CHECK(std::isfinite(depth.sample({mpr::Vec3<float>(0, 1.5f, 0), mpr::Vec3<float>(0, 0, -1)})));
  std::vector<mpr::Ray<float>> few(3, mpr::Ray<float>{mpr::Vec3<float>(0, 1.5f, 0), mpr::Vec3<float>(0, 0, -1)});
  std::vector<float> out(3);
  depth.sample_tile(few, 3, std::span<float>(out));
  CHECK(out[2] == depth.sample(few[2]));
}
#endif
