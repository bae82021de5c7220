#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

namespace {

template <class T>
mpr::PinholeCamera<T> classroom_camera(int w, int h) {
  return mpr::PinholeCamera<T>::look_at(mpr::Vec3<T>(0.3, 2.2, 3.5), mpr::Vec3<T>(0, 1.3, -8), mpr::Vec3<T>(0, 1, 0),
                                        T(1.0), w, h);
}

} // namespace

TEMPLATE_TEST_CASE("rasterizer and ray caster agree on a pinhole view of the classroom", "[scene][agreement]", float,
                   double) {
  using T = TestType;
  const int w = 160, h = 120;
  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scene::classroom<T>());
  const auto camera = classroom_camera<T>(w, h);
  const mpr::scene::RasterImage raster = mpr::scene::rasterize(*scene, camera, {.threads = 2});

  const T plane_depth = T(0.5);
  const mpr::PlanarSurface<T> plane = camera.image_plane(plane_depth);
  const mpr::GlcSelector<T> glc = mpr::pinhole_glc(camera, plane);
  const mpr::Region region(0, 0, w, h);
  const mpr::Renderer color_renderer(plane, glc, mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>(scene));
  const mpr::Renderer depth_renderer(plane, glc,
                                     mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast, mpr::HitDepth>(scene));
  mpr::Image<mpr::Rgb8> cast(w, h);
  mpr::Image<float> cast_depth(w, h);
  color_renderer.render(cast.view(), region, {2});
  depth_renderer.render(cast_depth.view(), region, {2});

  int same = 0, depth_ok = 0, both_hit = 0, coverage_mismatch = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (mpr::to_rgb8(raster.color(x, y)) == cast(x, y)) ++same;
      const float zr = raster.depth(x, y);
      const float tc = cast_depth(x, y);
      if (std::isinf(zr) != std::isinf(tc)) {
        ++coverage_mismatch;
        continue;
      }
      if (std::isinf(zr)) continue;
      ++both_hit;
      const double zc = static_cast<double>(tc) + static_cast<double>(plane_depth);
      if (std::abs(zc - zr) <= 1e-4 * zr) ++depth_ok;
    }
  const double total = double(w) * h;
  INFO("identical pixels " << same << " / " << total << ", depth within 1e-4: " << depth_ok << " / " << both_hit
                           << ", coverage mismatches " << coverage_mismatch);
  std::printf("agreement (%s): %d / %.0f identical pixels, depth within 1e-4 at %d / %d, coverage mismatches %d\n",
              sizeof(T) == 4 ? "float" : "double", same, total, depth_ok, both_hit, coverage_mismatch);
  CHECK(same >= 0.995 * total);
  CHECK(both_hit > 0.5 * total);
  // Depth: pixels where both hit the same surface; edges may hit different surfaces.
  CHECK(depth_ok >= 0.995 * both_hit);
  CHECK(coverage_mismatch <= 0.005 * total);
}

TEMPLATE_TEST_CASE("the same surface gives bit-identical colours in the rasterizer and the ray caster",
                   "[scene][agreement]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  // Uniformly coloured, untextured boxes at different depths and a floor: a pixel's colour then
  // depends only on which surface (triangle normal and colour) it hits, and both renderers call
  // the one Scene::shade, so wherever they hit the same surface the colours must be equal
  // exactly, not statistically.
  mpr::scene::Scene<T> scene;
  scene.add(mpr::scene::box<T>(V(-1.5, 0, -6), V(-0.5, 1, -5), mpr::Color(0.8f, 0.2f, 0.1f)));
  scene.add(mpr::scene::box<T>(V(0.2, 0, -8), V(1.4, 1.5, -7), mpr::Color(0.1f, 0.6f, 0.3f)));
  scene.add(mpr::scene::quad<T>(V(-4, 0, -2), V(8, 0, 0), V(0, 0, -10), mpr::Color(0.5f, 0.5f, 0.7f)));
  const auto shared = std::make_shared<const mpr::scene::Scene<T>>(std::move(scene));
  const int w = 80, h = 60;
  const auto camera = classroom_camera<T>(w, h);
  const mpr::scene::RasterImage raster = mpr::scene::rasterize(*shared, camera, {.threads = 2});
  const T plane_depth = T(0.5);
  const mpr::PlanarSurface<T> plane = camera.image_plane(plane_depth);
  const mpr::GlcSelector<T> glc = mpr::pinhole_glc(camera, plane);
  const mpr::Region region(0, 0, w, h);
  mpr::Image<mpr::Color> cast(w, h);
  mpr::Image<float> cast_depth(w, h);
  mpr::Renderer(plane, glc, mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>(shared))
      .render(cast.view(), region, {2});
  mpr::Renderer(plane, glc, mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast, mpr::HitDepth>(shared))
      .render(cast_depth.view(), region, {2});
  int compared = 0, different = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float zr = raster.depth(x, y);
      const double zc = static_cast<double>(cast_depth(x, y)) + static_cast<double>(plane_depth);
      if (std::isinf(zr) || !std::isfinite(zc) || std::abs(zc - zr) > 1e-5 * zr) continue;
      // Same depth, and away from edges between surfaces (all 4 neighbours show the same raster
      // colour), where the two may round to different sides.
      bool interior = x > 0 && y > 0 && x + 1 < w && y + 1 < h;
      for (const auto& [dx, dy] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}})
        interior = interior && (raster.color(x + dx, y + dy) == raster.color(x, y)).all();
      if (!interior) continue;
      ++compared;
      different += (raster.color(x, y) == cast(x, y)).all() ? 0 : 1;
    }
  INFO(compared << " pixels compared");
  CHECK(compared >= 400);
  CHECK(different == 0);
}

