// mpr-render end to end without spawning processes: command line -> Job -> frames, compared with
// the same render written directly against the C++ API (identical pixels), for every sampler
// kind; option errors; a 3-frame animation.
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <unistd.h>

namespace {

using Image = mpr::Image<mpr::Rgb8>;

using mpr_tools_test::job_of;

bool identical(const Image& a, const Image& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.data(), b.data(), sizeof(mpr::Rgb8) * static_cast<std::size_t>(a.width() * a.height())) == 0;
}

using mpr_tools_test::temp_folder;

Image noise_image(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(rng() & 255), static_cast<std::uint8_t>(rng() & 255),
                            static_cast<std::uint8_t>(rng() & 255)};
  return img;
}

/// The classroom image plane of the tool's defaults (centre 0,3.1,3 looking at 0,1.6,-8; 8 m wide).
template <class T>
mpr::PlanarSurface<T> classroom_plane(int w, int h) {
  const mpr::Vec3<T> centre(T(0), T(3.1), T(3)), look(T(0), T(1.6), T(-8));
  const mpr::Vec3<T> forward = (look - centre).normalized();
  const mpr::Vec3<T> right = forward.cross(mpr::Vec3<T>::UnitY()).normalized();
  const mpr::Vec3<T> down = forward.cross(right);
  return mpr::PlanarSurface<T>::centred(centre, T(8) * right, (T(8) * static_cast<T>(h) / static_cast<T>(w)) * down);
}

template <class Sampler, class Surface, class Selector>
Image direct(const Surface& surface, const Selector& selector, const Sampler& sampler, int w, int h) {
  Image image(w, h);
  mpr::Renderer(surface, selector, sampler).render(image.view(), mpr::Region(0, 0, w, h), mpr::RenderOptions{1});
  return image;
}

} // namespace

TEST_CASE("mpr-render options: good command lines", "[tools]") {
  const mpr_cli::Job a = job_of({"--size", "64x48", "--layout", "3x1", "--views", "A,G,pinhole:0;1.6;10", "--threads",
                                 "2", "--double", "--tilt-x", "0:30", "--frames", "5", "--output", "x/y.png"});
  CHECK(a.width == 64);
  CHECK(a.height == 48);
  CHECK(a.cols == 3);
  CHECK(a.rows == 1);
  REQUIRE(a.views.size() == 3);
  CHECK(a.views[2] == "pinhole:0,1.6,10");
  CHECK(a.threads == 2);
  CHECK(a.use_double);
  CHECK(a.frames == 5);
  CHECK(a.tilt_x.at(0.5) == Approx(15));
  CHECK(a.tilt_y.at(0.5) == 0);
  CHECK(mpr_cli::frame_path(a.output, 0) == std::filesystem::path("x/y_0001.png"));

  const mpr_cli::Job b = job_of({"--layout", "2x2", "--view", "H"});
  CHECK(b.views == std::vector<std::string>(4, "H"));
  CHECK(b.sampler == mpr_cli::SamplerKind::scene);

  const mpr_cli::Job c = job_of({"--view", "A", "--morph-to", "G", "--morph", "0=0,0.5=1,1=0", "--frames", "3"});
  CHECK(c.morph.at(0.5) == 1);
  CHECK(c.morph.at(1) == 0);
}

TEST_CASE("mpr-render options: bad command lines fail with an error naming the option", "[tools]") {
  const auto fails_with = [](std::vector<std::string> args, const std::string& what) {
    try {
      (void)job_of(args);
    } catch (const mpr::error& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(what) != std::string::npos);
      return;
    }
    FAIL("no error for " << args.front());
  };
  fails_with({"--bogus"}, "--bogus");
  fails_with({"stray"}, "stray");
  fails_with({"--size", "0x10"}, "--size");
  fails_with({"--size"}, "--size");
  fails_with({"--layout", "2x2", "--views", "A,B,C"}, "--views");
  fails_with({"--view", "A", "--views", "A"}, "--view");
  fails_with({"--radius", "5"}, "--radius");
  fails_with({"--stanford", "/nonexistent/mpr/folder"}, "/nonexistent/mpr/folder");
  fails_with({"--par", "/nonexistent/x_par.txt"}, "no such file");
  fails_with({"--tilt-x", "0:95"}, "--tilt");
  fails_with({"--tilt-x", "1=0,0=1"}, "--tilt-x");
  fails_with({"--frames", "0"}, "--frames");
  fails_with({"--scene", "kitchen"}, "--scene");
  fails_with({"--plane-centre", "0,0,0"}, "--plane-centre");
  fails_with({"--morph", "0:1"}, "--morph");
  fails_with({"--threads", "two"}, "--threads");
}

