#include "sampler/camera_frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/sampler/camera_frame_set.hpp>

TEST_CASE("CameraFrameSet keeps cameras, images, names and linear texels together", "[camera_frame_set]") {
  const auto cams = mpr_test::grid_cameras<double>(3, 1, 1.0, 4, 3, 4.0);
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (int k = 0; k < 3; ++k) images.emplace_back(4, 3, mpr::Rgb8{static_cast<std::uint8_t>(10 * k), 128, 255});
  const mpr::CameraFrameSet<double> frames(cams, images);
  REQUIRE(frames.size() == 3);
  CHECK(frames.name(2) == "frame 2");
  CHECK(frames.texels(1).size() == 12);
  CHECK(frames.texels(1)[5].c[0] == mpr::srgb8_to_linear(10));
  CHECK(frames.texels(1)[5].c[1] == mpr::srgb8_to_linear(128));
  CHECK(frames.texels(1)[5].c[2] == 1.0f);
  CHECK(frames.texels(1)[5].c[3] == 0.0f);

  const auto two = frames.without(1);
  REQUIRE(two.size() == 2);
  CHECK(two.name(1) == "frame 2");
  CHECK(two.camera(1).centre() == cams[2].centre());
  CHECK(two.texels(1)[0].c[0] == mpr::srgb8_to_linear(20));
  CHECK_THROWS_AS(frames.without(3), mpr::argument_error);

  const auto f = frames.cast<float>();
  REQUIRE(f.size() == 3);
  CHECK(f.camera(2).centre().isApprox(cams[2].centre().cast<float>()));
  CHECK(f.image(0) == frames.image(0));

  const std::vector<std::string> names{"a", "b"};
  CHECK_THROWS_AS((mpr::CameraFrameSet<double>(cams, images, names)), mpr::argument_error);

  // Linear frames are stored as given.
  std::vector<mpr::Image<mpr::Color>> linear{mpr::Image<mpr::Color>(4, 3, mpr::Color(0.25f, 2.0f, -1.0f))};
  const mpr::CameraFrameSet<double, mpr::Color> hdr({cams[0]}, linear);
  CHECK(hdr.texels(0)[11].c[1] == 2.0f);
  CHECK(hdr.texels(0)[11].c[2] == -1.0f);
}
