#include <catch2/catch.hpp>

#include <mpr/lightfield/frame_set.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

// linear16_copy: each code through the table, images at multiples of 32 values with at least 32
// after each (hand-worked offsets).
TEST_CASE("linear16_copy maps every code through the table into one padded buffer", "[camera_frame_set]") {
  std::vector<std::shared_ptr<const mpr::Image<mpr::Rgb8>>> images;
  images.push_back(std::make_shared<const mpr::Image<mpr::Rgb8>>(11, 1, mpr::Rgb8{1, 2, 3})); // 33 values
  images.push_back(std::make_shared<const mpr::Image<mpr::Rgb8>>(1, 1, mpr::Rgb8{250, 0, 7}));
  const std::vector<const mpr::Srgb8Texel*> at = {reinterpret_cast<const mpr::Srgb8Texel*>(images[0]->data()),
                                                  reinterpret_cast<const mpr::Srgb8Texel*>(images[1]->data())};
  std::array<std::uint16_t, 256> lut{};
  for (int c = 0; c < 256; ++c) lut[static_cast<std::size_t>(c)] = static_cast<std::uint16_t>(1000 + 3 * c);
  std::vector<const std::uint16_t*> out;
  const auto buffer = mpr::detail::linear16_copy(images, at, lut.data(), out);
  REQUIRE(buffer != nullptr);
  REQUIRE(out.size() == 2);
  // Image 0: 33 values, rounded up past a gap to 64, then 32 more: image 1 at 96; 3 values take
  // 32 + 32: 160 in all.
  CHECK(out[0] == buffer->data());
  CHECK(out[1] - out[0] == 96);
  CHECK(buffer->size() == 160);
  CHECK(out[0][0] == 1003);
  CHECK(out[0][1] == 1006);
  CHECK(out[0][32] == 1009); // pixel 10's blue
  CHECK(out[1][0] == 1750);
  CHECK(out[1][1] == 1000);
  CHECK(out[1][2] == 1021);
}