TEST_CASE("mpr-render: unknown views and impossible cameras fail when rendering", "[tools]") {
  const auto fails_with = [](std::vector<std::string> args, const std::string& what) {
    args.insert(args.end(), {"--size", "8x6"});
    const mpr_cli::Job job = job_of(args);
    try {
      (void)mpr_cli::render_frames(job);
    } catch (const mpr::error& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(what) != std::string::npos);
      return;
    }
    FAIL("no error for " << args.front() << " " << args[1]);
  };
  fails_with({"--view", "Z"}, "not a view");
  fails_with({"--view", "pinhole:1,2"}, "--view");
  fails_with({"--view", "cross_slit:0,0,0:1,0,0"}, "cross_slit:P1:D1:P2:D2");
  fails_with({"--view", "orthographic:1,0,0"}, "impossible camera"); // parallel to the plane
  fails_with({"--view", "corners:0,0,0:0,0,1:0,0,1"}, "impossible camera");
  fails_with({"--view", "A", "--morph-to", "corners:0,0,1:0,0,1:0,0,1", "--frames", "3"}, "--morph-to");
  fails_with({"--look-at", "0,3.1,3", "--plane-centre", "0,3.1,3", "--plane-size", "1,1"}, "--look-at");
}

TEMPLATE_TEST_CASE("mpr-render: classroom render equals the C++ API", "[tools]", float, double) {
  using T = TestType;
  const int w = 40, h = 30;
  std::vector<std::string> args{"--size", "40x30", "--view", "G", "--threads", "1"};
  if (std::is_same_v<T, double>) args.push_back("--double");
  std::ostringstream info;
  const std::vector<Image> frames = mpr_cli::render_frames(job_of(args), &info);
  REQUIRE(frames.size() == 1);

  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scene::classroom<T>());
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast> sampler(scene);
  const mpr::PlanarSurface<T> plane = classroom_plane<T>(w, h);
  const mpr::GlcSelector<T> glc = mpr::glc::gallery_view('G', plane, mpr::Vec3<T>(T(0), T(1.6), T(-8)), T(14));
  CHECK(identical(frames[0], direct(plane, glc, sampler, w, h)));
  CHECK(info.str().empty()); // no --print-camera
  // Stored expectations (not the library's own render): pixels of this 40 x 30 cross-slit view
  // recorded from mpr-render at commit af982cf, each where the image changes sharply from its
  // left neighbour, so a view shifted or transposed by a pixel, another camera or another scene
  // changes them. Within 2 codes (float vs double, FMA).
  struct Stored {
    int x, y;
    mpr::Rgb8 colour;
  };
  const Stored stored[] = {{25, 12, {41, 96, 68}},    {23, 6, {216, 214, 212}}, {13, 9, {41, 96, 68}},
                           {27, 5, {208, 204, 179}},  {6, 22, {38, 38, 169}},   {33, 21, {140, 29, 78}},
                           {36, 20, {188, 215, 246}}, {8, 18, {40, 176, 39}},   {24, 18, {228, 54, 224}},
                           {30, 18, {85, 151, 33}},   {16, 18, {40, 176, 98}},  {38, 26, {84, 90, 103}},
                           {29, 18, {218, 212, 197}}, {29, 20, {83, 83, 92}}};
  for (const Stored& p : stored) {
    const mpr::Rgb8 got = frames[0](p.x, p.y);
    INFO("pixel " << p.x << ", " << p.y << ": " << int(got.r) << " " << int(got.g) << " " << int(got.b));
    CHECK(std::abs(got.r - p.colour.r) <= 2);
    CHECK(std::abs(got.g - p.colour.g) <= 2);
    CHECK(std::abs(got.b - p.colour.b) <= 2);
  }
}