TEST_CASE("stateless policies take no bytes; samplers declare what they compute", "[scene][compile]") {
  using SceneF = mpr::scene::Scene<float>;
  using Color = mpr::SceneSampler<SceneF, mpr::RayCast>;
  using Depth = mpr::SceneSampler<SceneF, mpr::RayCast, mpr::HitDepth>;
  STATIC_REQUIRE(std::is_empty_v<mpr::RayCast>);
  STATIC_REQUIRE(std::is_empty_v<mpr::ShadedColor>);
  STATIC_REQUIRE(std::is_empty_v<mpr::HitDepth>);
  // The sampler is one shared pointer to the immutable scene + BVH: the tags add nothing.
  STATIC_REQUIRE(sizeof(Color) == sizeof(std::shared_ptr<const int>));
  STATIC_REQUIRE(sizeof(Depth) == sizeof(std::shared_ptr<const int>));
  STATIC_REQUIRE(mpr::RaySampler<Color>);
  STATIC_REQUIRE(mpr::RaySampler<Depth>);
  STATIC_REQUIRE(mpr::RaySampler<mpr::SceneSampler<mpr::scene::Scene<double>, mpr::RayCast>>);
  STATIC_REQUIRE(std::is_same_v<mpr::sampler_color_t<Color>, mpr::Color>);
  STATIC_REQUIRE(std::is_same_v<mpr::sampler_color_t<Depth>, float>); // depth only: no colour
  STATIC_REQUIRE(std::is_same_v<typename Color::scalar_type, float>);
  // Negative cases: a scene or a BVH alone is not a sampler; the depth sampler cannot fill an
  // 8-bit colour image (float stores as float only), the colour sampler can.
  STATIC_REQUIRE_FALSE(mpr::RaySampler<SceneF>);
  STATIC_REQUIRE_FALSE(mpr::RaySampler<mpr::scene::Bvh<float>>);
  STATIC_REQUIRE_FALSE(mpr::StorableAs<mpr::Rgb8, float>);
  STATIC_REQUIRE(mpr::StorableAs<mpr::Rgb8, mpr::Color>);
  // Renderer composition: float sampler with a double selector does not compose.
  STATIC_REQUIRE_FALSE(mpr::ComposablePolicies<mpr::PlanarSurface<double>, mpr::GlcSelector<double>, Color>);
  STATIC_REQUIRE(mpr::ComposablePolicies<mpr::PlanarSurface<float>, mpr::GlcSelector<float>, Color>);
}

TEST_CASE("untextured triangles never touch a texture; depth sampling never shades", "[scene][compile]") {
  using V = mpr::Vec3<float>;
  // A texture full of NaN: any lookup would poison the colour.
  mpr::Image<mpr::Color> poison(4, 4, mpr::Color(std::nanf(""), std::nanf(""), std::nanf("")));
  auto scene = std::make_shared<mpr::scene::Scene<float>>();
  const int tex = scene->add_texture(mpr::scene::Texture(poison));
  scene->add(mpr::scene::quad<float>(V(-1, -1, 2), V(1, 0, 0), V(0, 2, 0), mpr::Color(0.5f, 0.5f, 0.5f)), "plain");
  auto textured = mpr::scene::quad<float>(V(0, -1, 2), V(1, 0, 0), V(0, 2, 0), mpr::Color(1, 1, 1));
  textured.texture = tex;
  scene->add(textured, "poisoned");
  CHECK(scene->textured_triangles() == 2);
  const std::shared_ptr<const mpr::scene::Scene<float>> shared = scene;
  const mpr::SceneSampler<mpr::scene::Scene<float>, mpr::RayCast> color(shared);
  const mpr::SceneSampler<mpr::scene::Scene<float>, mpr::RayCast, mpr::HitDepth> depth(shared);
  const mpr::Ray<float> plain{V(-0.5f, 0, 0), V(0, 0, 1)}, poisoned{V(0.5f, 0, 0), V(0, 0, 2)};
  CHECK(color.sample(plain).allFinite());     // no texture work for the untextured quad
  CHECK(!color.sample(poisoned).allFinite()); // (the poison is real)
  CHECK(depth.sample(poisoned) == 1.0f);      // depth: t = 2 / |direction.z| = 1, no shading
  CHECK(depth.sample(plain) == 2.0f);
  CHECK(std::isinf(depth.sample({V(5, 5, 0), V(0, 0, 1)})));
  CHECK((color.sample({V(5, 5, 0), V(0, 0, 1)}) == scene->background()).all());
  using Sampler = mpr::SceneSampler<mpr::scene::Scene<float>, mpr::RayCast>;
  CHECK_THROWS_AS(Sampler(std::shared_ptr<const mpr::scene::Scene<float>>()), mpr::argument_error);
}

