// LerpRowCache (lightfield/lerp_row_cache.hpp): a row interpolated from the frames' 16-bit linear
// copy is the row interpolated from their 8-bit codes, bit for bit, at the process's SIMD level
// (the level ctest entries run it at each; the copy is read below AVX-512, where both rows are
// Highway kernels); rows are kept for the same texels, length, stride and offset, and recomputed
// otherwise.
#include <catch2/catch.hpp>

#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/lerp_row_cache.hpp>

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace {

// A row of random codes and its linear copy (the decode table's values), both with readable
// values past the end (as the frame set's buffers have).
struct CodeRow {
  std::vector<std::uint8_t> codes;
  std::vector<std::uint16_t> linear;
};

CodeRow random_row(std::size_t texels, std::mt19937& rng) {
  CodeRow r;
  r.codes.resize(3 * texels + 64);
  r.linear.resize(3 * texels + 64);
  const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
  for (std::size_t k = 0; k < r.codes.size(); ++k) {
    r.codes[k] = static_cast<std::uint8_t>(rng() % 256);
    r.linear[k] = lut[r.codes[k]];
  }
  return r;
}

} // namespace

TEST_CASE("LerpRowCache: a row from the 16-bit linear copy is the row from the codes", "[lerp_row_cache]") {
  std::mt19937 rng(1407);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
  const float scale = 1.0f / 65535.0f;
  int compared = 0;
  for (const std::size_t pixels : {1, 2, 7, 8, 33, 100, 517})
    for (const std::size_t stride : {1, 3, 8})
      for (int trial = 0; trial < 4; ++trial) {
        const std::size_t texels = stride * (pixels - 1) + 2;
        const CodeRow row = random_row(texels, rng);
        const CodeRow ahead = random_row(texels, rng);
        const float ax = trial == 0 ? 0.0f : unit(rng);
        mpr::LerpRowCache from_codes, from_linear;
        const float* a = from_codes.row(row.codes.data(), lut, 3 * pixels, ax, scale, stride, ahead.codes.data());
        const float* b = from_linear.row(row.codes.data(), lut, 3 * pixels, ax, scale, stride, ahead.codes.data(),
                                         row.linear.data(), ahead.linear.data());
        REQUIRE(a != nullptr);
        REQUIRE(b != nullptr);
        for (std::size_t j = 0; j < 3 * pixels; ++j) {
          INFO("pixels " << pixels << " stride " << stride << " ax " << ax << " channel " << j);
          REQUIRE(a[j] == b[j]);
          ++compared;
        }
      }
  CHECK(compared > 10000);
}

TEST_CASE("LerpRowCache keeps a row for the same texels, length, stride and offset", "[lerp_row_cache]") {
  std::mt19937 rng(77);
  const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
  const CodeRow row = random_row(40, rng), other = random_row(40, rng);
  mpr::LerpRowCache cache;
  const float* first = cache.row(row.codes.data(), lut, 30, 0.25f, 1.0f);
  REQUIRE(first != nullptr);
  const float kept = first[4];
  CHECK(cache.row(row.codes.data(), lut, 30, 0.25f + 5e-5f, 1.0f) == first); // within 1e-4 pixel: kept
  const float* second = cache.row(other.codes.data(), lut, 30, 0.25f, 1.0f);
  CHECK(second != first);
  CHECK(cache.row(row.codes.data(), lut, 30, 0.25f, 1.0f) == first); // both rows held
  CHECK(first[4] == kept);
  const float* moved = cache.row(row.codes.data(), lut, 30, 0.5f, 1.0f); // another offset: recomputed
  CHECK(moved != nullptr);
  CHECK(moved[4] != kept);
}
