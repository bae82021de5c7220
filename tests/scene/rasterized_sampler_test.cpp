#include <mpr/core/image_metrics.hpp>
#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <type_traits>

namespace {

template <class T>
using Scene = mpr::scene::Scene<T>;
template <class T, class I>
using RasterSampler = mpr::SceneSampler<Scene<T>, mpr::Rasterized<I>>;

// A pinhole view of the classroom from behind the plane, and its image plane at depth 1.
template <class T>
mpr::PinholeCamera<T> view_camera(int w, int h) {
  return mpr::PinholeCamera<T>::look_at(mpr::Vec3<T>(0.3, 2.2, 4.5), mpr::Vec3<T>(0, 1.3, -8), mpr::Vec3<T>(0, 1, 0),
                                        T(1.0), w, h);
}

template <class T, class Sampler>
mpr::Image<mpr::Rgb8> render_view(const mpr::PinholeCamera<T>& camera, const Sampler& sampler) {
  const mpr::PlanarSurface<T> plane = camera.image_plane(T(1));
  const mpr::Renderer renderer(plane, mpr::pinhole_glc(camera, plane), sampler);
  mpr::Image<mpr::Rgb8> image(camera.width(), camera.height());
  renderer.render(image.view(), mpr::Region(0, 0, camera.width(), camera.height()), {2});
  return image;
}

// A small array on `plane`: columns x rows cameras of 48x36, rasterized on two threads.
template <class T>
mpr::scene::VirtualArrayConfig<T> small_array(int columns, int rows) {
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = columns;
  config.rows = rows;
  config.width = 48;
  config.height = 36;
  config.raster.threads = 2;
  return config;
}

std::filesystem::path temp_folder(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("mpr_rasterized_" + name);
}

} // namespace

// An interpolation with only the per-ray path (the wrapper must then not claim batch or tile).
struct OnlyPerRay {
  template <class T, class Px>
  [[nodiscard]] mpr::Color sample(const mpr::FrameTable<T, Px>& table, const mpr::Ray<T>& ray) const noexcept {
    return table.camera_color(table.index().nearest(ray.origin, ray.direction), table.point_of(ray));
  }
};

TEST_CASE("rasterized scene sampler forwards exactly the interfaces of its frame sampler", "[scene][rasterized]") {
  STATIC_REQUIRE(mpr::TileRaySampler<RasterSampler<float, mpr::NearestCamera>>);
  STATIC_REQUIRE(mpr::TileRaySampler<RasterSampler<double, mpr::SyntheticAperture>>);
  STATIC_REQUIRE(mpr::TileRaySampler<RasterSampler<float, mpr::CylinderAperture>>);
  STATIC_REQUIRE(mpr::BatchRaySampler<RasterSampler<double, mpr::NearestCamera>>);
  STATIC_REQUIRE(mpr::RaySampler<RasterSampler<float, OnlyPerRay>>);
  STATIC_REQUIRE_FALSE(mpr::BatchRaySampler<mpr::CameraFrameSampler<OnlyPerRay, float>>);
  STATIC_REQUIRE_FALSE(mpr::BatchRaySampler<RasterSampler<float, OnlyPerRay>>);
  STATIC_REQUIRE_FALSE(mpr::TileRaySampler<RasterSampler<float, OnlyPerRay>>);
}

TEST_CASE("rasterized scene sampler: concepts and types", "[scene][rasterized]") {
  STATIC_REQUIRE(mpr::RaySampler<RasterSampler<float, mpr::NearestCamera>>);
  STATIC_REQUIRE(mpr::RaySampler<RasterSampler<double, mpr::SyntheticAperture>>);
  STATIC_REQUIRE(mpr::BatchRaySampler<RasterSampler<float, mpr::CylinderAperture>>);
  STATIC_REQUIRE(std::is_same_v<RasterSampler<double, mpr::NearestCamera>::scalar_type, double>);
  STATIC_REQUIRE(std::is_same_v<RasterSampler<float, mpr::NearestCamera>::frame_sampler_type,
                                mpr::CameraFrameSampler<mpr::NearestCamera, float, mpr::Rgb8>>);
  STATIC_REQUIRE(
      std::is_same_v<mpr::SceneSampler<Scene<float>, mpr::Rasterized<mpr::NearestCamera, mpr::Color>>::frame_set_type,
                     mpr::CameraFrameSet<float, mpr::Color>>);
  // Needs a scene and a plane: no default construction; the policy tag carries only the
  // interpolation's parameters.
  STATIC_REQUIRE_FALSE(std::is_default_constructible_v<RasterSampler<float, mpr::NearestCamera>>);
  STATIC_REQUIRE(sizeof(mpr::Rasterized<mpr::NearestCamera>) == 1);
  STATIC_REQUIRE(sizeof(mpr::Rasterized<mpr::CylinderAperture>) == sizeof(double));
}

