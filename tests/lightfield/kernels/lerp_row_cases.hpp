#pragma once
// The cases every implementation of the fractional-shift row passes (lightfield/kernels/):
// h[j] = scale ((1 - ax) lut[a[j]] + ax lut[a[j + 3]]), checked against hand-worked values and a
// closed form, at every SIMD level this CPU runs.
#include "simd_levels.hpp"

#include <mpr/lightfield/frame_set.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mpr_test {

/// Kernel(a, lut, ax, scale, h, m, ahead, level) is one implementation of the row.
template <class Kernel>
void check_lerp_row_kernel(const Kernel& kernel) {
  std::array<std::uint16_t, 256> times4{}; // lut[c] = 4 c: values exact in float
  for (std::size_t c = 0; c < 256; ++c) times4[c] = static_cast<std::uint16_t>(4 * c);
  for_each_simd_level([&](SimdLevel level) {
    DYNAMIC_SECTION("hand-worked row: 2 pixels, ax = 0.25, scale = 0.5 (h = 1.5 a[j] + 0.5 a[j + 3]), level "
                    << mpr::detail::simd_level_name(level)) {
      const std::uint8_t a[9] = {0, 51, 102, 255, 153, 204, 10, 20, 30};
      float h[7] = {0, 0, 0, 0, 0, 0, -7};
      kernel(a, times4.data(), 0.25f, 0.5f, h, 6, nullptr, level);
      const float expected[6] = {127.5f, 153.0f, 255.0f, 387.5f, 239.5f, 321.0f};
      for (int j = 0; j < 6; ++j) CHECK(h[j] == expected[j]);
      CHECK(h[6] == -7); // nothing written past the row
    }
    DYNAMIC_SECTION("every length from 1 to 300 channels, and a long row, against the closed form, level "
                    << mpr::detail::simd_level_name(level)) {
      std::vector<std::uint8_t> a(5000);
      for (std::size_t j = 0; j < a.size(); ++j) a[j] = static_cast<std::uint8_t>((7 * j + 3) % 256);
      for (std::size_t m : {std::size_t{1}, std::size_t{4200}, std::size_t{4990}})
        for (std::size_t len = m; len <= (m == 1 ? 300 : m); ++len) {
          std::vector<float> h(len + 1, -7.0f);
          kernel(a.data(), times4.data(), 0.75f, 0.25f, h.data(), len, a.data() + 1, level);
          bool ok = h[len] == -7.0f;
          for (std::size_t j = 0; j < len; ++j) // 0.25 (0.25 * 4 a[j] + 0.75 * 4 a[j + 3])
            ok = ok && h[j] == static_cast<float>(0.25 * a[j] + 0.75 * a[j + 3]);
          INFO("length " << len);
          REQUIRE(ok);
        }
    }
    DYNAMIC_SECTION("the sRGB decode table, ax = 0 and 1 and between, within float rounding, level "
                    << mpr::detail::simd_level_name(level)) {
      const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
      std::vector<std::uint8_t> a(803);
      for (std::size_t j = 0; j < a.size(); ++j) a[j] = static_cast<std::uint8_t>((j * 37) % 256);
      for (float ax : {0.0f, 0.3f, 1.0f}) {
        std::vector<float> h(800);
        kernel(a.data(), lut, ax, mpr::Srgb8Texel::scale, h.data(), h.size(), nullptr, level);
        double worst = 0;
        for (std::size_t j = 0; j < h.size(); ++j) {
          const double v = ((1.0 - ax) * lut[a[j]] + ax * lut[a[j + 3]]) / 65535.0;
          worst = std::max(worst, std::abs(h[j] - v));
        }
        INFO("ax " << ax);
        CHECK(worst <= 2e-7); // a few float roundings of values below 1
      }
    }
  });
}

} // namespace mpr_test