TEST_CASE("mpr-render: layout, rectification and --print-camera", "[tools]") {
  using T = float;
  const int w = 24, h = 18;
  const std::string quad = "-4.4,5.4,-14;4.4,5.4,-14;4.4,-1.2,-14;-4.4,-1.2,-14";
  std::ostringstream info;
  const std::vector<Image> frames = mpr_cli::render_frames(
      job_of({"--size", "24x18", "--layout", "2x1", "--views", "A,C", "--rectify", quad, "--print-camera"}), &info);
  REQUIRE(frames.size() == 1);
  REQUIRE(frames[0].width() == 2 * w);
  CHECK(info.str().find("view A: pinhole (rectified)") != std::string::npos);
  CHECK(info.str().find("view C: orthographic (rectified)") != std::string::npos);
  CHECK(info.str().find("centre:") != std::string::npos);

  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scene::classroom<T>());
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast> sampler(scene);
  const mpr::PlanarSurface<T> plane = classroom_plane<T>(w, h);
  const std::array<mpr::Vec3<T>, 4> wall = {mpr::Vec3<T>(-4.4f, 5.4f, -14), mpr::Vec3<T>(4.4f, 5.4f, -14),
                                            mpr::Vec3<T>(4.4f, -1.2f, -14), mpr::Vec3<T>(-4.4f, -1.2f, -14)};
  Image expected(2 * w, h);
  for (int k = 0; k < 2; ++k) {
    const mpr::GlcSelector<T> glc = mpr::glc::gallery_view("AC"[k], plane, mpr::Vec3<T>(0, 1.6f, -8), T(14));
    const mpr::glc::Rectified<T> r = mpr::glc::rectify(plane, glc, mpr::glc::target_region(plane, glc, wall));
    mpr::Renderer(r.surface, r.selector, sampler).render(expected.view(), mpr::Region(k * w, 0, w, h));
  }
  CHECK(identical(frames[0], expected));
}

#ifdef MPR_HAVE_TINYOBJLOADER
#include <mpr/scene/obj_loader.hpp>

TEST_CASE("mpr-render: OBJ render equals the C++ API", "[tools]") {
  using T = float;
  const std::filesystem::path dir = temp_folder("obj");
  const std::filesystem::path obj = dir / "tiny.obj";
  {
    std::ofstream out(obj);
    out << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 0 0 0.5\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n";
  }
  const int w = 20, h = 16;
  const std::vector<Image> frames =
      mpr_cli::render_frames(job_of({"--obj", obj.string(), "--size", "20x16", "--plane-centre", "0,0,3", "--look-at",
                                     "0,0,0", "--plane-size", "3,2.4", "--view", "pinhole:0,0,5"}));
  REQUIRE(frames.size() == 1);
  mpr::scene::Scene<T> scene;
  mpr::scene::add_obj(scene, obj);
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast> sampler(std::move(scene));
  const mpr::Vec3<T> centre(0, 0, 3), forward(0, 0, -1);
  const mpr::Vec3<T> right = forward.cross(mpr::Vec3<T>::UnitY()).normalized();
  const mpr::Vec3<T> down = forward.cross(right);
  const auto plane = mpr::PlanarSurface<T>::centred(centre, T(3) * right, T(2.4f) * down);
  const Image expected = direct(plane, mpr::glc::perspective(plane, mpr::Vec3<T>(0, 0, 5)), sampler, w, h);
  CHECK(identical(frames[0], expected));
  // Independent geometry: the ray from (0, 0, 5) through plane point (px, py, 3) meets z = 0 at
  // 2.5 (px, py), inside the pyramid's base [-1, 1]^2 when |px|, |py| < 0.4. The plane is 3 x 2.4
  // over 20 x 16 pixels, so pixel centres x + 0.5 in (7.33, 12.67) and y + 0.5 in (5.33, 10.67):
  // exactly columns 7..12 and rows 5..10 show the pyramid, every other pixel the background.
  const mpr::Rgb8 background = frames[0](0, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      INFO("pixel " << x << ", " << y);
      const bool pyramid = x >= 7 && x <= 12 && y >= 5 && y <= 10;
      CHECK((frames[0](x, y) == background) == !pyramid);
    }
  std::filesystem::remove_all(dir);
}
#endif

