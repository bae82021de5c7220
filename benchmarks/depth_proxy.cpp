// The depth-proxy render (mpr::DepthProxy, lightfield/depth_proxy.hpp): run time of one held-out
// view, its PSNR against the captured image, and its batch path's (`sample_rays`, sixteen rays
// at a time in SIMD lanes at every level from SSE4.2 up; `MPR_SIMD` lowers the level)
// agreement with the per-ray `sample(ray)` contract on the same rays:
// the same bits where the per-ray code has no fused multiply-add (builds without -march), else a
// few pixels where the rounding of a fused product moves a decision at a threshold.
//
//   build/bench/benchmarks/depth_proxy [DATA_DIR] [--quick] [--repeats=N] [--depth-cache=DIR]
//                                      [--no-per-ray] [--out=DIR] [--only=classroom|chess|temple]
//
// Workloads:
// - Stanford Chess view (08,08) (index 24) rendered from the 48 other views through its own
//   perspective GLC at z = 820, with their depth maps estimated by the plane sweep of
//   examples/leave_one_out (64 planes, 600-1400) and `DepthProxy{10}` (k = 4): the issue's
//   1400x800 workload. DATA_DIR (default $MPR_DATA_DIR) holds stanford/chess; without it the
//   Chess part is skipped. --depth-cache=DIR reads the 48 maps from DIR when all are there (PFM,
//   `mpr::read_depth_maps`), else estimates them and writes them there.
// - The Middlebury temple ring (templeSparseRing) view 3 from the 15 others, their depth
//   estimated and constrained to the visual hull as in examples/leave_one_out, with its depth
//   proxy (radius 0.5, k = 3, every camera in reach searched; cached in DIR/temple with
//   --depth-cache).
// - The classroom as a rasterized 8x6 array of 320x240 with exact z-buffer depth, camera 28
//   held out (--quick: a 4x3 array of 80x60).
//
// --only=NAME runs that workload alone.
// --out=DIR writes each render and the captured image as PNGs (depth_proxy_<set>[_captured].png).
// Times: 1 thread as thread CPU time and 2 threads wall-clock, median of --repeats (default 5)
// after one warm-up run.

#include "bench_common.hpp"
#include "leave_one_out_setup.hpp"

#include <mpr/core/image_metrics.hpp>
#include <mpr/io/depth_maps.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/par_file.hpp>
#include <mpr/io/stanford_light_field.hpp>
#include <mpr/scene/classroom.hpp>
#include <mpr/scene/rasterized_sampler.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace {

using T = float;

template <class Fn>
double thread_cpu_ms(Fn&& fn) {
  timespec a{}, b{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &a);
  fn();
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &b);
  return (static_cast<double>(b.tv_sec - a.tv_sec) + 1e-9 * static_cast<double>(b.tv_nsec - a.tv_nsec)) * 1e3;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Options {
  bool quick = false, per_ray = true;
  int repeats = 5;
  std::filesystem::path depth_cache, out;
  std::string only; // empty: every workload
  [[nodiscard]] bool runs(const char* name) const { return only.empty() || only == name; }
};

// Times the render of `held` (perspective GLC at `depth`) from `frames` through `proxy`
// and prints one table row, plus the per-ray check.
void run(const std::string& label, const std::shared_ptr<const mpr::CameraFrameSet<T, mpr::Rgb8>>& frames,
         const mpr::PinholeCamera<T>& held, T depth, const mpr::DepthProxy& proxy, const mpr::Image<mpr::Rgb8>& truth,
         const Options& o, const mpr::Color& background = mpr::Color(0, 0, 0)) {
  mpr::FrameSamplerConfig<T> config;
  config.background = background; // what a ray that escapes every depth map gets
  const mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Rgb8> sampler(frames, proxy, config);
  const auto renderer = mpr_loo::held_out_renderer(sampler, held, depth);
  const int w = held.width(), h = held.height();
  const mpr::Region region(0, 0, w, h);
  mpr::Image<mpr::Rgb8> image(w, h);
  renderer.render(image.view(), region, {1});
  std::vector<double> one, two;
  for (int i = 0; i < o.repeats; ++i) one.push_back(thread_cpu_ms([&] { renderer.render(image.view(), region, {1}); }));
  renderer.render(image.view(), region, {2});
  for (int i = 0; i < o.repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    renderer.render(image.view(), region, {2});
    two.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  if (!o.out.empty()) {
    std::string name = label.substr(0, label.find(' '));
    if (!name.empty() && name.back() == ',') name.pop_back();
    mpr::write_png(o.out / ("depth_proxy_" + name + ".png"), image);
    mpr::write_png(o.out / ("depth_proxy_" + name + "_captured.png"), truth);
  }
  using Sampler = mpr::CameraFrameSampler<mpr::DepthProxy, T, mpr::Rgb8>;
  std::string check = "not run (--no-per-ray)";
  if constexpr (!mpr::TileRaySampler<Sampler> && !mpr::BatchRaySampler<Sampler>)
    check = "none: DepthProxy answers per ray only";
  else if (o.per_ray) {
    const mpr::Renderer slow(held.image_plane(depth), mpr::pinhole_glc(held, held.image_plane(depth)),
                             mpr_bench::PerRay<decltype(sampler)>{sampler});
    mpr::Image<mpr::Rgb8> reference(w, h);
    double ms = thread_cpu_ms([&] { slow.render(reference.view(), region, {1}); });
    int worst = 0;
    long over = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const mpr::Rgb8 p = image(x, y), q = reference(x, y);
        const int d = std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
        worst = std::max(worst, d);
        over += d > 1;
      }
    char text[160];
    std::snprintf(text, sizeof text, "%.1f ms per ray (1 thread); largest difference %d levels, %ld pixels over 1", ms,
                  worst, over);
    check = text;
  }
  std::printf("| %s | %dx%d | %.1f | %.1f | %.2f | %s |\n", label.c_str(), w, h, median(one), median(two),
              mpr::compare_images(image.view(), truth.view()).psnr, check.c_str());
}

