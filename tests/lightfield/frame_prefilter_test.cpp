#include "io/light_field_test_files.hpp"
#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/io/stanford_light_field.hpp>
#include <mpr/lightfield/frame_prefilter.hpp>
#include <mpr/mpr.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>

namespace {

/// The 8-bit image `full` box-filtered in linear light over 2x2 blocks.
mpr::Image<mpr::Rgb8> box_half(const mpr::Image<mpr::Rgb8>& full) {
  mpr::Image<mpr::Rgb8> out(full.width() / 2, full.height() / 2);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x)
      out(x, y) = mpr::to_rgb8((mpr::to_color(full(2 * x, 2 * y)) + mpr::to_color(full(2 * x + 1, 2 * y)) +
                                mpr::to_color(full(2 * x, 2 * y + 1)) + mpr::to_color(full(2 * x + 1, 2 * y + 1))) *
                               0.25f);
  return out;
}

/// The synthetic-aperture refocus of `frames` on the plane z = `depth` seen by `view`.
template <class T>
mpr::Image<mpr::Rgb8> refocus(const std::shared_ptr<const mpr::CameraFrameSet<T>>& frames,
                              const mpr::PinholeCamera<T>& view, T depth) {
  const mpr::PlanarSurface<T> plane = view.image_plane(depth);
  mpr::Image<mpr::Rgb8> out(view.width(), view.height());
  mpr::Renderer(plane, mpr::pinhole_glc(view, plane), mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(frames))
      .render(out.view(), mpr::Region(0, 0, view.width(), view.height()), {0});
  return out;
}

int level_difference(const mpr::Rgb8& a, const mpr::Rgb8& b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

} // namespace

TEMPLATE_TEST_CASE("downsampled cameras see the world where the averaged blocks saw it", "[frame_prefilter]", float,
                   double) {
  using T = TestType;
  mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
  K(0, 0) = T(410);
  K(1, 1) = T(395);
  K(0, 1) = T(0.7);
  K(0, 2) = T(318.25);
  K(1, 2) = T(241.5);
  const mpr::Mat3<T> R = Eigen::AngleAxis<T>(T(0.2), mpr::Vec3<T>(1, 2, 3).normalized()).toRotationMatrix();
  const mpr::PinholeCamera<T> camera(K, R, mpr::Vec3<T>(T(0.3), T(-0.2), T(1.5)), 641, 481);
  for (const int k : {2, 3, 4}) {
    const mpr::PinholeCamera<T> small = mpr::downsampled(camera, k);
    CHECK(small.width() == 641 / k);
    CHECK(small.height() == 481 / k);
    CHECK(small.centre().isApprox(camera.centre()));
    // Pixel centres at integers: block b spans old pixels k b .. k b + k - 1, centred on
    // k b + (k - 1) / 2, which must project to b.
    for (const mpr::Vec3<T>& world :
         {mpr::Vec3<T>(0, 0, 5), mpr::Vec3<T>(T(-1.2), T(0.8), T(7)), mpr::Vec3<T>(T(2), T(1), T(9))}) {
      const auto pp = camera.project(world), qq = small.project(world);
      REQUIRE(pp);
      REQUIRE(qq);
      const mpr::Vec2<T> p = *pp, q = *qq;
      const T half = static_cast<T>(k - 1) / 2;
      CHECK(std::abs(q.x() - (p.x() - half) / static_cast<T>(k)) < T(1e-3));
      CHECK(std::abs(q.y() - (p.y() - half) / static_cast<T>(k)) < T(1e-3));
    }
  }
}

