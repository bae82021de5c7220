// The renderer loop with a trivial sampler: mpr's static policies against the same loop written
// with one virtual call per role per pixel (region, surface, selector, sampler), the design of
// the original 2004 system (pure virtual base classes). 500 x 500 rays, float and double.
// Then the cost of the pixel-sampling policy (include/mpr/sampling/): the default PixelCentre
// against Supersample<Stratified(1)> and Supersample<OwenSobol(1)> at one sample per pixel, and
// OwenSobol at 16 (Mrays/s counts every sample's ray). Last, issue 15's target "the
// pixel-sampling policy costs nothing at 1 spp": the renderer with PixelCentre against the loop
// the renderer ran before the policy existed, written out here (uv, point, ray, sample per pixel,
// rows over threads), timed alternately in the same run, with the median of the per-pair time
// ratios (renderer / direct; 1.00 = the same speed) and their spread. With one thread the times
// are the rendering thread's CPU time, steadier than the wall clock on a shared machine.
//
// usage: renderer_loop [--quick]
#include "bench_common.hpp"
#include "renderer_loop_virtual.hpp"

#include <mpr/mpr.hpp>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <memory>
#include <vector>

namespace {

using namespace mpr_bench;

template <class T>
void virtual_render(mpr::ImageView<mpr::Color> out, const VirtualRegion<T>& region, const VirtualSurface<T>& surface,
                    const VirtualSelector<T>& selector, const VirtualSampler<T>& sampler, int threads) {
  mpr::detail::parallel_rows(0, out.height(), threads, [&](int y) noexcept {
    for (int x = 0; x < out.width(); ++x) {
      const mpr::Pixel px{x, y};
      const mpr::Vec2<T> uv = region.pixel_to_uv(px);
      const mpr::Vec3<T> point = surface.point_at(uv);
      const mpr::Ray<T> ray = selector.ray_at(px, uv, point);
      out(x, y) = sampler.sample(ray);
    }
  });
}

template <class T>
void run(const char* scalar, int size, int repeats) {
  const mpr::PlanarSurface<T> plane({-1, -1, 1}, {2, 0, 0}, {0, 2, 0});
  const mpr::Vec3<T> eye(0, 0, 0);
  const mpr::GlcSelector<T> glc(plane, plane.point_at({0, 0}) - eye, plane.point_at({1, 0}) - eye,
                                plane.point_at({0, 1}) - eye);
  const mpr::Region region(0, 0, size, size);
  const mpr::Renderer renderer(plane, glc, DirectionColor<T>{});

  const VirtualPolicies<T> policies = make_virtual_policies<T>(region, plane, glc);

  mpr::Image<mpr::Color> a(size, size), b(size, size);
  const double rays = double(size) * size;
  for (int threads : {1, 2}) {
    const mpr_bench::Timing s =
        mpr_bench::time_repeated(repeats, [&] { renderer.render(a.view(), region, mpr::RenderOptions{threads}); });
    const mpr_bench::Timing v = mpr_bench::time_repeated(repeats, [&] {
      virtual_render<T>(b.view(), *policies.region, *policies.surface, *policies.selector, *policies.sampler, threads);
    });
    if (!(a == b)) {
      std::fprintf(stderr, "renderer_loop: static and virtual images differ\n");
      std::exit(1);
    }
    std::printf("| %-6s | %d | %8.1f (%.1f-%.1f) | %8.1f (%.1f-%.1f) | %5.2f |\n", scalar, threads,
                rays / s.median * 1e-6, rays / s.max * 1e-6, rays / s.min * 1e-6, rays / v.median * 1e-6,
                rays / v.max * 1e-6, rays / v.min * 1e-6, v.median / s.median);
  }
}

/// Mrays/s of the same loop under each pixel-sampling policy, float, `threads` threads.
void sampling_cost(int size, int repeats, int threads) {
  using T = float;
  const mpr::PlanarSurface<T> plane({-1, -1, 1}, {2, 0, 0}, {0, 2, 0});
  const mpr::Vec3<T> eye(0, 0, 0);
  const mpr::GlcSelector<T> glc(plane, plane.point_at({0, 0}) - eye, plane.point_at({1, 0}) - eye,
                                plane.point_at({0, 1}) - eye);
  const mpr::Region region(0, 0, size, size);
  mpr::Image<mpr::Color> image(size, size);
  const auto row = [&](const char* name, int spp, const auto& sampling) {
    const mpr::Renderer renderer(plane, glc, DirectionColor<T>{}, sampling);
    const mpr_bench::Timing t =
        mpr_bench::time_repeated(repeats, [&] { renderer.render(image.view(), region, mpr::RenderOptions{threads}); });
    const double rays = double(size) * size * spp;
    std::printf("| %-36s | %d | %3d | %8.1f (%.1f-%.1f) |\n", name, threads, spp, rays / t.median * 1e-6,
                rays / t.max * 1e-6, rays / t.min * 1e-6);
  };
  row("PixelCentre (default)", 1, mpr::PixelCentre{});
  row("Supersample<Stratified(1)>, box", 1, mpr::Supersample(mpr::Stratified(1)));
  row("Supersample<OwenSobol(1)>, box", 1, mpr::Supersample(mpr::OwenSobol(1)));
  row("Supersample<OwenSobol(16)>, box", 16, mpr::Supersample(mpr::OwenSobol(16)));
  row("Supersample<OwenSobol(16)>, Mitchell", 16, mpr::Supersample(mpr::OwenSobol(16), mpr::MitchellFilter()));
}

/// Seconds of CPU time of the calling thread.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

/// Seconds of wall-clock time.
double wall_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

/// The renderer (PixelCentre) against the pre-policy loop: `repeats` pairs, alternating which
/// goes first, each pair's time ratio renderer / direct.
void pixel_centre_vs_direct(int size, int repeats, int threads) {
  using T = float;
  const mpr::PlanarSurface<T> plane({-1, -1, 1}, {2, 0, 0}, {0, 2, 0});
  const mpr::Vec3<T> eye(0, 0, 0);
  const mpr::GlcSelector<T> glc(plane, plane.point_at({0, 0}) - eye, plane.point_at({1, 0}) - eye,
                                plane.point_at({0, 1}) - eye);
  const DirectionColor<T> sampler;
  const mpr::Region region(0, 0, size, size);
  const mpr::Renderer renderer(plane, glc, sampler, mpr::PixelCentre{});
  mpr::Image<mpr::Color> a(size, size), b(size, size);
  const auto with_renderer = [&] { renderer.render(a.view(), region, mpr::RenderOptions{threads}); };
  // The renderer's loop before the pixel-sampling policy (a sampler without batch paths).
  const auto direct = [&] {
    mpr::ImageView<mpr::Color> out = b.view();
    mpr::detail::parallel_rows(0, size, threads, [&](int y) noexcept {
      mpr::Color* row = out.row(y);
      for (int x = 0; x < size; ++x) {
        const mpr::Pixel px{x, y};
        const mpr::Vec2<T> uv = region.pixel_to_uv<T>(px);
        const mpr::Vec3<T> point = plane.point_at(uv);
        row[x] = sampler.sample(glc.ray_at(px, uv, point));
      }
    });
  };
  const auto clock = threads == 1 ? thread_cpu_seconds : wall_seconds;
  const auto time = [&](const auto& fn) {
    const double t0 = clock();
    fn();
    return clock() - t0;
  };
  with_renderer();
  direct();
  if (!(a == b)) {
    std::fprintf(stderr, "renderer_loop: the renderer and the direct loop differ\n");
    std::exit(1);
  }
  std::vector<double> tr, td, ratio;
  for (int i = 0; i < repeats; ++i) {
    double r = 0, d = 0;
    if (i % 2 == 0) {
      r = time(with_renderer);
      d = time(direct);
    } else {
      d = time(direct);
      r = time(with_renderer);
    }
    tr.push_back(r);
    td.push_back(d);
    ratio.push_back(r / d);
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  const double rays = double(size) * size;
  std::printf("| %d | %s | %8.1f | %8.1f | %.3f (%.3f-%.3f) |\n", threads, threads == 1 ? "thread CPU" : "wall",
              rays / median(tr) * 1e-6, rays / median(td) * 1e-6, median(ratio),
              *std::min_element(ratio.begin(), ratio.end()), *std::max_element(ratio.begin(), ratio.end()));
}

} // namespace

int main(int argc, char** argv) {
  const bool quick = mpr_bench::quick_mode(argc, argv);
  const int size = quick ? 64 : 500;
  const int repeats = quick ? 2 : 31;
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  std::printf("renderer loop, %dx%d rays, trivial sampler, median of %d runs (min-max in brackets)\n\n", size, size,
              repeats);
  std::printf("| scalar | threads | static Mrays/s | virtual Mrays/s | static speed-up |\n");
  std::printf("|---|---|---|---|---|\n");
  run<float>("float", size, repeats);
  run<double>("double", size, repeats);
  std::printf("\npixel sampling policy, float, %dx%d pixels, Mrays/s (every sample is a ray)\n\n", size, size);
  std::printf("| policy | threads | spp | Mrays/s |\n|---|---|---|---|\n");
  for (int threads : {1, 2}) sampling_cost(size, repeats, threads);
  std::printf("\nrenderer with PixelCentre (1 spp) against the loop before the policy, float, %dx%d pixels, %d "
              "alternating pairs; ratio = renderer time / direct time, median (min-max)\n\n",
              size, size, repeats);
  std::printf("| threads | clock | renderer Mrays/s | direct Mrays/s | ratio |\n|---|---|---|---|---|\n");
  for (int threads : {1, 2}) pixel_centre_vs_direct(size, repeats, threads);
  return 0;
}
