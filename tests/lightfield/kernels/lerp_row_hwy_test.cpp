#include <mpr/core/config.hpp>

#include <catch2/catch.hpp>

#if MPR_HAVE_HWY
#include "lightfield/kernels/lerp_row_cases.hpp"

#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/kernels/lerp_row_hwy.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

// Every level the CPU runs, avx512vbmi (the AVX3_DL target) included.
TEST_CASE("lerp_row_hwy: the fractional-shift row at every level", "[lerp_row_hwy]") {
  mpr_test::check_lerp_row_kernel([](const std::uint8_t* a, const std::uint16_t* lut, float ax, float scale, float* h,
                                     std::size_t m, const std::uint8_t* ahead, mpr::detail::SimdLevel level) {
    mpr::kernels::lerp_row_hwy(a, lut, ax, scale, h, m, ahead, level);
  });
}

TEST_CASE("srgb cubic decode: the rounded cubic is the sRGB decode table, code by code", "[lerp_row_hwy]") {
  const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
  const auto& cubic = mpr::kernels::srgb_cubic_table();
  int differ = 0;
  for (std::size_t c = 0; c < 256; ++c) differ += cubic[c] != lut[c] ? 1 : 0;
  CHECK(differ == 0);
  CHECK(mpr::kernels::srgb_cubic_matches(lut));
  std::array<std::uint16_t, 256> other{};
  for (std::size_t c = 0; c < 256; ++c) other[c] = lut[c];
  other[200] = static_cast<std::uint16_t>(other[200] + 1); // one entry off: another table
  CHECK_FALSE(mpr::kernels::srgb_cubic_matches(other.data()));
  // The kernels' vector decode at every level: with ax = 0 and scale 1 the row is the decoded
  // codes themselves, exactly (every code, at every position of a vector).
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    std::vector<std::uint8_t> a(3 * 256 + 3);
    for (std::size_t j = 0; j < a.size(); ++j) a[j] = static_cast<std::uint8_t>((j * 7 + j / 256) % 256);
    std::vector<float> h(3 * 256);
    mpr::kernels::lerp_row_hwy(a.data(), lut, 0.0f, 1.0f, h.data(), h.size(), nullptr, level);
    int wrong = 0;
    for (std::size_t j = 0; j < h.size(); ++j) wrong += h[j] != static_cast<float>(lut[a[j]]) ? 1 : 0;
    CHECK(wrong == 0);
  });
}

TEST_CASE("lerp_blend_row_hwy: the row, and the row above and this one blended into accumulators", "[lerp_row_hwy]") {
  std::array<std::uint16_t, 256> times4{}; // lut[c] = 4 c: every value below exact in float
  for (std::size_t c = 0; c < 256; ++c) times4[c] = static_cast<std::uint16_t>(4 * c);
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    for (std::size_t m : {std::size_t{6}, std::size_t{61}, std::size_t{1200}}) {
      std::vector<std::uint8_t> a(m + 3);
      for (std::size_t j = 0; j < a.size(); ++j) a[j] = static_cast<std::uint8_t>((11 * j + 5) % 256);
      std::vector<float> h(m + 1, -7.0f), hp(m), acc(m + 1, -7.0f);
      for (std::size_t j = 0; j < m; ++j) {
        hp[j] = static_cast<float>(j % 9);
        acc[j] = 0.5f;
      }
      // h = 0.5 (0.5 4 a[j] + 0.5 4 a[j + 3]) = a[j] + a[j + 3]; acc += 0.75 hp + 0.25 h.
      mpr::kernels::lerp_blend_row_hwy(a.data(), times4.data(), 0.5f, 0.5f, h.data(), m, nullptr, hp.data(), 0.75f,
                                       0.25f, acc.data(), level);
      int wrong = 0;
      for (std::size_t j = 0; j < m; ++j) {
        const float want_h = static_cast<float>(a[j] + a[j + 3]);
        wrong += h[j] != want_h || acc[j] != 0.5f + 0.75f * hp[j] + 0.25f * want_h ? 1 : 0;
      }
      INFO("m " << m);
      CHECK(wrong == 0);
      CHECK(h[m] == -7.0f); // nothing written past the row
      CHECK(acc[m] == -7.0f);
    }
  });
}

TEST_CASE("sum_code_rows_hwy: the rows' table values summed and added once, any table", "[lerp_row_hwy]") {
  std::array<std::uint16_t, 256> times4{};
  for (std::size_t c = 0; c < 256; ++c) times4[c] = static_cast<std::uint16_t>(4 * c);
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    for (std::size_t k : {std::size_t{1}, std::size_t{3}, std::size_t{300}})
      for (std::size_t m : {std::size_t{5}, std::size_t{64}, std::size_t{203}}) {
        std::vector<std::vector<std::uint8_t>> rows(k, std::vector<std::uint8_t>(m));
        std::vector<const std::uint8_t*> ptr;
        for (std::size_t c = 0; c < k; ++c) {
          for (std::size_t j = 0; j < m; ++j) rows[c][j] = static_cast<std::uint8_t>((13 * j + 29 * c + 1) % 256);
          ptr.push_back(rows[c].data());
        }
        std::vector<float> acc(m + 1, 0.5f);
        acc[m] = -7.0f;
        // 0.25 sum 4 a = sum a: whole numbers below 2^24, exact.
        mpr::kernels::sum_code_rows_hwy(ptr.data(), k, times4.data(), 0.25f, acc.data(), m, level);
        int wrong = 0;
        for (std::size_t j = 0; j < m; ++j) {
          long sum = 0;
          for (std::size_t c = 0; c < k; ++c) sum += rows[c][j];
          wrong += acc[j] != 0.5f + static_cast<float>(sum) ? 1 : 0;
        }
        INFO("k " << k << ", m " << m);
        CHECK(wrong == 0);
        CHECK(acc[m] == -7.0f);
      }
  });
}

#else
TEST_CASE("lerp_row_hwy: Highway not found", "[lerp_row_hwy]") { SUCCEED("Highway not found: kernel not built"); }
#endif
