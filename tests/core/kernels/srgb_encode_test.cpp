// core/kernels/srgb_encode.hpp: the x86 step of the sRGB row encoder, at every level this CPU runs,
// against the per-channel encoder; and run_at hands each body the level it is compiled for.
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/core/color.hpp>
#include <mpr/core/kernels/srgb_encode.hpp>
#include <mpr/core/simd.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace {

using mpr::detail::SimdLevel;

// The step at `level`, called from a body compiled for that level.
std::size_t step_at(SimdLevel level, const float* in, std::uint8_t* out, std::size_t m) {
  std::size_t done = 0;
  mpr::detail::run_at(level, [&](auto tag) MPR_INLINE_LAMBDA {
    const auto& t = mpr::detail::srgb_tables;
    done = mpr::detail::linear_to_srgb8_step(tag, in, out, m, t.bin_entry.data(), mpr::detail::SrgbTables::kBins,
                                             t.poly[0].data());
  });
  return done;
}

} // namespace

TEST_CASE("run_at compiles a body for the level it is asked for and tells it which", "[simd]") {
  mpr_test::for_each_simd_level([](SimdLevel level) {
    SimdLevel seen = SimdLevel::portable;
    int plain = 0;
    mpr::detail::run_at(level, [&](auto tag) MPR_INLINE_LAMBDA { seen = decltype(tag)::value; });
    mpr::detail::run_at(level, [&]() MPR_INLINE_LAMBDA { ++plain; });
    // avx512vbmi runs the avx512 body: its VBMI steps are kernels of their own.
    CHECK(seen == std::min(level, SimdLevel::avx512));
    CHECK(plain == 1);
  });
  CHECK(mpr_test::simd_levels().front() == SimdLevel::portable);
  CHECK(mpr::detail::simd_level() <= mpr::detail::cpu_simd_level());
  STATIC_REQUIRE(mpr::detail::SimdTag<SimdLevel::avx2>::value == SimdLevel::avx2);
}

TEST_CASE("sRGB row step: a multiple of 16 channels at AVX-512, of 8 at AVX2, none at portable, codes bit for bit",
          "[color][simd]") {
  std::vector<float> in;
  for (int i = 0; i <= 4000; ++i) in.push_back(static_cast<float>(i) / 3000.0f - 0.1f);
  // Four floats either side of every threshold and of every bin edge: where the one-gather
  // step's split of a bin (SrgbTables::bin_entry) would first go wrong.
  const auto around = [&](float v) {
    for (int s = 0; s < 4; ++s) v = std::nextafter(v, 0.0f);
    for (int s = 0; s < 9; ++s, v = std::nextafter(v, 2.0f)) in.push_back(v);
  };
  for (int k = 0; k < 255; ++k) around(mpr::detail::srgb_tables.threshold[static_cast<std::size_t>(k)]);
  for (int i = 1; i < mpr::detail::SrgbTables::kBins; ++i)
    around(static_cast<float>(i) / static_cast<float>(mpr::detail::SrgbTables::kBins));
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (const float v : {nan, -inf, inf, -0.0f, 1.0f, 2.0f}) in.push_back(v);
  mpr_test::for_each_simd_level([&](SimdLevel level) {
    for (const std::size_t m : {std::size_t{0}, std::size_t{7}, std::size_t{8}, std::size_t{15}, std::size_t{16},
                                std::size_t{47}, in.size()}) {
      std::vector<std::uint8_t> out(m + 16, 7);
      const std::size_t done = step_at(level, in.data(), out.data(), m);
      const std::size_t width = level >= SimdLevel::avx512 ? 16 : level == SimdLevel::avx2 ? 8 : 0;
      CHECK(done == (width == 0 ? 0 : m - m % width));
      int wrong = 0;
      for (std::size_t j = 0; j < done; ++j) wrong += out[j] != mpr::linear_to_srgb8(in[j]) ? 1 : 0;
      CHECK(wrong == 0);
      for (std::size_t j = done; j < m + 16; ++j) CHECK(out[j] == 7); // nothing past what it reports
    }
  });
}

TEST_CASE("sRGB row step: every float of [0.0031308, 1) and every 16th below it gives its code", "[color][simd]") {
  // The AVX-512 step takes the nearest integer of a polynomial estimate wherever that estimate is
  // not within 1/1024 of k + 1/2 (SrgbTables::poly): exact only if the estimate's error stays
  // below that for every float it is asked about, which this checks for all of them.
  constexpr std::uint32_t kKnee = 0x3b4d2e1c, kOne = 0x3f800000, kChunk = 1U << 16; // 0.0031308f, 1.0f
  static_assert(kKnee < kOne);
  std::vector<float> in;
  in.reserve(kChunk);
  std::vector<std::uint8_t> out(kChunk);
  mpr_test::for_each_simd_level([&](SimdLevel level) {
    std::size_t wrong = 0, checked = 0;
    const auto check = [&] {
      const std::size_t done = step_at(level, in.data(), out.data(), in.size());
      for (std::size_t j = 0; j < done; ++j) wrong += out[j] != mpr::linear_to_srgb8(in[j]) ? 1 : 0;
      checked += done;
      in.clear();
    };
    for (std::uint32_t bits = 0; bits < kOne; bits += bits < kKnee ? 16 : 1) {
      in.push_back(std::bit_cast<float>(bits));
      if (in.size() == kChunk) check();
    }
    check();
    CHECK(wrong == 0);
    CHECK(checked >= (level >= SimdLevel::avx2 ? (kOne - kKnee) : 0));
  });
}
