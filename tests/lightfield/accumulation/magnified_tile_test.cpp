// The magnified block (mpr/lightfield/accumulation/magnified_tile.hpp: each camera row resampled once into a
// stored row, output rows blended from two stored rows) at every instruction-set level against a
// long-double reference, for output rows closer together than the camera's rows going down and up
// the camera, steps of a small ratio (a plan of one period), within the plan's tolerance of one,
// of none, near 1 (no plan) and above 1; 8-bit codes read as codes or from a 16-bit linear copy,
// and float channels; and which blocks take that path.

#include "lightfield/channel_values.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/accumulation/magnified_tile.hpp>

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

// A step a float projection gives for 2 / 3: a plan takes it as 2 / 3 (within its tolerance).
constexpr double kNearTwoThirds = 2.0 / 3.0 + 2e-7;

template <class C>
void check_magnified_tile(bool with_linear) {
  std::mt19937_64 rng(2100 + sizeof(C));
  std::uniform_real_distribution<double> unit(0, 1);
  const mpr_test::ChannelValues<C> channels;
  const auto value = [&](C c) -> LD { return channels.value(c); };
  constexpr float kSentinel = -12345.0f;
  constexpr std::size_t kGuard = 29;
  int failures = 0, cases = 0;
  mpr_test::for_each_simd_level([&](mpr_test::SimdLevel level) {
    for (const std::size_t width : {2u, 19u, 300u})
      for (const double s : {0.5, 2.0 / 3.0, kNearTwoThirds, 0.7071, 0.9995, 1.0, 1.4583333, 2.0, 2.5})
        for (const std::size_t n : {1u, 16u, 17u, 45u, 190u}) {
          const std::size_t height = 12, rows = 2 + rng() % 10;
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
          // Output rows sy camera rows apart (|sy| < 1: a magnified view, going down or up the
          // camera), one of them on a camera row (vertical fraction 0).
          const double sy = (rng() % 2 == 0 ? 1 : -1) * (0.3 + 0.65 * unit(rng));
          const double y0 = sy > 0 ? unit(rng) : static_cast<double>(height - 2) + unit(rng) * 0.99;
          for (std::size_t r = 0; r < rows; ++r) {
            const double y = std::clamp(y0 + sy * static_cast<double>(r), 0.0, static_cast<double>(height - 1) - 1e-9);
            iy[r] = std::min(static_cast<int>(std::floor(y)), static_cast<int>(height) - 2);
            ay[r] = static_cast<float>(y - iy[r]);
          }
          ay[rows / 2] = 0.0f;
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
          // The codes' 16-bit table values, followed by 32 more (as the frames' copy is).
          std::vector<std::uint16_t> linear;
          if constexpr (std::is_same_v<C, std::uint8_t>) {
            if (with_linear) {
              for (const C c : image) linear.push_back(channels.lut[c]);
              linear.resize(linear.size() + 32, 0);
              t.linear = linear.data();
            }
          }
          t.ahead = image.data() + (rng() % image.size()); // prefetched only
          t.ahead_stride = static_cast<std::ptrdiff_t>(3 * width * sizeof(C));
          mpr::detail::ResampleTileWork work;
          CHECK(mpr::detail::resample_tile_stored(t, work, level));
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
            // The plan moves positions by up to 2e-7 n pixels for the step near 2 / 3.
            const LD moved = s == kNearTwoThirds ? LD(2e-7) * LD(n) : 0;
            const LD tolerance = sc * (1e-5L + moved) * spread + 8 * LD(std::numeric_limits<float>::epsilon()) * size;
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

TEST_CASE("resample_tile_stored: every level adds each row's blend of its two resampled camera rows, nothing else",
          "[magnified_tile]") {
  SECTION("8-bit sRGB codes") { check_magnified_tile<std::uint8_t>(false); }
  SECTION("8-bit sRGB codes with their 16-bit linear copy") { check_magnified_tile<std::uint8_t>(true); }
  SECTION("float channels") { check_magnified_tile<float>(false); }
}

TEST_CASE("magnified_rows: blocks whose rows repeat camera rows, moving at most one row at a time",
          "[magnified_tile]") {
  mpr::detail::ResampleTile<std::uint8_t> t;
  const auto with = [&](const std::vector<int>& iy) {
    t.iy = iy.data();
    t.rows = iy.size();
    return mpr::detail::magnified_rows(t);
  };
  CHECK(with({3, 3, 4, 5, 5, 6})); // 1.5x: 4 camera rows for 6 output rows
  CHECK(with({6, 5, 5, 4}));       // going up the camera
  CHECK_FALSE(with({3, 4, 5, 6})); // one output row per camera row: nothing to share
  CHECK_FALSE(with({3, 3, 5, 5})); // a jump of two rows
  CHECK_FALSE(with({3}));          // one row
}
