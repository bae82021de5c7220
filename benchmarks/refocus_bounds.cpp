// What bounds a Chess-sized refocus (49 views of 1400x800 RGB, 8-bit frames and their 16-bit
// linear copy, one thread, thread CPU time): the parts of the synthetic aperture's render timed
// alone, at every SIMD level this CPU runs, in one run with the levels interleaved.
//
// - read: every byte of the frames read once in the order the tiles read them (tiles of 8
//   output rows, cameras inner), summed with the plainest loop: the memory floor of a render
//   that reads each frame once (the codes at the VBMI level, the 16-bit copy below it).
// - 2-D shift, streamed: `detail::shift_tile` (the fractional-shift pass of accumulation/
//   shift_tile.hpp) for the 49 cameras over every tile, each camera at its own sub-pixel offset
//   and reading its own frame, the next camera's block prefetched as the render does.
// - 2-D shift, in cache: the same passes with every camera reading the same 9 rows into the
//   same accumulators, so nothing waits for memory: the arithmetic floor of the pass.
// - encode: `linear_to_srgb8_row` over the 1400x800 output (the 8-bit store of every render).
//
// The frames are generated (a smooth image with noise), so no data set is needed. Usage:
// refocus_bounds [--quick]. See docs/performance.md ("Chess by level").
#include "bench_common.hpp"

#include <mpr/core/color.hpp>
#include <mpr/core/concepts.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/lightfield/accumulation/shift_tile.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace {

using mpr::detail::SimdLevel;

double thread_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

/// The frames: `cameras` images of `width` x `height` RGB codes and the same as 16-bit linear
/// values (`Srgb8Texel::linear16()`), with a margin of `kMargin` pixels the shifts read into.
struct Frames {
  static constexpr int kMargin = 8;
  int cameras, width, height;
  std::size_t stride; // channels per row
  std::vector<std::vector<std::uint8_t>> codes;
  std::vector<std::vector<std::uint16_t>> linear;

  Frames(int c, int w, int h) : cameras(c), width(w), height(h), stride(3 * static_cast<std::size_t>(w)) {
    std::mt19937 rng(45);
    const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
    for (int k = 0; k < cameras; ++k) {
      std::vector<std::uint8_t> f(stride * static_cast<std::size_t>(h) + 64);
      std::vector<std::uint16_t> l(f.size());
      for (std::size_t j = 0; j < f.size(); ++j) {
        f[j] = static_cast<std::uint8_t>((j % stride / 3 + j / stride + rng() % 24) % 256);
        l[j] = lut[f[j]];
      }
      codes.push_back(std::move(f));
      linear.push_back(std::move(l));
    }
  }
  [[nodiscard]] int out_width() const { return width - 2 * kMargin; }
  [[nodiscard]] int out_height() const { return height - 2 * kMargin; }
};

/// Camera k's shift in pixels: a 7 x 7 grid of cameras 2.37 pixels apart, so that each has its
/// own sub-pixel offsets (as Chess at z = 820).
double shift_x(int k) { return 2.37 * (k % 7 - 3); }
double shift_y(int k) { return 2.37 * (k / 7 % 7 - 3); }

/// Reads every byte the tiles read, in their order; returns a sum so nothing is optimised away.
template <class V>
std::uint64_t read_tiles(const Frames& f, const std::vector<std::vector<V>>& frames) {
  std::uint64_t sum = 0;
  const std::size_t row_bytes = f.stride * sizeof(V);
  for (int y0 = 0; y0 < f.out_height(); y0 += mpr::kTileRows)
    for (int k = 0; k < f.cameras; ++k) {
      const int rows = std::min(mpr::kTileRows, f.out_height() - y0);
      const auto* p = reinterpret_cast<const unsigned char*>(frames[static_cast<std::size_t>(k)].data()) +
                      static_cast<std::size_t>(y0 + Frames::kMargin) * row_bytes;
      const std::size_t words = static_cast<std::size_t>(rows) * row_bytes / 8;
      for (std::size_t w = 0; w < words; ++w) {
        std::uint64_t v;
        std::memcpy(&v, p + 8 * w, 8);
        sum += v;
      }
    }
  return sum;
}