void classroom(const Options& o) {
  const auto scene = mpr::scene::classroom<T>();
  const mpr::Vec3<T> eye(0, 3.1f, 3.0f), target(0, 1.6f, -8);
  const mpr::Vec3<T> forward = (target - eye).normalized();
  const mpr::Vec3<T> right = forward.cross(mpr::Vec3<T>::UnitY()).normalized();
  const mpr::Vec3<T> down = forward.cross(right);
  const auto room = mpr::PlanarSurface<T>::centred(eye, T(8) * right, T(6) * down);
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = o.quick ? 4 : 8;
  config.rows = o.quick ? 3 : 6;
  config.width = o.quick ? 80 : 320;
  config.height = o.quick ? 60 : 240;
  config.depth_maps = true;
  const auto array = mpr::scene::rasterize_virtual_array(scene, room, config);
  const std::size_t held = o.quick ? 5 : 28;
  const auto others = std::make_shared<const mpr::CameraFrameSet<T, mpr::Rgb8>>(array.frames.without(held));
  const T spacing = (array.frames.camera(1).centre() - array.frames.camera(0).centre()).norm();
  run("classroom, rasterized " + std::to_string(config.columns) + "x" + std::to_string(config.rows) +
          ", exact depth, camera " + std::to_string(held),
      others, array.frames.camera(held), array.focal_depth, mpr::DepthProxy{2 * spacing}, array.frames.image(held), o,
      scene.background());
}

