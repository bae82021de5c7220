#include "glc_test_util.hpp"

#include <mpr/glc/classify.hpp>

#include <catch2/catch.hpp>

#include <limits>
#include <type_traits>

using mpr::glc::Type;

namespace {

template <class T>
void check_coefficients(const mpr::glc::Classification<T>& cl, double a, double b, double c, double disc) {
  CHECK(cl.characteristic.a == a);
  CHECK(cl.characteristic.b == b);
  CHECK(cl.characteristic.c == c);
  CHECK(cl.characteristic.discriminant == disc);
}

} // namespace

// Every exact canonical example of glc-math.md sec. 5: all dyadic, so A, B, C, the discriminant,
// the depths and the slit geometry are exact in float and double and compared with ==.
TEMPLATE_TEST_CASE("classify: exact canonical examples", "[glc][classify]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto plane = glc_test::unit_plane<T>();
  const auto run = [&](T s0x, T s0y, T s1x, T s1y, T s2x, T s2y) {
    return mpr::glc::classify(plane, glc_test::from_st<T>(plane, s0x, s0y, s1x, s1y, s2x, s2y));
  };

  SECTION("pinhole") {
    const auto cl = run(0, 0, 0.5, 0, 0, 0.5);
    CHECK(cl.type == Type::pinhole);
    check_coefficients(cl, 0.25, -1, 1, 0);
    CHECK(cl.depths[0] == T(2));
    CHECK(cl.centre == V(0, 0, 2));
  }
  SECTION("orthographic") {
    const auto cl = run(0.5, 0.25, 1.5, 0.25, 0.5, 1.25);
    CHECK(cl.type == Type::orthographic);
    check_coefficients(cl, 0, 0, 1, 0);
    CHECK((cl.direction - V(0.5, 0.25, 1).normalized()).norm() <= 4 * std::numeric_limits<T>::epsilon());
  }
  SECTION("pushbroom") {
    const auto cl = run(0, 0, 1, 0, 0, 0.5);
    CHECK(cl.type == Type::pushbroom);
    check_coefficients(cl, 0, -0.5, 1, 0.25);
    CHECK(cl.slit_count == 1);
    CHECK(cl.depths[0] == T(2));
    CHECK(cl.slits[0].point.y() == T(0));
    CHECK(cl.slits[0].point.z() == T(2));
    CHECK(cl.slits[0].direction.cwiseAbs() == V(1, 0, 0));
  }
  SECTION("cross-slit") {
    const auto cl = run(0, 0, 0.5, 0, 0, 0.75);
    CHECK(cl.type == Type::cross_slit);
    check_coefficients(cl, 0.125, -0.75, 1, 0.0625);
    CHECK(cl.slit_count == 2);
    CHECK(cl.depths[0] == T(2));
    CHECK(cl.depths[1] == T(4));
    CHECK(cl.slits[0].point.x() == T(0));
    CHECK(cl.slits[0].point.z() == T(2));
    CHECK(cl.slits[0].direction.cwiseAbs() == V(0, 1, 0));
    CHECK(cl.slits[1].point.y() == T(0));
    CHECK(cl.slits[1].point.z() == T(4));
    CHECK(cl.slits[1].direction.cwiseAbs() == V(1, 0, 0));
  }
  SECTION("pencil") {
    const auto cl = run(0, 0, 0.5, 0, 0.5, 0.5);
    CHECK(cl.type == Type::pencil);
    check_coefficients(cl, 0.25, -1, 1, 0);
    CHECK(cl.depths[0] == T(2));
    CHECK(cl.slits[0].point.y() == T(0));
    CHECK(cl.slits[0].point.z() == T(2));
    CHECK(cl.slits[0].direction.cwiseAbs() == V(1, 0, 0));
  }
  SECTION("twisted orthographic") {
    const auto cl = run(0, 0, 1, 0, 0.5, 1);
    CHECK(cl.type == Type::twisted_orthographic);
    check_coefficients(cl, 0, 0, 1, 0);
  }
  SECTION("bilinear") {
    const auto cl = run(0, 0, 1, 0.5, -0.5, 1);
    CHECK(cl.type == Type::bilinear);
    check_coefficients(cl, 0.25, 0, 1, -1);
    CHECK(cl.roots.complex);
    CHECK(cl.roots.real == 0);
    CHECK(cl.roots.imag == 2);
  }
  SECTION("EPI (plane x + z = 1), through three world rays") {
    const auto tp = mpr::glc::two_plane(plane, glc_test::rays<T>({{{1, 0, 0, 0}, {1, 1, 0, 3}, {1, 2, 0, -1}}}));
    const auto cl = mpr::glc::classify(tp);
    CHECK(cl.type == Type::epi);
    check_coefficients(cl, 0, 0, 0, 0);
  }
  SECTION("affinely dependent generators are an error, not an EPI") {
    const auto tp = mpr::glc::two_plane(plane, glc_test::rays<T>({{{0, 0, 0, 0}, {2, 0, 1, 1}, {1, 0, 0.5, 0.5}}}));
    CHECK_THROWS_AS(mpr::glc::classify(tp), mpr::argument_error);
    CHECK_THROWS_WITH(mpr::glc::classify(tp), Catch::Contains("generators") && Catch::Contains("affinely dependent"));
    // Three copies of one ray, too.
    const auto same = mpr::glc::two_plane(plane, glc_test::rays<T>({{{0, 0, 1, 1}, {0, 0, 1, 1}, {0, 0, 1, 1}}}));
    CHECK_THROWS_AS(mpr::glc::classify(same), mpr::argument_error);
  }
  SECTION("a public 'twisted orthographic' preset is really a pushbroom") {
    const auto tp = mpr::glc::two_plane(plane, glc_test::rays<T>({{{0, 0, 0, 0}, {0, 0.5, 0.5, 0}, {0.5, 0, 0, 0.5}}}));
    const auto cl = mpr::glc::classify(tp);
    CHECK(cl.type == Type::pushbroom);
    check_coefficients(cl, 0, 0.5, -0.25, 0.25);
    CHECK(cl.depths[0] == T(0.5));
  }
}

