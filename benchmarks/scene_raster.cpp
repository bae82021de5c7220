// The software rasterizer on the classroom demo scene: 640 x 480 views of the gallery's
// perspective camera (view A), views/s and ms per view with 1 and 2 threads.
//
// usage: scene_raster [--quick]
#include "bench_common.hpp"

#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  using T = float;
  using V = mpr::Vec3<T>;
  const bool quick = mpr_bench::quick_mode(argc, argv);
  const int width = quick ? 160 : 640, height = quick ? 120 : 480;
  const int repeats = quick ? 1 : 51;
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  const auto scene = mpr::scene::classroom<T>();
  const V eye(0, 3.1f, 3.0f);
  const auto camera = mpr::PinholeCamera<T>::look_at(eye, V(0, 1.6f, -8), V(0, 1, 0), T(1.1), width, height);
  std::printf("classroom: %zu triangles, %dx%d, median of %d runs (min-max in brackets)\n\n", scene.size(), width,
              height, repeats);
  std::printf("| threads | tile | ms/view | views/s |\n|---|---|---|---|\n");
  mpr::Image<mpr::Color> color(width, height);
  mpr::Image<float> depth(width, height);
  for (int threads : {1, 2})
    for (int tile : {32, 64}) {
      mpr::scene::RasterOptions options;
      options.threads = threads;
      options.tile = tile;
      const mpr_bench::Timing t = mpr_bench::time_repeated(
          repeats, [&] { mpr::scene::rasterize(scene, camera, color.view(), depth.view(), options); });
      std::printf("| %d | %d | %.2f (%.2f-%.2f) | %.0f |\n", threads, tile, t.median * 1e3, t.min * 1e3, t.max * 1e3,
                  1.0 / t.median);
    }
  return 0;
}
