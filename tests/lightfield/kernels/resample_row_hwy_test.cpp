// The Highway resampling row (lightfield/kernels/resample_row_hwy.inl, `resample_row_hwy`) at
// every level the CPU runs, the AVX3_DL target at avx512vbmi included (`resample_row` takes the
// VBMI step there): a hand-worked row (8-bit codes and float channels), and the plain loop `resample_row_portable` on
// random rows (codes of both halves of the byte range, the sRGB table's cubic decode and another table's gather, steps
// of magnified and reduced output) with the row ending where its allocation ends.
#include <mpr/core/config.hpp>

#include <catch2/catch.hpp>

#if MPR_HAVE_HWY
#include "simd_levels.hpp"

#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/kernels/lerp_row_hwy.hpp>
#include <mpr/lightfield/kernels/magnified_plan.hpp>
#include <mpr/lightfield/kernels/resample_row.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

TEST_CASE("resample_row_hwy: a hand-worked row at every level", "[resample_row_hwy]") {
  std::array<std::uint16_t, 256> times4{}; // lut[c] = 4 c; with scale 1/4 the value is the code
  for (std::size_t c = 0; c < 256; ++c) times4[c] = static_cast<std::uint16_t>(4 * c);
  // Four texels (r g b); pixels at 0.25 + 0.75 i: pairs 0, 1, 1, 2, 2 (clamped to the last pair),
  // fractions 0.25, 0, 0.75, 0.5 and 1 (3.25 - 2 clamped).
  const std::vector<std::uint8_t> row = {0, 10, 200, 100, 20, 250, 50, 30, 0, 255, 40, 128};
  const float want[5][3] = {
      {25, 12.5f, 212.5f}, {100, 20, 250}, {62.5f, 27.5f, 62.5f}, {152.5f, 35, 64}, {255, 40, 128}};
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    std::vector<float> h(3 * 5 + 20, -1.0f);
    mpr::kernels::resample_row_hwy(row.data(), 4, times4.data(), 0.25, 0.75, 0.25f, h.data(), 5, nullptr, level);
    for (std::size_t i = 0; i < 5; ++i)
      for (std::size_t k = 0; k < 3; ++k) {
        INFO("pixel " << i << " channel " << k);
        CHECK(h[3 * i + k] == Approx(want[i][k]).margin(1e-4));
      }
    int written_past = 0;
    for (std::size_t j = 15; j < h.size(); ++j) written_past += h[j] != -1.0f ? 1 : 0;
    CHECK(written_past == 0);
    // The same row as float channels (the table unused), scaled by 2.
    const std::vector<float> channels(row.begin(), row.end());
    std::vector<float> hf(3 * 5 + 20, -1.0f);
    mpr::kernels::resample_row_hwy(channels.data(), 4, nullptr, 0.25, 0.75, 2.0f, hf.data(), 5, nullptr, level);
    for (std::size_t i = 0; i < 5; ++i)
      for (std::size_t k = 0; k < 3; ++k) {
        INFO("float channels: pixel " << i << " channel " << k);
        CHECK(hf[3 * i + k] == Approx(2 * want[i][k]).margin(1e-4));
      }
    CHECK(std::all_of(hf.begin() + 15, hf.end(), [](float v) { return v == -1.0f; }));
  });
}

TEST_CASE("resample_row_hwy: the plain loop's values on random rows, every level", "[resample_row_hwy]") {
  std::mt19937_64 rng(45);
  std::uniform_real_distribution<double> unit(0, 1);
  std::array<std::uint16_t, 256> other{}; // not the sRGB table: the kernels gather from it
  for (std::size_t c = 0; c < 256; ++c) other[c] = static_cast<std::uint16_t>((c * c * 3 + 17 * c) % 65536);
  const std::uint16_t* luts[2] = {mpr::Srgb8Texel::linear16(), other.data()};
  int failures = 0, cases = 0;
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    for (const std::uint16_t* lut : luts)
      for (const std::size_t texels : {2u, 5u, 64u, 1400u})
        for (const double s : {0.5, 2.0 / 3.0, 0.9999, 1.0, 1.4583333, 2.5, 5.25})
          for (const std::size_t n : {1u, 3u, 4u, 7u, 8u, 16u, 17u, 31u, 200u}) {
            // Exactly the row's bytes: a read past its last pair leaves the allocation.
            std::vector<std::uint8_t> row(3 * texels);
            for (std::uint8_t& c : row) c = static_cast<std::uint8_t>(rng() % 256);
            const double reach = static_cast<double>(texels - 1) * (rng() % 4 == 0 ? 1.3 : 1.0);
            const double x = std::max(0.0, reach - s * static_cast<double>(n - 1)) * unit(rng);
            const float scale = 1.0f / 65535;
            std::vector<float> got(3 * n + 8, -1.0f), want(3 * n);
            mpr::kernels::resample_row_hwy(row.data(), texels, lut, x, s, scale, got.data(), n, nullptr, level);
            mpr::detail::resample_row_portable(row.data(), texels, lut, x, s, scale, want.data(), n);
            ++cases;
            for (std::size_t j = 3 * n; j < got.size(); ++j) failures += got[j] != -1.0f ? 1 : 0;
            for (std::size_t j = 0; j < 3 * n; ++j)
              if (!(std::abs(got[j] - want[j]) <= 2e-5f * scale * 65535) && ++failures <= 5)
                FAIL_CHECK("texels " << texels << " s " << s << " n " << n << " value " << j << ": " << got[j] << " vs "
                                     << want[j]);
          }
  });
  CHECK(cases > 0);
  CHECK(failures == 0);
}