TEMPLATE_TEST_CASE("classify: rays on the other side of the plane", "[glc][classify]", float, double) {
  using T = TestType;
  // The pinhole example mirrored: the rays travel to -z; depths are measured along the rays.
  const auto plane = glc_test::unit_plane<T>();
  const mpr::GlcSelector<T> sel(plane, mpr::Vec3<T>(0, 0, -1), mpr::Vec3<T>(-0.5, 0, -1), mpr::Vec3<T>(0, -0.5, -1));
  const auto cl = mpr::glc::classify(plane, sel);
  CHECK(cl.type == Type::pinhole);
  CHECK(cl.depths[0] == T(2));
  CHECK(cl.centre == mpr::Vec3<T>(0, 0, -2));
}

TEMPLATE_TEST_CASE("classify: a selector built for another plane is rejected", "[glc][classify]", float, double) {
  using T = TestType;
  const auto plane = glc_test::unit_plane<T>();
  const mpr::PlanarSurface<T> other(mpr::Vec3<T>::Zero(), mpr::Vec3<T>::UnitX(), mpr::Vec3<T>::UnitZ());
  const auto sel = mpr::glc::orthographic(other, mpr::Vec3<T>(0, 1, 0));
  CHECK_THROWS_WITH(mpr::glc::classify(plane, sel), Catch::Contains("selector"));
}

TEST_CASE("classify: to_string names every type", "[glc][classify]") {
  STATIC_REQUIRE(mpr::glc::to_string(Type::cross_slit) == "cross_slit");
  STATIC_REQUIRE(mpr::glc::to_string(Type::twisted_orthographic) == "twisted_orthographic");
  CHECK(mpr::glc::to_string(Type::epi) == "epi");
  CHECK(mpr::glc::to_string(Type::pinhole) == "pinhole");
  CHECK(mpr::glc::to_string(Type::orthographic) == "orthographic");
  CHECK(mpr::glc::to_string(Type::pushbroom) == "pushbroom");
  CHECK(mpr::glc::to_string(Type::pencil) == "pencil");
  CHECK(mpr::glc::to_string(Type::bilinear) == "bilinear");
  // All eight names differ.
  const Type all[] = {Type::pinhole, Type::orthographic,         Type::pushbroom, Type::cross_slit,
                      Type::pencil,  Type::twisted_orthographic, Type::bilinear,  Type::epi};
  for (const Type a : all)
    for (const Type b : all) CHECK((a == b) == (mpr::glc::to_string(a) == mpr::glc::to_string(b)));
}

// The scale of the pinhole/pencil decision: the generators must cross the double slit's depth
// within lateral_tolerance * max(L, |depth|), L the generator triangle's longest side (here
// sqrt 2). A pinhole near its image plane (depth 0.01 << L) pins the L (a tolerance scaled by
// |depth| alone would call a miss of 0.5e-4 a pencil, one scaled by 1 a miss of 1.2e-4); one at
// depth 2 > L pins |depth|.
TEMPLATE_TEST_CASE("classify: the pinhole tolerance is lateral_tolerance * max(L, |depth|)", "[glc][classify]", float,
                   double) {
  using T = TestType;
  const auto plane = glc_test::unit_plane<T>();
  const double tol = std::is_same_v<T, float> ? 1e-4 : 1e-9; // ClassifyConfig's lateral_tolerance
  // Generators at uv (0,0), (1,0), (0,1) through C = (0.3, 0.2, D), the third shifted along x so
  // that it passes C's depth `miss` from C (s = u (1 - 1/D) + c / D on z = 1, plus miss / D).
  const auto type = [&](double D, double miss) {
    const auto s = [&](double u, double c) { return static_cast<T>(u * (1 - 1 / D) + c / D); };
    return mpr::glc::classify(plane, glc_test::from_st<T>(plane, s(0, 0.3), s(0, 0.2), s(1, 0.3), s(0, 0.2),
                                                          static_cast<T>(0.3 / D + miss / D), s(1, 0.2)))
        .type;
  };
  for (const double m : {0.0, 0.5, 1.2}) {
    INFO("depth 0.01, miss " << m << " x tolerance");
    CHECK(type(0.01, m * tol) == Type::pinhole);
  }
  for (const double m : {1.7, 3.0}) {
    INFO("depth 0.01, miss " << m << " x tolerance");
    CHECK(type(0.01, m * tol) == Type::pencil);
  }
  CHECK(type(2.0, 1.7 * tol) == Type::pinhole); // max(L, 2) = 2
  CHECK(type(2.0, 2.4 * tol) == Type::pencil);
}
