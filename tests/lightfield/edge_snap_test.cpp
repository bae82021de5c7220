#include <mpr/lightfield/edge_snap.hpp>

#include <catch2/catch.hpp>

#include <limits>

namespace {

// 3x3: the top row black at value 0, the bottom row white at value 20, the middle row grey `code`
// at value `middle` (a mixed pixel of the edge between them).
struct Edge {
  mpr::Image<float> values{3, 3};
  mpr::Image<mpr::Rgb8> guide{3, 3};
  Edge(std::uint8_t code, float middle) {
    for (int x = 0; x < 3; ++x) {
      values(x, 0) = 0;
      values(x, 1) = middle;
      values(x, 2) = 20;
      guide(x, 0) = {0, 0, 0};
      guide(x, 1) = {code, code, code};
      guide(x, 2) = {255, 255, 255};
    }
  }
};

} // namespace

TEST_CASE("edge snap: a mixed pixel takes the side that covers more than half of it in linear light", "[edge_snap]") {
  // Code 200 is 0.578 in linear light (((200/255 + 0.055) / 1.055)^2.4): mostly white, the
  // bottom side's 20, although the sweep gave it the top's 0.
  const Edge white(200, 0.0f);
  CHECK(mpr::snap_mixed_pixels(white.values.view(), white.guide.view())(1, 1) == 20.0f);
  // Code 170 is 0.402 in linear light (0.667 as a code: a blend of codes would say white):
  // mostly black, the top side's 0.
  const Edge black(170, 20.0f);
  const mpr::Image<float> out = mpr::snap_mixed_pixels(black.values.view(), black.guide.view());
  CHECK(out(1, 1) == 0.0f);
  // The outermost rows and columns are kept.
  CHECK(out(0, 1) == 20.0f);
  CHECK(out(2, 1) == 20.0f);
  CHECK(out(1, 2) == 20.0f);
}

TEST_CASE("edge snap: the axis of the larger jump decides, and small jumps are left alone", "[edge_snap]") {
  // Transposed: black on the left (0), white on the right (20): the horizontal jump.
  mpr::Image<float> values(3, 3);
  mpr::Image<mpr::Rgb8> guide(3, 3);
  for (int y = 0; y < 3; ++y) {
    values(0, y) = 0;
    values(1, y) = 0;
    values(2, y) = 20;
    guide(0, y) = {0, 0, 0};
    guide(1, y) = {200, 200, 200};
    guide(2, y) = {255, 255, 255};
  }
  values(1, 0) = 5; // a vertical jump of 5 across (1, 1), smaller than the horizontal 20
  CHECK(mpr::snap_mixed_pixels(values.view(), guide.view())(1, 1) == 20.0f);
  // With the jump threshold above 20 nothing is an edge.
  CHECK(mpr::snap_mixed_pixels(values.view(), guide.view(), {25})(1, 1) == 0.0f);
  CHECK(mpr::snap_mixed_pixels(values.view(), guide.view(), {std::numeric_limits<double>::infinity()})(1, 1) == 0.0f);
  // Sides of one colour: colour cannot tell, the value stays.
  for (int y = 0; y < 3; ++y) guide(2, y) = {0, 0, 0};
  CHECK(mpr::snap_mixed_pixels(values.view(), guide.view())(1, 1) == 0.0f);
}

TEST_CASE("edge snap: bad settings and sizes are refused by name", "[edge_snap]") {
  const Edge e(200, 0.0f);
  CHECK_THROWS_WITH(mpr::snap_mixed_pixels(e.values.view(), e.guide.view(), {0.0}), Catch::Contains("jump"));
  CHECK_THROWS_WITH(mpr::snap_mixed_pixels(e.values.view(), mpr::Image<mpr::Rgb8>(2, 3).view()),
                    Catch::Contains("guide"));
}
