#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/frame_set.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

TEST_CASE("CameraFrameSet keeps cameras, images, names and linear texels together", "[camera_frame_set]") {
  const auto cams = mpr_test::grid_cameras<double>(3, 1, 1.0, 4, 3, 4.0);
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (int k = 0; k < 3; ++k) images.emplace_back(4, 3, mpr::Rgb8{static_cast<std::uint8_t>(10 * k), 128, 255});
  const mpr::CameraFrameSet<double> frames(cams, images);
  REQUIRE(frames.size() == 3);
  CHECK(frames.name(2) == "frame 2");
  CHECK(frames.texels(1).size() == 12);
  // 8-bit frames keep their codes (3 bytes a texel), decoded while sampling through a 16-bit
  // linear table: the exact decoded value rounded to 1/65535.
  STATIC_REQUIRE(std::is_same_v<mpr::CameraFrameSet<double>::texel_type, mpr::Srgb8Texel>);
  STATIC_REQUIRE(std::is_same_v<mpr::CameraFrameSet<double, mpr::Color>::texel_type, mpr::LinearTexel>);
  STATIC_REQUIRE(sizeof(mpr::Srgb8Texel) == 3);
  STATIC_REQUIRE(sizeof(mpr::LinearTexel) == 12);
  CHECK(frames.texels(1)[5].c[0] == 10);
  CHECK(frames.texels(1)[5].c[1] == 128);
  CHECK(frames.texels(1)[5].c[2] == 255);
  const std::uint16_t* table = mpr::Srgb8Texel::linear16();
  CHECK(mpr::texel_decode_table<mpr::Srgb8Texel>() == table);
  CHECK(mpr::texel_decode_table<mpr::LinearTexel>() == nullptr);
  const auto fixed = [&](std::uint8_t code) { return static_cast<double>(table[code]) / 65535.0; };
  CHECK(std::abs(fixed(10) - mpr::srgb8_to_linear(10)) <= 0.5 / 65535 + 1e-9);
  CHECK(std::abs(fixed(128) - mpr::srgb8_to_linear(128)) <= 0.5 / 65535 + 1e-9);
  CHECK(table[255] == 65535);
  CHECK(table[0] == 0);
  // Every 8-bit code survives the fixed-point step: it decodes back to the same code.
  std::vector<mpr::Image<mpr::Rgb8>> ramp{mpr::Image<mpr::Rgb8>(256, 1)};
  for (int v = 0; v < 256; ++v)
    ramp[0](v, 0) = mpr::Rgb8{static_cast<std::uint8_t>(v), 0, static_cast<std::uint8_t>(255 - v)};
  const mpr::CameraFrameSet<double> codes({mpr::PinholeCamera<double>(cams[0].K(), cams[0].R(), cams[0].t(), 256, 1)},
                                          ramp);
  int mismatches = 0;
  for (int v = 0; v < 256; ++v) {
    const mpr::Srgb8Texel& t = codes.texels(0)[static_cast<std::size_t>(v)];
    const mpr::Color c(static_cast<float>(table[t.c[0]]) * mpr::Srgb8Texel::scale,
                       static_cast<float>(table[t.c[1]]) * mpr::Srgb8Texel::scale,
                       static_cast<float>(table[t.c[2]]) * mpr::Srgb8Texel::scale);
    if (!(mpr::to_rgb8(c) == ramp[0](v, 0))) ++mismatches;
  }
  CHECK(mismatches == 0);

  const auto two = frames.without(1);
  REQUIRE(two.size() == 2);
  CHECK(two.name(1) == "frame 2");
  CHECK(two.camera(1).centre() == cams[2].centre());
  CHECK(two.texels(1)[0].c[0] == frames.texels(2)[0].c[0]);
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

TEST_CASE("CameraFrameSet decodes its images into one buffer, each 64-byte aligned, shared by its copies",
          "[camera_frame_set]") {
  // Sizes that are not multiples of 64 texels, 8-bit and linear.
  const auto cams = mpr_test::grid_cameras<double>(4, 1, 1.0, 7, 5, 4.0);
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (int k = 0; k < 4; ++k) {
    images.emplace_back(7, 5);
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 7; ++x)
        images.back()(x, y) =
            mpr::Rgb8{static_cast<std::uint8_t>(k), static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y)};
  }
  const mpr::CameraFrameSet<double> frames(cams, images);
  for (std::size_t k = 0; k < 4; ++k) {
    INFO("image " << k);
    const auto t = frames.texels(k);
    CHECK(t.size() == 35);
    CHECK(reinterpret_cast<std::uintptr_t>(t.data()) % 64 == 0);
    if (k > 0) CHECK(t.data() >= frames.texels(k - 1).data() + 35 + 1); // no overlap
    int wrong = 0;
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 7; ++x) {
        const mpr::Srgb8Texel& v = t[static_cast<std::size_t>(7 * y + x)];
        wrong += v.c[0] != k || v.c[1] != x || v.c[2] != y ? 1 : 0;
      }
    CHECK(wrong == 0);
  }
  // without(), copies and cast<U>() keep the images and their texels where they are (nothing
  // decoded or copied).
  const auto three = frames.without(1);
  CHECK(three.texels(0).data() == frames.texels(0).data());
  CHECK(three.texels(1).data() == frames.texels(2).data());
  CHECK(three.texels(2).data() == frames.texels(3).data());
  CHECK(three.image(1).data() == frames.image(2).data());
  const mpr::CameraFrameSet<double> copy = frames;
  CHECK(copy.texels(3).data() == frames.texels(3).data());
  CHECK(copy.image(3).data() == frames.image(3).data());
  const mpr::CameraFrameSet<float> single = frames.cast<float>();
  REQUIRE(single.size() == 4);
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK(single.texels(k).data() == frames.texels(k).data());
    CHECK(single.texels(k).size() == 35);
    CHECK(single.image(k).data() == frames.image(k).data());
    CHECK(single.name(k) == frames.name(k));
    CHECK(single.camera(k).centre().template cast<double>().isApprox(frames.camera(k).centre(), 1e-6));
  }

  const std::vector<mpr::Image<mpr::Color>> linear(3, mpr::Image<mpr::Color>(7, 5, mpr::Color(0.5f, 1.5f, -2.0f)));
  const mpr::CameraFrameSet<double, mpr::Color> hdr({cams[0], cams[1], cams[2]}, linear);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(reinterpret_cast<std::uintptr_t>(hdr.texels(k).data()) % 64 == 0);
    CHECK(hdr.texels(k)[34].c[1] == 1.5f);
  }
}