TEMPLATE_TEST_CASE("downsampled frames average each block in linear light", "[frame_prefilter]", float, double) {
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(2, 1, 1.0, 4, 2, 4.0);
  std::vector<mpr::Image<mpr::Rgb8>> images(2, mpr::Image<mpr::Rgb8>(4, 2));
  // Camera 0: a black/white block (the mean of linear 0 and 1 is 0.5: code 188, not the code
  // mean 128) and a block of one colour (keeps its code).
  images[0](0, 0) = images[0](1, 1) = mpr::Rgb8{0, 0, 0};
  images[0](1, 0) = images[0](0, 1) = mpr::Rgb8{255, 255, 255};
  for (int y = 0; y < 2; ++y)
    for (int x = 2; x < 4; ++x) images[0](x, y) = mpr::Rgb8{37, 141, 250};
  // Camera 1: four different codes.
  images[1](0, 0) = {10, 20, 30};
  images[1](1, 0) = {200, 100, 50};
  images[1](0, 1) = {90, 180, 0};
  images[1](1, 1) = {255, 1, 77};
  const mpr::CameraFrameSet<T> frames(cams, images, {"left", "right"});
  const mpr::CameraFrameSet<T> half = mpr::downsampled(frames, 2);
  REQUIRE(half.size() == 2);
  CHECK(half.name(1) == "right");
  REQUIRE(half.image(0).width() == 2);
  REQUIRE(half.image(0).height() == 1);
  CHECK(half.image(0)(0, 0) == (mpr::Rgb8{188, 188, 188}));
  CHECK(half.image(0)(1, 0) == (mpr::Rgb8{37, 141, 250}));
  const mpr::Color mean = (mpr::to_color(images[1](0, 0)) + mpr::to_color(images[1](1, 0)) +
                           mpr::to_color(images[1](0, 1)) + mpr::to_color(images[1](1, 1))) *
                          0.25f;
  CHECK(half.image(1)(0, 0) == mpr::to_rgb8(mean));
  // The samplers read the new images.
  CHECK(half.texels(0)[0].c[0] == 188);
  // Factor 1 is a copy; factors below 1 or above a camera's size are refused, naming it.
  CHECK(mpr::downsampled(frames, 1).image(1)(1, 1) == images[1](1, 1));
  CHECK_THROWS_WITH(mpr::downsampled(frames, 0), Catch::Contains("factor"));
  CHECK_THROWS_WITH(mpr::downsampled(frames, 3), Catch::Contains("left") && Catch::Contains("4x2"));

  // Every code of a uniform block survives (the mean of four equal floats is exact).
  std::vector<mpr::Image<mpr::Rgb8>> ramp{mpr::Image<mpr::Rgb8>(512, 2)};
  for (int x = 0; x < 512; ++x)
    for (int y = 0; y < 2; ++y)
      ramp[0](x, y) = mpr::Rgb8{static_cast<std::uint8_t>(x / 2), static_cast<std::uint8_t>(255 - x / 2), 7};
  const auto ramp_half = mpr::downsampled(
      mpr::CameraFrameSet<T>({mpr::PinholeCamera<T>(cams[0].K(), cams[0].R(), cams[0].t(), 512, 2)}, ramp), 2);
  int changed = 0;
  for (int x = 0; x < 256; ++x)
    if (!(ramp_half.image(0)(x, 0) == ramp[0](2 * x, 0))) ++changed;
  CHECK(changed == 0);
}