TEMPLATE_TEST_CASE("virtual array cameras: grid, spacing, orientation, bad input", "[scene][rasterized]", float,
                   double) {
  using T = TestType;
  const auto plane = mpr::PlanarSurface<T>::centred(mpr::Vec3<T>(1, 2, 3), mpr::Vec3<T>(4, 0, 0),
                                                    mpr::Vec3<T>(0, -3, 0)); // normal: 4x * -3y -> -z
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = 4;
  config.rows = 3;
  config.width = 40;
  config.height = 30;
  config.behind = T(0.5);
  const auto cameras = mpr::scene::virtual_array_cameras(plane, config);
  REQUIRE(cameras.size() == 12);
  const mpr::Vec3<T> normal = plane.normal().normalized();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      const auto& cam = cameras[static_cast<std::size_t>(r * 4 + c)];
      const mpr::Vec3<T> expected(T(1) + (T(c) - T(1.5)) * T(1), T(2) - (T(r) - T(1)) * T(1), T(3.5));
      CHECK((cam.centre() - expected).norm() < T(1e-5));
      CHECK((cam.forward() - normal).norm() < T(1e-5));
      CHECK(cam.width() == 40);
      // Horizontal field of view 100 degrees.
      CHECK(std::abs(2 * std::atan(T(20) / cam.K()(0, 0)) - T(1.7453292519943295)) < T(1e-5));
    }
  config.spacing = T(0.25);
  const auto tight = mpr::scene::virtual_array_cameras(plane, config);
  CHECK(std::abs((tight[1].centre() - tight[0].centre()).norm() - T(0.25)) < T(1e-5));
  CHECK(std::abs((tight[4].centre() - tight[0].centre()).norm() - T(0.25)) < T(1e-5));

  auto bad = config;
  bad.columns = 0;
  CHECK_THROWS_AS(mpr::scene::virtual_array_cameras(plane, bad), mpr::argument_error);
  bad = config;
  bad.spacing = std::numeric_limits<T>::quiet_NaN();
  CHECK_THROWS_AS(mpr::scene::virtual_array_cameras(plane, bad), mpr::argument_error);
  bad = config;
  bad.horizontal_fov = T(3.2);
  CHECK_THROWS_AS(mpr::scene::virtual_array_cameras(plane, bad), mpr::argument_error);
  bad = config;
  bad.behind = T(-1);
  CHECK_THROWS_AS(mpr::scene::virtual_array_cameras(plane, bad), mpr::argument_error);
  bad = config;
  bad.focal_depth = std::numeric_limits<T>::infinity();
  CHECK_THROWS_AS(mpr::scene::virtual_array_cameras(plane, bad), mpr::argument_error);
  bad = config;
  bad.height = -3;
  CHECK_THROWS_AS(mpr::scene::virtual_array_cameras(plane, bad), mpr::argument_error);
}

TEMPLATE_TEST_CASE("a view from one virtual camera's position equals that camera's frame (nearest camera)",
                   "[scene][rasterized]", float, double) {
  using T = TestType;
  const Scene<T> scene = mpr::scene::classroom<T>();
  const mpr::PinholeCamera<T> view = view_camera<T>(64, 48);
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = 4;
  config.rows = 3;
  config.width = 64;
  config.height = 48;
  config.filter = mpr::PixelFilter::nearest;
  config.raster.threads = 2;
  const mpr::PlanarSurface<T> plane = view.image_plane(T(1));
  const RasterSampler<T, mpr::NearestCamera> sampler(scene, plane, config);
  REQUIRE(sampler.frames().size() == 12);
  CHECK(sampler.focal_depth() > T(1)); // the median depth of the classroom, metres
  CHECK(sampler.focal_depth() < T(30));

  for (const std::size_t k : {std::size_t{5}, std::size_t{10}}) {
    const mpr::PinholeCamera<T>& cam = sampler.frames().camera(k);
    const mpr::Image<mpr::Rgb8> image = render_view(cam, sampler);
    const mpr::Image<mpr::Rgb8>& frame = sampler.frames().image(k);
    long same = 0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) same += image(x, y) == frame(x, y) ? 1 : 0;
    INFO("camera " << k << ": " << same << " of " << image.width() * image.height() << " pixels identical");
    CHECK(same == static_cast<long>(image.width()) * image.height());
  }
}

