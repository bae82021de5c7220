#pragma once
// Shared helpers for mpr's benchmark programs: the machine description every report starts
// with, repeated timing with median and min-max spread, and a sampler wrapper that forces the
// per-ray path.

#include <mpr/core/ray.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace mpr_bench {

/// The 1-, 5- and 15-minute load averages (/proc/loadavg), or "unknown".
inline std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  if (!(f >> a >> b >> c)) return "unknown";
  return a + " " + b + " " + c;
}

/// CPU model (from /proc/cpuinfo), hardware threads, compiler, build type and flags.
inline std::string machine_description() {
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  std::string text =
      "machine: " + cpu + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads\ncompiler: ";
#if defined(__clang__)
  text += "clang ";
#elif defined(__GNUC__)
  text += "g++ ";
#endif
  text += __VERSION__;
#ifdef MPR_BENCH_BUILD_TYPE
  text += std::string("\nbuild: ") + MPR_BENCH_BUILD_TYPE + ", flags:" + MPR_BENCH_FLAGS;
#endif
#if defined(_OPENMP)
  text += ", OpenMP";
#endif
  return text;
}

/// Median, minimum and maximum of repeated timings, in seconds.
struct Timing {
  double median = 0, min = 0, max = 0;
};

/// Runs `fn` once to warm up, then `repeats` times, timing each run.
template <class Fn>
Timing time_repeated(int repeats, Fn&& fn) {
  fn();
  std::vector<double> seconds;
  for (int i = 0; i < repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  return {seconds[seconds.size() / 2], seconds.front(), seconds.back()};
}

/// True when `--quick` is among the arguments (ctest's smoke run).
inline bool quick_mode(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--quick") == 0) return true;
  return false;
}

/// Hides a sampler's batch and tile interfaces, so the renderer calls `sample(ray)` per pixel
/// (the reference a batch or tile path is checked against).
template <class S>
struct PerRay {
  using scalar_type = typename S::scalar_type;
  using color_type = typename S::color_type;
  S inner;
  [[nodiscard]] color_type sample(const mpr::Ray<scalar_type>& ray) const noexcept { return inner.sample(ray); }
};

} // namespace mpr_bench
