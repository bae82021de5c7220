// lerp_row_or_linear (lightfield/kernels/lerp_row_or_linear.hpp): at every SIMD level the row read
// from the 16-bit linear copy is `lerp_row` of the codes, bit for bit, and nothing past the row is
// written; the copy is read exactly below AVX-512 (with Highway).
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/core/config.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/kernels/lerp_row_or_linear.hpp>

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

using mpr::detail::SimdLevel;

TEST_CASE("lerp_row_reads_linear: below AVX-512, where the codes' row is the Highway one", "[lerp_row_or_linear]") {
  STATIC_REQUIRE(mpr::detail::lerp_row_reads_linear(SimdLevel::portable) == (MPR_HAVE_HWY != 0));
  STATIC_REQUIRE(mpr::detail::lerp_row_reads_linear(SimdLevel::avx2) == (MPR_HAVE_HWY != 0));
  STATIC_REQUIRE(!mpr::detail::lerp_row_reads_linear(SimdLevel::avx512));
  STATIC_REQUIRE(!mpr::detail::lerp_row_reads_linear(SimdLevel::avx512vbmi));
}

TEST_CASE("lerp_row_or_linear: the row from the linear copy is the codes' row at every level", "[lerp_row_or_linear]") {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
  constexpr float kSentinel = -7.0f;
  int compared = 0;
  for (const std::size_t m : {3, 6, 21, 48, 96, 300, 1503}) {
    // m + 3 codes are read, and the copy has readable values past them (as the frames' buffers).
    std::vector<std::uint8_t> codes(m + 3 + 64);
    std::vector<std::uint16_t> linear(codes.size());
    for (std::size_t k = 0; k < codes.size(); ++k) {
      codes[k] = static_cast<std::uint8_t>(rng() % 256);
      linear[k] = lut[codes[k]];
    }
    for (const float ax : {0.0f, 0.5f, unit(rng)}) {
      mpr_test::for_each_simd_level([&](SimdLevel level) {
        std::vector<float> a(m + 16, kSentinel), b(m + 16, kSentinel);
        mpr::detail::lerp_row(codes.data(), lut, ax, 1.0f / 65535.0f, a.data(), m,
                              static_cast<const std::uint8_t*>(nullptr), level);
        mpr::detail::lerp_row_or_linear(codes.data(), linear.data(), lut, ax, 1.0f / 65535.0f, b.data(), m,
                                        static_cast<const std::uint8_t*>(nullptr), linear.data() + m, level);
        INFO("m " << m << " ax " << ax);
        REQUIRE(a == b);
        for (std::size_t j = m; j < b.size(); ++j) REQUIRE(b[j] == kSentinel);
        compared += static_cast<int>(m);
      });
    }
  }
  CHECK(compared > 5000); // one level (MPR_SIMD=portable) compares 5931 channels
}