TEST_CASE("a rasterized array converges to the ray-cast image as it gets denser", "[scene][rasterized]") {
  using T = float;
  const auto scene = std::make_shared<const Scene<T>>(mpr::scene::classroom<T>());
  const mpr::PinholeCamera<T> view = view_camera<T>(96, 72);
  const mpr::Image<mpr::Rgb8> truth = render_view(view, mpr::SceneSampler<Scene<T>, mpr::RayCast>(scene));
  // The array lies in the view's image plane, one metre in front of its eye.
  const mpr::PlanarSurface<T> plane = view.image_plane(T(1));
  const auto psnr_of = [&](int columns, int rows, int width, auto interpolation) {
    mpr::scene::VirtualArrayConfig<T> config;
    config.columns = columns;
    config.rows = rows;
    config.width = width;
    config.height = width * 3 / 4;
    config.raster.threads = 2;
    using I = decltype(interpolation);
    const mpr::SceneSampler<Scene<T>, mpr::Rasterized<I>> sampler(*scene, plane, config,
                                                                  mpr::Rasterized<I>{interpolation});
    const mpr::ImageError e = mpr::compare_images(render_view(view, sampler).view(), truth.view());
    std::printf("rasterized array %dx%d of %dx%d: PSNR %.2f dB, p99 %.1f\n", columns, rows, width, width * 3 / 4,
                e.psnr, e.p99);
    return e.psnr;
  };
  const double sparse = psnr_of(2, 2, 64, mpr::NearestCamera{});
  const double medium = psnr_of(6, 4, 96, mpr::NearestCamera{});
  const double dense = psnr_of(16, 12, 160, mpr::NearestCamera{});
  // Measured (float and double alike): 15.6, 17.8 and 20.4 dB; the residual is mostly edge
  // pixels of the high-contrast textures, resampled twice (frame pixels, then bilinear).
  CHECK(medium > sparse + 1.0);
  CHECK(dense > medium + 1.0);
  CHECK(dense > 19.5);
  // A cylinder aperture of one grid spacing on the dense array stays close to the ray-cast image.
  const double spacing = plane.width_vector().norm() / 16;
  const double cylinder = psnr_of(16, 12, 160, mpr::CylinderAperture{spacing});
  CHECK(cylinder > 19.0);
  CHECK(cylinder != dense); // the aperture changes the image (its weights: the next test)
}

