#include <mpr/io/pfm.hpp>

#include "io/linear_render.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

namespace {
std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("mpr_pfm_" + name);
}

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string float_bytes(float v, bool little) {
  unsigned char b[4];
  std::memcpy(b, &v, 4);
  if (little != (std::endian::native == std::endian::little)) {
    std::swap(b[0], b[3]);
    std::swap(b[1], b[2]);
  }
  return std::string(reinterpret_cast<const char*>(b), 4);
}
} // namespace

TEST_CASE("PFM round trip keeps every float, infinities included, top row first", "[io][pfm]") {
  mpr::Image<float> image(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) image(x, y) = 0.25f * static_cast<float>(x) + 10.0f * static_cast<float>(y) + 1e-3f;
  image(4, 2) = std::numeric_limits<float>::infinity();
  const auto path = temp_path("roundtrip.pfm");
  mpr::write_pfm(path, image);
  const mpr::Image<float> back = mpr::read_pfm(path);
  REQUIRE(back.width() == 5);
  REQUIRE(back.height() == 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) CHECK(back(x, y) == image(x, y));
  // The file stores the bottom row first, little-endian.
  const std::vector<unsigned char> bytes = mpr::encode_pfm(image.view());
  const std::string header = "Pf\n5 3\n-1\n";
  REQUIRE(bytes.size() == header.size() + 60);
  float first = 0;
  std::memcpy(&first, bytes.data() + header.size(), 4);
  if constexpr (std::endian::native == std::endian::little) CHECK(first == image(0, 2));
}

TEST_CASE("PFM reads both byte orders and any white space in the header", "[io][pfm]") {
  const auto path = temp_path("big.pfm");
  // 2 x 2, big-endian (positive scale), header split over spaces and tabs; bottom row first.
  write_bytes(path, "Pf 2\t2\n1.0\n" + float_bytes(3, false) + float_bytes(4, false) + float_bytes(1, false) +
                        float_bytes(2, false));
  const mpr::Image<float> big = mpr::read_pfm(path);
  CHECK(big(0, 0) == 1.0f);
  CHECK(big(1, 0) == 2.0f);
  CHECK(big(0, 1) == 3.0f);
  CHECK(big(1, 1) == 4.0f);
  write_bytes(path, "Pf\n1 1\n-0.5\n" + float_bytes(7.5f, true));
  CHECK(mpr::read_pfm(path)(0, 0) == 7.5f);
}

TEST_CASE("bad PFM files are one io_error naming the file and the reason", "[io][pfm]") {
  const auto path = temp_path("bad.pfm");
  const auto refuse = [&](const std::string& bytes, const char* reason) {
    write_bytes(path, bytes);
    try {
      (void)mpr::read_pfm(path);
      FAIL("no exception for: " << reason);
    } catch (const mpr::io_error& e) {
      CHECK(e.path() == path.string());
      CHECK_THAT(e.what(), Catch::Contains(reason));
    }
  };
  const std::string one = float_bytes(1, true);
  refuse("P6\n1 1\n255\n", "does not start with Pf");
  refuse("PF\n1 1\n-1\n" + one + one + one, "colour map (PF)");
  refuse("Pf\n0 1\n-1\n", "not two positive integers");
  refuse("Pf\n-3 1\n-1\n", "not two positive integers");
  refuse("Pf\n1x 1\n-1\n" + one, "not two positive integers");
  refuse("Pf\n99999999999 1\n-1\n", "not two positive integers");
  refuse("Pf\n1 1\n0\n" + one, "is not a non-zero number");
  refuse("Pf\n1 1\nnan\n" + one, "is not a non-zero number");
  refuse("Pf\n1 1\n-1x\n" + one, "is not a non-zero number");
  refuse("Pf\n1 1\n-1", "no data after the header");
  refuse("Pf\n2 2\n-1\n" + one, "needs 16 bytes of data, the file has 4");
  refuse("Pf\n1 1\n-1\n" + one + "x", "needs 4 bytes of data, the file has 5");
  refuse("Pf", "not two positive integers");
  refuse("", "empty file");
  // Above the pixel limit: refused from the header, before allocating.
  mpr::LoadLimits small;
  small.max_image_pixels = 100;
  write_bytes(path, "Pf\n20 20\n-1\n");
  CHECK_THROWS_WITH(mpr::read_pfm(path, small), Catch::Contains("max_image_pixels"));
  // Not a regular file, missing file.
  CHECK_THROWS_WITH(mpr::read_pfm(std::filesystem::temp_directory_path()), Catch::Contains("not a regular file"));
  CHECK_THROWS_WITH(mpr::read_pfm(temp_path("missing.pfm")), Catch::Contains("missing.pfm"));
  // Writing: an empty image and a missing folder are refused, nothing left behind.
  CHECK_THROWS_AS(mpr::write_pfm(temp_path("empty.pfm"), mpr::Image<float>()), mpr::io_error);
  CHECK_THROWS_AS(mpr::write_pfm(temp_path("no_such_folder/x.pfm"), mpr::Image<float>(1, 1)), mpr::io_error);
}

