#include <mpr/glc/focus.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using mpr::glc::FocusType;
using Mat2 = mpr::glc::Mat2<double>;

namespace {
Mat2 m(double a, double b, double c, double d) {
  Mat2 r;
  r << a, b, c, d;
  return r;
}
} // namespace

TEST_CASE("classify_focus names every focus type with its focal depths", "[glc]") {
  const double h = 2; // lens plane 2 units behind the image plane
  // F = 0: a thin lens focused on the image plane.
  auto c = mpr::glc::classify_focus(Mat2(Mat2::Zero()), h);
  CHECK(c.type == FocusType::anastigmatic);
  CHECK(c.count == 1);
  CHECK(c.depths[0] == 0);
  // F = f I: z = 1 / (1 - f) with the lens plane at 0 and the image plane at 1, so f = 1/2 gives
  // z = 2: one lens-to-image distance in front of the image plane.
  c = mpr::glc::classify_focus(Mat2(0.5 * Mat2::Identity()), h);
  CHECK(c.type == FocusType::anastigmatic);
  CHECK(c.depths[0] == Approx(h));
  // F = I: the pixel's rays are parallel: focus at infinity.
  c = mpr::glc::classify_focus(Mat2(Mat2::Identity()), h);
  CHECK(c.type == FocusType::anastigmatic);
  CHECK(std::isinf(c.depths[0]));
  // Distinct eigenvalues 0 and 1/2 (the reference notes' example): focal lines on the image
  // plane and at z = 2.
  c = mpr::glc::classify_focus(m(0, 0, 0, 0.5), h);
  CHECK(c.type == FocusType::astigmatic);
  CHECK(c.count == 2);
  CHECK(c.depths[0] == Approx(0).margin(1e-12));
  CHECK(c.depths[1] == Approx(h));
  CHECK(c.eigenvalues[1] == Approx(0.5));
  // Not diagonal, same eigenvalues: a rotated astigmatic lens.
  const double s = std::sqrt(0.5);
  Mat2 rot;
  rot << s, -s, s, s;
  c = mpr::glc::classify_focus(Mat2(rot * m(0.25, 0, 0, 0.75) * rot.transpose()), h);
  CHECK(c.type == FocusType::astigmatic);
  CHECK(c.depths[0] == Approx(h * 0.25 / 0.75));
  CHECK(c.depths[1] == Approx(h * 3));
  // A Jordan block: pencil-like focus; with eigenvalue 1, twisted.
  c = mpr::glc::classify_focus(m(0.5, 1, 0, 0.5), h);
  CHECK(c.type == FocusType::pencil);
  CHECK(c.depths[0] == Approx(h));
  CHECK(mpr::glc::classify_focus(m(1, 0.3, 0, 1), h).type == FocusType::twisted);
  // Complex eigenvalues (a rotation): nothing is ever sharp.
  c = mpr::glc::classify_focus(m(0.5, -0.5, 0.5, 0.5), h);
  CHECK(c.type == FocusType::none);
  CHECK(c.count == 0);
  // An eigenvalue above 1 focuses behind the lens plane's far side (a virtual focus).
  CHECK(mpr::glc::classify_focus(Mat2(2 * Mat2::Identity()), h).depths[0] == Approx(-2 * h));
  CHECK(mpr::glc::to_string(FocusType::astigmatic) == "astigmatic");
  CHECK(mpr::glc::to_string(FocusType::none) == "none");
}

TEST_CASE("classify_focus and focus_at_depth agree, and refuse bad input", "[glc]") {
  for (const double depth : {0.0, 0.3, 5.0, 120.0})
    CHECK(mpr::glc::classify_focus(mpr::glc::focus_at_depth(1.5, depth), 1.5).depths[0] == Approx(depth).margin(1e-12));
  CHECK_THROWS_AS(mpr::glc::classify_focus(Mat2(Mat2::Zero()), 0.0), mpr::argument_error);
  CHECK_THROWS_AS(mpr::glc::classify_focus(Mat2(Mat2::Constant(std::numeric_limits<double>::infinity())), 1.0),
                  mpr::argument_error);
}