TEST_CASE("a rasterized cylinder aperture blends the array's frames with weights 1 - d / r", "[scene][rasterized]") {
  using T = double;
  const auto scene = std::make_shared<const Scene<T>>(mpr::scene::classroom<T>());
  const mpr::PinholeCamera<T> view = view_camera<T>(64, 48);
  const mpr::PlanarSurface<T> plane = view.image_plane(T(1));
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = 5;
  config.rows = 4;
  config.width = 64;
  config.height = 48;
  config.raster.threads = 2;
  const double radius = 1.6 * plane.width_vector().norm() / 5; // reaches several cameras
  const RasterSampler<T, mpr::CylinderAperture> sampler(*scene, plane, config,
                                                        mpr::Rasterized<mpr::CylinderAperture>{{radius}});
  const mpr::Image<mpr::Rgb8> image = render_view(view, sampler);
  const mpr::Renderer renderer(plane, mpr::pinhole_glc(view, plane), sampler);
  const mpr::Region region(0, 0, 64, 48);
  const auto& frames = sampler.frames();
  // The expectation, from the definition: the colour at X = ray.at(focal depth) is the mean of
  // the frames' bilinear colours at X's projection (in linear colour), weighted by 1 - d / r over
  // the cameras whose centre lies within r of the ray line and that see X (in front, inside the
  // image).
  int blended = 0, compared = 0;
  for (int y = 1; y < 48; y += 5)
    for (int x = 2; x < 64; x += 5) {
      const mpr::Ray<T> ray = renderer.ray_at({x, y}, region);
      const mpr::Vec3<T> X = ray.at(sampler.focal_depth());
      const mpr::Vec3<T> dir = ray.direction.normalized();
      Eigen::Array3d acc = Eigen::Array3d::Zero();
      double wsum = 0;
      int used = 0;
      bool near_edge = false;
      for (std::size_t k = 0; k < frames.size(); ++k) {
        const mpr::PinholeCamera<T>& cam = frames.camera(k);
        const double d = (cam.centre() - ray.origin).cross(dir).norm();
        near_edge = near_edge || std::abs(d - radius) < 1e-6;
        if (d >= radius || (cam.R() * X + cam.t()).z() <= 0) continue;
        const mpr::Vec3<T> q = cam.K() * (cam.R() * X + cam.t());
        const double px = q.x() / q.z(), py = q.y() / q.z();
        if (px < -0.5 || py < -0.5 || px >= cam.width() - 0.5 || py >= cam.height() - 0.5) continue;
        const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
        const double ax = px - x0, ay = py - y0;
        const auto texel = [&](int i, int j) -> Eigen::Array3d {
          const mpr::Rgb8 p = frames.image(k)(std::clamp(i, 0, cam.width() - 1), std::clamp(j, 0, cam.height() - 1));
          return mpr::to_color(p).cast<double>();
        };
        const Eigen::Array3d c = (1 - ax) * (1 - ay) * texel(x0, y0) + ax * (1 - ay) * texel(x0 + 1, y0) +
                                 (1 - ax) * ay * texel(x0, y0 + 1) + ax * ay * texel(x0 + 1, y0 + 1);
        acc += (1 - d / radius) * c;
        wsum += 1 - d / radius;
        ++used;
      }
      if (near_edge || used == 0) continue;
      blended += used >= 2 ? 1 : 0;
      ++compared;
      const mpr::Rgb8 want = mpr::to_rgb8(mpr::Color((acc / wsum).cast<float>()));
      const mpr::Rgb8 got = image(x, y);
      INFO("pixel " << x << ", " << y << ": " << used << " cameras, got " << int(got.r) << " " << int(got.g) << " "
                    << int(got.b) << ", expected " << int(want.r) << " " << int(want.g) << " " << int(want.b));
      CHECK(std::max({std::abs(got.r - want.r), std::abs(got.g - want.g), std::abs(got.b - want.b)}) <= 1);
    }
  INFO(compared << " pixels compared, " << blended << " of them blend two or more cameras");
  CHECK(compared >= 100);
  CHECK(blended >= compared / 2);
}

