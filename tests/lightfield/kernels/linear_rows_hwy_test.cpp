// The shift-and-add rows on 16-bit linear values (mpr/lightfield/kernels/linear_rows_hwy.inl,
// called through kernels/lerp_row_hwy.hpp) at every level: hand-worked sums and blends, and the
// same floats as the 8-bit kernels give for the codes whose table values the rows hold.

#include <mpr/core/config.hpp>

#include <catch2/catch.hpp>

#if MPR_HAVE_HWY
#include "simd_levels.hpp"

#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/kernels/lerp_row_hwy.hpp>

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

TEST_CASE("sum_linear_rows_hwy: the rows' values summed and added once", "[linear_rows_hwy]") {
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    for (std::size_t k : {std::size_t{1}, std::size_t{3}, std::size_t{300}})
      for (std::size_t m : {std::size_t{5}, std::size_t{64}, std::size_t{203}}) {
        std::vector<std::vector<std::uint16_t>> rows(k, std::vector<std::uint16_t>(m));
        std::vector<const std::uint16_t*> ptr;
        for (std::size_t c = 0; c < k; ++c) {
          for (std::size_t j = 0; j < m; ++j)
            rows[c][j] = static_cast<std::uint16_t>(4 * ((13 * j + 29 * c + 1) % 4096));
          ptr.push_back(rows[c].data());
        }
        std::vector<float> acc(m + 1, 0.5f);
        acc[m] = -7.0f;
        // 0.25 sum of multiples of 4 below 2^14, 300 of them: whole numbers below 2^24, exact.
        mpr::kernels::sum_linear_rows_hwy(ptr.data(), k, 0.25f, acc.data(), m, level);
        int wrong = 0;
        for (std::size_t j = 0; j < m; ++j) {
          long sum = 0;
          for (std::size_t c = 0; c < k; ++c) sum += rows[c][j] / 4;
          wrong += acc[j] != 0.5f + static_cast<float>(sum) ? 1 : 0;
        }
        INFO("k " << k << ", m " << m);
        CHECK(wrong == 0);
        CHECK(acc[m] == -7.0f);
      }
  });
}

TEST_CASE("lerp_row_linear_hwy: the row h = scale ((1 - ax) a[j] + ax a[j + 3]), and its blend", "[linear_rows_hwy]") {
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    for (std::size_t m : {std::size_t{1}, std::size_t{7}, std::size_t{48}, std::size_t{100}}) {
      std::vector<std::uint16_t> a(m + 3);
      for (std::size_t j = 0; j < a.size(); ++j) a[j] = static_cast<std::uint16_t>(4 * j);
      // ax = 1/4, scale 2: 1.5 (4 j) + 0.5 (4 j + 12) = 8 j + 6, exact.
      std::vector<float> h(m + 1, -7.0f), hp(m, 1.0f), acc(m + 1, 0.25f);
      acc[m] = -7.0f;
      mpr::kernels::lerp_row_linear_hwy(a.data(), 0.25f, 2.0f, h.data(), m, a.data(), level);
      int wrong = 0;
      for (std::size_t j = 0; j < m; ++j) wrong += h[j] != static_cast<float>(8 * j + 6) ? 1 : 0;
      std::fill(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(m), 0.0f);
      // acc += 0.5 hp + 0.5 h = 0.5 + 4 j + 3.
      mpr::kernels::lerp_blend_row_linear_hwy(a.data(), 0.25f, 2.0f, h.data(), m, nullptr, hp.data(), 0.5f, 0.5f,
                                              acc.data(), level);
      for (std::size_t j = 0; j < m; ++j) {
        wrong += h[j] != static_cast<float>(8 * j + 6) ? 1 : 0;
        wrong += acc[j] != 0.25f + 0.5f + static_cast<float>(4 * j + 3) ? 1 : 0;
      }
      INFO("m " << m);
      CHECK(wrong == 0);
      CHECK(h[m] == -7.0f);
      CHECK(acc[m] == -7.0f);
    }
  });
}

TEST_CASE("linear rows: the 8-bit kernels' floats for the codes whose table values they read", "[linear_rows_hwy]") {
  const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
  const float scale = mpr::Srgb8Texel::scale;
  std::mt19937 rng(45);
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    for (std::size_t m : {std::size_t{3}, std::size_t{61}, std::size_t{600}}) {
      const std::size_t k = 49;
      std::vector<std::vector<std::uint8_t>> codes(k, std::vector<std::uint8_t>(m + 3));
      std::vector<std::vector<std::uint16_t>> values(k, std::vector<std::uint16_t>(m + 3));
      std::vector<const std::uint8_t*> p8;
      std::vector<const std::uint16_t*> p16;
      for (std::size_t c = 0; c < k; ++c) {
        for (std::size_t j = 0; j < m + 3; ++j) values[c][j] = lut[codes[c][j] = static_cast<std::uint8_t>(rng())];
        p8.push_back(codes[c].data());
        p16.push_back(values[c].data());
      }
      std::vector<float> sum8(m, 0.125f), sum16(m, 0.125f);
      mpr::kernels::sum_code_rows_hwy(p8.data(), k, lut, scale, sum8.data(), m, level);
      mpr::kernels::sum_linear_rows_hwy(p16.data(), k, scale, sum16.data(), m, level);
      const float ax = 0.3f, ay = 0.7f;
      std::vector<float> hp(m), h8(m), h16(m), acc8(m, 0.5f), acc16(m, 0.5f);
      for (std::size_t j = 0; j < m; ++j) hp[j] = static_cast<float>(rng() % 1000) / 999.0f;
      mpr::kernels::lerp_blend_row_hwy(p8[1], lut, ax, scale, h8.data(), m, nullptr, hp.data(), 1 - ay, ay, acc8.data(),
                                       level);
      mpr::kernels::lerp_blend_row_linear_hwy(p16[1], ax, scale, h16.data(), m, nullptr, hp.data(), 1 - ay, ay,
                                              acc16.data(), level);
      INFO("m " << m);
      CHECK(sum8 == sum16);
      CHECK(h8 == h16);
      CHECK(acc8 == acc16);
    }
  });
}

#else
TEST_CASE("linear rows: Highway not found", "[linear_rows_hwy]") { SUCCEED("Highway not found: kernel not built"); }
#endif
