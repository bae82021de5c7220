// Plane-sweep depth estimation (mpr::estimate_depth, lightfield/depth_estimation.hpp): run time
// on Stanford Chess (all 49 views, 1 and 2 threads) and accuracy against exact depth on a
// rasterized virtual array of the classroom.
//
//   build/bench/benchmarks/depth_estimation [DATA_DIR] [--quick] [--planes=N] [--views=N] [--tuned]
//
// DATA_DIR (default: $MPR_DATA_DIR) holds stanford/chess; without it the Chess part is skipped.
// --quick (ctest's smoke run) sweeps a small classroom array only. --planes=, --neighbours=,
// --best=, --truncation=, --spatial=, --range= change the classroom's settings (default: the
// PlaneSweepConfig defaults, 64 planes, and a second row with settings for this array: all four
// neighbours, 256 planes, spatial 3); Chess runs with the library's defaults (`estimate_scene_depth`:
// the range from the calibration, each stage's time printed), --tuned with the range 600..1400
// set; --views limits the Chess views timed (default all, else one by one
// with estimate_depth); --threads=N times only N threads; --no-classroom skips the accuracy part;
// --out=DIR writes camera 28's exact depth and each row's estimate as colour-mapped PNGs
// (classroom_depth_exact.png, classroom_depth_estimated_<row>.png, one depth range).

#include "bench_common.hpp"

#include <mpr/io/depth_maps.hpp>
#include <mpr/io/stanford_light_field.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/scene_depth.hpp>
#include <mpr/scene/classroom.hpp>
#include <mpr/scene/rasterized_sampler.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <sys/resource.h>
#include <utility>
#include <vector>

namespace {

template <class Fn>
double seconds(Fn&& fn) {
  const auto start = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// CPU seconds of the process so far (user + system, all threads).
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The classroom as an 8 x 6 array of rasterized cameras (as examples/lightfield_glc_gallery.cpp
// makes it), camera 28's depth estimated from the colours against its exact z-buffer, once per
// settings row (each: a label and the sweep; near, far and threads are set here).
void classroom_accuracy(bool quick, std::vector<std::pair<std::string, mpr::PlaneSweepConfig>> runs,
                        const std::filesystem::path& out) {
  using T = float;
  const auto scene = mpr::scene::classroom<T>();
  const mpr::Vec3<T> eye(0, 3.1f, 3.0f), target(0, 1.6f, -8);
  const mpr::Vec3<T> forward = (target - eye).normalized();
  const mpr::Vec3<T> right = forward.cross(mpr::Vec3<T>::UnitY()).normalized();
  const mpr::Vec3<T> down = forward.cross(right);
  const auto room = mpr::PlanarSurface<T>::centred(eye, T(8) * right, T(6) * down);
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = 8;
  config.rows = 6;
  config.width = quick ? 80 : 320;
  config.height = quick ? 60 : 240;
  config.depth_maps = true;
  const auto array = mpr::scene::rasterize_virtual_array(scene, room, config);
  const std::size_t camera = 28;
  const mpr::Image<float>& truth = array.frames.depth(camera);
  const mpr::Image<mpr::Rgb8>& image = array.frames.image(camera);
  const int w = image.width(), h = image.height();
  const auto luma = [&](int x, int y) {
    const mpr::Rgb8 p = image(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1));
    return 0.299 * p.r + 0.587 * p.g + 0.114 * p.b;
  };
  std::printf("\nclassroom, 8x6 rasterized cameras of %dx%d, camera %zu from colours, 1.5..30 m, 2 threads\n\n", w, h,
              camera);
  const mpr::DepthRange range = mpr::depth_range(truth.view());
  if (!out.empty()) mpr::write_depth_preview(out / "classroom_depth_exact.png", truth.view(), range);
  bool header = false;
  int run = 0;
  for (auto& [label, sweep] : runs) {
    sweep.near = 1.5;
    sweep.far = 30;
    if (quick) sweep.planes = 16;
    sweep.threads = 2;
    mpr::DepthEstimate e;
    const double s = seconds([&, &config = sweep] { e = mpr::estimate_depth(array.frames, camera, config); });
    std::vector<double> all, textured, signed_textured;
    int within1 = 0, within5 = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double z = truth(x, y);
        if (!std::isfinite(z)) continue;
        const double error = std::abs(static_cast<double>(e.depth(x, y)) - z) / z;
        all.push_back(error);
        within1 += error <= 0.01;
        within5 += error <= 0.05;
        const double gx = luma(x + 1, y) - luma(x - 1, y), gy = luma(x, y + 1) - luma(x, y - 1);
        if (std::hypot(gx, gy) > 60) {
          textured.push_back(error);
          signed_textured.push_back((static_cast<double>(e.depth(x, y)) - z) / z);
        }
      }
    if (!out.empty())
      mpr::write_depth_preview(out / ("classroom_depth_estimated_" + std::to_string(run) + ".png"), e.depth.view(),
                               range);
    ++run;
    const double count = static_cast<double>(all.size());
    if (!header) {
      std::printf("| settings | time s | median rel. error, textured (%zu px, luma gradient > 60) | median rel. "
                  "error, all (%zu px) | within 1%% | within 5%% | median signed error, textured |\n"
                  "|---|---|---|---|---|---|---|\n",
                  textured.size(), all.size());
      header = true;
    }
    std::printf("| %s: %d planes, neighbours %d best %d, truncation %.2f, spatial %.0f, range %.2f | %.3f | %.2f%% | "
                "%.2f%% | %.1f%% | %.1f%% | %+.2f%% |\n",
                label.c_str(), sweep.planes, sweep.neighbours, sweep.best, sweep.truncation, sweep.spatial, sweep.range,
                s, 100 * median(textured), 100 * median(all), 100 * within1 / count, 100 * within5 / count,
                100 * median(signed_textured));
  }
}

} // namespace

