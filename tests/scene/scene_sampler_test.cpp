#include <mpr/mpr.hpp>
#include <mpr/sampler/pinhole_camera.hpp>
#include <mpr/scene.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <type_traits>

namespace {

template <class T> mpr::PinholeCamera<T> classroom_camera(int w, int h) {
  return mpr::PinholeCamera<T>::look_at(mpr::Vec3<T>(0.3, 2.2, 3.5), mpr::Vec3<T>(0, 1.3, -8), mpr::Vec3<T>(0, 1, 0),
                                        T(1.0), w, h);
}

} // namespace

TEMPLATE_TEST_CASE("rasterizer and ray caster agree on a pinhole view of the classroom", "[scene][agreement]", float,
                   double) {
  using T = TestType;
  const int w = 160, h = 120;
  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scenes::classroom<T>());
  const auto camera = classroom_camera<T>(w, h);
  const mpr::scene::RasterImage raster = mpr::scene::rasterize(*scene, camera, {.threads = 2});

  const T plane_depth = T(0.5);
  const mpr::PlanarSurface<T> plane = camera.image_plane(plane_depth);
  const mpr::GlcSelector<T> glc = camera.glc_on(plane);
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
