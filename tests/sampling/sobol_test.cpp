#include <mpr/sampling/sobol.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

TEST_CASE("Sobol building blocks: bit reversal and the first points of dimensions 0 and 1", "[sampling]") {
  CHECK(mpr::detail::reverse_bits(1) == 0x80000000U);
  CHECK(mpr::detail::reverse_bits(0x0000f00fU) == 0xf00f0000U);
  CHECK(mpr::detail::reverse_bits(mpr::detail::reverse_bits(0x12345678U)) == 0x12345678U);
  // Dimension 0: 0, 1/2, 1/4, 3/4, 1/8, ...; dimension 1 (direction numbers 1/2, 3/4, 5/8 in
  // index order, not Gray-code order): 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
  const std::uint32_t d0[] = {0, 0x80000000U, 0x40000000U, 0xc0000000U, 0x20000000U};
  const std::uint32_t d1[] = {0,           0x80000000U, 0xc0000000U, 0x40000000U,
                              0xa0000000U, 0x20000000U, 0x60000000U, 0xe0000000U};
  for (std::uint32_t i = 0; i < 5; ++i) CHECK(mpr::detail::sobol_dim0(i) == d0[i]);
  for (std::uint32_t i = 0; i < 8; ++i) CHECK(mpr::detail::sobol_dim1(i) == d1[i]);
}

TEST_CASE("Owen scrambling keeps digits nested: equal leading bits stay equal, and it permutes", "[sampling]") {
  // Two values sharing their top k bits still share their top k bits after scrambling.
  const std::uint32_t seed = 0x1234abcdU;
  for (int k = 1; k < 32; k += 5) {
    const std::uint32_t a = 0xa5a5a5a5U, b = a ^ (1U << (31 - k)); // differ first at bit k from the top
    const std::uint32_t sa = mpr::detail::owen_scramble(a, seed), sb = mpr::detail::owen_scramble(b, seed);
    const std::uint32_t top = ~0U << (32 - k);
    CHECK((sa & top) == (sb & top));
    CHECK(((sa ^ sb) >> (31 - k) & 1U) == 1U); // and still differ at bit k
  }
  // A bijection on 8-bit prefixes: the 256 values i << 24 map to 256 distinct top bytes.
  std::vector<int> seen(256, 0);
  for (std::uint32_t i = 0; i < 256; ++i) ++seen[mpr::detail::owen_scramble(i << 24, seed) >> 24];
  for (const int s : seen) CHECK(s == 1);
}

TEST_CASE("OwenSobol: each pixel's 2^m points are a (0, m, 2)-net, different per pixel", "[sampling]") {
  for (int m = 0; m <= 8; ++m) {
    const int count = 1 << m;
    const mpr::OwenSobol pattern(count);
    for (const mpr::Pixel px : {mpr::Pixel{0, 0}, mpr::Pixel{17, 3}, mpr::Pixel{-2, 1000}}) {
      std::vector<mpr::SamplePoint> points;
      for (int i = 0; i < count; ++i) {
        const mpr::SamplePoint p = pattern.point(px, i);
        REQUIRE(p.x >= 0);
        REQUIRE(p.x < 1);
        REQUIRE(p.y >= 0);
        REQUIRE(p.y < 1);
        points.push_back(p);
      }
      // Every elementary box of 2^a x 2^(m-a) cells holds exactly one point.
      for (int a = 0; a <= m; ++a) {
        const int nx = 1 << a, ny = 1 << (m - a);
        std::vector<int> cells(static_cast<std::size_t>(count), 0);
        for (const mpr::SamplePoint& p : points)
          ++cells[static_cast<std::size_t>(static_cast<int>(p.y * ny) * nx + static_cast<int>(p.x * nx))];
        for (const int c : cells) REQUIRE(c == 1);
      }
    }
  }
  const mpr::OwenSobol s(16);
  CHECK(s.point({4, 4}, 3) == s.point({4, 4}, 3));
  CHECK_FALSE(s.point({4, 4}, 3) == s.point({5, 4}, 3));
  CHECK_FALSE(s.point({4, 4}, 3) == mpr::OwenSobol(16, 1).point({4, 4}, 3));
}

TEST_CASE("OwenSobol: counts outside [1, 65536] throw naming the parameter", "[sampling]") {
  CHECK_THROWS_AS(mpr::OwenSobol(0), mpr::argument_error);
  CHECK_THROWS_AS(mpr::OwenSobol(-1), mpr::argument_error);
  CHECK_THROWS_AS(mpr::OwenSobol(65537), mpr::argument_error);
  CHECK_NOTHROW(mpr::OwenSobol(7));
  try {
    (void)mpr::OwenSobol(0);
  } catch (const mpr::argument_error& e) {
    CHECK(e.parameter() == "samples per pixel");
  }
}

TEST_CASE("OwenSobol lens points: a net of their own, not tied to the image points", "[sampling]") {
  STATIC_REQUIRE(mpr::LensSamplePattern<mpr::OwenSobol>);
  for (const int m : {4, 6}) {
    const int count = 1 << m;
    const mpr::OwenSobol pattern(count);
    std::vector<int> cells(static_cast<std::size_t>(count), 0);
    int same = 0;
    for (int i = 0; i < count; ++i) {
      const mpr::SamplePoint p = pattern.lens_point({7, 7}, i);
      ++cells[static_cast<std::size_t>(static_cast<int>(p.y * 4) * (count / 4) + static_cast<int>(p.x * (count / 4)))];
      same += p == pattern.point({7, 7}, i) ? 1 : 0;
    }
    for (const int c : cells) CHECK(c == 1); // (0, m, 2)-net: the 4 x count/4 boxes
    CHECK(same == 0);
  }
  // Neighbouring image points (consecutive indices) get lens points from anywhere: the image
  // and lens coordinates are nearly uncorrelated over a pixel.
  const mpr::OwenSobol pattern(256);
  double sx = 0, sl = 0, sxx = 0, sll = 0, sxl = 0;
  for (int i = 0; i < 256; ++i) {
    const double x = pattern.point({1, 2}, i).x, l = pattern.lens_point({1, 2}, i).x;
    sx += x, sl += l, sxx += x * x, sll += l * l, sxl += x * l;
  }
  const double n = 256, cov = sxl / n - sx * sl / n / n;
  const double corr = cov / std::sqrt((sxx / n - sx * sx / n / n) * (sll / n - sl * sl / n / n));
  CHECK(std::fabs(corr) < 0.2);
}
