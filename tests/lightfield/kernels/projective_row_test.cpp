// The projective-row kernel (lightfield/kernels/projective_row.hpp): every SIMD level against a
// long-double reference of the same sums, on rows that cross the image borders, pass behind the
// camera, stand still or step several pixels at a time, with and without per-point weights, for
// 8-bit codes (with and without their 16-bit linear copy) and float channels and float and double
// coordinates. Nothing past a row's end is written.
#include "lightfield/projective_reference.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/kernels/projective_row.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

namespace {

using LD = long double;
using mpr::detail::ProjectiveRow;
using mpr::detail::SimdLevel;
using mpr_test::Expected;
using mpr_test::expected;

constexpr std::size_t kLengths[] = {0, 1, 5, 15, 16, 17, 31, 32, 33, 64, 100, 257};
constexpr std::size_t kGuard = 21;
constexpr float kSentinel = -12345.0f;

// A decode table that is not the sRGB one (the kernels then gather from the table rather than
// evaluate the sRGB cubic): a steep, uneven curve through whole numbers below 2^16.
const std::uint16_t* other_table() {
  static const auto table = [] {
    std::vector<std::uint16_t> t(256);
    for (int c = 0; c < 256; ++c)
      t[static_cast<std::size_t>(c)] = static_cast<std::uint16_t>((c * c * 7 + c * 13) % 65536);
    return t;
  }();
  return table.data();
}

// How the row is run: the dispatcher (`projective_row` at the level), or the Highway kernel
// called directly at the level (at avx512 and above, where the dispatcher runs the AVX-512
// kernel, its AVX2 target).
enum class Entry { dispatch, hwy };

template <class T, class C>
void run_row(Entry entry, const ProjectiveRow<T, C>& r, std::size_t n, const float* rw, float* acc, float* seen,
             SimdLevel level) {
#if MPR_HAVE_HWY && defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<T, float>)
    if (entry == Entry::hwy && mpr::kernels::projective_row_hwy(r, n, rw, acc, seen, level)) return;
#endif
  (void)entry;
  mpr::detail::projective_row(r, n, rw, acc, seen, level);
}

// Whether 8-bit rows also carry their 16-bit linear copy (`ProjectiveRow::linear`, as the frames
// hold it below the VBMI level); with one, each result must also equal, bit for bit, the same row
// run without it (the kernels' claim: the same sums).
enum class Copy { none, linear16 };

template <class T, class C>
void check_kernel(const std::uint16_t* table = mpr::Srgb8Texel::linear16(), Entry entry = Entry::dispatch,
                  Copy copy = Copy::none) {
  std::mt19937_64 rng(2007 + sizeof(T) * 10 + sizeof(C));
  std::uniform_real_distribution<double> unit(0, 1);
  const int width = 37, height = 23;
  // 8-bit codes are read a 32-bit word at a time: the frames' allocator pads its buffers so.
  std::vector<C, mpr::detail::HugePageAllocator<C>> texels(3 * width * height);
  for (C& c : texels) {
    if constexpr (std::is_same_v<C, float>)
      c = static_cast<float>(4 * unit(rng) - 1);
    else
      c = static_cast<C>(rng() % (std::is_same_v<C, std::uint8_t> ? 256 : 65536));
  }
  const float scale = std::is_same_v<C, float> ? 1.0f : 1.0f / 65535.0f;
  const std::uint16_t* lut = std::is_same_v<C, std::uint8_t> ? table : nullptr;
  // The copy, with 32 readable values after the last (as `CameraFrameSet::linear16`'s).
  std::vector<std::uint16_t> linear;
  if constexpr (std::is_same_v<C, std::uint8_t>)
    if (copy == Copy::linear16) {
      linear.assign(texels.size() + 32, 0);
      for (std::size_t k = 0; k < texels.size(); ++k) linear[k] = lut[texels[k]];
    }
  int differ = 0;
  // Coordinates far from the origin make float rounding of the projective map realistic.
  const LD margin = std::is_same_v<T, float> ? 2e-3L : 1e-9L;
  int failures = 0, compared = 0, seen_points = 0;
  for (const std::size_t n : kLengths)
    for (int trial = 0; trial < 12; ++trial) {
      const bool weighted = trial % 2 == 1;
      // A row across the image: pixel (x, y) = (a + i b) / (c + i d), from a start point and a
      // step in pixels, lifted by a random positive depth and depth slope; trials 8-9 let w
      // cross zero (the row passes behind the camera), 10-11 stand still (b = d = 0).
      const double depth = 200 + 800 * unit(rng);
      const double x0 = -10 + (width + 20) * unit(rng), y0 = -6 + (height + 12) * unit(rng);
      const double sx = (trial < 4 ? 1.0 : 6.0) * (2 * unit(rng) - 1),
                   sy = (trial < 4 ? 0.2 : 3.0) * (2 * unit(rng) - 1);
      double dw = n > 1 ? depth * (0.5 * unit(rng) - 0.25) / static_cast<double>(n) : 0;
      if (trial == 8 || trial == 9) dw = -2 * depth / std::max<double>(1, static_cast<double>(n));
      ProjectiveRow<T, C> r{{static_cast<T>(x0 * depth), static_cast<T>(y0 * depth), static_cast<T>(depth)},
                            {static_cast<T>((x0 + sx) * (depth + dw) - x0 * depth),
                             static_cast<T>((y0 + sy) * (depth + dw) - y0 * depth), static_cast<T>(dw)},
                            width,
                            height,
                            texels.data(),
                            scale,
                            lut,
                            linear.empty() ? nullptr : linear.data()};
      if (trial >= 10) r.hs[0] = r.hs[1] = r.hs[2] = 0;
      std::vector<float> rw(n);
      for (float& v : rw) v = unit(rng) < 0.25 ? (unit(rng) < 0.5 ? 0.0f : -1.0f) : static_cast<float>(unit(rng));
      std::vector<float> acc0(3 * n + kGuard, kSentinel), seen0(n + kGuard, kSentinel);
      for (std::size_t j = 0; j < 3 * n; ++j) acc0[j] = static_cast<float>(unit(rng));
      for (std::size_t j = 0; j < n; ++j) seen0[j] = static_cast<float>(unit(rng));
      mpr_test::for_each_simd_level([&](SimdLevel level) {
        std::vector<float> acc = acc0, seen = seen0;
        run_row(entry, r, n, weighted ? rw.data() : nullptr, acc.data(), seen.data(), level);
        if (r.linear != nullptr) {
          ProjectiveRow<T, C> codes = r;
          codes.linear = nullptr;
          std::vector<float> acc_codes = acc0, seen_codes = seen0;
          run_row(entry, codes, n, weighted ? rw.data() : nullptr, acc_codes.data(), seen_codes.data(), level);
          differ += acc != acc_codes || seen != seen_codes ? 1 : 0;
        }
        for (std::size_t j = 3 * n; j < acc.size(); ++j) failures += acc[j] != kSentinel ? 1 : 0;
        for (std::size_t j = n; j < seen.size(); ++j) failures += seen[j] != kSentinel ? 1 : 0;
        for (std::size_t i = 0; i < n; ++i) {
          const LD weight = weighted ? LD(rw[i]) : 1.0L;
          const Expected e = expected(r, i, weight, margin);
          if (e.ambiguous) continue;
          ++compared;
          seen_points += e.seen ? 1 : 0;
          std::string why;
          if (!mpr_test::matches(e, weight, std::is_same_v<T, float>, seen[i], seen0[i], &acc[3 * i], &acc0[3 * i],
                                 why) &&
              ++failures <= 5)
            FAIL_CHECK(mpr::detail::simd_level_name(level)
                       << " n=" << n << " trial=" << trial << " i=" << i << ": " << why);
        }
      });
    }
  CHECK(failures == 0);
  CHECK(differ == 0);
  CHECK(compared > 1000);
  CHECK(seen_points > 300); // the rows do cross the image
}

} // namespace

