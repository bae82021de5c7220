// The resampled block (mpr/lightfield/kernels/resample_tile.hpp) at every instruction-set level
// against a long-double reference: every output row gets the blend of its two camera rows, each
// resampled at x + s i with the row's clamping, and nothing outside the block is written.

#include "lightfield/channel_values.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/kernels/resample_tile.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

namespace {

using LD = long double;

template <class C>
void check_resample_tile() {
  std::mt19937_64 rng(1400 + sizeof(C));
  std::uniform_real_distribution<double> unit(0, 1);
  const mpr_test::ChannelValues<C> channels;
  const auto value = [&](C c) -> LD { return channels.value(c); };
  constexpr float kSentinel = -12345.0f;
  constexpr std::size_t kGuard = 29;
  int failures = 0, cases = 0;
  mpr_test::for_each_simd_level([&](mpr_test::SimdLevel level) {
    for (const std::size_t width : {2u, 19u, 300u})
      for (const double s : {0.5, 1.0, 1.4583333, 2.0, 2.5})
        for (const std::size_t n : {1u, 16u, 17u, 45u, 190u}) {
          const std::size_t height = 12, rows = 1 + rng() % 6;
          std::vector<C> image(3 * width * height);
          for (C& c : image) {
            if constexpr (std::is_same_v<C, float>)
              c = static_cast<float>(4 * unit(rng) - 1);
            else
              c = static_cast<C>(rng() % 256);
          }
          // Mostly inside the row; one case in four runs past its end (the clamped last pair).
          const double reach = static_cast<double>(width - 1) * (rng() % 4 == 0 ? 1.5 : 1.0);
          const double x = std::max(0.0, reach - s * static_cast<double>(n - 1)) * unit(rng);
          std::vector<int> iy(rows);
          std::vector<float> ay(rows);
          for (std::size_t r = 0; r < rows; ++r) {
            iy[r] = static_cast<int>(rng() % (height - 1));
            ay[r] = r == 0 ? 1.0f : static_cast<float>(unit(rng));
          }
          const std::ptrdiff_t acc_stride = static_cast<std::ptrdiff_t>(3 * n + kGuard);
          std::vector<float> acc(static_cast<std::size_t>(acc_stride) * rows, kSentinel);
          for (std::size_t r = 0; r < rows; ++r)
            for (std::size_t j = 0; j < 3 * n; ++j)
              acc[r * static_cast<std::size_t>(acc_stride) + j] = static_cast<float>(unit(rng));
          const std::vector<float> acc0 = acc;
          mpr::detail::ResampleTile<C> t;
          t.texels = image.data();
          t.width = width;
          t.x = x;
          t.s = s;
          t.n = n;
          t.rows = rows;
          t.iy = iy.data();
          t.ay = ay.data();
          t.scale = channels.scale;
          t.lut = channels.lut;
          t.acc = acc.data();
          t.acc_stride = acc_stride;
          mpr::detail::ResampleTileWork work;
          CHECK(mpr::detail::resample_tile(t, work, level));
          ++cases;
          for (std::size_t at = 0; at < acc.size(); ++at) {
            const std::size_t r = at / static_cast<std::size_t>(acc_stride);
            const std::size_t j = at % static_cast<std::size_t>(acc_stride);
            if (j >= 3 * n) {
              if (acc[at] != acc0[at] && ++failures <= 5) FAIL_CHECK("written outside the block at " << at);
              continue;
            }
            const std::size_t i = j / 3, k = j % 3;
            const LD xi = LD(x) + LD(s) * LD(i);
            const LD p = std::clamp(std::floor(xi), LD(0), LD(width) - 2);
            const LD f = std::clamp(xi - p, LD(0), LD(1));
            const std::size_t a = 3 * static_cast<std::size_t>(p) + k;
            const C* top = image.data() + 3 * width * static_cast<std::size_t>(iy[r]);
            const C* bottom = top + 3 * width;
            const LD sc = LD(t.scale), y = LD(ay[r]);
            const LD h0 = sc * ((1 - f) * value(top[a]) + f * value(top[a + 3]));
            const LD h1 = sc * ((1 - f) * value(bottom[a]) + f * value(bottom[a + 3]));
            const LD want = LD(acc0[at]) + (1 - y) * h0 + y * h1;
            // Float positions (up to 40 pixels from a group's start) and float arithmetic.
            const LD spread =
                std::abs(value(top[a + 3]) - value(top[a])) + std::abs(value(bottom[a + 3]) - value(bottom[a]));
            const LD size = std::abs(LD(acc0[at])) + sc * (std::abs(value(top[a])) + std::abs(value(top[a + 3])) +
                                                           std::abs(value(bottom[a])) + std::abs(value(bottom[a + 3])));
            const LD tolerance = sc * 1e-5L * spread + 8 * LD(std::numeric_limits<float>::epsilon()) * size;
            if (!(std::abs(LD(acc[at]) - want) <= tolerance) && ++failures <= 5)
              FAIL_CHECK("width " << width << " s " << s << " n " << n << " row " << r << " pixel " << i << " channel "
                                  << k << ": " << acc[at] << " vs " << static_cast<double>(want));
          }
        }
  });
  CHECK(cases > 0);
  CHECK(failures == 0);
}

} // namespace