TEMPLATE_TEST_CASE("downsampled frames of sizes that are not multiples of the factor", "[frame_prefilter]", float,
                   double) {
  using T = TestType;
  // A 7 x 5 image of distinct codes per pixel, and a camera with radial distortion.
  mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
  K(0, 0) = K(1, 1) = T(6);
  K(0, 2) = T(3);
  K(1, 2) = T(2);
  const mpr::PinholeCamera<T> camera(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>::Zero(), 7, 5, {T(0.05), T(-0.01)});
  mpr::Image<mpr::Rgb8> image(7, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x)
      image(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(30 * x + 7 * y), static_cast<std::uint8_t>(200 - 25 * y),
                              static_cast<std::uint8_t>((x * 53 + y * 91) % 256)};
  const mpr::CameraFrameSet<T> frames({camera, camera}, {image, image});
  for (const int k : {2, 3}) {
    INFO("factor " << k);
    const mpr::CameraFrameSet<T> one = mpr::downsampled(frames, k, 1), two = mpr::downsampled(frames, k, 2);
    REQUIRE(one.image(0).width() == 7 / k);
    REQUIRE(one.image(0).height() == 5 / k);
    CHECK(one.camera(1).distortion().k1 == camera.distortion().k1);
    CHECK(one.camera(1).distortion().k2 == camera.distortion().k2);
    int wrong = 0, differ = 0;
    for (int y = 0; y < 5 / k; ++y)
      for (int x = 0; x < 7 / k; ++x) {
        mpr::Color sum = mpr::Color::Zero();
        for (int dy = 0; dy < k; ++dy)
          for (int dx = 0; dx < k; ++dx) sum += mpr::to_color(image(k * x + dx, k * y + dy));
        const mpr::Rgb8 want = mpr::to_rgb8(sum / static_cast<float>(k * k));
        for (std::size_t i = 0; i < 2; ++i) {
          const mpr::Rgb8 got = one.image(i)(x, y);
          wrong += std::max({std::abs(want.r - got.r), std::abs(want.g - got.g), std::abs(want.b - got.b)}) > 1;
          differ += !(two.image(i)(x, y) == got); // workers share cameras, not pixels: the same codes
        }
      }
    CHECK(wrong == 0);
    CHECK(differ == 0);
  }
  CHECK_THROWS_WITH(mpr::downsampled(camera, 0), Catch::Contains("factor"));
  CHECK_THROWS_WITH(mpr::downsampled(camera, 6), Catch::Contains("factor") && Catch::Contains("7x5"));
  CHECK(mpr::downsampled(camera, 5).width() == 1);
}

TEMPLATE_TEST_CASE("downsampled linear frames and depth maps", "[frame_prefilter]", float, double) {
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(1, 1, 1.0, 3, 2, 4.0);
  std::vector<mpr::Image<mpr::Color>> images{mpr::Image<mpr::Color>(3, 2, mpr::Color(2.0f, -1.0f, 0.25f))};
  images[0](0, 0) = mpr::Color(-2.0f, 3.0f, 0.25f);
  const float inf = std::numeric_limits<float>::infinity();
  mpr::Image<float> depth(3, 2, inf);
  depth(1, 0) = 7.0f;
  depth(0, 1) = 5.0f;
  depth(2, 0) = 1.0f; // in the dropped third column
  const mpr::CameraFrameSet<T, mpr::Color> frames =
      mpr::CameraFrameSet<T, mpr::Color>(cams, images).with_depth({depth});
  const auto half = mpr::downsampled(frames, 2);
  REQUIRE(half.image(0).width() == 1);
  // HDR and negative values average unclamped: (-2 + 3 * 2) / 4 = 1, (3 - 3) / 4 = 0.
  CHECK(half.image(0)(0, 0)[0] == 1.0f);
  CHECK(half.image(0)(0, 0)[1] == 0.0f);
  CHECK(half.image(0)(0, 0)[2] == 0.25f);
  REQUIRE(half.has_depth());
  CHECK(half.depth(0)(0, 0) == 5.0f); // the nearest depth of the block
  CHECK(half.depth_near(0) == 5.0f);
  const auto nothing =
      mpr::downsampled(mpr::CameraFrameSet<T, mpr::Color>(cams, images).with_depth({mpr::Image<float>(3, 2, inf)}), 2);
  CHECK(nothing.depth(0)(0, 0) == inf);
}

