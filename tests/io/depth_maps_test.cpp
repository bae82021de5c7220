#include "lightfield/frame_test_scenes.hpp"

#include <mpr/io/depth_maps.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

namespace {
std::filesystem::path temp_folder(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("mpr_depth_maps_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}
} // namespace

TEMPLATE_TEST_CASE("depth maps round trip through a folder of PFM files named after the frames", "[io][depth_maps]",
                   float, double) {
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(2, 1, 1.0, 6, 4, 4.0);
  const std::vector<mpr::Image<mpr::Rgb8>> images(2, mpr::Image<mpr::Rgb8>(6, 4));
  std::vector<mpr::Image<float>> maps{mpr::Image<float>(6, 4, 3.0f), mpr::Image<float>(6, 4, 5.0f)};
  maps[1](5, 3) = std::numeric_limits<float>::infinity();
  const auto frames = mpr::CameraFrameSet<T>(cams, images, {"cam_000_000.png", "sub/cam_000_001.png"}).with_depth(maps);
  CHECK(mpr::depth_map_name("sub/cam_000_001.png") == "cam_000_001.pfm");
  const auto dir = temp_folder("roundtrip");
  mpr::write_depth_maps(dir, frames);
  const std::vector<mpr::Image<float>> back = mpr::read_depth_maps(dir, frames);
  REQUIRE(back.size() == 2);
  CHECK(back[0](2, 2) == 3.0f);
  CHECK(std::isinf(back[1](5, 3)));
  CHECK(mpr::CameraFrameSet<T>(cams, images).with_depth(back).has_depth());
  // A set without depth has nothing to write.
  CHECK_THROWS_AS(mpr::write_depth_maps(dir, mpr::CameraFrameSet<T>(cams, images)), mpr::argument_error);

  // Wrong size, NaN and a missing file name the file.
  mpr::write_pfm(dir / "cam_000_001.pfm", mpr::Image<float>(4, 6, 1.0f));
  CHECK_THROWS_WITH(mpr::read_depth_maps(dir, frames),
                    Catch::Contains("cam_000_001.pfm") && Catch::Contains("depth map is 4x6"));
  mpr::Image<float> nan_map(6, 4, 1.0f);
  nan_map(1, 2) = std::nanf("");
  mpr::write_pfm(dir / "cam_000_001.pfm", nan_map);
  CHECK_THROWS_WITH(mpr::read_depth_maps(dir, frames),
                    Catch::Contains("cam_000_001.pfm") && Catch::Contains("at pixel (1, 2)"));
  std::filesystem::remove(dir / "cam_000_001.pfm");
  CHECK_THROWS_WITH(mpr::read_depth_maps(dir, frames), Catch::Contains("cam_000_001.pfm"));
}

TEST_CASE("depth preview colours near to far with a legend, infinity black", "[io][depth_maps]") {
  mpr::Image<float> depth(300, 20);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 300; ++x) depth(x, y) = 1.0f + static_cast<float>(x) / 299.0f;
  depth(0, 0) = std::numeric_limits<float>::infinity();
  const mpr::DepthRange range = mpr::depth_range(depth.view());
  CHECK(range.near == 1.0f);
  CHECK(range.far == 2.0f);
  const mpr::Image<mpr::Rgb8> preview = mpr::depth_preview(depth.view());
  REQUIRE(preview.width() == 300);
  REQUIRE(preview.height() > 20 + 18); // legend strip: ramp and two lines of text at scale 2
  CHECK(preview(0, 0) == mpr::Rgb8{0, 0, 0});
  CHECK(preview(0, 5) == mpr::depth_ramp(0.0f));
  CHECK(preview(299, 5) == mpr::depth_ramp(1.0f));
  // Near is bright, far is dark.
  const auto luma = [](mpr::Rgb8 c) { return c.r + c.g + c.b; };
  CHECK(luma(mpr::depth_ramp(0.0f)) > luma(mpr::depth_ramp(0.5f)));
  CHECK(luma(mpr::depth_ramp(0.5f)) > luma(mpr::depth_ramp(1.0f)));
  // The legend's ramp runs under the image, and its text is drawn (white pixels below the ramp).
  CHECK(preview(0, 24) == mpr::depth_ramp(0.0f));
  int white = 0;
  for (int y = 20; y < preview.height(); ++y)
    for (int x = 0; x < 300; ++x) white += preview(x, y) == mpr::Rgb8{255, 255, 255} ? 1 : 0;
  CHECK(white > 50);
  // A map with nothing seen is all black; an empty map gives an empty preview.
  const mpr::Image<float> none(10, 10, std::numeric_limits<float>::infinity());
  CHECK(mpr::depth_preview(none.view())(5, 5) == mpr::Rgb8{0, 0, 0});
  CHECK(mpr::depth_preview(mpr::ImageView<const float>()).empty());
  const auto dir = temp_folder("preview");
  mpr::write_depth_preview(dir / "p.png", depth.view());
  CHECK(std::filesystem::file_size(dir / "p.png") > 0);
}