TEST_CASE("resample_tile: every level adds each row's blend of its two resampled camera rows, nothing else",
          "[resample_tile]") {
  SECTION("8-bit sRGB codes") { check_resample_tile<std::uint8_t>(); }
  SECTION("float channels") { check_resample_tile<float>(); }
}

TEST_CASE("resample_blend: every level blends two resampled rows into one, weighted, groups kept between rows",
          "[resample_tile]") {
  using LD = long double;
  std::mt19937_64 rng(960);
  std::uniform_real_distribution<double> unit(0, 1);
  const mpr_test::ChannelValues<std::uint8_t> channels;
  const auto value = [&](std::uint8_t c) -> LD { return channels.value(c); };
  constexpr float kSentinel = -12345.0f;
  constexpr std::size_t kGuard = 17, width = 300, height = 6;
  std::vector<std::uint8_t> image(3 * width * height);
  for (std::uint8_t& c : image) c = static_cast<std::uint8_t>(rng() % 256);
  int failures = 0, calls = 0;
  mpr_test::for_each_simd_level([&](mpr_test::SimdLevel level) {
    mpr::detail::ResampleTileWork work; // kept across calls: groups reused where positions repeat
    for (const double s : {0.75, 2.0, 2.5})
      for (const std::size_t n : {1u, 16u, 37u, 100u})
        for (int repeat = 0; repeat < 3; ++repeat) { // the same positions twice, then half a pixel on
          const double x = std::max(0.0, (static_cast<double>(width) - 1 - s * static_cast<double>(n - 1)) * 0.4) +
                           (repeat == 2 ? 0.5 : 0.0);
          const std::size_t y = static_cast<std::size_t>(repeat) % (height - 1);
          const std::uint8_t* top = image.data() + 3 * width * y;
          const std::uint8_t* bottom = top + 3 * width;
          const float ay = static_cast<float>(unit(rng));
          std::vector<float> rw(n);
          for (float& w : rw) w = unit(rng) < 0.2 ? 0.0f : static_cast<float>(unit(rng));
          const bool weighted = (calls++ % 2) == 0;
          std::vector<float> acc(3 * n + kGuard, kSentinel);
          for (std::size_t j = 0; j < 3 * n; ++j) acc[j] = static_cast<float>(unit(rng));
          const std::vector<float> acc0 = acc;
          CHECK(mpr::detail::resample_blend(top, bottom, width, channels.lut, x, s, channels.scale, ay,
                                            weighted ? rw.data() : nullptr, acc.data(), n, work, level));
          for (std::size_t j = 3 * n; j < acc.size(); ++j) failures += acc[j] != kSentinel ? 1 : 0;
          for (std::size_t i = 0; i < n; ++i)
            for (std::size_t k = 0; k < 3; ++k) {
              const LD xi = LD(x) + LD(s) * LD(i);
              const LD p = std::clamp(std::floor(xi), LD(0), LD(width) - 2);
              const LD f = std::clamp(xi - p, LD(0), LD(1));
              const std::size_t a = 3 * static_cast<std::size_t>(p) + k;
              const LD sc = LD(channels.scale);
              const LD h0 = sc * ((1 - f) * value(top[a]) + f * value(top[a + 3]));
              const LD h1 = sc * ((1 - f) * value(bottom[a]) + f * value(bottom[a + 3]));
              const LD r = weighted ? LD(rw[i]) : 1.0L;
              const LD want = LD(acc0[3 * i + k]) + r * ((1 - LD(ay)) * h0 + LD(ay) * h1);
              const LD spread =
                  std::abs(value(top[a + 3]) - value(top[a])) + std::abs(value(bottom[a + 3]) - value(bottom[a]));
              const LD tolerance =
                  sc * 1e-5L * spread + 8 * LD(std::numeric_limits<float>::epsilon()) * (1 + 2 * sc * 65535);
              if (!(std::abs(LD(acc[3 * i + k]) - want) <= tolerance) && ++failures <= 5)
                FAIL_CHECK("s " << s << " n " << n << " repeat " << repeat << " pixel " << i << " channel " << k << ": "
                                << acc[3 * i + k] << " vs " << static_cast<double>(want));
            }
        }
  });
  CHECK(calls > 0);
  CHECK(failures == 0);
}
