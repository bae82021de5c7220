#include <mpr/glc/aperture.hpp>
#include <mpr/sampling/sobol.hpp>

#include <catch2/catch.hpp>

#include <cmath>
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
