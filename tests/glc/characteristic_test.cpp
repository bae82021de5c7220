#include "glc_test_util.hpp"

#include <mpr/glc/characteristic.hpp>

#include <catch2/catch.hpp>

#include <cmath>

namespace {
// Twice the signed area of the generator triangle at depth z, straight from the definition.
double area_at(const mpr::glc::TwoPlane<double>& tp, double z) {
  const auto p = [&](int k) { return mpr::Vec2<double>(tp[k].u + z * tp[k].sigma, tp[k].v + z * tp[k].tau); };
  const mpr::Vec2<double> a = p(1) - p(0), b = p(2) - p(0);
  return a.x() * b.y() - a.y() * b.x();
}
} // namespace

TEST_CASE("characteristic: D(z) is the doubled area of the generator triangle at depth z", "[glc][characteristic]") {
  glc_test::Rng rng(3);
  for (int i = 0; i < 100; ++i) {
    const auto cam = glc_test::random_camera<double>(mpr::glc::Type::cross_slit, rng);
    const auto tp = mpr::glc::two_plane(cam.plane, cam.selector);
    const auto ch = mpr::glc::characteristic(tp);
    for (const double z : {-3.0, 0.0, 0.5, 7.0}) CHECK(ch(z) == Approx(area_at(tp, z)).margin(1e-12));
    CHECK(ch.discriminant == Approx(ch.b * ch.b - 4 * ch.a * ch.c).margin(1e-12));
  }
}

TEST_CASE("characteristic: invariances of A, B, C", "[glc][characteristic]") {
  using G = mpr::glc::Generator<double>;
  const mpr::Vec3<double> o = mpr::Vec3<double>::Zero(), x = mpr::Vec3<double>::UnitX(), y = mpr::Vec3<double>::UnitY();
  // The cross-slit example (sigma, tau, u, v).
  const std::array<G, 3> g{G{0, 0, 0, 0}, G{-0.5, 0, 1, 0}, G{0, -0.25, 0, 1}};
  const auto base = mpr::glc::characteristic(mpr::glc::TwoPlane<double>(o, x, y, 1, g));
  // Swapping two generators negates all three.
  const auto swapped = mpr::glc::characteristic(mpr::glc::TwoPlane<double>(o, x, y, 1, {g[1], g[0], g[2]}));
  CHECK(swapped.a == -base.a);
  CHECK(swapped.b == -base.b);
  CHECK(swapped.c == -base.c);
  // Translating the plane coordinates by 1e8 changes nothing (edge form).
  std::array<G, 3> far = g;
  for (G& k : far) k.u += 1e8, k.v -= 1e8;
  const auto moved = mpr::glc::characteristic(mpr::glc::TwoPlane<double>(o, x, y, 1, far));
  CHECK(moved.a == base.a);
  CHECK(moved.b == base.b);
  CHECK(moved.c == base.c);
  // Moving the reference plane to depth 1.5: (A, B + 2 A zs, A zs^2 + B zs + C).
  std::array<G, 3> shifted = g;
  for (G& k : shifted) k.u += 1.5 * k.sigma, k.v += 1.5 * k.tau;
  const auto s = mpr::glc::characteristic(mpr::glc::TwoPlane<double>(o, x, y, 1, shifted));
  CHECK(s.a == 0.125);
  CHECK(s.b == -0.375);
  CHECK(s.c == 5.0 / 32);
  CHECK(s.discriminant == Approx(base.discriminant).epsilon(1e-14));
}

TEST_CASE("characteristic: discriminant and roots without cancellation", "[glc][characteristic]") {
  // Kahan's discriminant keeps the sign where the naive formula loses it.
  const double b = 1 + 0x1p-27, a = 1, c = (1 + 0x1p-26) / 4; // b^2 - 4ac = 2^-54 exactly, naive gives 0
  CHECK(mpr::glc::discriminant(a, b, c) == std::ldexp(1.0, -54));
  // Pushbroom plus 1e-11: the near root is exact to machine precision, the far one is -1e11-ish.
  mpr::glc::Characteristic<double> ch{1e-11 * 0.5, -0.5 - 1e-11, 1, 0};
  ch.discriminant = mpr::glc::discriminant(ch.a, ch.b, ch.c);
  const mpr::glc::Roots r = mpr::glc::roots(ch);
  CHECK_FALSE(r.complex);
  CHECK(r.first == Approx(2).epsilon(1e-15));
  CHECK(r.second == Approx(1e11).epsilon(1e-9));
  // A = 0: one root at infinity; A = B = 0: both; all zero: `all`.
  CHECK(std::isinf(mpr::glc::roots({0, -0.5, 1, 0.25}).second));
  CHECK(mpr::glc::roots({0, -0.5, 1, 0.25}).first == 2);
  CHECK(std::isinf(mpr::glc::roots({0, 0, 1, 0}).first));
  CHECK(mpr::glc::roots({0, 0, 0, 0}).all);
  const mpr::glc::Roots complex = mpr::glc::roots({0.25, 0, 1, -1});
  CHECK(complex.complex);
  CHECK(complex.imag == 2);
}