void chess(const std::filesystem::path& data, const Options& o) {
  const auto all = mpr::read_stanford_light_field<T>(data / "stanford" / "chess");
  const mpr_loo::LooSetup<T> setup = mpr_loo::chess_setup<T>();
  const std::size_t k = 24;
  auto others = mpr::CameraFrameSet<T, mpr::Rgb8>(all.without(k));
  std::vector<mpr::Image<float>> maps;
  bool cached = !o.depth_cache.empty();
  for (std::size_t i = 0; cached && i < others.size(); ++i)
    cached = std::filesystem::exists(o.depth_cache / mpr::depth_map_name(others.name(i)));
  const auto start = std::chrono::steady_clock::now();
  if (cached) {
    maps = mpr::read_depth_maps(o.depth_cache, others);
  } else {
    mpr::PlaneSweepConfig sweep = mpr_loo::sweep_config(setup, others);
    sweep.threads = 2;
    maps = mpr::estimate_depth_maps(others, sweep);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("Chess: depth maps of the 48 other views %s in %.1f s\n\n", cached ? "read" : "estimated", s);
  auto with = std::make_shared<const mpr::CameraFrameSet<T, mpr::Rgb8>>(std::move(others).with_depth(std::move(maps)));
  if (!cached && !o.depth_cache.empty()) {
    std::filesystem::create_directories(o.depth_cache);
    mpr::write_depth_maps(o.depth_cache, *with);
  }
  std::printf("| workload | output | 1 thread, CPU ms | 2 threads, wall ms | PSNR (dB) | batch path against per ray |\n"
              "|---|---|---|---|---|---|\n");
  run("Chess (08,08) from 48 views, estimated depth", with, all.camera(k), setup.depth_of(all.camera(k)),
      setup.depth_proxy, all.image(k), o);
}

// The Middlebury temple ring, view 3 (templeSR0004) held out: the other 15 views' depth estimated
// and constrained to the visual hull as in examples/leave_one_out, with its depth proxy.
void temple(const std::filesystem::path& data, const Options& o) {
  const auto all = mpr::read_par_file<T>(mpr_loo::temple_par_file<T>(data));
  const mpr_loo::LooSetup<T> setup = mpr_loo::temple_setup<T>();
  const std::size_t k = setup.held_out.front();
  auto others = mpr::CameraFrameSet<T, mpr::Rgb8>(all.without(k));
  const std::filesystem::path cache = o.depth_cache.empty() ? o.depth_cache : o.depth_cache / "temple";
  std::vector<mpr::Image<float>> maps;
  bool cached = !cache.empty();
  for (std::size_t i = 0; cached && i < others.size(); ++i)
    cached = std::filesystem::exists(cache / mpr::depth_map_name(others.name(i)));
  const auto start = std::chrono::steady_clock::now();
  if (cached) {
    maps = mpr::read_depth_maps(cache, others);
  } else {
    mpr::PlaneSweepConfig sweep = mpr_loo::sweep_config(setup, others);
    sweep.threads = 2;
    maps = mpr::estimate_depth_maps(others, sweep);
    mpr::VisualHullConfig hull_config;
    hull_config.near = sweep.near;
    hull_config.far = sweep.far;
    const std::vector<mpr::Image<float>> hull =
        mpr::visual_hull_depth_maps(others, mpr::BrightnessSilhouette{*setup.silhouette}, hull_config);
    for (std::size_t i = 0; i < maps.size(); ++i) mpr::constrain_to_visual_hull(maps[i], hull[i]);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("\ntemple: depth maps of the 15 other views %s in %.1f s\n\n",
              cached ? "read" : "estimated and constrained to the visual hull", s);
  auto with = std::make_shared<const mpr::CameraFrameSet<T, mpr::Rgb8>>(std::move(others).with_depth(std::move(maps)));
  if (!cached && !cache.empty()) {
    std::filesystem::create_directories(cache);
    mpr::write_depth_maps(cache, *with);
  }
  std::printf("| workload | output | 1 thread, CPU ms | 2 threads, wall ms | PSNR (dB) | batch path against per ray |\n"
              "|---|---|---|---|---|---|\n");
  run("temple ring, view 3 from the 15 others, estimated depth and visual hull", with, all.camera(k),
      setup.depth_of(all.camera(k)), setup.depth_proxy, all.image(k), o);
}

} // namespace

int main(int argc, char** argv) try {
  Options o;
  o.quick = mpr_bench::quick_mode(argc, argv);
  std::filesystem::path data;
  if (const char* env = std::getenv("MPR_DATA_DIR")) data = env;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick")
      continue;
    else if (a == "--no-per-ray")
      o.per_ray = false;
    else if (a.rfind("--repeats=", 0) == 0)
      o.repeats = std::max(1, std::atoi(a.c_str() + 10));
    else if (a.rfind("--depth-cache=", 0) == 0)
      o.depth_cache = a.substr(14);
    else if (a.rfind("--out=", 0) == 0)
      o.out = a.substr(6);
    else if (a.rfind("--only=", 0) == 0) {
      o.only = a.substr(7);
      if (o.only != "classroom" && o.only != "chess" && o.only != "temple")
        throw std::runtime_error("--only: expected classroom, chess or temple, got '" + o.only + "'");
    } else if (!a.empty() && a[0] == '-')
      throw std::runtime_error("unknown option " + a);
    else
      data = a;
  }
  if (o.quick) o.repeats = 1;
  std::printf("%s\n\n", mpr_bench::machine_description().c_str());
  std::printf("| workload | output | 1 thread, CPU ms | 2 threads, wall ms | PSNR (dB) | batch path against per ray |\n"
              "|---|---|---|---|---|---|\n");
  if (o.runs("classroom")) classroom(o);
  std::printf("\n");
  if (o.runs("chess")) {
    if (o.quick || data.empty() || !std::filesystem::exists(data / "stanford" / "chess"))
      std::printf("Chess: skipped (%s)\n", o.quick ? "--quick" : "no data; pass DATA_DIR or set MPR_DATA_DIR");
    else
      chess(data, o);
  }
  if (o.runs("temple") && !o.quick && !data.empty() && std::filesystem::exists(mpr_loo::temple_par_file<T>(data)))
    temple(data, o);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "depth_proxy: %s\n", e.what());
  return 1;
}
