#include <mpr/sampling/filters.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>

namespace {

/// sum over integer k of profile(x + k): 1 for a filter whose unit-spaced copies partition unity.
template <class F>
double shifted_sum(const F& f, double x) {
  double sum = 0;
  for (int k = -8; k <= 8; ++k) sum += f.profile(x + k);
  return sum;
}

/// The 2-D integral of evaluate() over the support, midpoint rule on a fine grid.
template <class F>
double integral(const F& f) {
  const int n = 400;
  const double r = f.radius(), h = 2 * r / n;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sum += f.evaluate(-r + (i + 0.5) * h, -r + (j + 0.5) * h);
  return sum * h * h;
}

} // namespace

TEST_CASE("tent: (r - |dx|)(r - |dy|) exactly; radius 1 partitions unity", "[sampling]") {
  const mpr::TentFilter tent;
  CHECK(tent.radius() == 2);
  CHECK(tent.evaluate(0, 0) == 4);
  CHECK(tent.evaluate(0.5, -1) == 1.5);
  CHECK(tent.evaluate(2, 0) == 0);
  CHECK(tent.evaluate(-2.5, 0) == 0);
  const mpr::TentFilter bilinear(1);
  for (double x = -0.5; x <= 0.5; x += 0.0625) CHECK(shifted_sum(bilinear, x) == Approx(1).margin(1e-15));
  CHECK(integral(bilinear) == Approx(1).epsilon(1e-4));
}

TEST_CASE("Gaussian: shifted to 0 at the radius, never negative", "[sampling]") {
  const mpr::GaussianFilter g;
  CHECK(g.radius() == 1.5);
  CHECK(g.sigma() == 0.5);
  const double peak = 1 / std::sqrt(2 * std::numbers::pi * 0.25), edge = peak * std::exp(-1.5 * 1.5 / 0.5);
  CHECK(g.profile(0) == Approx(peak - edge).epsilon(1e-15));
  CHECK(g.evaluate(0, 0) == Approx((peak - edge) * (peak - edge)).epsilon(1e-15));
  CHECK(g.profile(0.5) == Approx(peak * std::exp(-0.5) - edge).epsilon(1e-15));
  CHECK(g.profile(1.5) == 0);
  CHECK(g.profile(-1.6) == 0);
  for (double x = -2; x <= 2; x += 0.01) CHECK(g.profile(x) >= 0);
  CHECK_THROWS_AS(mpr::GaussianFilter(1.5, 0), mpr::argument_error);
}

TEST_CASE("Mitchell-Netravali: exact knots, unit integral, partition of unity for B + 2C = 1", "[sampling]") {
  const mpr::MitchellFilter m; // B = C = 1/3, radius 2: profile = Mitchell's k
  CHECK(m.radius() == 2);
  CHECK(m.profile(0) == Approx(8.0 / 9).epsilon(1e-15));  // (6 - 2B) / 6
  CHECK(m.profile(1) == Approx(1.0 / 18).epsilon(1e-15)); // B / 6
  CHECK(m.profile(-1) == Approx(1.0 / 18).epsilon(1e-15));
  CHECK(m.profile(1.5) == Approx(-5.0 / 144).epsilon(1e-14)); // the negative lobe
  CHECK(m.profile(2) == 0);
  CHECK(m.profile(3) == 0);
  CHECK(m.evaluate(0, 1) == Approx(8.0 / 9 / 18).epsilon(1e-15));
  for (double x = -0.5; x <= 0.5; x += 0.0625) CHECK(shifted_sum(m, x) == Approx(1).epsilon(1e-14));
  const mpr::MitchellFilter catmull_rom(2, 0, 0.5); // B + 2C = 1 too
  for (double x = -0.5; x <= 0.5; x += 0.0625) CHECK(shifted_sum(catmull_rom, x) == Approx(1).epsilon(1e-14));
  CHECK(integral(m) == Approx(1).epsilon(1e-4));
  // A radius of 1 squeezes the cubic into one pixel: profile(x) = k(2x).
  CHECK(mpr::MitchellFilter(1).profile(0.5) == Approx(1.0 / 18).epsilon(1e-15));
  CHECK_THROWS_AS(mpr::MitchellFilter(2, std::numeric_limits<double>::quiet_NaN()), mpr::argument_error);
}

TEST_CASE("Lanczos: 1 at 0, 0 at the other integers and outside the radius", "[sampling]") {
  const mpr::LanczosFilter l;
  CHECK(l.radius() == 4);
  CHECK(l.profile(0) == 1);
  for (int k = 1; k <= 4; ++k) {
    CHECK(l.profile(k) == Approx(0).margin(1e-15));
    CHECK(l.profile(-k) == Approx(0).margin(1e-15));
  }
  const double x = 0.5; // sinc(1/2) sinc(1/6)
  CHECK(l.profile(x) ==
        Approx((2 / std::numbers::pi) * std::sin(std::numbers::pi / 6) / (std::numbers::pi / 6)).epsilon(1e-14));
  CHECK(l.profile(4.01) == 0);
  CHECK(l.profile(1e-9) == Approx(1).epsilon(1e-15));
  CHECK(shifted_sum(l, 0) == Approx(1).epsilon(1e-14));
  // Lanczos-3 (tau = radius) partitions unity to within 1%.
  const mpr::LanczosFilter lanczos3(3, 3);
  for (double t = -0.5; t <= 0.5; t += 0.0625) CHECK(shifted_sum(lanczos3, t) == Approx(1).epsilon(0.01));
}

TEST_CASE("every filter: finite weights everywhere, 0 beyond the radius, bad parameters throw", "[sampling]") {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const auto check = [&](const auto& f) {
    for (const double x : {0.0, -0.0, 1e-300, 0.25, -0.7, 1.0, 1.5, 2.0, 3.999, 4.0, 1e300, -1e300, inf, -inf})
      for (const double y : {0.0, 0.3, -1.2, inf}) {
        const double w = f.evaluate(x, y);
        CHECK(std::isfinite(w));
        if (std::fabs(x) > f.radius() || std::fabs(y) > f.radius()) CHECK(w == 0);
      }
  };
  check(mpr::BoxFilter());
  check(mpr::TentFilter());
  check(mpr::GaussianFilter());
  check(mpr::MitchellFilter());
  check(mpr::LanczosFilter());
  for (const double bad : {0.0, -0.5, nan, inf}) {
    CHECK_THROWS_AS(mpr::TentFilter(bad), mpr::argument_error);
    CHECK_THROWS_AS(mpr::GaussianFilter(bad), mpr::argument_error);
    CHECK_THROWS_AS(mpr::MitchellFilter(bad), mpr::argument_error);
    CHECK_THROWS_AS(mpr::LanczosFilter(bad), mpr::argument_error);
    CHECK_THROWS_AS(mpr::LanczosFilter(4, bad), mpr::argument_error);
  }
}