TEMPLATE_TEST_CASE("a half-scale refocus of prefiltered frames is the box-filtered full-scale refocus",
                   "[frame_prefilter]", float, double) {
  using T = TestType;
  // 3x3 cameras 2 apart, focal length 16 pixels: on the plane z = 16 neighbouring cameras are two
  // pixels apart, so the full-scale refocus samples whole texels and the half-scale one of the
  // prefiltered frames whole blocks, the same blocks the box filter of the full image averages:
  // equal up to rounding. (A principal point off by half a pixel would shift every block.)
  const auto cams = mpr_test::grid_cameras<T>(3, 3, 2.0, 32, 24, 16.0);
  const auto images = mpr_test::with_detail(mpr_test::plane_images(cams, 16.0), 7, 0x3F, 0x1F, 0x3F);
  const auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(cams, images);
  const auto half_frames = std::make_shared<const mpr::CameraFrameSet<T>>(mpr::downsampled(*frames, 2));
  const mpr::PinholeCamera<T> centre = mpr_test::camera_at<T>(mpr::Vec3<T>::Zero(), 32, 24, 16.0);
  // The half-scale view written out, not derived by `downsampled`: focal length 8, the image
  // centre at (7.5, 5.5).
  const mpr::PinholeCamera<T> small = mpr_test::camera_at<T>(mpr::Vec3<T>::Zero(), 16, 12, 8.0);
  const mpr::Image<mpr::Rgb8> full = refocus(frames, centre, T(16)), half = refocus(half_frames, small, T(16));
  const mpr::Image<mpr::Rgb8> boxed = box_half(full);
  // Away from the border, where every camera sees the block.
  int worst = 0;
  for (int y = 2; y < 10; ++y)
    for (int x = 2; x < 14; ++x) worst = std::max(worst, level_difference(half(x, y), boxed(x, y)));
  CHECK(worst <= 1);
}

TEST_CASE("Chess at half scale from prefiltered frames", "[frame_prefilter][real_data]") {
  const std::filesystem::path root = mpr_test::data_dir() / "stanford" / "chess";
  if (!std::filesystem::is_directory(root)) {
    WARN("real data not found under '" << root.string() << "' (set MPR_DATA_DIR): skipped");
    return;
  }
  using T = float;
  const auto lf = std::make_shared<const mpr::CameraFrameSet<T>>(mpr::read_stanford_light_field<T>(root));
  const auto lh = std::make_shared<const mpr::CameraFrameSet<T>>(mpr::downsampled(*lf, 2));
  REQUIRE(lh->camera(0).width() == 700);
  REQUIRE(lh->camera(0).height() == 400);
  mpr::Mat3<T> K = lf->camera(0).K();
  K(0, 2) = T(699.5);
  K(1, 2) = T(399.5);
  const mpr::PinholeCamera<T> centre(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>::Zero(), 1400, 800);
  mpr::Mat3<T> Kh = K; // the half-scale view written out, not derived by `downsampled`
  Kh(0, 0) *= T(0.5);
  Kh(1, 1) *= T(0.5);
  Kh(0, 2) = T(349.5);
  Kh(1, 2) = T(199.5);
  const mpr::PinholeCamera<T> small(Kh, mpr::Mat3<T>::Identity(), mpr::Vec3<T>::Zero(), 700, 400);
  // At the reference plane z = 1000 every camera's shift is a whole pixel at the full scale: the
  // half-scale refocus of the prefiltered frames is the box-filtered full refocus up to rounding
  // and, for odd shifts, the half-scale tent across two blocks.
  const mpr::Image<mpr::Rgb8> full = refocus(lf, centre, T(1000)), half = refocus(lh, small, T(1000));
  const mpr::Image<mpr::Rgb8> boxed = box_half(full);
  double squared = 0;
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 700; ++x)
      for (int c = 0; c < 3; ++c) {
        const double d = double((&half(x, y).r)[c]) - double((&boxed(x, y).r)[c]);
        squared += d * d;
      }
  const double psnr = 10 * std::log10(255.0 * 255.0 / (squared / (700.0 * 400.0 * 3.0)));
  INFO("PSNR " << psnr << " dB");
  CHECK(psnr > 50); // 58.1 dB measured
}
