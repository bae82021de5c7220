#include <mpr/core/image.hpp>

#include <catch2/catch.hpp>

#include <memory>
#include <vector>

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

TEST_CASE("Image::borrow uses the caller's pixels in place and holds their owner", "[image]") {
  auto storage = std::make_shared<std::vector<int>>(std::vector<int>{1, 2, 3, 4, 5, 6});
  std::weak_ptr<std::vector<int>> watch = storage;
  mpr::Image<int> image = mpr::Image<int>::borrow(storage->data(), 3, 2, storage);
  int* pixels = storage->data();
  storage.reset(); // the image alone keeps the memory alive now
  REQUIRE(!watch.expired());
  CHECK(image.borrowed());
  CHECK(image.data() == pixels);
  CHECK(image(2, 1) == 6); // row-major: pixel (2, 1) is the sixth value
  pixels[4] = 50;          // the caller's change shows in the image ...
  CHECK(image(1, 1) == 50);
  image(0, 0) = 10; // ... and a write through the image lands in the caller's memory
  CHECK(pixels[0] == 10);

  const mpr::Image<int> copy = image; // a copy owns its pixels
  CHECK(!copy.borrowed());
  CHECK(copy.data() != pixels);
  CHECK(copy == image);
  CHECK(copy.owner() == nullptr);

  mpr::Image<int> moved = std::move(image); // a move keeps the borrowed pixels and the owner
  CHECK(moved.borrowed());
  CHECK(moved.data() == pixels);
  CHECK(image.empty()); // NOLINT(bugprone-use-after-move): a moved-from image is empty
  mpr::Image<int> owned(2, 2, 7);
  owned = moved; // copy-assigned: owned pixels, equal values
  CHECK(!owned.borrowed());
  CHECK(owned.width() == 3);
  CHECK(owned(0, 0) == 10);
  moved = mpr::Image<int>(1, 1, 0);
  CHECK(watch.expired()); // the last borrower let the owner go
  CHECK_THROWS_AS(mpr::Image<int>::borrow(nullptr, 2, 2), mpr::argument_error);
  CHECK_THROWS_AS(mpr::Image<int>::borrow(pixels, -1, 2), mpr::argument_error);
}