TEST_CASE("mpr-render: _par.txt light field equals the C++ API", "[tools]") {
  using T = float;
  const std::filesystem::path dir = temp_folder("par");
  const int cw = 8, ch = 6;
  {
    std::ofstream par(dir / "tiny_par.txt");
    par << "3\n";
    for (int i = 0; i < 3; ++i) {
      const std::string name = "view" + std::to_string(i) + ".png";
      mpr::write_png(dir / name, noise_image(cw, ch, 7u + static_cast<unsigned>(i)));
      par << name << " 8 0 3.5 0 8 2.5 0 0 1  1 0 0 0 1 0 0 0 1  " << -0.1 * (i - 1) << " 0 0\n";
    }
  }
  for (const std::string interp : {"nearest", "synthetic"}) {
    const std::vector<Image> frames = mpr_cli::render_frames(
        job_of({"--par", (dir / "tiny_par.txt").string(), "--focal-depth", "2", "--interp", interp}));
    REQUIRE(frames.size() == 1);
    const auto set = std::make_shared<const mpr::CameraFrameSet<T>>(mpr::read_par_file<T>(dir / "tiny_par.txt"));
    const mpr::PinholeCamera<T>& ref = set->camera(1);
    const mpr::PlanarSurface<T> plane = ref.image_plane(2);
    const Image expected =
        interp == "nearest"
            ? direct(plane, mpr::pinhole_glc(ref, plane), mpr::CameraFrameSampler<mpr::NearestCamera, T>(set), cw, ch)
            : direct(plane, mpr::pinhole_glc(ref, plane), mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(set), cw,
                     ch);
    INFO(interp);
    CHECK(identical(frames[0], expected));
    // Independent formula. Camera i has K = [8 0 3.5; 0 8 2.5; 0 0 1], R = I, centre
    // (0.1 (i - 1), 0, 0); the view is camera 1 (the middle one) focused at depth 2, so its pixel
    // (x, y) sees X = ((x - 3.5) / 4, (y - 2.5) / 4, 2), which camera i sees at pixel
    // (x - 0.4 (i - 1), y). Nearest: camera 1 itself (the ray passes through its centre), so the
    // view is camera 1's image. Synthetic: the mean, in linear colour, of every camera whose
    // pixel lies in [-0.5, 7.5), bilinear between pixel centres, edge pixels repeated.
    int worst = 0;
    for (int y = 0; y < ch; ++y)
      for (int x = 0; x < cw; ++x) {
        mpr::Rgb8 want;
        if (interp == "nearest") {
          want = noise_image(cw, ch, 8u)(x, y);
        } else {
          mpr::Color acc = mpr::Color::Zero();
          int seen = 0;
          for (int i = 0; i < 3; ++i) {
            const double xi = x - 0.4 * (i - 1);
            if (xi < -0.5 || xi >= cw - 0.5) continue;
            const Image img = noise_image(cw, ch, 7u + static_cast<unsigned>(i));
            const int x0 = static_cast<int>(std::floor(xi));
            const float a = static_cast<float>(xi - x0);
            const auto lin = [&](int xx) { return mpr::to_color(img(std::clamp(xx, 0, cw - 1), y)); };
            acc += (1 - a) * lin(x0) + a * lin(x0 + 1);
            ++seen;
          }
          REQUIRE(seen >= 2);
          want = mpr::to_rgb8(acc / static_cast<float>(seen));
        }
        const mpr::Rgb8 got = frames[0](x, y);
        worst = std::max({worst, std::abs(got.r - want.r), std::abs(got.g - want.g), std::abs(got.b - want.b)});
      }
    CHECK(worst <= 1);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("mpr-render: Stanford folder light field equals the C++ API", "[tools]") {
  using T = float;
  const std::filesystem::path dir = temp_folder("stanford");
  const int cw = 10, ch = 8;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c)
      mpr::write_png(dir / ("out_0" + std::to_string(r) + "_0" + std::to_string(c) + "_" + std::to_string(-5 * r) +
                            ".0_" + std::to_string(5 * c) + ".0.png"),
                     noise_image(cw, ch, 100u + static_cast<unsigned>(2 * r + c)));
  const std::vector<Image> frames = mpr_cli::render_frames(job_of(
      {"--stanford", dir.string(), "--interp", "cylinder", "--radius", "6", "--focal-depth", "900", "--size", "10x8"}));
  REQUIRE(frames.size() == 1);
  const auto set = std::make_shared<const mpr::CameraFrameSet<T>>(mpr::read_stanford_light_field<T>(dir));
  mpr::Vec3<T> mean = mpr::Vec3<T>::Zero();
  for (std::size_t i = 0; i < set->size(); ++i) mean += set->camera(i).centre();
  mean /= T(4);
  mpr::Mat3<T> K = set->camera(0).K();
  K(0, 2) = T(0.5) * (cw - 1);
  K(1, 2) = T(0.5) * (ch - 1);
  const mpr::PinholeCamera<T> ref(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>(-mean), cw, ch);
  const mpr::PlanarSurface<T> plane = ref.image_plane(900);
  const Image expected =
      direct(plane, mpr::pinhole_glc(ref, plane),
             mpr::CameraFrameSampler<mpr::CylinderAperture, T>(set, mpr::CylinderAperture{6}), cw, ch);
  CHECK(identical(frames[0], expected));
  std::filesystem::remove_all(dir);
}

TEST_CASE("mpr-render: a 3-frame animation (tilt sweep and GLC morph)", "[tools]") {
  using T = float;
  const int w = 24, h = 18;
  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scene::classroom<T>());
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast> sampler(scene);
  const mpr::Vec3<T> aim(0, 1.6f, -8);

  const std::vector<Image> tilt =
      mpr_cli::render_frames(job_of({"--size", "24x18", "--view", "A", "--tilt-x", "0:20", "--frames", "3"}));
  REQUIRE(tilt.size() == 3);
  for (int f = 0; f < 3; ++f) {
    const T angle = static_cast<T>(10.0 * f * std::numbers::pi / 180);
    const mpr::PlanarSurface<T> plane = f == 0 ? classroom_plane<T>(w, h) : classroom_plane<T>(w, h).tilted(angle, 0);
    INFO("frame " << f);
    CHECK(identical(tilt[static_cast<std::size_t>(f)],
                    direct(plane, mpr::glc::gallery_view('A', plane, aim, T(14)), sampler, w, h)));
  }
  CHECK(!identical(tilt[0], tilt[2]));

  const std::vector<Image> morph =
      mpr_cli::render_frames(job_of({"--size", "24x18", "--view", "A", "--morph-to", "G", "--frames", "3"}));
  REQUIRE(morph.size() == 3);
  const mpr::PlanarSurface<T> plane = classroom_plane<T>(w, h);
  const mpr::GlcSelector<T> a = mpr::glc::gallery_view('A', plane, aim, T(14));
  const mpr::GlcSelector<T> g = mpr::glc::gallery_view('G', plane, aim, T(14));
  for (int f = 0; f < 3; ++f) {
    const T s = static_cast<T>(0.5 * f);
    const auto mix = [s](const mpr::Vec3<T>& p, const mpr::Vec3<T>& q) { return mpr::Vec3<T>((1 - s) * p + s * q); };
    const mpr::GlcSelector<T> m(plane, mix(a.d00(), g.d00()), mix(a.d10(), g.d10()), mix(a.d01(), g.d01()));
    INFO("frame " << f);
    CHECK(identical(morph[static_cast<std::size_t>(f)], direct(plane, m, sampler, w, h)));
  }
  CHECK(!identical(morph[0], morph[1]));
  CHECK(!identical(morph[1], morph[2]));
}