TEST_CASE("PFM header: a \\r\\n ending is read, a token above 32 bytes is refused, not cut", "[io][pfm]") {
  const auto path = temp_path("crlf.pfm");
  // "\r\n" after the scale (Windows tools write it): the data follows the "\n".
  write_bytes(path, "Pf\r\n2 1\r\n-1\r\n" + float_bytes(5.5f, true) + float_bytes(-2, true));
  const mpr::Image<float> crlf = mpr::read_pfm(path);
  REQUIRE(crlf.width() == 2);
  CHECK(crlf(0, 0) == 5.5f);
  CHECK(crlf(1, 0) == -2.0f);
  // The single white-space byte still ends the header when the data takes the rest: a first
  // data byte of 0x0A after "\r" is data.
  const std::string nl_first = "\n\x00\x00\x40"; // 0x4000000A, a little-endian float
  float expected = 0;
  std::memcpy(&expected, nl_first.data(), 4);
  write_bytes(path, std::string("Pf\n1 1\n-1\r") + std::string(nl_first.data(), 4));
  if constexpr (std::endian::native == std::endian::little) CHECK(mpr::read_pfm(path)(0, 0) == expected);
  // A 34-byte scale: cut at 33 bytes, its last byte was taken for the header's end and the four
  // data bytes passed for the data.
  const std::string long_scale = "-1." + std::string(31, '0');
  REQUIRE(long_scale.size() == 34);
  write_bytes(path, "Pf\n1 1\n" + long_scale + "\n" + float_bytes(1, true));
  CHECK_THROWS_WITH(mpr::read_pfm(path), Catch::Contains("longer than 32 bytes") && Catch::Contains("crlf.pfm"));
  write_bytes(path, "Pf\n1 1\n" + long_scale.substr(0, 33) + "\n" + float_bytes(1, true));
  CHECK_THROWS_WITH(mpr::read_pfm(path), Catch::Contains("longer than 32 bytes"));
  write_bytes(path, "Pf\n1 1\n" + long_scale.substr(0, 32) + "\n" + float_bytes(1, true));
  CHECK(mpr::read_pfm(path)(0, 0) == 1.0f);
}

TEST_CASE("PFM: the header and the file's length are checked before the data is read", "[io][pfm][limits]") {
  const auto path = temp_path("sparse.pfm");
  // 1,000 MB, a valid 2x2 header: the length disagrees with the size; refused from the header.
  write_bytes(path, "Pf\n2 2\n-1\n");
  std::filesystem::resize_file(path, 1000ull << 20);
  CHECK_THROWS_WITH(mpr::read_pfm(path), Catch::Contains("needs 16 bytes of data"));
  // A header that does not end in the first 4096 bytes.
  write_bytes(path, "Pf\n2 2" + std::string(5000, ' ') + "-1\n" + std::string(16, '\0'));
  CHECK_THROWS_WITH(mpr::read_pfm(path), Catch::Contains("header longer than 4096 bytes"));
  std::filesystem::remove(path);
}