TEST_CASE("CameraFrameSet holds 8-bit frames as 16-bit linear values below the VBMI level", "[camera_frame_set]") {
  using Level = mpr::detail::SimdLevel;
  using Set = mpr::CameraFrameSet<double>;
  CHECK(Set::holds_linear16(Level::portable) == bool(MPR_HAVE_HWY));
  CHECK(Set::holds_linear16(Level::avx2) == bool(MPR_HAVE_HWY));
  CHECK(Set::holds_linear16(Level::avx512) == bool(MPR_HAVE_HWY));
  CHECK_FALSE(Set::holds_linear16(Level::avx512vbmi));
  CHECK_FALSE(mpr::CameraFrameSet<double, mpr::Color>::holds_linear16(Level::portable));
  // Codes 0, 1, 10, 128, 200, 255: 65535 x their linear values (IEC 61966-2-1) are 0, 19.89,
  // 198.92, 14146.42, 37851.73, 65535.
  const std::array<std::uint8_t, 6> codes{0, 1, 10, 128, 200, 255};
  const std::array<std::uint16_t, 6> want{0, 20, 199, 14146, 37852, 65535};
  const auto cams = mpr_test::grid_cameras<double>(3, 1, 1.0, 7, 5, 4.0);
  std::vector<mpr::Image<mpr::Rgb8>> images(3, mpr::Image<mpr::Rgb8>(7, 5));
  for (std::size_t k = 0; k < 3; ++k)
    for (int i = 0; i < 35; ++i) {
      const std::size_t c = (k + static_cast<std::size_t>(i)) % 6;
      images[k](i % 7, i / 7) = mpr::Rgb8{codes[c], codes[(c + 1) % 6], codes[(c + 2) % 6]};
    }
  const Set frames(cams, images);
  REQUIRE((frames.linear16(0) != nullptr) == Set::holds_linear16());
  if (!Set::holds_linear16()) return;
  int wrong = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(reinterpret_cast<std::uintptr_t>(frames.linear16(k)) % 64 == 0);
    if (k > 0) CHECK(frames.linear16(k) >= frames.linear16(k - 1) + 3 * 35 + 32); // values after each
    for (std::size_t i = 0; i < 35; ++i)
      for (std::size_t ch = 0; ch < 3; ++ch) wrong += frames.linear16(k)[3 * i + ch] != want[(k + i + ch) % 6] ? 1 : 0;
  }
  CHECK(wrong == 0);
  // Copies share the values.
  CHECK(frames.without(0).linear16(1) == frames.linear16(2));
  CHECK(frames.cast<float>().linear16(2) == frames.linear16(2));
}