TEST_CASE("mpr-render: LFCA light field equals the C++ API", "[tools]") {
  const std::filesystem::path dir = temp_folder("lfca");
  const int cw = 10, ch = 8;
  {
    std::ofstream positions(dir / "positions.txt");
    for (int i = 0; i < 3; ++i) {
      const std::string id = "cam" + std::to_string(i);
      positions << id << " " << 4 * i << " " << (i == 1 ? 3 : 0) << "\n";
      mpr::write_png(dir / (id + ".png"), noise_image(cw, ch, 200u + static_cast<unsigned>(i)));
      std::ofstream(dir / (id + ".homography.txt")) << "1 0 " << 0.5 * i << "\n0 1 0\n0 0 1\n";
    }
  }
  const std::vector<Image> frames = mpr_cli::render_frames(
      job_of({"--lfca", (dir / "positions.txt").string(), "--interp", "nearest", "--focal-depth", "800", "--double"}));
  REQUIRE(frames.size() == 1);
  using D = double;
  const auto set = std::make_shared<const mpr::CameraFrameSet<D>>(mpr::read_lfca<D>(dir / "positions.txt"));
  mpr::Vec3<D> mean = mpr::Vec3<D>::Zero();
  for (std::size_t i = 0; i < set->size(); ++i) mean += set->camera(i).centre();
  mean /= D(3);
  mpr::Mat3<D> K = set->camera(0).K();
  K(0, 2) = D(0.5) * (cw - 1);
  K(1, 2) = D(0.5) * (ch - 1);
  const mpr::PinholeCamera<D> ref(K, mpr::Mat3<D>::Identity(), mpr::Vec3<D>(-mean), cw, ch);
  const mpr::PlanarSurface<D> plane = ref.image_plane(800);
  CHECK(identical(frames[0], direct(plane, mpr::pinhole_glc(ref, plane),
                                    mpr::CameraFrameSampler<mpr::NearestCamera, D>(set), cw, ch)));
  std::filesystem::remove_all(dir);
}