TEST_CASE("PFM: a depth map with structure comes back bit for bit, rows in place", "[io][pfm]") {
  // A 7 x 5 map with a depth edge, a slanted plane, a hole (+inf), NaN, -0, a denormal and the
  // float extremes: every value at its own (x, y), so a flipped, shifted or transposed row shows.
  mpr::Image<float> map(7, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x)
      map(x, y) = x < 3 ? 2.0f + 0.125f * static_cast<float>(y) : 9.5f - 0.5f * static_cast<float>(x + 7 * y);
  map(4, 1) = std::numeric_limits<float>::infinity();
  map(5, 1) = std::numeric_limits<float>::quiet_NaN();
  map(6, 1) = -0.0f;
  map(0, 4) = std::numeric_limits<float>::denorm_min();
  map(1, 4) = std::numeric_limits<float>::max();
  map(2, 4) = std::numeric_limits<float>::lowest();
  const auto path = temp_path("structured.pfm");
  mpr::write_pfm(path, map);
  const mpr::Image<float> back = mpr::read_pfm(path);
  REQUIRE(back.width() == 7);
  REQUIRE(back.height() == 5);
  int differ = 0;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) differ += std::memcmp(&back(x, y), &map(x, y), 4) != 0 ? 1 : 0;
  CHECK(differ == 0);
  // Spot values written out: the edge between columns 2 and 3 of row 3, the slant of row 0.
  CHECK(back(2, 3) == 2.375f);
  CHECK(back(3, 3) == 9.5f - 0.5f * 24);
  CHECK(back(6, 0) == 6.5f);
  CHECK(std::isnan(back(5, 1)));
  CHECK(std::signbit(back(6, 1)));
  std::filesystem::remove(path);
}

TEMPLATE_TEST_CASE("RGB PFM keeps the renderer's linear values exactly", "[io][pfm]", float, double) {
  const mpr::Image<mpr::Color> render = mpr_test::linear_render<TestType>();
  // The render spans values outside [0, 1], which an 8-bit file would clamp.
  float low = 1, high = 0;
  for (int y = 0; y < render.height(); ++y)
    for (int x = 0; x < render.width(); ++x)
      low = std::min(low, render(x, y).minCoeff()), high = std::max(high, render(x, y).maxCoeff());
  REQUIRE(low < 0);
  REQUIRE(high > 1);
  const auto path = temp_path("rgb.pfm");
  mpr::write_pfm(path, render);
  const mpr::Image<mpr::Color> back = mpr::read_pfm_rgb(path);
  REQUIRE(back.width() == render.width());
  REQUIRE(back.height() == render.height());
  for (int y = 0; y < render.height(); ++y)
    for (int x = 0; x < render.width(); ++x) CHECK((back(x, y) == render(x, y)).all());
  // A one-channel reader refuses the colour file, and the colour reader a one-channel one.
  CHECK_THROWS_WITH(mpr::read_pfm(path), Catch::Contains("colour map (PF)"));
  mpr::write_pfm(temp_path("grey.pfm"), mpr::Image<float>(2, 2));
  CHECK_THROWS_WITH(mpr::read_pfm_rgb(temp_path("grey.pfm")), Catch::Contains("one-channel map (Pf)"));
}

TEST_CASE("RGB PFM bytes worked out by hand: PF header, bottom row first, R G B per pixel", "[io][pfm]") {
  mpr::Image<mpr::Color> image(2, 2);
  image(0, 0) = mpr::Color(1, 2, 3); // top row
  image(1, 0) = mpr::Color(4, 5, 6);
  image(0, 1) = mpr::Color(-0.5f, 0, 7); // bottom row: first in the file
  image(1, 1) = mpr::Color(8, 9, 1e30f);
  const std::vector<unsigned char> bytes = mpr::encode_pfm(image.view());
  const std::string header = "PF\n2 2\n-1\n";
  REQUIRE(bytes.size() == header.size() + 48);
  CHECK(std::string(bytes.begin(), bytes.begin() + static_cast<long>(header.size())) == header);
  const float expected[12] = {-0.5f, 0, 7, 8, 9, 1e30f, 1, 2, 3, 4, 5, 6};
  for (int k = 0; k < 12; ++k)
    CHECK(std::string(reinterpret_cast<const char*>(bytes.data()) + header.size() + 4 * k, 4) ==
          float_bytes(expected[k], true));
}

TEST_CASE("RGB PFM of a big-endian file reads the same values", "[io][pfm]") {
  const auto path = temp_path("rgb_big.pfm");
  write_bytes(path, "PF\n1 1\n1.0\n" + float_bytes(0.25f, false) + float_bytes(-3, false) + float_bytes(1e-20f, false));
  const mpr::Image<mpr::Color> image = mpr::read_pfm_rgb(path);
  CHECK(image(0, 0)[0] == 0.25f);
  CHECK(image(0, 0)[1] == -3.0f);
  CHECK(image(0, 0)[2] == 1e-20f);
  write_bytes(path, "PF\n2 1\n-1\n" + float_bytes(1, true)); // 3 of the 24 bytes
  CHECK_THROWS_WITH(mpr::read_pfm_rgb(path), Catch::Contains("needs 24 bytes of data, the file has 4"));
}
