// Compiled to nothing without OpenEXR (tests/CMakeLists.txt defines MPR_HAVE_OPENEXR when found).
#if defined(MPR_HAVE_OPENEXR)
#include <mpr/io/exr.hpp>

#include "io/linear_render.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace {
std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("mpr_exr_" + name);
}
} // namespace

TEMPLATE_TEST_CASE("float OpenEXR keeps the renderer's linear values exactly", "[io][exr]", float, double) {
  const mpr::Image<mpr::Color> render = mpr_test::linear_render<TestType>();
  const auto path = temp_path("float.exr");
  mpr::write_exr(path, render.view(), mpr::ExrSample::float32);
  const mpr::Image<mpr::Color> back = mpr::read_exr(path);
  REQUIRE(back.width() == render.width());
  REQUIRE(back.height() == render.height());
  for (int y = 0; y < render.height(); ++y)
    for (int x = 0; x < render.width(); ++x) CHECK((back(x, y) == render(x, y)).all());
}

TEMPLATE_TEST_CASE("half OpenEXR keeps the renderer's linear values to half precision", "[io][exr]", float, double) {
  const mpr::Image<mpr::Color> render = mpr_test::linear_render<TestType>();
  const auto path = temp_path("half.exr");
  mpr::write_exr(path, render.view()); // half by default
  const mpr::Image<mpr::Color> back = mpr::read_exr(path);
  REQUIRE(back.width() == render.width());
  REQUIRE(back.height() == render.height());
  int differ = 0;
  for (int y = 0; y < render.height(); ++y)
    for (int x = 0; x < render.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = render(x, y)[c], b = back(x, y)[c];
        // Half has 11 significant bits: rounding to nearest is within 2^-11 relative, and within
        // 2^-25 (half the smallest subnormal step, 2^-24) near 0.
        CHECK(std::abs(b - v) <= std::max(std::abs(v) * 0x1p-11f, 0x1p-25f));
        differ += b != v ? 1 : 0;
      }
  CHECK(differ > 0); // it is half: most float values are not representable
}

TEST_CASE("half OpenEXR values worked out by hand", "[io][exr]") {
  mpr::Image<mpr::Color> image(2, 1);
  image(0, 0) = mpr::Color(0.1f, 1.0f / 3, -2.5f);
  image(1, 0) = mpr::Color(1e5f, 65504, 0.0f);
  const auto path = temp_path("hand.exr");
  mpr::write_exr(path, image.view(), mpr::ExrSample::half);
  const mpr::Image<mpr::Color> back = mpr::read_exr(path);
  CHECK(back(0, 0)[0] == 0.0999755859375f); // 1638 * 2^-14, the half nearest 0.1
  CHECK(back(0, 0)[1] == 0.333251953125f);  // 1365 * 2^-12
  CHECK(back(0, 0)[2] == -2.5f);            // exact
  CHECK(std::isinf(back(1, 0)[0]));         // above the largest half, 65504
  CHECK(back(1, 0)[1] == 65504.0f);
  CHECK(back(1, 0)[2] == 0.0f);
  // The file starts with OpenEXR's magic number 20000630 (76 2f 31 01).
  const std::vector<unsigned char> bytes = mpr::encode_exr(image.view(), mpr::ExrSample::half);
  REQUIRE(bytes.size() > 4);
  CHECK((bytes[0] == 0x76 && bytes[1] == 0x2f && bytes[2] == 0x31 && bytes[3] == 0x01));
}

TEST_CASE("OpenEXR: a failed write leaves no file, a bad file is named", "[io][exr]") {
  const mpr::Image<mpr::Color> image(2, 2, mpr::Color(0.5f, 0.5f, 0.5f));
  const auto missing = temp_path("no_such_folder") / "x.exr";
  CHECK_THROWS_WITH(mpr::write_exr(missing, image.view()), Catch::Contains(missing.string()));
  CHECK_FALSE(std::filesystem::exists(missing));
  CHECK_THROWS_WITH(mpr::encode_exr(mpr::Image<mpr::Color>().view(), mpr::ExrSample::half, "e.exr"),
                    Catch::Contains("e.exr: cannot write an empty image"));
  const auto path = temp_path("cut.exr");
  std::vector<unsigned char> bytes = mpr::encode_exr(image.view(), mpr::ExrSample::float32);
  bytes.resize(bytes.size() / 2);
  mpr::write_file_atomically(path, bytes);
  CHECK_THROWS_WITH(mpr::read_exr(path), Catch::Contains(path.string()));
  const auto png = temp_path("not.exr");
  mpr::write_file_atomically(png, std::vector<unsigned char>{'n', 'o', 't'});
  CHECK_THROWS_WITH(mpr::read_exr(png), Catch::Contains(png.string()));
}
#endif