TEST_CASE("mpr-render: --rectify plane keeps the untilted framing", "[tools]") {
  // Untilted, the rectifying homography is the identity up to rounding: nearly every pixel equals
  // the plain render. Tilted, the view's rays through the untilted plane's corners still hit the
  // output corners, so the classroom's pinhole view barely moves while the plain tilt shifts it.
  const auto render = [](std::vector<std::string> extra) {
    std::vector<std::string> args{"--size", "48x36", "--view", "A"};
    args.insert(args.end(), extra.begin(), extra.end());
    return mpr_cli::render_frames(job_of(args)).at(0);
  };
  const auto differing = [](const Image& a, const Image& b) {
    long n = 0;
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x) n += !(a(x, y) == b(x, y));
    return n;
  };
  const Image plain = render({});
  const long pixels = 48 * 36;
  CHECK(differing(plain, render({"--rectify", "plane"})) < pixels / 50);
  CHECK(differing(plain, render({"--tilt-y", "20", "--rectify", "plane"})) < pixels / 20);
  CHECK(differing(plain, render({"--tilt-y", "20"})) > pixels / 4);
}

TEST_CASE("mpr-render: rasterized classroom (virtual array) equals the C++ API", "[tools]") {
  using T = float;
  const int w = 32, h = 24;
  const std::vector<Image> frames =
      mpr_cli::render_frames(job_of({"--size", "32x24", "--view", "A", "--raster", "3x2", "--interp", "cylinder",
                                     "--radius", "2", "--focal-depth", "9"}));
  REQUIRE(frames.size() == 1);
  const mpr::scene::Scene<T> scene = mpr::scene::classroom<T>();
  const mpr::PlanarSurface<T> plane = classroom_plane<T>(w, h);
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = 3;
  config.rows = 2;
  config.focal_depth = T(9);
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::CylinderAperture>> sampler(
      scene, plane, config, mpr::Rasterized<mpr::CylinderAperture>{mpr::CylinderAperture{2}});
  CHECK(identical(frames[0],
                  direct(plane, mpr::glc::gallery_view('A', plane, mpr::Vec3<T>(0, 1.6f, -8), T(14)), sampler, w, h)));
  // --raster-samples reaches the array: anti-aliased frames, the same as the API's.
  const std::vector<Image> smooth =
      mpr_cli::render_frames(job_of({"--size", "32x24", "--view", "A", "--raster", "3x2", "--raster-samples", "3",
                                     "--interp", "cylinder", "--radius", "2", "--focal-depth", "9"}));
  REQUIRE(smooth.size() == 1);
  config.samples = 3;
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::CylinderAperture>> smooth_sampler(
      scene, plane, config, mpr::Rasterized<mpr::CylinderAperture>{mpr::CylinderAperture{2}});
  const Image api =
      direct(plane, mpr::glc::gallery_view('A', plane, mpr::Vec3<T>(0, 1.6f, -8), T(14)), smooth_sampler, w, h);
  CHECK(identical(smooth[0], api));
  CHECK_FALSE(identical(smooth[0], frames[0]));
  CHECK_THROWS_AS(job_of({"--raster", "3x2", "--stanford", "/nonexistent"}), mpr::error);
  CHECK_THROWS_AS(job_of({"--focal-depth", "9"}), mpr::argument_error); // scene without --raster
}