TEMPLATE_TEST_CASE("projective_row: every level adds the bilinear pixels of the reference, nothing else",
                   "[projective_row]", float, double) {
  SECTION("8-bit sRGB codes") { check_kernel<TestType, std::uint8_t>(); }
  SECTION("float channels") { check_kernel<TestType, float>(); }
  SECTION("8-bit codes, another decode table") { check_kernel<TestType, std::uint8_t>(other_table()); }
  SECTION("8-bit sRGB codes with their 16-bit linear copy") {
    check_kernel<TestType, std::uint8_t>(mpr::Srgb8Texel::linear16(), Entry::dispatch, Copy::linear16);
  }
}

TEST_CASE("projective_row_hwy: the Highway kernel at every level adds the bilinear pixels of the reference",
          "[projective_row]") {
  SECTION("8-bit sRGB codes") { check_kernel<float, std::uint8_t>(mpr::Srgb8Texel::linear16(), Entry::hwy); }
  SECTION("8-bit codes, another decode table") { check_kernel<float, std::uint8_t>(other_table(), Entry::hwy); }
  SECTION("float channels") { check_kernel<float, float>(nullptr, Entry::hwy); }
  SECTION("8-bit sRGB codes with their 16-bit linear copy") {
    check_kernel<float, std::uint8_t>(mpr::Srgb8Texel::linear16(), Entry::hwy, Copy::linear16);
  }
  SECTION("8-bit codes, another decode table, with the copy") {
    check_kernel<float, std::uint8_t>(other_table(), Entry::hwy, Copy::linear16);
  }
}