int main(int argc, char** argv) {
  const bool quick = mpr_bench::quick_mode(argc, argv);
  std::string data;
  int views = 0, only_threads = 0;
  mpr::PlaneSweepConfig classroom_config; // the settings of the classroom run (defaults, 64 planes)
  std::filesystem::path out;              // --out=DIR: the classroom's depth maps as PNG previews
  bool classroom = true, options = false; // options: a sweep setting was given
  bool tuned = false;                     // --tuned: Chess with the range 600..1400 set
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--planes=", 0) == 0 || a.rfind("--neighbours=", 0) == 0 || a.rfind("--best=", 0) == 0 ||
        a.rfind("--truncation=", 0) == 0 || a.rfind("--spatial=", 0) == 0 || a.rfind("--range=", 0) == 0)
      options = true;
    if (a.rfind("--planes=", 0) == 0)
      classroom_config.planes = std::atoi(a.c_str() + 9);
    else if (a.rfind("--neighbours=", 0) == 0)
      classroom_config.neighbours = std::atoi(a.c_str() + 13);
    else if (a.rfind("--best=", 0) == 0)
      classroom_config.best = std::atoi(a.c_str() + 7);
    else if (a.rfind("--truncation=", 0) == 0)
      classroom_config.truncation = std::atof(a.c_str() + 13);
    else if (a.rfind("--spatial=", 0) == 0)
      classroom_config.spatial = std::atof(a.c_str() + 10);
    else if (a.rfind("--range=", 0) == 0)
      classroom_config.range = std::atof(a.c_str() + 8);
    else if (a.rfind("--views=", 0) == 0)
      views = std::atoi(a.c_str() + 8);
    else if (a.rfind("--threads=", 0) == 0)
      only_threads = std::atoi(a.c_str() + 10);
    else if (a.rfind("--out=", 0) == 0)
      out = a.substr(6);
    else if (a == "--no-classroom")
      classroom = false;
    else if (a == "--tuned")
      tuned = true;
    else if (a != "--quick")
      data = a;
  }
  if (data.empty()) {
    const char* env = std::getenv("MPR_DATA_DIR");
    data = env != nullptr ? env : "";
  }
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  std::printf("plane-sweep kernels: %s; load average at start: %s\n", mpr::detail::simd_level_name(),
              mpr_bench::load_average().c_str());
  if (classroom) {
    std::vector<std::pair<std::string, mpr::PlaneSweepConfig>> runs{{options ? "given" : "defaults", classroom_config}};
    if (!options) {
      // For this array: every neighbour counts (the four at 1 m see nearly all of camera 28's
      // view, and two of them agree on false matches along the floor's checkers and the rows of
      // desks), planes 0.34 px of disparity apart at the 1 m baseline (64 planes: 1.35 px), and
      // the spatial extent of the defaults (12 px, set for 1400-pixel Chess frames) scaled to
      // 320-pixel frames.
      mpr::PlaneSweepConfig array = classroom_config;
      array.best = 4;
      array.planes = 256;
      array.spatial = 3;
      runs.emplace_back("for this array", array);
    }
    classroom_accuracy(quick, runs, out);
  }

  const std::filesystem::path chess = std::filesystem::path(data) / "stanford" / "chess";
  if (quick || data.empty() || !std::filesystem::is_directory(chess)) {
    std::printf("\nChess: skipped (%s)\n", quick ? "--quick" : "no data; pass DATA_DIR or set MPR_DATA_DIR");
    return 0;
  }
  const auto lf = mpr::read_stanford_light_field<float>(chess);
  mpr::PlaneSweepConfig sweep; // the defaults: the range from the calibration
  if (tuned) {
    sweep.near = 600;
    sweep.far = 1400;
  }
  const std::size_t n = views > 0 ? std::min<std::size_t>(static_cast<std::size_t>(views), lf.size()) : lf.size();
  std::printf(
      "\nStanford Chess: %zu views of %dx%d, %zu of them estimated (each against up to %d neighbours), %d planes "
      "over %s, default settings (best %d, truncation %.2f, spatial %.0f, range %.2f)\n\n",
      lf.size(), lf.camera(0).width(), lf.camera(0).height(), n, sweep.neighbours, sweep.planes,
      tuned ? "600..1400 (--tuned)" : "the range from the calibration (estimate_scene_depth)", sweep.best,
      sweep.truncation, sweep.spatial, sweep.range);
  std::printf("| threads | total s (wall) | ms per view (wall) | CPU s (all threads) | stages s (wall) | range | load "
              "average after |\n|---|---|---|---|---|---|---|\n");
  for (const int threads : {2, 1}) {
    if (only_threads > 0 && threads != only_threads) continue;
    sweep.threads = threads;
    std::map<std::string, double> stages; // each stage's time when it ended
    sweep.progress = [&](const mpr::DepthProgress& p) {
      if (p.done == p.total) stages[p.stage] = p.seconds;
    };
    double s = 0;
    const double cpu = cpu_seconds();
    std::string range = tuned ? "600..1400" : "";
    if (n == lf.size()) {
      s = seconds([&] {
        mpr::SceneDepthConfig config;
        config.sweep = sweep;
        const mpr::SceneDepth d = mpr::estimate_scene_depth(lf, config);
        if (!tuned)
          range = std::to_string(static_cast<int>(d.range.near)) + ".." + std::to_string(static_cast<int>(d.range.far));
      });
    } else {
      const mpr::PlaneSweepConfig ranged = mpr::with_sweep_range(lf, sweep);
      for (std::size_t i = 0; i < n; ++i) s += seconds([&] { (void)mpr::estimate_depth(lf, i, ranged); });
      range = std::to_string(static_cast<int>(ranged.near)) + ".." + std::to_string(static_cast<int>(ranged.far));
    }
    std::string times;
    for (const auto& [stage, t] : stages)
      times += (times.empty() ? "" : ", ") + stage + " " + std::to_string(t).substr(0, 5);
    std::printf("| %d | %.2f | %.0f | %.2f | %s | %s | %s |\n", threads, s, 1000 * s / static_cast<double>(n),
                cpu_seconds() - cpu, times.c_str(), range.c_str(), mpr_bench::load_average().c_str());
    std::fflush(stdout);
  }
  return 0;
}
