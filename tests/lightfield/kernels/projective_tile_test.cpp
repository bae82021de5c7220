// The projective-tile kernel (lightfield/kernels/projective_tile.hpp): every SIMD level against the
// long-double reference of each row's points, on tiles of a tilted plane (rows nearly level in
// the camera, a few crossing camera rows), steep and sheared tiles (groups too spread for the
// box windows), tiles that leave the image or pass behind the camera, and images narrower and
// wider than one chunk's box; every other trial weighs each ray (some weights zero or negative:
// those rays are skipped). Each row adds to its own outputs, with gaps between rows: nothing
// outside a row's points is written.
#include "lightfield/projective_reference.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/kernels/projective_tile.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

namespace {

using mpr::detail::ProjectiveRow;
using mpr::detail::SimdLevel;
using mpr_test::LD;

constexpr std::size_t kGuard = 21;
constexpr std::size_t kGap = 5, kOffset = 2; // per-row outputs: n + kGap apart, from kOffset
constexpr float kSentinel = -12345.0f;

// One tile's rows: point (i, r) at the homogeneous pixel (x, y, 1) depth + i step_i + r step_r,
// with the depth itself affine in i and r (a tilted plane).
struct TileShape {
  double x0, y0, depth, sx, sy, rx, ry, dwi, dwr;
};

template <class T, class C>
std::vector<ProjectiveRow<T, C>> tile_rows(const TileShape& s, std::size_t rows, int width, int height, const C* texels,
                                           float scale, const std::uint16_t* lut) {
  std::vector<ProjectiveRow<T, C>> out;
  for (std::size_t r = 0; r < rows; ++r) {
    const double rr = static_cast<double>(r);
    const double x = s.x0 + rr * s.rx, y = s.y0 + rr * s.ry, w = s.depth + rr * s.dwr;
    // Point i: pixel (x + i sx, y + i sy) at depth w + i dwi.
    out.push_back({{static_cast<T>(x * w), static_cast<T>(y * w), static_cast<T>(w)},
                   {static_cast<T>((x + s.sx) * (w + s.dwi) - x * w), static_cast<T>((y + s.sy) * (w + s.dwi) - y * w),
                    static_cast<T>(s.dwi)},
                   width,
                   height,
                   texels,
                   scale,
                   lut});
  }
  return out;
}

template <class T, class C>
void check_tiles(int width, int height) {
  std::mt19937_64 rng(4004 + sizeof(T) * 10 + sizeof(C) + static_cast<unsigned>(width));
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<C, mpr::detail::HugePageAllocator<C>> texels(3 * static_cast<std::size_t>(width) * height);
  for (C& c : texels) {
    if constexpr (std::is_same_v<C, float>)
      c = static_cast<float>(4 * unit(rng) - 1);
    else
      c = static_cast<C>(rng() % 256);
  }
  const float scale = std::is_same_v<C, float> ? 1.0f : 1.0f / 65535.0f;
  const std::uint16_t* lut = std::is_same_v<C, std::uint8_t> ? mpr::Srgb8Texel::linear16() : nullptr;
  const LD margin = std::is_same_v<T, float> ? 2e-3L : 1e-9L;
  int failures = 0, compared = 0, seen_points = 0;
  for (const std::size_t rows : {1u, 3u, 8u, 13u})
    for (const std::size_t n : {0u, 1u, 15u, 16u, 17u, 64u, 65u, 100u, 257u})
      for (int trial = 0; trial < 10; ++trial) {
        // Trials 0-4: a tilted plane's tile (rows nearly level, about one camera row apart);
        // 5-6: steep or spread rows (the gather step); 7: rows that leave the image; 8: rows
        // that pass behind the camera; 9: a tile standing still.
        const double depth = 200 + 800 * unit(rng);
        TileShape s{};
        s.depth = depth;
        s.x0 = -4 + (width / 2.0) * unit(rng);
        s.y0 = -2 + (height - rows * 1.2) * unit(rng);
        s.sx = (0.3 + 1.9 * unit(rng)) * (unit(rng) < 0.2 ? -1 : 1);
        s.sy = 0.08 * (2 * unit(rng) - 1);
        s.rx = 0.3 * (2 * unit(rng) - 1);
        s.ry = 0.6 + 0.8 * unit(rng);
        s.dwi = n > 1 ? depth * (0.2 * unit(rng) - 0.1) / static_cast<double>(n) : 0;
        s.dwr = depth * (0.02 * unit(rng) - 0.01);
        if (trial == 5) s.sy = 1.5 * (2 * unit(rng) - 1);
        if (trial == 6) s.sx = 3 + 3 * unit(rng), s.ry = 4 + 10 * unit(rng);
        if (trial == 7) s.x0 = width - 20 * unit(rng), s.y0 = height - 5 * unit(rng);
        if (trial == 8) s.dwi = -2 * depth / std::max<double>(1, static_cast<double>(n));
        if (trial == 9) s.sx = s.sy = s.dwi = 0;
        const std::vector<ProjectiveRow<T, C>> tile =
            tile_rows<T, C>(s, rows, width, height, texels.data(), scale, lut);
        // Each row's outputs at its own place: rows kStride apart, from kOffset on, as the
        // cylinder's rows of a group are (their own arrays, from the camera's span); every slot
        // between and after them must keep its sentinel.
        const std::size_t stride = n + kGap, slots = stride * rows;
        const auto at_of = [&](std::size_t r, std::size_t i) { return stride * r + kOffset + i; };
        std::vector<float> acc0(3 * slots + kGuard, kSentinel), seen0(slots + kGuard, kSentinel);
        std::vector<char> in_row(slots, 0);
        for (std::size_t r = 0; r < rows; ++r)
          for (std::size_t i = 0; i < n; ++i) {
            const std::size_t at = at_of(r, i);
            in_row[at] = 1;
            seen0[at] = static_cast<float>(unit(rng));
            for (int k = 0; k < 3; ++k) acc0[3 * at + k] = static_cast<float>(unit(rng));
          }
        const bool weighted = trial % 2 == 1;
        std::vector<float> rw(slots);
        for (float& x : rw) {
          const double u = unit(rng);
          x = u < 0.15 ? 0.0f : u < 0.2 ? -1.0f : static_cast<float>(2 * unit(rng));
        }
        const auto weight_of = [&](std::size_t at) { return weighted ? static_cast<LD>(rw[at]) : 1.0L; };
        mpr_test::for_each_simd_level([&](SimdLevel level) {
          std::vector<float> acc = acc0, seen = seen0;
          std::vector<mpr::detail::TileRowOut> out;
          for (std::size_t r = 0; r < rows; ++r)
            out.push_back({acc.data() + 3 * at_of(r, 0), seen.data() + at_of(r, 0),
                           weighted ? rw.data() + at_of(r, 0) : nullptr});
          mpr::detail::projective_tile(std::span<const ProjectiveRow<T, C>>(tile),
                                       std::span<const mpr::detail::TileRowOut>(out), n, level);
          for (std::size_t j = 0; j < seen.size(); ++j)
            if (j >= slots || in_row[j] == 0) {
              failures += seen[j] != kSentinel ? 1 : 0;
              for (std::size_t k = 3 * j; k < 3 * j + 3 && k < acc.size(); ++k) failures += acc[k] != kSentinel ? 1 : 0;
            }
          for (std::size_t r = 0; r < rows; ++r)
            for (std::size_t i = 0; i < n; ++i) {
              const std::size_t at = at_of(r, i);
              const mpr_test::Expected e = mpr_test::expected(tile[r], i, weight_of(at), margin);
              if (e.ambiguous) continue;
              ++compared;
              seen_points += e.seen ? 1 : 0;
              std::string why;
              if (!mpr_test::matches(e, weight_of(at), std::is_same_v<T, float>, seen[at], seen0[at], &acc[3 * at],
                                     &acc0[3 * at], why) &&
                  ++failures <= 5)
                FAIL_CHECK(mpr::detail::simd_level_name(level)
                           << " " << width << "x" << height << " rows=" << rows << " n=" << n << " trial=" << trial
                           << (weighted ? " weighted" : "") << " row " << r << " i=" << i << ": " << why);
            }
        });
      }
  CHECK(failures == 0);
  CHECK(compared > 20000);
  CHECK(seen_points > 10000); // the tiles do cross the image
}

} // namespace

TEMPLATE_TEST_CASE("projective_tile: every level adds each row's bilinear pixels, nothing else", "[projective_tile]",
                   float, double) {
  SECTION("8-bit sRGB codes, an image narrower than a chunk's box") { check_tiles<TestType, std::uint8_t>(61, 40); }
  SECTION("8-bit sRGB codes, an image wider than a chunk's box") { check_tiles<TestType, std::uint8_t>(400, 60); }
  SECTION("float channels") { check_tiles<TestType, float>(200, 50); }
}
