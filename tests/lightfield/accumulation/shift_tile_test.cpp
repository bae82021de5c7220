// The 2-D shift-and-add kernel (mpr/lightfield/accumulation/shift_tile.hpp) at every instruction-set
// level against a long-double reference: every output row gets its two camera rows' bilinear
// blend (or, at a vertical offset of 0, its one row; at offsets of 0 both ways, its texels),
// nothing outside the block is written (accumulators beside each row, the rows' ends, the working
// memory's end), whatever the accumulators' alignment. 8-bit codes also with their 16-bit linear
// copy (`ShiftTile::linear`: read instead of the codes below the VBMI level).

#include "lightfield/channel_values.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/accumulation/shift_tile.hpp>

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
void check_shift_tile(bool linear = false) {
  std::mt19937_64 rng(2004 + sizeof(C));
  std::uniform_real_distribution<double> unit(0, 1);
  const mpr_test::ChannelValues<C> channels;
  const auto value = [&](C c) -> LD { return channels.value(c); };
  constexpr float kSentinel = -12345.0f;
  constexpr std::size_t kGuard = 37;
  int failures = 0, cases = 0;
  mpr_test::for_each_simd_level([&](mpr_test::SimdLevel level) {
    for (const std::size_t pixels : {1u, 2u, 5u, 16u, 21u, 22u, 43u, 64u, 100u, 467u})
      for (const std::size_t rows : {1u, 2u, 8u}) {
        const std::size_t m = 3 * pixels;
        // Camera rows with room on both sides; the block starts a few texels in.
        const std::ptrdiff_t stride = static_cast<std::ptrdiff_t>(m + 3 + 3 * (rng() % 4));
        std::vector<C> texels(static_cast<std::size_t>(stride) * (rows + 1) + 3);
        for (C& c : texels) {
          if constexpr (std::is_same_v<C, float>)
            c = static_cast<float>(4 * unit(rng) - 1);
          else
            c = static_cast<C>(rng() % (std::is_same_v<C, std::uint8_t> ? 256 : 65536));
        }
        // Accumulator rows at any alignment (offset in floats), with room beside each row.
        const std::size_t offset = rng() % 16;
        const std::ptrdiff_t acc_stride = static_cast<std::ptrdiff_t>(m + kGuard + (rng() % 2) * 8);
        std::vector<float> acc(offset + static_cast<std::size_t>(acc_stride) * rows + kGuard, kSentinel);
        for (std::size_t r = 0; r < rows; ++r)
          for (std::size_t j = 0; j < m; ++j)
            acc[offset + r * static_cast<std::size_t>(acc_stride) + j] = static_cast<float>(unit(rng));
        const std::vector<float> acc0 = acc;
        mpr::detail::ShiftTile<C> t;
        t.texels = texels.data() + (stride - static_cast<std::ptrdiff_t>(m) - 3 > 0 ? 3 : 0);
        t.stride = stride;
        t.rows = rows;
        t.m = m;
        t.ax = cases % 5 == 0 ? 0.0f : static_cast<float>(unit(rng));
        t.ay = cases % 7 == 0 ? 1.0f : cases % 3 == 0 ? 0.0f : static_cast<float>(unit(rng));
        t.scale = channels.scale;
        t.lut = channels.lut;
        t.acc = acc.data() + offset;
        t.acc_stride = acc_stride;
        std::vector<std::uint16_t> values; // the 16-bit linear copy: each code's table entry
        if constexpr (std::is_same_v<C, std::uint8_t>)
          if (linear) {
            for (const C c : texels) values.push_back(channels.lut[c]);
            t.linear = values.data() + (t.texels - texels.data());
          }
        std::vector<float> work(mpr::detail::shift_tile_work(m) + kGuard, kSentinel);
        // Every other case asks for a camera ahead (prefetched only).
        const C* ahead = cases % 2 == 1 ? texels.data() : nullptr;
        mpr::detail::shift_tile(t, work.data(), ahead, stride, ahead != nullptr ? t.linear : nullptr, level);
        ++cases;
        for (std::size_t j = mpr::detail::shift_tile_work(m); j < work.size(); ++j)
          failures += work[j] != kSentinel ? 1 : 0;
        for (std::size_t at = 0; at < acc.size(); ++at) {
          const bool inside = at >= offset && (at - offset) / static_cast<std::size_t>(acc_stride) < rows &&
                              (at - offset) % static_cast<std::size_t>(acc_stride) < m;
          if (!inside) {
            if (acc[at] != acc0[at] && ++failures <= 5) FAIL_CHECK("written outside the block at " << at);
            continue;
          }
          const std::size_t r = (at - offset) / static_cast<std::size_t>(acc_stride);
          const std::size_t j = (at - offset) % static_cast<std::size_t>(acc_stride);
          const C* top = t.texels + static_cast<std::ptrdiff_t>(r) * stride;
          const C* bottom = top + stride;
          const LD s = LD(t.scale), ax = LD(t.ax), ay = LD(t.ay);
          const LD h0 = s * ((1 - ax) * value(top[j]) + ax * value(top[j + 3]));
          const LD h1 = s * ((1 - ax) * value(bottom[j]) + ax * value(bottom[j + 3]));
          const LD want = LD(acc0[at]) + (1 - ay) * h0 + ay * h1;
          const LD size = std::abs(LD(acc0[at])) + s * (std::abs(value(top[j])) + std::abs(value(top[j + 3])) +
                                                        std::abs(value(bottom[j])) + std::abs(value(bottom[j + 3])));
          if (!(std::abs(LD(acc[at]) - want) <= 8 * LD(std::numeric_limits<float>::epsilon()) * size) &&
              ++failures <= 5)
            FAIL_CHECK("pixels " << pixels << " rows " << rows << " offset " << offset << " row " << r << " channel "
                                 << j << ": " << acc[at] << " vs " << static_cast<double>(want));
        }
      }
  });
  CHECK(cases > 0);
  CHECK(failures == 0);
}

} // namespace

TEST_CASE("shift_tile: every level adds each row's bilinear blend of its two camera rows, nothing else",
          "[shift_tile]") {
  SECTION("8-bit sRGB codes") { check_shift_tile<std::uint8_t>(); }
  SECTION("8-bit sRGB codes with their 16-bit linear values") { check_shift_tile<std::uint8_t>(true); }
  SECTION("16-bit channels") { check_shift_tile<std::uint16_t>(); }
  SECTION("float channels") { check_shift_tile<float>(); }
}
