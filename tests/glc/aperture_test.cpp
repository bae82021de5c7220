#include <mpr/glc/aperture.hpp>
#include <mpr/sampling/sobol.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace {

/// Mean of |a|^2 over n scrambled Sobol lens points, and the largest |a|.
template <class Shape>
std::pair<double, double> moments(const Shape& shape, int n) {
  const mpr::OwenSobol pattern(n);
  double second = 0, largest = 0;
  for (int i = 0; i < n; ++i) {
    const mpr::Vec2<double> a = shape.at(pattern.lens_point({2, 9}, i));
    second += a.squaredNorm() / n;
    largest = std::max(largest, a.norm());
  }
  return {second, largest};
}

} // namespace

TEST_CASE("aperture shapes fill their shape uniformly (second moments) and stay inside it", "[glc]") {
  STATIC_REQUIRE(mpr::glc::ApertureShape<mpr::glc::DiscAperture>);
  STATIC_REQUIRE(mpr::glc::ApertureShape<mpr::glc::SquareAperture>);
  STATIC_REQUIRE(mpr::glc::ApertureShape<mpr::glc::PolygonAperture>);
  STATIC_REQUIRE(mpr::glc::ApertureShape<mpr::glc::GaussianAperture>);
  STATIC_REQUIRE_FALSE(mpr::glc::ApertureShape<int>);
  STATIC_REQUIRE_FALSE(mpr::glc::ApertureShape<mpr::OwenSobol>);
  const int n = 4096;
  // Unit disc: E|a|^2 = 1/2. Square [-1, 1]^2: 2/3. Regular hexagon of circumradius 1:
  // (2 + cos(60 deg)) / 6 = 5/12 (per triangle (0, v0, v1)). Gaussian sigma 1 in 2-D: 2 (cut at 4 sigma).
  auto [disc2, disc_max] = moments(mpr::glc::DiscAperture{}, n);
  CHECK(disc2 == Approx(0.5).epsilon(0.01));
  CHECK(disc_max <= 1 + 1e-12);
  auto [square2, square_max] = moments(mpr::glc::SquareAperture{}, n);
  CHECK(square2 == Approx(2.0 / 3).epsilon(0.01));
  CHECK(square_max <= std::sqrt(2.0) + 1e-12);
  auto [hex2, hex_max] = moments(mpr::glc::PolygonAperture(6), n);
  CHECK(hex2 == Approx(5.0 / 12).epsilon(0.01));
  CHECK(hex_max <= 1 + 1e-12);
  auto [gauss2, gauss_max] = moments(mpr::glc::GaussianAperture{}, n);
  CHECK(gauss2 == Approx(2).epsilon(0.03));
  CHECK(gauss_max <= 4 + 1e-12);
  // The polygon's points lie inside it: within the apothem along each edge normal.
  const mpr::glc::PolygonAperture pentagon(5);
  const mpr::OwenSobol pattern(512);
  for (int i = 0; i < 512; ++i) {
    const mpr::Vec2<double> a = pentagon.at(pattern.point({0, 0}, i));
    for (int k = 0; k < 5; ++k) {
      const double mid = (k + 0.5) * 2 * std::numbers::pi / 5;
      REQUIRE(a.dot(mpr::Vec2<double>(std::cos(mid), std::sin(mid))) <= std::cos(std::numbers::pi / 5) + 1e-12);
    }
  }
  CHECK_THROWS_AS(mpr::glc::PolygonAperture(2), mpr::argument_error);
  CHECK_THROWS_AS(mpr::glc::PolygonAperture(65), mpr::argument_error);
}

TEST_CASE("PolygonAperture clamps a sample outside [0, 1) before choosing the triangle", "[glc][aperture]") {
  // The triangle index comes from a float-to-int conversion of p.x * blades: out of range (or
  // NaN) it would be undefined; clamped, NaN and -3e38 read p.x = 0 (the centre, radius 0) and
  // +inf and 3e38 read p.x = 1 (the last triangle's outer edge, t = 0.5 its midpoint).
  const mpr::glc::PolygonAperture pentagon(5);
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const double step = 2 * std::numbers::pi / 5;
  const mpr::Vec2<double> last_mid(0.5 * (std::cos(4 * step) + 1), 0.5 * std::sin(4 * step));
  for (const double x : {nan, -inf, -3e38, -1.0}) CHECK(pentagon.at({x, 0.5}).norm() == 0.0);
  for (const double x : {inf, 3e38, 1.0}) {
    const mpr::Vec2<double> a = pentagon.at({x, 0.5});
    CHECK((a - last_mid).norm() < 1e-12);
  }
}

TEST_CASE("the disc aperture: Shirley-Chiu angles worked by hand, and every sector filled alike", "[glc]") {
  const mpr::glc::DiscAperture disc;
  // (a, b) = (2x - 1, 2y - 1); for |a| > |b| the point is at radius |a|, angle pi/4 * b / a (plus
  // pi for a < 0); otherwise radius |b|, angle pi/2 - pi/4 * a / b (plus pi for b < 0).
  const double pi = std::numbers::pi;
  const auto polar = [&](double x, double y) {
    const mpr::Vec2<double> p = disc.at({x, y});
    return std::pair{p.norm(), std::atan2(p.y(), p.x())};
  };
  const struct {
    double x, y, radius, angle;
  } cases[] = {
      {1.0, 0.75, 1.0, pi / 8},            // a = 1, b = 0.5
      {0.25, 0.625, 0.5, pi - pi / 8},     // a = -0.5, b = 0.25: pi + pi/4 * (-0.5)
      {0.625, 1.0, 1.0, pi / 2 - pi / 16}, // a = 0.25, b = 1
      {0.5, 0.0, 1.0, -pi / 2},            // a = 0, b = -1
      {0.125, 0.25, 0.75, -pi + pi / 6},   // a = -0.75, b = -0.5: pi/4 * (2/3) - pi
      {0.75, 0.25, 0.5, -pi / 4},          // a = 0.5, b = -0.5: the diagonal
  };
  for (const auto& c : cases) {
    const auto [r, angle] = polar(c.x, c.y);
    INFO("lens point (" << c.x << ", " << c.y << ")");
    CHECK(r == Approx(c.radius).epsilon(1e-12));
    CHECK(angle == Approx(c.angle).epsilon(1e-12));
  }
  // Area-preserving: each of 16 equal sectors holds 1/16 of 4096 stratified points, as does each
  // of 4 rings of equal area (radii sqrt(k/4)).
  const int n = 4096;
  const mpr::OwenSobol pattern(n);
  int sector[16] = {}, ring[4] = {};
  for (int i = 0; i < n; ++i) {
    const mpr::Vec2<double> p = disc.at(pattern.lens_point({2, 9}, i));
    const double angle = std::atan2(p.y(), p.x()) + pi; // [0, 2 pi]
    ++sector[std::min(15, static_cast<int>(angle / (2 * pi) * 16))];
    ++ring[std::min(3, static_cast<int>(p.squaredNorm() * 4))];
  }
  for (int s = 0; s < 16; ++s) {
    INFO("sector " << s);
    CHECK(std::abs(sector[s] - n / 16) <= 24); // 256 each; stratification keeps it within a few percent
  }
  for (int k = 0; k < 4; ++k) {
    INFO("ring " << k);
    CHECK(std::abs(ring[k] - n / 4) <= 32);
  }
}
