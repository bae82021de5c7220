// The final joint weighted median of the plane sweep (mpr::weighted_median,
// lightfield/depth_median.hpp) alone: its CPU time on one thread on a Chess view's refined plane
// coordinate, at the SIMD level chosen for the machine (the environment variable MPR_SIMD lowers it).
//
//   build/bench/benchmarks/depth_median [DATA_DIR] [--quick] [--views=0,24]
//
// DATA_DIR (default: $MPR_DATA_DIR) holds stanford/chess. For each view, estimate_depth with
// the defaults but the final filters off gives the input (the plane coordinate recovered from the
// depth, the confidence, the view's image as the guide); then weighted_median with the defaults
// runs 5 times on one thread and the least thread CPU time is printed, with the share of windows
// spanning more than `flat` (the ones filtered). --quick (ctest's smoke run) filters a small
// synthetic step instead.

#include "bench_common.hpp"

#include <mpr/core/simd.hpp>
#include <mpr/io/stanford_light_field.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/depth_median.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Least thread CPU time of 5 runs of the filter with the defaults on one thread.
double best_of_5(mpr::ImageView<const float> values, mpr::ImageView<const mpr::Rgb8> guide,
                 mpr::ImageView<const float> confidence) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 5; ++i) {
    const double start = thread_cpu_seconds();
    const mpr::Image<float> out = mpr::weighted_median(values, guide, confidence, {}, 1);
    best = std::min(best, thread_cpu_seconds() - start);
    if (out.width() != values.width()) std::abort();
  }
  return best;
}

// The share of pixels whose window spans more than `flat`.
double filtered_share(const mpr::Image<float>& v, int r, double flat) {
  long n = 0;
  for (int y = 0; y < v.height(); ++y)
    for (int x = 0; x < v.width(); ++x) {
      float lo = v(x, y), hi = lo;
      for (int b = std::max(0, y - r); b <= std::min(v.height() - 1, y + r); ++b)
        for (int a = std::max(0, x - r); a <= std::min(v.width() - 1, x + r); ++a) {
          lo = std::min(lo, v(a, b));
          hi = std::max(hi, v(a, b));
        }
      n += hi - lo > flat;
    }
  return static_cast<double>(n) / (static_cast<double>(v.width()) * v.height());
}

} // namespace

int main(int argc, char** argv) {
  std::string data = std::getenv("MPR_DATA_DIR") ? std::getenv("MPR_DATA_DIR") : "";
  std::vector<int> views{0, 24};
  const bool quick = mpr_bench::quick_mode(argc, argv);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--views=", 0) == 0) {
      views.clear();
      std::stringstream list(a.substr(8));
      for (std::string v; std::getline(list, v, ',');) views.push_back(std::atoi(v.c_str()));
    } else if (a.rfind("--", 0) != 0) {
      data = a;
    }
  }
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  std::printf("SIMD level: %s; load average at start: %s\n\n", mpr::detail::simd_level_name(),
              mpr_bench::load_average().c_str());
  std::printf("| input | pixels | windows spanning > 1 plane | ms (thread CPU, least of 5) |\n|---|---|---|---|\n");
  if (quick) {
    mpr::Image<float> values(200, 120), confidence(200, 120, 1.0f);
    mpr::Image<mpr::Rgb8> guide(200, 120);
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 200; ++x) {
        values(x, y) = x < 100 ? 3.0f + 0.01f * static_cast<float>((x * 7 + y * 13) % 50) : 20.0f;
        guide(x, y) = x < 100 ? mpr::Rgb8{30, 60, 90} : mpr::Rgb8{200, 180, 160};
      }
    const double s = best_of_5(values.view(), guide.view(), confidence.view());
    std::printf("| synthetic step (--quick) | 200x120 | %.1f %% | %.2f |\n", 100 * filtered_share(values, 3, 1.0),
                1000 * s);
    return 0;
  }
  const std::filesystem::path chess = std::filesystem::path(data) / "stanford" / "chess";
  if (data.empty() || !std::filesystem::is_directory(chess)) {
    std::printf("Chess: skipped (no data; pass DATA_DIR or set MPR_DATA_DIR)\n");
    return 0;
  }
  const auto lf = mpr::read_stanford_light_field<float>(chess);
  mpr::PlaneSweepConfig sweep = mpr::with_sweep_range(lf, mpr::PlaneSweepConfig{});
  sweep.median.radius = 0;
  sweep.snap.jump = std::numeric_limits<double>::infinity();
  const double inv_near = 1 / sweep.near, inv_far = 1 / sweep.far;
  for (const int view : views) {
    if (view < 0 || static_cast<std::size_t>(view) >= lf.size()) continue;
    const mpr::DepthEstimate e = mpr::estimate_depth(lf, static_cast<std::size_t>(view), sweep);
    // The plane coordinate back from the depth (planes are even in inverse depth).
    mpr::Image<float> coordinate(e.depth.width(), e.depth.height());
    for (int y = 0; y < coordinate.height(); ++y)
      for (int x = 0; x < coordinate.width(); ++x)
        coordinate(x, y) =
            static_cast<float>((1.0 / e.depth(x, y) - inv_near) * (sweep.planes - 1) / (inv_far - inv_near));
    const double s = best_of_5(coordinate.view(), lf.image(static_cast<std::size_t>(view)).view(), e.confidence.view());
    std::printf("| Chess view %d, plane coordinate | %dx%d | %.1f %% | %.1f |\n", view, coordinate.width(),
                coordinate.height(), 100 * filtered_share(coordinate, 3, 1.0), 1000 * s);
  }
  std::printf("\nload average at the end: %s\n", mpr_bench::load_average().c_str());
  return 0;
}
