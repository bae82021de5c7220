#include <mpr/core/color.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

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
}
