#include <mpr/core/image.hpp>

#include <catch2/catch.hpp>

TEST_CASE("Image stores pixels row-major, y down", "[image]") {
  mpr::Image<int> image(4, 3, 7);
  CHECK(image.width() == 4);
  CHECK(image.height() == 3);
  CHECK(image(3, 2) == 7);
  image(1, 2) = 42;
  CHECK(image.data()[2 * 4 + 1] == 42);
  CHECK(image.view()(1, 2) == 42);
  CHECK_THROWS_AS(mpr::Image<int>(-1, 2), mpr::argument_error);
}

TEST_CASE("ImageView subviews share storage and clip", "[image]") {
  mpr::Image<int> image(5, 4, 0);
  const mpr::ImageView<int> sub = image.view().subview(1, 1, 3, 2);
  CHECK(sub.width() == 3);
  CHECK(sub.height() == 2);
  CHECK(sub.stride() == 5);
  sub(2, 1) = 9;
  CHECK(image(3, 2) == 9);
  const mpr::ImageView<int> clipped = image.view().subview(3, -2, 10, 4);
  CHECK(clipped.width() == 2);
  CHECK(clipped.height() == 2);
  CHECK(&clipped(0, 0) == &image(3, 0));
  CHECK(image.view().subview(7, 7, 2, 2).empty());
  const mpr::ImageView<const int> read_only = sub;
  CHECK(read_only(2, 1) == 9);
}

TEST_CASE("convert_image maps every pixel", "[image]") {
  mpr::Image<int> image(3, 2, 1);
  image(2, 1) = 5;
  const mpr::Image<double> doubled =
      mpr::convert_image<double>(mpr::ImageView<const int>(image.view()), [](int v) { return 2.0 * v; });
  CHECK(doubled(2, 1) == 10.0);
  CHECK(doubled(0, 0) == 2.0);
}