/// The 2-D shift passes of a whole view at `level` into `acc`; `in_cache`: every camera reads
/// camera 0's first rows into the first tile's accumulators.
void shift_tiles(const Frames& f, std::vector<float>& acc, std::vector<float>& work, bool in_cache, SimdLevel level) {
  const std::size_t m = 3 * static_cast<std::size_t>(f.out_width());
  const auto block = [&](int k, int y0, std::ptrdiff_t& first, float& ax, float& ay) {
    const double x = Frames::kMargin + shift_x(k), y = Frames::kMargin + y0 + shift_y(k);
    const double ix = std::floor(x), iy = std::floor(y);
    ax = static_cast<float>(x - ix);
    ay = static_cast<float>(y - iy);
    first =
        static_cast<std::ptrdiff_t>(iy) * static_cast<std::ptrdiff_t>(f.stride) + 3 * static_cast<std::ptrdiff_t>(ix);
  };
  for (int y0 = 0; y0 < f.out_height(); y0 += mpr::kTileRows)
    for (int k = 0; k < f.cameras; ++k) {
      const int source = in_cache ? 0 : k, tile_row = in_cache ? 0 : y0;
      std::ptrdiff_t first = 0, next = 0;
      float ax = 0, ay = 0, nx = 0, ny = 0;
      block(k, tile_row, first, ax, ay);
      mpr::detail::ShiftTile<std::uint8_t> t;
      t.texels = f.codes[static_cast<std::size_t>(source)].data() + first;
      t.linear = f.linear[static_cast<std::size_t>(source)].data() + first;
      t.stride = static_cast<std::ptrdiff_t>(f.stride);
      t.rows = static_cast<std::size_t>(std::min(mpr::kTileRows, f.out_height() - y0));
      t.m = m;
      t.ax = ax;
      t.ay = ay;
      t.scale = mpr::Srgb8Texel::scale;
      t.lut = mpr::Srgb8Texel::linear16();
      t.acc = acc.data() + static_cast<std::size_t>(tile_row) * m;
      t.acc_stride = static_cast<std::ptrdiff_t>(m);
      const std::uint8_t* ahead = nullptr;
      const std::uint16_t* ahead_linear = nullptr;
      if (!in_cache && k + 1 < f.cameras) { // the next camera's block, as the render prefetches it
        block(k + 1, y0, next, nx, ny);
        ahead = f.codes[static_cast<std::size_t>(k) + 1].data() + next;
        ahead_linear = f.linear[static_cast<std::size_t>(k) + 1].data() + next;
      }
      mpr::detail::shift_tile(t, work.data(), ahead, t.stride, ahead_linear, level);
    }
}

struct Row {
  std::string name;
  std::function<void()> run;
  std::vector<double> ms;
};

} // namespace

int main(int argc, char** argv) {
  const bool quick = mpr_bench::quick_mode(argc, argv);
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  std::printf("cpu level: %s, load average: %s\n", mpr::detail::simd_level_name(mpr::detail::cpu_simd_level()),
              mpr_bench::load_average().c_str());
  const int repeats = quick ? 1 : 7;
  const Frames f(quick ? 3 : 49, 1400 + 2 * Frames::kMargin, quick ? 40 : 800 + 2 * Frames::kMargin);
  const std::size_t m = 3 * static_cast<std::size_t>(f.out_width());
  const std::size_t channels = m * static_cast<std::size_t>(f.out_height());
  std::vector<float> acc(channels, 0.0f), work(mpr::detail::shift_tile_work(m) + 16);
  std::vector<float> colours(channels);
  std::mt19937 rng(7);
  for (float& c : colours) c = static_cast<float>(rng() % 100000) / 100000.0f;
  std::vector<std::uint8_t> encoded(channels);
  std::uint64_t sink = 0;
  std::vector<Row> rows;
  rows.push_back({"read the 8-bit codes in tile order", [&] { sink += read_tiles(f, f.codes); }, {}});
  rows.push_back({"read the 16-bit copy in tile order", [&] { sink += read_tiles(f, f.linear); }, {}});
  for (SimdLevel level : {SimdLevel::portable, SimdLevel::avx2, SimdLevel::avx512, SimdLevel::avx512vbmi}) {
    if (level > mpr::detail::cpu_simd_level()) break;
    const std::string at = std::string(" @") + mpr::detail::simd_level_name(level);
    rows.push_back({"2-D shift, streamed" + at, [&, level] { shift_tiles(f, acc, work, false, level); }, {}});
    rows.push_back({"2-D shift, in cache" + at, [&, level] { shift_tiles(f, acc, work, true, level); }, {}});
    rows.push_back({"sRGB encode of the output" + at,
                    [&, level] {
                      for (int y = 0; y < f.out_height(); ++y)
                        mpr::linear_to_srgb8_row(colours.data() + static_cast<std::size_t>(y) * m,
                                                 encoded.data() + static_cast<std::size_t>(y) * m, m, level);
                    },
                    {}});
  }
  for (int rep = 0; rep <= repeats; ++rep)
    for (Row& r : rows) {
      const double t0 = thread_ms();
      r.run();
      if (rep > 0) r.ms.push_back(thread_ms() - t0); // the first is a warm-up
    }
  std::printf("Chess-sized refocus parts: %d cameras, output %dx%d, 1 thread, thread CPU ms, median of %d (min-max), "
              "rows interleaved\n",
              f.cameras, f.out_width(), f.out_height(), repeats);
  std::printf("| part | ms | min | max |\n|---|---|---|---|\n");
  for (Row& r : rows) {
    std::sort(r.ms.begin(), r.ms.end());
    std::printf("| %s | %.2f | %.2f | %.2f |\n", r.name.c_str(), r.ms[r.ms.size() / 2], r.ms.front(), r.ms.back());
  }
  std::printf("load average after: %s (checksum %llu)\n", mpr_bench::load_average().c_str(),
              static_cast<unsigned long long>(sink % 1000));
  return 0;
}
