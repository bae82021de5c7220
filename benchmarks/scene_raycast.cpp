// Ray casting the classroom demo scene: BVH build time, then primary-ray throughput (Mrays/s)
// of a 1000 x 1000 perspective view and of a cross-slit view on the same image plane, with 1
// and 2 threads, for the shaded-colour sampler and for the depth-only sampler (no shading).
// Then anti-aliasing (issue 15): gallery view G (cross-slit) at 640 x 480 with 1 (pixel centres),
// 4 and 16 scrambled Sobol samples per pixel, box filter, ms per view.
//
// usage: scene_raycast [--quick]
#include "bench_common.hpp"

#include <mpr/glc.hpp>
#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>

#include <cstdio>
#include <memory>

namespace {

using T = float;
using V = mpr::Vec3<T>;

/// The gallery's plane and frame (examples/gallery.cpp): 8 x 6 m, looking into the room.
struct Setup {
  V centre{0, 3.1f, 3.0f};
  V forward, right, down;
  Setup() {
    forward = (V(0, 1.6f, -8) - centre).normalized();
    right = forward.cross(V::UnitY()).normalized();
    down = forward.cross(right);
  }
  [[nodiscard]] mpr::PlanarSurface<T> plane() const {
    return mpr::PlanarSurface<T>::centred(centre, T(8) * right, T(6) * down);
  }
  /// d = forward + (x / fx) right + (y / fy) down: a pinhole for fx == fy, else cross-slit.
  [[nodiscard]] mpr::GlcSelector<T> two_slit(T fx, T fy) const {
    const auto p = plane();
    const auto dir = [&](T u, T v) {
      const V offset = p.point_at({u, v}) - centre;
      return V(forward + offset.dot(right) / fx * right + offset.dot(down) / fy * down);
    };
    return {p, dir(0, 0), dir(1, 0), dir(0, 1)};
  }
};

template <class Output>
void run(const char* view, const char* output, const std::shared_ptr<const mpr::scene::Scene<T>>& scene,
         const mpr::GlcSelector<T>& glc, int size, int repeats) {
  const Setup setup;
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast, Output> sampler(scene);
  const mpr::Renderer renderer(setup.plane(), glc, sampler);
  using Px = std::conditional_t<std::is_same_v<Output, mpr::HitDepth>, float, mpr::Rgb8>;
  mpr::Image<Px> image(size, size);
  const double rays = double(size) * size;
  for (int threads : {1, 2}) {
    const mpr_bench::Timing t = mpr_bench::time_repeated(
        repeats, [&] { renderer.render(image.view(), mpr::Region(0, 0, size, size), mpr::RenderOptions{threads}); });
    std::printf("| %-12s | %-12s | %d | %6.2f (%.2f-%.2f) | %7.1f |\n", view, output, threads, rays / t.median * 1e-6,
                rays / t.max * 1e-6, rays / t.min * 1e-6, t.median * 1e3);
  }
}

/// Gallery view G at `w` x `h`, shaded colour, `spp` samples per pixel (1: pixel centres).
void antialiased(const std::shared_ptr<const mpr::scene::Scene<T>>& scene, int w, int h, int repeats) {
  const Setup setup;
  const mpr::PlanarSurface<T> plane = setup.plane();
  const mpr::GlcSelector<T> g = mpr::glc::gallery_view('G', plane, V(0, 1.6f, -8), T(14));
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast> sampler(scene);
  mpr::Image<mpr::Rgb8> image(w, h);
  const auto row = [&](int spp, const auto& sampling) {
    const mpr::Renderer renderer(plane, g, sampler, sampling);
    for (int threads : {1, 2}) {
      const mpr_bench::Timing t = mpr_bench::time_repeated(
          repeats, [&] { renderer.render(image.view(), mpr::Region(0, 0, w, h), mpr::RenderOptions{threads}); });
      const double rays = double(w) * h * spp;
      std::printf("| G cross-slit %dx%d | %3d | %d | %6.2f (%.2f-%.2f) | %7.1f (%.1f-%.1f) |\n", w, h, spp, threads,
                  rays / t.median * 1e-6, rays / t.max * 1e-6, rays / t.min * 1e-6, t.median * 1e3, t.min * 1e3,
                  t.max * 1e3);
    }
  };
  row(1, mpr::PixelCentre{});
  row(4, mpr::Supersample(mpr::OwenSobol(4)));
  row(16, mpr::Supersample(mpr::OwenSobol(16)));
}

} // namespace

int main(int argc, char** argv) {
  const bool quick = mpr_bench::quick_mode(argc, argv);
  const int size = quick ? 64 : 1000;
  const int repeats = quick ? 1 : 9;
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scene::classroom<T>());
  const mpr_bench::Timing build = mpr_bench::time_repeated(quick ? 1 : 9, [&] { mpr::scene::Bvh<T> bvh(*scene); });
  const mpr::scene::Bvh<T> bvh(*scene);
  std::printf("classroom: %zu triangles (%zu textured), BVH %zu nodes, depth %d, build %.1f ms (%.1f-%.1f), float\n\n",
              scene->size(), scene->textured_triangles(), bvh.nodes().size(), bvh.depth(), build.median * 1e3,
              build.min * 1e3, build.max * 1e3);
  std::printf("primary rays, %dx%d, median of %d runs (min-max in brackets)\n\n", size, size, repeats);
  std::printf("| view | output | threads | Mrays/s | ms/view |\n|---|---|---|---|---|\n");
  const Setup setup;
  const mpr::GlcSelector<T> perspective = setup.two_slit(5, 5);
  const mpr::GlcSelector<T> cross_slit = setup.two_slit(3, 14);
  {
    // Untimed warm-up of the whole process (threads, caches, clock) before the first table row.
    const mpr::Renderer warm(setup.plane(), perspective, mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>(scene));
    mpr::Image<mpr::Rgb8> image(size, size);
    for (int i = 0; i < (quick ? 1 : 3); ++i) warm.render(image.view(), mpr::Region(0, 0, size, size));
  }
  run<mpr::ShadedColor>("perspective", "colour", scene, perspective, size, repeats);
  run<mpr::HitDepth>("perspective", "depth only", scene, perspective, size, repeats);
  run<mpr::ShadedColor>("cross-slit", "colour", scene, cross_slit, size, repeats);
  run<mpr::HitDepth>("cross-slit", "depth only", scene, cross_slit, size, repeats);
  std::printf("\nanti-aliased view, shaded colour, box filter, median of %d runs (min-max in brackets)\n\n", repeats);
  std::printf("| view | spp | threads | Mrays/s | ms/view |\n|---|---|---|---|---|\n");
  antialiased(scene, quick ? 64 : 640, quick ? 48 : 480, repeats);
  return 0;
}
