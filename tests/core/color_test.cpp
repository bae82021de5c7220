#include <mpr/core/color.hpp>

#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

TEST_CASE("8-bit sRGB round trip is exact for every code", "[color]") {
  for (int k = 0; k < 256; ++k) {
    const auto code = static_cast<std::uint8_t>(k);
    CHECK(mpr::linear_to_srgb8(mpr::srgb8_to_linear(code)) == code);
  }
}

TEST_CASE("linear_to_srgb8 equals correctly rounded encoding", "[color]") {
  // Dense sweep plus the exact float neighbours of every decision boundary.
  for (int i = 0; i <= 200000; ++i) {
    const float x = static_cast<float>(i) / 200000.0f;
    const double exact = 255.0 * mpr::srgb_encode(static_cast<double>(x));
    const int expected = static_cast<int>(std::floor(exact + 0.5));
    INFO("x = " << x);
    REQUIRE(mpr::linear_to_srgb8(x) == expected);
  }
  for (int k = 0; k < 255; ++k) {
    const double boundary = mpr::srgb_decode((k + 0.5) / 255.0);
    float f = static_cast<float>(boundary);
    const float below = std::nextafter(f, 0.0f), above = std::nextafter(f, 1.0f);
    for (float x : {below, f, above}) {
      const int expected = static_cast<double>(x) >= boundary ? k + 1 : k;
      INFO("k = " << k << " x = " << x);
      REQUIRE(mpr::linear_to_srgb8(x) == expected);
    }
  }
}

TEST_CASE("to_rgb8 clamps and maps NaN to zero", "[color]") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  CHECK(mpr::to_rgb8(mpr::Color(-1.0f, 2.0f, nan)) == mpr::Rgb8{0, 255, 0});
  CHECK(mpr::to_rgb8(mpr::Color(-inf, inf, 0.5f)) == mpr::Rgb8{0, 255, 188});
  CHECK(mpr::to_color(mpr::Rgb8{0, 255, 188}).isApprox(mpr::Color(0.0f, 1.0f, 0.5029f), 1e-3f));
}

TEST_CASE("PixelTraits store colours in each pixel type", "[color]") {
  const mpr::Color c(0.25f, 0.5f, 1.0f);
  CHECK(mpr::PixelTraits<mpr::Color>::from_color(c).isApprox(c, 0.0f));
  CHECK(mpr::PixelTraits<mpr::Rgb8>::from_color(c) == mpr::to_rgb8(c));
  CHECK(mpr::PixelTraits<float>::from_color(c) == Approx(0.2126 * 0.25 + 0.7152 * 0.5 + 0.0722));
  CHECK(mpr::PixelTraits<float>::from_color(3.5f) == 3.5f);
  STATIC_REQUIRE(mpr::StorableAs<mpr::Rgb8, mpr::Color>);
  STATIC_REQUIRE(mpr::StorableAs<float, float>);
  STATIC_REQUIRE_FALSE(mpr::StorableAs<mpr::Rgb8, float>);
  // The row form (used by the renderer for whole rows) stores what from_color stores, pixel by
  // pixel, and nothing past the end.
  std::vector<mpr::Color> row;
  for (int i = 0; i < 37; ++i)
    row.emplace_back(static_cast<float>(i) / 36.0f, 1.0f - static_cast<float>(i) / 40.0f,
                     static_cast<float>(i % 5) * 0.3f - 0.2f);
  std::vector<mpr::Rgb8> out(row.size() + 1, mpr::Rgb8{7, 7, 7});
  mpr::PixelTraits<mpr::Rgb8>::from_colors(row.data(), out.data(), row.size());
  int wrong = 0;
  for (std::size_t i = 0; i < row.size(); ++i) wrong += out[i] == mpr::to_rgb8(row[i]) ? 0 : 1;
  CHECK(wrong == 0);
  CHECK(out.back() == mpr::Rgb8{7, 7, 7});
}

TEST_CASE("linear_to_srgb8_row gives the per-channel codes bit for bit", "[color]") {
  // Every channel value that matters: both float neighbours of each code boundary, a dense
  // sweep of [0, 1], and the values clamped or mapped to 0 (negative, -0, NaN, infinities,
  // subnormals, >= 1), at every position of a 16-wide vector and in the tails.
  std::vector<float> in;
  for (int k = 0; k < 255; ++k) {
    const float t = mpr::detail::srgb_tables.threshold[static_cast<std::size_t>(k)];
    in.push_back(t);
    in.push_back(std::nextafter(t, 0.0f));
    in.push_back(std::nextafter(t, 2.0f));
  }
  for (int i = 0; i <= 100000; ++i) in.push_back(static_cast<float>(i) / 100000.0f);
  const float inf = std::numeric_limits<float>::infinity();
  for (const float v : {-1.0f, -0.0f, 0.0f, std::numeric_limits<float>::quiet_NaN(), -inf, inf,
                        std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::min(), 1.0f,
                        std::nextafter(1.0f, 0.0f), std::nextafter(1.0f, 2.0f), 1e30f, -1e30f})
    for (int r = 0; r < 17; ++r) in.push_back(v);
  // Every level this CPU runs (AVX-512 and AVX2 have their own 16- and 8-wide steps).
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    for (const std::size_t length : {in.size(), std::size_t{0}, std::size_t{1}, std::size_t{15}, std::size_t{16},
                                     std::size_t{17}, std::size_t{33}}) {
      for (std::size_t offset = 0; offset < 3; ++offset) {
        const std::size_t m = std::min(length, in.size() - offset);
        std::vector<std::uint8_t> out(m + 4, 7);
        mpr::linear_to_srgb8_row(in.data() + offset, out.data(), m, level);
        int wrong = 0;
        for (std::size_t j = 0; j < m; ++j) wrong += out[j] != mpr::linear_to_srgb8(in[offset + j]) ? 1 : 0;
        CHECK(wrong == 0);
        CHECK(out[m] == 7); // nothing written past the end
      }
    }
  });
}
