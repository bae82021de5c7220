#include <mpr/lightfield/depth_proxy/depth_walk.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

// detail::depth_lookup, hand-worked: a 3 x 2 map whose pixels all differ by more than the
// tolerance (so a lookup returns the nearest pixel), and a smooth one (bilinear).
TEMPLATE_TEST_CASE("depth_lookup: nearest or bilinear, and edge pixels for any point outside the map",
                   "[depth_walk][numerics]", float, double) {
  using T = TestType;
  const std::vector<float> d = {10, 20, 30, // row 0
                                40, 50, 60};
  const T tol = T(0.01);
  const auto at = [&](T x, T y) { return mpr::detail::depth_lookup(d.data(), 3, 2, x, y, tol); };
  CHECK(at(0, 0) == 10);
  CHECK(at(T(1.4), T(0.6)) == 50); // nearest of the four around (1.4, 0.6)
  CHECK(at(T(1.6), T(0.2)) == 30);
  const T inf = std::numeric_limits<T>::infinity();
  // Far outside, infinite or beyond int's range: the edge pixels. floor(inf) converted to int is
  // undefined (UBSan float-cast-overflow); on x86 it gave INT_MIN, column 0, the wrong edge.
  CHECK(at(inf, 0) == 30);
  CHECK(at(T(3e38), T(1)) == 60);
  CHECK(at(-inf, 1) == 40);
  CHECK(at(T(-3e38), T(-3e38)) == 10);
  CHECK(at(2, inf) == 60);
  CHECK(at(inf, inf) == 60);
  CHECK(at(T(4e9), T(-4e9)) == 30);
  CHECK(at(std::numeric_limits<T>::quiet_NaN(), 1) == 40);
  // Smooth: bilinear between the four, clamped at the edges the same way.
  const std::vector<float> s = {100, 101, 102, 101, 102, 103};
  const auto smooth = [&](T x, T y) { return mpr::detail::depth_lookup(s.data(), 3, 2, x, y, tol); };
  CHECK(smooth(T(0.5), T(0.5)) == Approx(101.0));
  CHECK(smooth(T(1.25), 0) == Approx(101.25));
  CHECK(smooth(inf, T(0.5)) == Approx(102.5));
  CHECK(smooth(-inf, -inf) == Approx(100.0));
}