TEST_CASE("gather_indexable: 32-bit channel offsets for the whole image", "[projective_row]") {
  STATIC_REQUIRE(mpr::detail::gather_indexable(1400, 800));
  STATIC_REQUIRE(mpr::detail::gather_indexable(1, 1));
  STATIC_REQUIRE(!mpr::detail::gather_indexable(0, 10));
  STATIC_REQUIRE(!mpr::detail::gather_indexable(40000, 20000)); // 2.4e9 channels
  STATIC_REQUIRE(mpr::detail::gather_indexable(26000, 27000));  // 2.106e9 channels
}

TEST_CASE("projective_row: a w that is subnormal, overflows or is infinite is seen as by the plain loop",
          "[projective_row]") {
  // An ordinary row scaled by 1e-39 (w subnormal), a finite row whose w overflows to inf from
  // point 4 on, and w = inf itself: the plain loop divides and sees every point; the AVX-512
  // kernels must not lose them to a reciprocal estimate that is 0 or inf there.
  std::vector<std::uint8_t, mpr::detail::HugePageAllocator<std::uint8_t>> texels(3 * 4 * 4, 200);
  const std::uint16_t* lut = mpr::Srgb8Texel::linear16();
  const float rows[3][6] = {{1.5e-39f, 1.5e-39f, 1e-39f, 0, 0, 0},
                            {2e30f, 3e30f, 1e30f, 0, 0, 1e38f},
                            {1, 1, std::numeric_limits<float>::infinity(), 0, 0, 0}};
  for (const auto& h : rows) {
    const ProjectiveRow<float, std::uint8_t> r{{h[0], h[1], h[2]}, {h[3], h[4], h[5]}, 4,  4,
                                               texels.data(),      1.0f / 65535.0f,    lut};
    std::vector<float> want_acc(3 * 16, 0), want_seen(16, 0);
    mpr::detail::projective_row(r, 16, nullptr, want_acc.data(), want_seen.data(), SimdLevel::portable);
    CHECK(std::count(want_seen.begin(), want_seen.end(), 1.0f) == 16);
    mpr_test::for_each_simd_level([&](SimdLevel level) {
      std::vector<float> acc(3 * 16, 0), seen(16, 0);
      mpr::detail::projective_row(r, 16, nullptr, acc.data(), seen.data(), level);
      CHECK(seen == want_seen);
      for (std::size_t j = 0; j < acc.size(); ++j) CHECK(acc[j] == Approx(want_acc[j]).epsilon(1e-5));
    });
  }
}