TEST_CASE("mpr-render: --interp depth with --depth-maps equals the C++ API; bad maps name the file", "[tools]") {
  using T = float;
  const std::filesystem::path dir = temp_folder("par_depth");
  const int cw = 8, ch = 6;
  {
    std::ofstream par(dir / "tiny_par.txt");
    par << "3\n";
    for (int i = 0; i < 3; ++i) {
      const std::string name = "view" + std::to_string(i) + ".png";
      mpr::write_png(dir / name, noise_image(cw, ch, 7u + static_cast<unsigned>(i)));
      mpr::write_pfm(dir / ("view" + std::to_string(i) + ".pfm"), mpr::Image<float>(cw, ch, 2.0f + 0.1f * i));
      par << name << " 8 0 3.5 0 8 2.5 0 0 1  1 0 0 0 1 0 0 0 1  " << -0.1 * (i - 1) << " 0 0\n";
    }
  }
  const std::vector<std::string> args{"--par",         (dir / "tiny_par.txt").string(),
                                      "--focal-depth", "2",
                                      "--interp",      "depth",
                                      "--depth-maps",  dir.string(),
                                      "--radius",      "0.25"};
  const std::vector<Image> frames = mpr_cli::render_frames(job_of(args));
  REQUIRE(frames.size() == 1);
  mpr::CameraFrameSet<T> loaded = mpr::read_par_file<T>(dir / "tiny_par.txt");
  std::vector<mpr::Image<float>> maps = mpr::read_depth_maps(dir, loaded);
  const auto set = std::make_shared<const mpr::CameraFrameSet<T>>(std::move(loaded).with_depth(std::move(maps)));
  const mpr::PinholeCamera<T>& ref = set->camera(1);
  const mpr::PlanarSurface<T> plane = ref.image_plane(2);
  CHECK(identical(frames[0], direct(plane, mpr::pinhole_glc(ref, plane),
                                    mpr::CameraFrameSampler<mpr::DepthProxy, T>(set, mpr::DepthProxy{0.25}), cw, ch)));
  // A light field under --interp depth needs maps; a map of the wrong size names its file.
  CHECK_THROWS_WITH(job_of({"--par", (dir / "tiny_par.txt").string(), "--interp", "depth"}),
                    Catch::Contains("--depth-maps"));
  mpr::write_pfm(dir / "view2.pfm", mpr::Image<float>(ch, cw, 2.0f));
  CHECK_THROWS_WITH(mpr_cli::render_frames(job_of(args)), Catch::Contains("view2.pfm") && Catch::Contains("6x8"));
  std::filesystem::remove_all(dir);
}