TEST_CASE("plan_magnified_hwy: one period for a step of a small ratio, the whole row otherwise, none near 1",
          "[resample_row_hwy]") {
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    using mpr::kernels::PlanOutcome;
    mpr::kernels::MagnifiedPlan plan;
    // 1.5x: 3 pixels a pattern, 2 texels on; a period of 9 vectors whatever the lanes (4, 8, 16).
    REQUIRE(mpr::kernels::plan_magnified_hwy(plan, 3.25, 2.0 / 3.0, 2000, 1400, level) == PlanOutcome::made);
    CHECK(plan.period == 9);
    CHECK(plan.advance == 6 * plan.lanes); // 3 N pixels, 2 N texels

    // Within the tolerance over the row: the same period (a float projection's step).
    REQUIRE(mpr::kernels::plan_magnified_hwy(plan, 3.25, 2.0 / 3.0 + 2e-7, 2000, 1400, level) == PlanOutcome::made);
    CHECK(plan.period == 9);
    // 2x: 2 pixels, 1 texel; 3 vectors.
    REQUIRE(mpr::kernels::plan_magnified_hwy(plan, 0.5, 0.5, 300, 1400, level) == PlanOutcome::made);
    CHECK(plan.period == 3);
    CHECK(2 * plan.advance == 3 * plan.lanes); // N pixels, N / 2 texels
    // No ratio of 16 or less within the tolerance: the whole row.
    REQUIRE(mpr::kernels::plan_magnified_hwy(plan, 0.5, 0.70710678, 300, 1400, level) == PlanOutcome::made);
    CHECK(plan.period == (900 + plan.lanes - 1) / plan.lanes);
    CHECK(plan.advance == 0);
    // A ratio whose last pixel falls past the row's last texel (its pairs clamped): the whole row.
    REQUIRE(mpr::kernels::plan_magnified_hwy(plan, 0.5, 0.5, 300, 100, level) == PlanOutcome::made);
    CHECK(plan.advance == 0);
    // Float positions within 1e-3 of a step of 1 (not 1): no plan; 1 itself: a period of one texel.
    CHECK(mpr::kernels::plan_magnified_hwy(plan, 0.5, 0.9995, 300, 1400, level) == PlanOutcome::no_plan);
    REQUIRE(mpr::kernels::plan_magnified_hwy(plan, 0.5, 1.0, 300, 1400, level) == PlanOutcome::made);
    CHECK(plan.period == 3);
    CHECK(plan.advance == 3 * plan.lanes); // N pixels, N texels
  });
}

TEST_CASE("resample_planned_hwy: every lane's pair within one vector of values, blended in the same pass",
          "[resample_row_hwy]") {
  std::mt19937_64 rng(46);
  std::uniform_real_distribution<double> unit(0, 1);
  int failures = 0, cases = 0;
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    for (const double s : {0.25, 0.5, 0.6, 2.0 / 3.0, 0.7071, 0.8, 0.99, 1.0})
      for (const std::size_t n : {1u, 5u, 16u, 17u, 100u, 333u}) {
        const std::size_t texels = static_cast<std::size_t>(std::ceil(s * static_cast<double>(n))) + 40;
        const double x = 3 * unit(rng);
        INFO("s " << s << " n " << n);
        mpr::kernels::MagnifiedPlan plan;
        REQUIRE(mpr::kernels::plan_magnified_hwy(plan, x, s, n, texels, level) == mpr::kernels::PlanOutcome::made);
        // Values read past the last texel (N + 3 values: the plan's reads) as the frames allow.
        std::vector<std::uint16_t> row(3 * texels + 64);
        for (auto& v : row) v = static_cast<std::uint16_t>(rng() % 65536);
        const std::size_t j_first = static_cast<std::size_t>(x);
        std::vector<float> h(3 * n, -1.0f), above(3 * n), acc(3 * n), acc0;
        for (auto& a : above) a = static_cast<float>(unit(rng) * 65535);
        for (auto& a : acc) a = static_cast<float>(unit(rng));
        acc0 = acc;
        const float w0 = 0.3f, w1 = 0.7f;
        mpr::kernels::resample_planned_hwy(plan, row.data() + 3 * j_first, h.data(), 0, 3 * n, above.data(), w0, w1,
                                           acc.data());
        ++cases;
        for (std::size_t c = 0; c < 3 * n; ++c) {
          const double xi = x + s * static_cast<double>(c / 3);
          const std::size_t j = std::min(static_cast<std::size_t>(xi), texels - 2);
          const double f = std::clamp(xi - static_cast<double>(j), 0.0, 1.0);
          const double v0 = row[3 * j + c % 3], v1 = row[3 * j + 3 + c % 3];
          const double want = v0 + f * (v1 - v0);
          const double blended = acc0[c] + w0 * above[c] + w1 * want;
          if (!(std::abs(h[c] - want) <= 2e-5 * std::abs(v1 - v0) + 4e-7 * (v0 + v1)) ||
              !(std::abs(acc[c] - blended) <= 1e-5 * (std::abs(v1 - v0) + above[c]) + 4e-7 * (v0 + v1) + 1e-6)) {
            if (++failures <= 5)
              FAIL_CHECK("s " << s << " n " << n << " channel " << c << ": " << h[c] << " vs " << want << ", acc "
                              << acc[c] << " vs " << blended);
          }
        }
      }
  });
  CHECK(cases > 0);
  CHECK(failures == 0);
}

#endif
