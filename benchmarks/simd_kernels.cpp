// The synthetic aperture's fractional-shift row (8-bit codes decoded to linear light and
// interpolated at a fixed sub-pixel offset) in each implementation, at every level this CPU runs,
// in one run with the methods interleaved: mpr's own kernels (`detail::lerp_row_portable`, the
// plain loop compiled per level by `run_at`, and the hand-written AVX-512 and VBMI steps), the
// Highway kernel and the xsimd kernel (lightfield/kernels/). 1 thread, thread CPU time; the
// workload is Chess-sized: 49 views x 800 rows of 1400 RGB pixels a "frame", over 256 distinct
// camera rows (1 MiB). Also prints each kernel's largest difference from the plain loop (in
// units of the largest value). See docs/simd.md.

#include "bench_common.hpp"

#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>
#include <mpr/lightfield/frame_set.hpp>
#if MPR_HAVE_HWY
#include <mpr/lightfield/kernels/lerp_row_hwy.hpp>
#endif
#if MPR_HAVE_XSIMD
#include <mpr/lightfield/kernels/lerp_row_xsimd.hpp>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using mpr::detail::SimdLevel;
using Kernel = std::function<void(const std::uint8_t*, const std::uint16_t*, float, float, float*, std::size_t,
                                  const std::uint8_t*)>;

struct Method {
  Method(std::string n, Kernel k) : name(std::move(n)), run(std::move(k)) {}
  std::string name;
  Kernel run;
  std::vector<double> ms;
  double max_diff = 0;
};

double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::vector<Method> methods() {
  namespace d = mpr::detail;
  std::vector<Method> out;
  const SimdLevel best = d::cpu_simd_level();
#if defined(MPR_SIMD_X86)
  const bool vbmi = best >= SimdLevel::avx512vbmi;
#else
  const bool vbmi = false;
#endif
  for (SimdLevel level : {SimdLevel::portable, SimdLevel::avx2, SimdLevel::avx512}) {
    if (level > best) break;
    const std::string tag = d::simd_level_name(level);
    // mpr today: the plain loop per level; at avx512 the hand-written step (VBMI apart).
    if (level == SimdLevel::avx512) {
#if defined(MPR_SIMD_X86)
      out.emplace_back("mpr " + tag, [](auto a, auto lut, float ax, float s, float* h, std::size_t m, auto ahead) {
        d::lerp_row_codes_avx512(a, lut, ax, s, h, m, ahead);
      });
      if (vbmi)
        out.emplace_back("mpr avx512+vbmi", [](auto a, auto lut, float ax, float s, float* h, std::size_t m,
                                               auto ahead) { d::lerp_row_codes_vbmi(a, lut, ax, s, h, m, ahead); });
#endif
    } else {
      out.emplace_back("mpr " + tag, [level](auto a, auto lut, float ax, float s, float* h, std::size_t m, auto ahead) {
        d::run_at(level, [&]() MPR_INLINE_LAMBDA { d::lerp_row_portable(a, lut, ax, s, h, m, ahead); });
      });
    }
#if MPR_HAVE_HWY
    if (mpr::kernels::lerp_row_hwy_has(level)) {
      out.emplace_back("highway " + tag,
                       [level](auto a, auto lut, float ax, float s, float* h, std::size_t m, auto ahead) {
                         mpr::kernels::lerp_row_hwy(a, lut, ax, s, h, m, ahead, level, false);
                       });
      if (level == SimdLevel::avx512 && vbmi)
        out.emplace_back("highway avx512+vbmi",
                         [](auto a, auto lut, float ax, float s, float* h, std::size_t m, auto ahead) {
                           mpr::kernels::lerp_row_hwy(a, lut, ax, s, h, m, ahead, SimdLevel::avx512, true);
                         });
    }
#endif
#if MPR_HAVE_XSIMD
    if (mpr::kernels::lerp_row_xsimd_has(level))
      out.emplace_back("xsimd " + tag,
                       [level](auto a, auto lut, float ax, float s, float* h, std::size_t m, auto ahead) {
                         mpr::kernels::lerp_row_xsimd(a, lut, ax, s, h, m, ahead, level);
                       });
#endif
  }
  return out;
}

} // namespace

int main(int argc, char** argv) {
  const bool quick = mpr_bench::quick_mode(argc, argv);
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  std::printf("cpu level: %s%s, load average: %s\n", mpr::detail::simd_level_name(mpr::detail::cpu_simd_level()), "",
              mpr_bench::load_average().c_str());
  constexpr std::size_t kPixels = 1400, kRows = 256;
  constexpr std::size_t m = 3 * kPixels, stride = m + 64;
  const int frame_rows = quick ? 49 : 49 * 800, repeats = quick ? 1 : 9;
  std::vector<std::uint8_t> codes(kRows * stride);
  std::mt19937 rng(45);
  for (std::size_t r = 0; r < kRows; ++r) // a smooth image with noise: every code occurs
    for (std::size_t j = 0; j < stride; ++j)
      codes[r * stride + j] = static_cast<std::uint8_t>((j / 3 + r + (rng() % 24)) % 256);
  const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
  const float scale = mpr::Srgb8Texel::scale, ax = 0.37f;
  std::vector<float> h(m + 64), reference(m + 64);
  std::vector<Method> all = methods();
  // Correctness: every row and offset of a sweep against the plain loop.
  for (Method& k : all)
    for (std::size_t r = 0; r < kRows; r += 17)
      for (float x : {0.0f, 0.25f, 0.37f, 0.999f}) {
        const std::size_t len = m - 3 * (r % 7); // lengths off the vector widths too
        mpr::detail::lerp_row_portable(&codes[r * stride], lut, x, scale, reference.data(), len);
        std::fill(h.begin(), h.end(), -1.0f);
        k.run(&codes[r * stride], lut, x, scale, h.data(), len, nullptr);
        for (std::size_t j = 0; j < len; ++j)
          k.max_diff = std::max(k.max_diff, static_cast<double>(std::abs(h[j] - reference[j])));
        if (h[len] != -1.0f) k.max_diff = 1e9; // wrote past the row
      }
  for (int rep = 0; rep < repeats + 1; ++rep)
    for (Method& k : all) {
      const double t0 = thread_seconds();
      for (int i = 0; i < frame_rows; ++i) {
        const std::size_t r = static_cast<std::size_t>(i) % kRows, next = (r + 1) % kRows;
        k.run(&codes[r * stride], lut, ax, scale, h.data(), m, &codes[next * stride]);
      }
      if (rep > 0) k.ms.push_back(1e3 * (thread_seconds() - t0)); // the first is a warm-up
    }
  std::printf("fractional-shift row, %zu channels, %d rows a frame (Chess 1400x800, 49 views), 1 thread, "
              "thread CPU time, %d runs interleaved\n",
              m, frame_rows, repeats);
  std::printf("| kernel | ms/frame median | min | max | max |diff| (of 1.0) |\n|---|---|---|---|---|\n");
  for (Method& k : all) {
    std::sort(k.ms.begin(), k.ms.end());
    std::printf("| %s | %.2f | %.2f | %.2f | %.1e |\n", k.name.c_str(), k.ms[k.ms.size() / 2], k.ms.front(),
                k.ms.back(), k.max_diff);
  }
  std::printf("load average after: %s\n", mpr_bench::load_average().c_str());
  for (const Method& k : all)
    if (k.max_diff > 1e-5) return 1; // 1/500 of an 8-bit level's smallest linear step is 7.7e-6
  return 0;
}
