// The resampling row kernel (lightfield/kernels/resample_row.hpp): every SIMD level against a
// long-double reference, for 8-bit codes and float channels, steps below, at and above one camera
// pixel (and past the VBMI step's limit, where the plain loop runs), positions that reach the
// row's last texel pair and run past it (clamped), and lengths around the 16-pixel step. Nothing
// past the row's end is written.
#include "lightfield/channel_values.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/kernels/resample_row.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <type_traits>
#include <vector>

namespace {

using LD = long double;

template <class C>
void check_resample() {
  std::mt19937_64 rng(2026 + sizeof(C));
  std::uniform_real_distribution<double> unit(0, 1);
  const mpr_test::ChannelValues<C> channels;
  const std::uint16_t* lut = channels.lut;
  const float scale = channels.scale;
  const auto value = [&](C c) -> LD { return channels.value(c); };
  constexpr float kSentinel = -12345.0f;
  constexpr std::size_t kGuard = 50;
  int failures = 0, cases = 0;
  mpr_test::for_each_simd_level([&](mpr_test::SimdLevel level) {
    for (const std::size_t texels : {2u, 3u, 17u, 41u, 300u, 1400u})
      for (const double s : {0.3, 0.75, 1.0, 1.4583333, 2.0, 2.5, 3.7})
        for (const std::size_t n : {0u, 1u, 15u, 16u, 17u, 33u, 100u, 257u}) {
          std::vector<C> row(3 * texels);
          for (C& c : row) {
            if constexpr (std::is_same_v<C, float>)
              c = static_cast<float>(4 * unit(rng) - 1);
            else
              c = static_cast<C>(rng() % 256);
          }
          // Mostly inside the row; one case in four runs past its end (the clamped last pair).
          const double reach = static_cast<double>(texels - 1) * (rng() % 4 == 0 ? 1.5 : 1.0);
          const double x = n > 1 ? std::max(0.0, reach - s * static_cast<double>(n - 1)) * unit(rng)
                                 : unit(rng) * static_cast<double>(texels - 1);
          std::vector<float> h(3 * n + kGuard, kSentinel);
          // Every other case asks for a next row ahead (prefetched only: the same values).
          const std::vector<C> next(row.rbegin(), row.rend());
          mpr::detail::resample_row(row.data(), texels, lut, x, s, scale, h.data(), n,
                                    cases % 2 == 1 ? next.data() : nullptr, level);
          ++cases;
          for (std::size_t j = 3 * n; j < h.size(); ++j) failures += h[j] != kSentinel ? 1 : 0;
          for (std::size_t i = 0; i < n; ++i) {
            const LD xi = LD(x) + LD(s) * LD(i);
            const LD j = std::clamp(std::floor(xi), LD(0), LD(texels) - 2);
            const LD f = std::clamp(xi - j, LD(0), LD(1));
            const std::size_t a = 3 * static_cast<std::size_t>(j);
            for (std::size_t k = 0; k < 3; ++k) {
              const LD va = value(row[a + k]), vb = value(row[a + 3 + k]);
              const LD want = LD(scale) * ((1 - f) * va + f * vb);
              // Float positions (up to 40 pixels from the group's start) and float arithmetic.
              const LD tolerance = LD(scale) * (1e-5L * std::abs(vb - va) + 4e-7L * (std::abs(va) + std::abs(vb)));
              if (!(std::abs(LD(h[3 * i + k]) - want) <= tolerance) && ++failures <= 5)
                FAIL_CHECK("texels " << texels << " s " << s << " n " << n << " pixel " << i << " channel " << k << ": "
                                     << h[3 * i + k] << " vs " << static_cast<double>(want));
            }
          }
        }
  });
  CHECK(cases > 0);
  CHECK(failures == 0);
}

} // namespace

TEST_CASE("resample_row: every level interpolates the row at x + s i like the reference, nothing else",
          "[resample_row]") {
  SECTION("8-bit sRGB codes") { check_resample<std::uint8_t>(); }
  SECTION("float channels") { check_resample<float>(); }
}

TEST_CASE("resample_row: the VBMI step's window holds every texel pair of a 16-pixel group", "[resample_row]") {
  // 16 pixels at the largest step, from just below a texel boundary: the last pair ends inside
  // the 128-byte window, and the largest byte index stays below 128.
  constexpr double s = mpr::detail::kResampleMaxStep;
  constexpr double last_pair = 0.999999 + 15 * s; // texel offset of the 16th pixel's left texel
  STATIC_REQUIRE(3 * (static_cast<int>(last_pair) + 1) + 2 < 128);
#if defined(MPR_SIMD_X86)                                            // the step's byte patterns exist where it does
  STATIC_REQUIRE(mpr::detail::kResamplePatterns.offset[1][31] == 5); // the last code: right texel's blue
  STATIC_REQUIRE(mpr::detail::kResamplePatterns.pixel[1][31] == 15);
  STATIC_REQUIRE(mpr::detail::kResamplePatterns.lane_pixel[2][15] == 15);
#endif
}

TEST_CASE("decode_row16: every code's table value at every level, nothing past the row", "[resample_row]") {
  const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
  std::vector<std::uint8_t> codes(300);
  for (std::size_t k = 0; k < codes.size(); ++k) codes[k] = static_cast<std::uint8_t>((k * 7 + k / 256) % 256);
  mpr_test::for_each_simd_level([&](mpr_test::SimdLevel level) {
    for (const std::size_t count : {0u, 1u, 63u, 64u, 65u, 256u, 300u}) {
      INFO("count " << count);
      std::vector<std::uint16_t> out(count + 70, 0xBEEF);
      mpr::detail::decode_row16(codes.data(), lut, out.data(), count, level);
      int wrong = 0;
      for (std::size_t k = 0; k < count; ++k) wrong += out[k] != lut[codes[k]] ? 1 : 0;
      for (std::size_t k = count; k < out.size(); ++k) wrong += out[k] != 0xBEEF ? 1 : 0;
      CHECK(wrong == 0);
    }
  });
}
