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
#endif