TEST_CASE("CameraFrameSet::on_plane declares the array plane, checked against the centres", "[camera_frame_set]") {
  // grid_cameras puts the centres on z = 0.
  const auto cams = mpr_test::grid_cameras<double>(3, 2, 1.0, 4, 3, 4.0);
  const std::vector<mpr::Image<mpr::Rgb8>> images(6, mpr::Image<mpr::Rgb8>(4, 3));
  CHECK_FALSE(mpr::CameraFrameSet<double>(cams, images).array_plane().has_value());
  const auto planar = mpr::CameraFrameSet<double>(cams, images).on_plane({mpr::Vec3<double>::Zero(), {0, 0, -3}});
  REQUIRE(planar.array_plane().has_value());
  CHECK(planar.array_plane()->normal == mpr::Vec3<double>(0, 0, -3));
  CHECK(planar.without(0).array_plane().has_value());
  // A plane the centres do not lie on, a zero normal and a NaN point are refused.
  using Error = mpr::argument_error;
  CHECK_THROWS_AS(mpr::CameraFrameSet<double>(cams, images).on_plane({mpr::Vec3<double>::Zero(), {0, 1, 0}}), Error);
  CHECK_THROWS_AS(mpr::CameraFrameSet<double>(cams, images).on_plane({{0, 0, 0.01}, {0, 0, 1}}), Error);
  CHECK_THROWS_AS(mpr::CameraFrameSet<double>(cams, images).on_plane({mpr::Vec3<double>::Zero(), {0, 0, 0}}), Error);
  CHECK_THROWS_AS(
      mpr::CameraFrameSet<double>(cams, images).on_plane({mpr::Vec3<double>::Constant(std::nan("")), {0, 0, 1}}),
      Error);
}

TEMPLATE_TEST_CASE("CameraFrameSet::with_depth carries one checked depth map per camera", "[camera_frame_set]", float,
                   double) {
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(3, 1, 1.0, 4, 3, 4.0);
  const std::vector<mpr::Image<mpr::Rgb8>> images(3, mpr::Image<mpr::Rgb8>(4, 3));
  const mpr::CameraFrameSet<T> plain(cams, images);
  CHECK_FALSE(plain.has_depth());
  std::vector<mpr::Image<float>> maps;
  for (int k = 0; k < 3; ++k) maps.emplace_back(4, 3, 2.0f + static_cast<float>(k));
  maps[1](3, 2) = std::numeric_limits<float>::infinity(); // nothing seen
  const auto with = mpr::CameraFrameSet<T>(cams, images, {"a", "b", "c"}).with_depth(maps);
  REQUIRE(with.has_depth());
  CHECK(with.depth(2)(0, 0) == 4.0f);
  CHECK(std::isinf(with.depth(1)(3, 2)));
  // Leave-one-out and the scalar cast keep the maps in step with the cameras.
  const auto without = with.without(1);
  REQUIRE(without.has_depth());
  CHECK(without.size() == 2);
  CHECK(without.depth(0)(0, 0) == 2.0f);
  CHECK(without.depth(1)(0, 0) == 4.0f);
  CHECK(&without.depth(1)(0, 0) == &with.depth(2)(0, 0)); // shared, not copied
  // The nearest depth of each map (where a surface search may start), kept in step too.
  maps[0](1, 1) = 1.5f;
  const auto nearest = mpr::CameraFrameSet<T>(cams, images).with_depth(maps);
  CHECK(nearest.depth_near(0) == 1.5f);
  CHECK(nearest.depth_near(1) == 3.0f); // the +inf pixel does not count
  CHECK(nearest.depth_near(2) == 4.0f);
  CHECK(nearest.without(0).depth_near(0) == 3.0f);
  std::vector<mpr::Image<float>> unseen(3, mpr::Image<float>(4, 3, std::numeric_limits<float>::infinity()));
  CHECK(std::isinf(mpr::CameraFrameSet<T>(cams, images).with_depth(unseen).depth_near(2)));
  const auto other = with.template cast<std::conditional_t<std::is_same_v<T, float>, double, float>>();
  REQUIRE(other.has_depth());
  CHECK(other.depth(0)(1, 1) == 2.0f);
  CHECK(&other.depth(1)(0, 0) == &with.depth(1)(0, 0));
  CHECK(std::isinf(other.depth(1)(3, 2)));
  CHECK(other.depth_near(2) == 4.0f);
  // An empty list drops them.
  CHECK_FALSE(mpr::CameraFrameSet<T>(with).with_depth({}).has_depth());

  // Wrong count, wrong size, NaN, zero and negative depths name the camera.
  const auto refuse = [&](std::vector<mpr::Image<float>> bad, const char* what) {
    CHECK_THROWS_WITH(mpr::CameraFrameSet<T>(cams, images, {"a", "b", "c"}).with_depth(std::move(bad)),
                      Catch::Contains("depth maps") && Catch::Contains(what));
  };
  refuse({maps[0], maps[1]}, "3 cameras but 2 depth maps");
  auto sized = maps;
  sized[2] = mpr::Image<float>(3, 4, 1.0f);
  refuse(sized, "c: depth map is 3x4");
  for (const float v : {std::nanf(""), 0.0f, -1.0f, -std::numeric_limits<float>::infinity()}) {
    auto bad = maps;
    bad[1](2, 1) = v;
    refuse(bad, "b: depth");
  }
}