TEMPLATE_TEST_CASE("the batch ray cast (sample_rays, closest_hits) equals the per-ray one bit for bit",
                   "[scene][batch]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  using Color = mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>;
  using Depth = mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast, mpr::HitDepth>;
  STATIC_REQUIRE(mpr::BatchRaySampler<Color>);
  STATIC_REQUIRE(mpr::BatchRaySampler<Depth>);
  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scene::classroom<T>());
  const Color color(scene);
  const Depth depth(scene);
  // A camera's rays (coherent) with degenerate ones mixed in: zero and NaN directions, which
  // finish at once and must not disturb the rays walked alongside them.
  const auto camera = classroom_camera<T>(97, 61);
  std::vector<mpr::Ray<T>> rays;
  for (int y = 0; y < 61; ++y)
    for (int x = 0; x < 97; ++x) {
      rays.push_back(camera.ray_through(mpr::Vec2<T>(T(x) + T(0.5), T(y) + T(0.5))));
      if ((x * 7 + y) % 23 == 0) rays.push_back({V(0, 1, 0), V::Zero()});
      if ((x * 5 + y) % 31 == 0) rays.push_back({V(0, 1, 0), V(std::nan(""), 0, -1)});
    }
  for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(3), rays.size()}) {
    const std::span<const mpr::Ray<T>> batch(rays.data(), n);
    std::vector<mpr::Color> c(n);
    std::vector<float> d(n);
    std::vector<mpr::scene::Hit<T>> h(n);
    color.sample_rays(batch, std::span<mpr::Color>(c));
    depth.sample_rays(batch, std::span<float>(d));
    color.bvh().closest_hits(batch, std::span<mpr::scene::Hit<T>>(h));
    int differ = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const mpr::Color ci = color.sample(rays[i]);
      const float di = depth.sample(rays[i]);
      const mpr::scene::Hit<T> hi = color.bvh().closest_hit(rays[i]);
      differ += std::memcmp(ci.data(), c[i].data(), sizeof(float) * 3) != 0;
      differ += std::memcmp(&di, &d[i], sizeof(float)) != 0;
      differ += hi.triangle != h[i].triangle || std::memcmp(&hi.t, &h[i].t, sizeof(T)) != 0 ||
                std::memcmp(&hi.b1, &h[i].b1, sizeof(T)) != 0 || std::memcmp(&hi.b2, &h[i].b2, sizeof(T)) != 0;
    }
    INFO(n << " rays");
    CHECK(differ == 0);
  }
}

TEMPLATE_TEST_CASE("the tile ray cast (sample_tile, 4 x 4 packets) equals the per-ray one bit for bit",
                   "[scene][batch][packet]", float, double) {
  using T = TestType;
  using Color = mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>;
  using Depth = mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast, mpr::HitDepth>;
  STATIC_REQUIRE(mpr::TileRaySampler<Color>);
  STATIC_REQUIRE(mpr::TileRaySampler<Depth>);
  STATIC_REQUIRE_FALSE(mpr::TileRaySampler<mpr::RayCast>); // the policy tag is no sampler
  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scene::classroom<T>());
  const Color color(scene);
  const Depth depth(scene);
  const auto camera = classroom_camera<T>(97, 61);
  // Widths and row counts that are and are not multiples of the 4 x 4 packets.
  for (const int width : {1, 3, 4, 37, 97})
    for (const int rows : {1, 4, 6, 8}) {
      std::vector<mpr::Ray<T>> rays;
      for (int y = 0; y < rows; ++y)
        for (int x = 0; x < width; ++x)
          rays.push_back(camera.ray_through(mpr::Vec2<T>(T(x) + T(0.5), T(y * 7) + T(0.5))));
      std::vector<mpr::Color> c(rays.size());
      std::vector<float> d(rays.size());
      color.sample_tile(rays, width, std::span<mpr::Color>(c));
      depth.sample_tile(rays, width, std::span<float>(d));
      int differ = 0;
      for (std::size_t i = 0; i < rays.size(); ++i) {
        const mpr::Color ci = color.sample(rays[i]);
        const float di = depth.sample(rays[i]);
        differ += std::memcmp(ci.data(), c[i].data(), sizeof(float) * 3) != 0;
        differ += std::memcmp(&di, &d[i], sizeof(float)) != 0;
      }
      INFO(width << " x " << rows << " rays");
      CHECK(differ == 0);
    }
}
