// Compiled to nothing without libpng (tests/CMakeLists.txt defines MPR_HAVE_LIBPNG when found).
#if defined(MPR_HAVE_LIBPNG)
#include <mpr/io/png16.hpp>

#include "io/linear_render.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace {
std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("mpr_png16_" + name);
}
} // namespace

TEST_CASE("16-bit sRGB codes worked out by hand", "[io][png16]") {
  // 65535 * (1.055 * x^(1/2.4) - 0.055), rounded; 12.92 x on the linear segment (x <= 0.0031308).
  CHECK(mpr::to_png16_code(0.5f) == 48192);  // 48191.62
  CHECK(mpr::to_png16_code(0.18f) == 30235); // 30234.97
  CHECK(mpr::to_png16_code(0.002f) == 1693); // 65535 * 12.92 * 0.002 = 1693.42
  CHECK(mpr::to_png16_code(1.0f) == 65535);
  CHECK(mpr::to_png16_code(0.0f) == 0);
  CHECK(mpr::to_png16_code(7.5f) == 65535); // clamped
  CHECK(mpr::to_png16_code(-0.25f) == 0);
  CHECK(mpr::to_png16_code(std::numeric_limits<float>::quiet_NaN()) == 0);
  CHECK(mpr::from_png16_code(65535) == 1.0f);
  CHECK(mpr::from_png16_code(0) == 0.0f);
  CHECK(std::abs(mpr::from_png16_code(48192) - 0.5f) < 2e-5f);
}

TEST_CASE("16-bit PNG file: signature, IHDR of 16-bit RGB and an sRGB chunk", "[io][png16]") {
  const mpr::Image<mpr::Color> image(3, 2, mpr::Color(0.5f, 0.18f, 0.002f));
  const std::vector<unsigned char> bytes = mpr::encode_png16(image.view());
  REQUIRE(bytes.size() > 33);
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  CHECK(std::equal(signature, signature + 8, bytes.begin()));
  CHECK(std::string(bytes.begin() + 12, bytes.begin() + 16) == "IHDR");
  CHECK(bytes[19] == 3);  // width 3 (big-endian, low byte)
  CHECK(bytes[23] == 2);  // height 2
  CHECK(bytes[24] == 16); // bit depth
  CHECK(bytes[25] == 2);  // colour type 2: RGB
  CHECK(std::string(bytes.begin(), bytes.end()).find("sRGB") != std::string::npos);
}

TEMPLATE_TEST_CASE("16-bit PNG keeps the renderer's linear values to the code", "[io][png16]", float, double) {
  const mpr::Image<mpr::Color> render = mpr_test::linear_render<TestType>();
  const auto path = temp_path("render.png");
  mpr::write_png16(path, render.view());
  const mpr::Image<mpr::Rgb16> back = mpr::read_png16(path);
  REQUIRE(back.width() == render.width());
  REQUIRE(back.height() == render.height());
  int inside = 0;
  for (int y = 0; y < render.height(); ++y)
    for (int x = 0; x < render.width(); ++x) {
      const mpr::Rgb16 p = back(x, y);
      const std::uint16_t codes[3] = {p.r, p.g, p.b};
      for (int c = 0; c < 3; ++c) {
        const float v = render(x, y)[c];
        // Each code is the rounded encoding of the clamped value (independent: the formula in double).
        const double clamped = std::clamp(static_cast<double>(v), 0.0, 1.0);
        const double encoded = clamped <= 0.0031308 ? 12.92 * clamped : 1.055 * std::pow(clamped, 1 / 2.4) - 0.055;
        CHECK(std::abs(codes[c] - 65535 * encoded) <= 0.5 + 1e-6);
        if (v > 0 && v < 1) {
          ++inside;
          // Decoded, within half a code step of the value (the step's slope at most 12.92 / 65535 ... 1/65535 per
          // code).
          CHECK(std::abs(mpr::from_png16_code(codes[c]) - v) <= 0.5f / 65535 * 2.4f * 1.1f + 1e-6f);
        }
      }
    }
  CHECK(inside > render.width() * render.height() / 2); // many channels lie inside (0, 1)
}

TEST_CASE("read_png16 reads an 8-bit PNG's codes as 257 c", "[io][png16]") {
  mpr::Image<mpr::Rgb8> image(2, 1);
  image(0, 0) = {0, 128, 255};
  image(1, 0) = {1, 2, 3};
  const auto path = temp_path("eight.png");
  mpr::write_png(path, image);
  const mpr::Image<mpr::Rgb16> back = mpr::read_png16(path);
  CHECK(back(0, 0) == mpr::Rgb16{0, 128 * 257, 65535});
  CHECK(back(1, 0) == mpr::Rgb16{257, 514, 771});
}

TEST_CASE("16-bit PNG: a failed write leaves no file, a bad file is named", "[io][png16]") {
  const mpr::Image<mpr::Color> image(2, 2, mpr::Color(0.5f, 0.5f, 0.5f));
  const auto missing = temp_path("no_such_folder") / "x.png";
  CHECK_THROWS_WITH(mpr::write_png16(missing, image.view()), Catch::Contains(missing.string()));
  CHECK_FALSE(std::filesystem::exists(missing));
  CHECK_THROWS_WITH(mpr::encode_png16(mpr::Image<mpr::Color>().view(), "e.png"),
                    Catch::Contains("e.png: cannot write an empty image"));
  const auto path = temp_path("cut.png");
  std::vector<unsigned char> bytes = mpr::encode_png16(image.view());
  bytes.resize(bytes.size() / 2);
  mpr::write_file_atomically(path, bytes);
  CHECK_THROWS_WITH(mpr::read_png16(path), Catch::Contains(path.string()));
}
#endif