TEMPLATE_TEST_CASE("CameraFrameSet::depth_bounds holds every surface point the depth maps show", "[camera_frame_set]",
                   float, double) {
  using T = TestType;
  // Two cameras of 40 x 30 pixels (focal 30, principal point at the centre) at x = 0 and x = 2,
  // looking along +z. Camera 0 sees z = 5 everywhere: its points span x, y = 5 (p - c) / 30 over
  // the pixel centres p, i.e. [-3.25, 3.25] x [-2.4167, 2.4167] x {5}, widened by two pixels at
  // depth 5 (1/3). Camera 1 sees one pixel at depth 10 and nothing elsewhere.
  const std::vector<mpr::PinholeCamera<T>> cams{mpr_test::camera_at<T>(mpr::Vec3<T>(0, 0, 0), 40, 30, 30.0),
                                                mpr_test::camera_at<T>(mpr::Vec3<T>(2, 0, 0), 40, 30, 30.0)};
  const std::vector<mpr::Image<mpr::Rgb8>> images(2, mpr::Image<mpr::Rgb8>(40, 30));
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<mpr::Image<float>> maps{mpr::Image<float>(40, 30, 5.0f), mpr::Image<float>(40, 30, inf)};
  maps[1](19, 14) = 10.0f; // the ray through (19, 14) leaves the centre at (-0.5, -0.5) / 30
  const auto set = mpr::CameraFrameSet<T>(cams, images).with_depth(maps);
  const auto& b = set.depth_bounds();
  const double m0 = 2.0 * 5.0 / 30.0, m1 = 2.0 * 10.0 / 30.0;
  const double lo[3] = {-3.25 - m0, -14.5 * 5.0 / 30.0 - m0, 5.0 - m0};
  const double hi[3] = {3.25 + m0, 14.5 * 5.0 / 30.0 + m0, 10.0 + m1};
  for (int a = 0; a < 3; ++a) {
    INFO("axis " << a);
    CHECK(static_cast<double>(b[0][a]) == Approx(lo[a]).epsilon(1e-5));
    CHECK(static_cast<double>(b[1][a]) == Approx(hi[a]).epsilon(1e-5));
  }
  // Leave-one-out recomputes the box from the remaining maps; maps that show nothing give an
  // empty box (lower corner above the upper), as does a set without maps.
  const auto only_pixel = set.without(0);
  CHECK(static_cast<double>(only_pixel.depth_bounds()[0].x()) == Approx(2.0 - 0.5 * 10.0 / 30.0 - m1).epsilon(1e-5));
  CHECK(static_cast<double>(only_pixel.depth_bounds()[1].z()) == Approx(10.0 + m1).epsilon(1e-5));
  const auto unseen = mpr::CameraFrameSet<T>(cams, images)
                          .with_depth(std::vector<mpr::Image<float>>(2, mpr::Image<float>(40, 30, inf)));
  CHECK_FALSE(unseen.depth_bounds()[0].z() <= unseen.depth_bounds()[1].z());
  CHECK_FALSE(mpr::CameraFrameSet<T>(cams, images).depth_bounds()[0].z() <=
              mpr::CameraFrameSet<T>(cams, images).depth_bounds()[1].z());
}