TEMPLATE_TEST_CASE("a virtual array written as _par.txt + PNGs reads back and samples identically",
                   "[scene][rasterized][io]", float, double) {
  using T = TestType;
  const Scene<T> scene = mpr::scene::classroom<T>();
  const mpr::PinholeCamera<T> view = view_camera<T>(48, 36);
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = 3;
  config.rows = 2;
  config.width = 48;
  config.height = 36;
  config.raster.threads = 2;
  const mpr::PlanarSurface<T> plane = view.image_plane(T(1));
  const RasterSampler<T, mpr::CylinderAperture> sampler(scene, plane, config,
                                                        mpr::Rasterized<mpr::CylinderAperture>{{0.2}});
  const std::filesystem::path folder = temp_folder(sizeof(T) == 4 ? "float" : "double");
  std::filesystem::remove_all(folder);
  const std::filesystem::path par = mpr::write_frame_set(folder, "classroom", sampler.frames());
  CHECK(par.filename() == "classroom_par.txt");
  REQUIRE(std::filesystem::exists(folder / "cam_001_002.png"));

  const mpr::CameraFrameSet<T> reloaded = mpr::read_par_file<T>(par);
  REQUIRE(reloaded.size() == sampler.frames().size());
  for (std::size_t i = 0; i < reloaded.size(); ++i) {
    const auto& a = reloaded.camera(i);
    const auto& b = sampler.frames().camera(i);
    CHECK(reloaded.name(i) == sampler.frames().name(i));
    CHECK((a.K() - b.K()).cwiseAbs().maxCoeff() <= T(1e-4) * b.K().cwiseAbs().maxCoeff());
    CHECK((a.R() - b.R()).cwiseAbs().maxCoeff() <= T(1e-6));
    CHECK((a.centre() - b.centre()).norm() <= T(1e-5));
    REQUIRE(reloaded.image(i).width() == b.width());
    bool same = true;
    for (int y = 0; y < b.height(); ++y)
      for (int x = 0; x < b.width(); ++x) same = same && reloaded.image(i)(x, y) == sampler.frames().image(i)(x, y);
    CHECK(same);
  }
  // The reloaded data set, sampled with the same policy and focal depth, renders the same view.
  const RasterSampler<T, mpr::CylinderAperture> again(
      mpr::scene::VirtualArray<T, mpr::Rgb8>{reloaded, sampler.focal_depth()}, scene.background(), config.filter,
      mpr::Rasterized<mpr::CylinderAperture>{{0.2}});
  const mpr::Image<mpr::Rgb8> a = render_view(view, sampler), b = render_view(view, again);
  const mpr::ImageError e = mpr::compare_images(a.view(), b.view());
  CHECK(e.max <= 1.0); // identical frames; cameras equal to 17 digits (float: to rounding)

  // Bad stems and unwritable folders are reported.
  CHECK_THROWS_AS(mpr::write_frame_set(folder, "a b", sampler.frames()), mpr::argument_error);
  CHECK_THROWS_AS(mpr::write_frame_set(folder / "cam_000_000.png" / "sub", "x", sampler.frames()), mpr::io_error);
  std::filesystem::remove_all(folder);
}

TEMPLATE_TEST_CASE("a virtual array keeps the rasterizer's exact depth maps on request", "[scene][rasterized]", float,
                   double) {
  using T = TestType;
  const Scene<T> scene = mpr::scene::classroom<T>();
  const mpr::PinholeCamera<T> view = view_camera<T>(48, 36);
  const mpr::PlanarSurface<T> plane = view.image_plane(T(1));
  mpr::scene::VirtualArrayConfig<T> config = small_array<T>(3, 2);
  CHECK_FALSE(mpr::scene::rasterize_virtual_array(scene, plane, config).frames.has_depth());
  config.depth_maps = true;
  const auto array = mpr::scene::rasterize_virtual_array(scene, plane, config);
  REQUIRE(array.frames.has_depth());
  int finite = 0, background = 0;
  for (const std::size_t k : {std::size_t{0}, std::size_t{4}}) {
    const mpr::scene::RasterImage r = mpr::scene::rasterize(scene, array.frames.camera(k), config.raster);
    const mpr::Image<float>& d = array.frames.depth(k);
    for (int y = 0; y < d.height(); ++y)
      for (int x = 0; x < d.width(); ++x) {
        CHECK((d(x, y) == r.depth(x, y) || (std::isinf(d(x, y)) && std::isinf(r.depth(x, y)))));
        (std::isfinite(d(x, y)) ? finite : background) += 1;
      }
  }
  CHECK(finite > 1000); // the room fills most of each view
  // A rasterized sampler whose interpolation reads depth keeps them without being asked.
  config.depth_maps = false;
  const RasterSampler<T, mpr::DepthProxy> proxy(scene, plane, config, {mpr::DepthProxy{2.0}});
  CHECK(proxy.frames().has_depth());
  const RasterSampler<T, mpr::NearestCamera> nearest(scene, plane, config);
  CHECK_FALSE(nearest.frames().has_depth());
}

TEMPLATE_TEST_CASE("a virtual array with samples = n averages n x n points per pixel in linear light",
                   "[scene][rasterized]", float, double) {
  using T = TestType;
  const Scene<T> scene = mpr::scene::classroom<T>();
  const mpr::PinholeCamera<T> view = view_camera<T>(48, 36);
  const mpr::PlanarSurface<T> plane = view.image_plane(T(1));
  mpr::scene::VirtualArrayConfig<T> config = small_array<T>(2, 2);
  config.depth_maps = true;
  const auto point_sampled = mpr::scene::rasterize_virtual_array<mpr::Color>(scene, plane, config);
  const std::size_t k = 3;
  for (const int n : {3, 5}) {
    INFO("samples " << n);
    config.samples = n;
    const auto array = mpr::scene::rasterize_virtual_array<mpr::Color>(scene, plane, config);
    // The oracle: n x n copies of the camera, each with its principal point moved by (-i / n,
    // -j / n) for i, j in -(n - 1) / 2 .. (n - 1) / 2, rasterized at the frame's own size: pixel
    // (x, y) of a copy sees the camera's point (x + i / n, y + j / n).
    const mpr::PinholeCamera<T>& camera = array.frames.camera(k);
    const int h = (n - 1) / 2;
    mpr::Image<mpr::Color> mean(48, 36, mpr::Color::Zero());
    for (int j = -h; j <= h; ++j)
      for (int i = -h; i <= h; ++i) {
        mpr::Mat3<T> K = camera.K();
        K(0, 2) -= T(i) / T(n);
        K(1, 2) -= T(j) / T(n);
        const mpr::scene::RasterImage r =
            mpr::scene::rasterize(scene, mpr::PinholeCamera<T>(K, camera.R(), camera.t(), 48, 36), config.raster);
        for (int y = 0; y < 36; ++y)
          for (int x = 0; x < 48; ++x) mean(x, y) += r.color(x, y) / static_cast<float>(n * n);
      }
    const mpr::Image<mpr::Color>& frame = array.frames.image(k);
    int close = 0, smoothed = 0;
    double largest = 0;
    for (int y = 0; y < 36; ++y)
      for (int x = 0; x < 48; ++x) {
        const double d = (frame(x, y) - mean(x, y)).abs().maxCoeff();
        largest = std::max(largest, d);
        close += d < 1e-4;
        smoothed += (frame(x, y) - point_sampled.frames.image(k)(x, y)).abs().maxCoeff() > 0.01f;
      }
    INFO("largest difference from the oracle " << largest);
    // Points on a triangle's edge may fall to either side in the two rasterizations (their
    // vertices snap to different grids; seen: 7 of 1,728 pixels at n = 3, by at most 0.011, 34
    // at n = 5, by at most 0.044): allow 3% of the pixels, and a few points of a pixel.
    CHECK(close >= 48 * 36 * 97 / 100);
    CHECK(largest < 0.25);
    CHECK(smoothed > 48 * 36 / 20); // edges and textures differ from the point-sampled frame
    // Depth: the middle point is the pixel centre, so the map is the point-sampled one.
    const mpr::Image<float>& d = array.frames.depth(k);
    const mpr::Image<float>& d1 = point_sampled.frames.depth(k);
    int same = 0;
    for (int y = 0; y < 36; ++y)
      for (int x = 0; x < 48; ++x)
        same += (std::isinf(d(x, y)) && std::isinf(d1(x, y))) || std::abs(d(x, y) - d1(x, y)) <= 1e-5f * d1(x, y);
    CHECK(same >= 48 * 36 * 99 / 100);
    // 8-bit frames are the same means, encoded.
    if (n == 3) {
      const auto codes = mpr::scene::rasterize_virtual_array(scene, plane, config);
      int encoded = 0;
      for (int y = 0; y < 36; ++y)
        for (int x = 0; x < 48; ++x) encoded += codes.frames.image(k)(x, y) == mpr::to_rgb8(frame(x, y));
      CHECK(encoded == 48 * 36);
    }
  }

  auto bad = config;
  for (const int n : {0, 2, 17}) {
    bad.samples = n;
    CHECK_THROWS_WITH(mpr::scene::virtual_array_cameras(plane, bad), Catch::Contains("samples"));
  }
  bad.samples = 15;
  bad.width = 1100; // 16,500 points across
  CHECK_THROWS_WITH(mpr::scene::virtual_array_cameras(plane, bad), Catch::Contains("samples"));
  bad.width = 48;
  bad.height = 1100; // and down
  CHECK_THROWS_WITH(mpr::scene::virtual_array_cameras(plane, bad), Catch::Contains("samples"));
}