TEST_CASE("CameraFrameSet reads borrowed 8-bit images in place when 64 bytes after them are readable",
          "[camera_frame_set]") {
  // Three 7x5 images in one 4 KiB-aligned block of memory, placed so that each ends at a chosen
  // offset in a 4 KiB block: 105 bytes of pixels ending at offset 1000 and 4032 (64 bytes of the
  // block left after them: shared) and at 4050 (46 left: decoded into the set's buffer).
  const auto cams = mpr_test::grid_cameras<double>(3, 1, 1.0, 7, 5, 4.0);
  constexpr std::size_t kBlock = 4096, kBytes = 7 * 5 * 3;
  const std::shared_ptr<std::uint8_t[]> memory(
      new (std::align_val_t(kBlock)) std::uint8_t[3 * kBlock],
      [](std::uint8_t* p) { ::operator delete[](p, std::align_val_t(kBlock)); });
  const std::array<std::size_t, 3> ends{1000, 4032, 4050};
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (std::size_t k = 0; k < 3; ++k) {
    std::uint8_t* start = memory.get() + k * kBlock + ends[k] - kBytes;
    for (std::size_t b = 0; b < kBytes; ++b) start[b] = static_cast<std::uint8_t>(b + 40 * k);
    images.push_back(mpr::Image<mpr::Rgb8>::borrow(reinterpret_cast<mpr::Rgb8*>(start), 7, 5, memory));
  }
  CHECK(!mpr::CameraFrameSet<double>::can_share(images[2]));
  CHECK(!mpr::CameraFrameSet<double>::can_share(mpr::Image<mpr::Rgb8>(7, 5))); // owned
  if constexpr (MPR_ADDRESS_SANITIZER) { // never shared there (a read past an allocation is reported)
    CHECK(!mpr::CameraFrameSet<double>::can_share(images[0]));
    return;
  }
  CHECK(mpr::CameraFrameSet<double>::can_share(images[0]));
  CHECK(mpr::CameraFrameSet<double>::can_share(images[1]));
  CHECK(memory.use_count() == 4);

  const mpr::CameraFrameSet<double> frames(cams, std::move(images)); // moved: a copy would own its pixels
  CHECK(memory.use_count() == 4); // the set's three images borrow it (the third's texels decoded)
  for (std::size_t k = 0; k < 3; ++k) {
    INFO("image " << k);
    CHECK(frames.shares_image(k) == (k < 2));
    CHECK(frames.image(k).data() == reinterpret_cast<const mpr::Rgb8*>(memory.get() + k * kBlock + ends[k] - kBytes));
    const auto t = frames.texels(k);
    REQUIRE(t.size() == 35);
    if (k < 2)
      CHECK(static_cast<const void*>(t.data()) == static_cast<const void*>(frames.image(k).data()));
    else
      CHECK(reinterpret_cast<std::uintptr_t>(t.data()) % 64 == 0);
    // Texel 6 is pixel (6, 0): bytes 18, 19, 20 of the image.
    CHECK(t[6].c[0] == 18 + 40 * k);
    CHECK(t[6].c[2] == 20 + 40 * k);
  }
  // A shared image's texels are the borrowed memory: a change there shows to the samplers.
  memory[kBlock + ends[1] - kBytes + 18] = 7;
  CHECK(frames.texels(1)[6].c[0] == 7);
  // without() and cast<U>() keep reading it in place.
  CHECK(frames.without(0).shares_image(0));
  CHECK(frames.without(0).texels(0).data() == frames.texels(1).data());
  CHECK(frames.cast<float>().shares_image(1));
  CHECK(frames.cast<float>().texels(2).data() == frames.texels(2).data());

  // Linear images are always decoded (their texels are floats in the set's layout).
  std::vector<mpr::Color> linear(35, mpr::Color(0.25f, 0.5f, 2.0f));
  const auto borrowed = mpr::Image<mpr::Color>::borrow(linear.data(), 7, 5);
  CHECK(!mpr::CameraFrameSet<double, mpr::Color>::can_share(borrowed));
  const mpr::CameraFrameSet<double, mpr::Color> hdr({cams[0]}, {borrowed});
  CHECK(!hdr.shares_image(0));
  CHECK(hdr.texels(0)[34].c[2] == 2.0f);
}
