// GLC views of camera arrays in two-plane terms (lightfield/array_view.hpp): the footprint of
// planar grids, lines and rings; fit_to_array keeps every ray's crossing inside the array for all
// nine gallery views (focal plane parallel or tilted), keeps the types that can be kept, and
// makes the nine views differ; array_coverage against crossings counted by hand.
#include "frame_test_scenes.hpp"

#include <mpr/render/renderer.hpp>
#include <mpr/glc.hpp>
#include <mpr/lightfield/array_view.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace {

template <class T>
using Frames = mpr::CameraFrameSet<T, mpr::Color>;

/// `nx` x `ny` cameras, spacing 2, on the plane z = 0 (declared by the caller, as loaders do).
template <class T>
std::shared_ptr<const Frames<T>> grid(int nx, int ny) {
  const auto cams = mpr_test::grid_cameras<T>(nx, ny, 2.0, 64, 48, 60.0);
  Frames<T> f(cams, mpr_test::constant_images(cams));
  return std::make_shared<const Frames<T>>(std::move(f).on_plane(mpr::Plane<T>{}));
}

template <class T>
mpr::GlcSelector<T> prototype(char letter, const mpr::PlanarSurface<T>& focal) {
  return mpr::glc::gallery_view<T>(letter, focal, mpr::Vec3<T>(focal.centre() + T(10) * focal.normal()),
                                   focal.width_vector().norm());
}

/// Where the GLC's ray at uv meets the camera plane, in the footprint's coordinates.
template <class T>
mpr::Vec2<T> crossing_at(const mpr::PlanarSurface<T>& focal, const mpr::GlcSelector<T>& glc,
                         const mpr::ArrayFootprint<T>& f, mpr::Vec2<T> uv) {
  const std::optional<mpr::Vec2<T>> x = f.crossing(glc.ray_at({}, uv, focal.point_at(uv)));
  REQUIRE(x.has_value());
  return *x;
}

} // namespace

TEMPLATE_TEST_CASE("array_footprint: a planar grid keeps its plane, rectangle and spacing", "[lightfield][array_view]",
                   float, double) {
  using T = TestType;
  const auto frames = grid<T>(7, 5);
  const mpr::PinholeCamera<T> ref = mpr_test::camera_at<T>(mpr::Vec3<T>::Zero(), 64, 48, 60.0);
  const mpr::ArrayFootprint<T> f = mpr::array_footprint(*frames, ref);
  CHECK(f.planar);
  CHECK(f.cameras == 35);
  CHECK(f.half_u == Approx(6).margin(1e-5));
  CHECK(f.half_v == Approx(4).margin(1e-5));
  CHECK(f.spacing == Approx(2).margin(1e-5));
  CHECK(f.centre.norm() < T(1e-5));
  CHECK(std::abs(f.axis_u.x()) == Approx(1));
  CHECK(f.normal.z() == Approx(1)); // towards the scene, as the reference looks
  CHECK_FALSE(f.one_dimensional());
  CHECK(f.contains(mpr::Vec2<T>(6.9, -4.9), T(1)));
  CHECK_FALSE(f.contains(mpr::Vec2<T>(7.1, 0), T(1)));
  CHECK_FALSE(f.crossing(mpr::Ray<T>{mpr::Vec3<T>(0, 0, 5), mpr::Vec3<T>(1, 0, 0)}).has_value());
}

TEMPLATE_TEST_CASE("array_footprint: a ring is projected on the reference's plane and is one-dimensional",
                   "[lightfield][array_view]", float, double) {
  using T = TestType;
  // 24 cameras on a horizontal circle of radius 10 around the origin, all looking at it.
  std::vector<mpr::PinholeCamera<T>> cams;
  for (int i = 0; i < 24; ++i) {
    const double a = 2 * std::numbers::pi * i / 24;
    const mpr::Vec3<T> eye(static_cast<T>(10 * std::sin(a)), T(0), static_cast<T>(-10 * std::cos(a)));
    cams.push_back(mpr::PinholeCamera<T>::look_at(eye, mpr::Vec3<T>::Zero(), mpr::Vec3<T>(0, -1, 0), T(1), 64, 48));
  }
  const Frames<T> frames(cams, mpr_test::constant_images(cams));
  REQUIRE_FALSE(frames.array_plane().has_value());
  const mpr::ArrayFootprint<T> f = mpr::array_footprint(frames, cams[0]);
  CHECK_FALSE(f.planar);
  // Within 60 degrees of camera 0: cameras -4..4 (4 x 15 = 60 degrees is the limit itself).
  CHECK(f.cameras == 9);
  CHECK(f.half_u == Approx(10 * std::sin(std::numbers::pi / 3)).epsilon(1e-4));
  CHECK(f.half_v < T(1e-4));
  CHECK(f.one_dimensional());
  // A reference looking straight up sees no camera of the ring from the front.
  const mpr::PinholeCamera<T> up =
      mpr::PinholeCamera<T>::look_at(mpr::Vec3<T>::Zero(), mpr::Vec3<T>(0, 10, 0), mpr::Vec3<T>(0, 0, 1), T(1), 64, 48);
  CHECK_THROWS_WITH(mpr::array_footprint(frames, up), Catch::Contains("within 60 degrees"));
}

TEMPLATE_TEST_CASE("fit_to_array: every gallery view's rays cross the camera plane inside the array",
                   "[lightfield][array_view]", float, double) {
  using T = TestType;
  const auto frames = grid<T>(7, 5);
  const mpr::PinholeCamera<T> ref = mpr_test::camera_at<T>(mpr::Vec3<T>::Zero(), 64, 48, 60.0);
  const mpr::ArrayFootprint<T> f = mpr::array_footprint(*frames, ref);
  for (const T tilt : {T(0), T(0.35)}) {
    const mpr::PlanarSurface<T> focal = ref.image_plane(T(100)).tilted(tilt, T(0.5) * tilt);
    for (const mpr::glc::GalleryEntry& e : mpr::glc::gallery) {
      INFO("view " << e.id << ", tilt " << tilt);
      const mpr::GlcSelector<T> raw = prototype<T>(e.id, focal);
      const mpr::GlcSelector<T> glc = mpr::fit_to_array(focal, raw, f);
      // The unfitted views leave the 12 x 8 array almost entirely (their crossings span the view).
      CHECK(mpr::array_coverage(focal, raw, f).outside > 0.4);
      const mpr::ArrayCoverage c = mpr::array_coverage(focal, glc, f);
      CHECK(c.outside == 0);
      // The crossings fill 0.9 of the array along one axis (up to the tilt's non-affinity), less
      // for the views that look from one side (oblique, looking down, any on a tilted plane).
      const bool aside = e.id == 'C' || e.id == 'F' || tilt != 0;
      INFO("span " << c.span_u << " x " << c.span_v);
      CHECK(std::max(c.span_u, c.span_v) > (aside ? 0.3 : 0.85));
      for (const mpr::Vec2<T>& uv :
           {mpr::Vec2<T>(0, 0), mpr::Vec2<T>(1, 0), mpr::Vec2<T>(0, 1), mpr::Vec2<T>(1, 1), mpr::Vec2<T>(0.3, 0.8)}) {
        const mpr::Vec2<T> x = crossing_at(focal, glc, f, uv);
        CHECK(f.contains(x, T(0.5) * f.spacing));
        if (tilt == 0) CHECK(f.contains(x, T(1e-3))); // parallel planes: exactly the affine map
      }
      // Same side as the prototype: towards the scene.
      CHECK(glc.direction_at({0.5, 0.5}).dot(focal.normal()) > 0);
    }
  }
}

TEMPLATE_TEST_CASE("fit_to_array: pinhole, cross-slit, pencil and bilinear keep their type; parallel rays converge",
                   "[lightfield][array_view]", float, double) {
  using T = TestType;
  const auto frames = grid<T>(7, 5);
  const mpr::PinholeCamera<T> ref = mpr_test::camera_at<T>(mpr::Vec3<T>::Zero(), 64, 48, 60.0);
  const mpr::ArrayFootprint<T> f = mpr::array_footprint(*frames, ref);
  const mpr::PlanarSurface<T> focal = ref.image_plane(T(100));
  const auto type_of = [&](char letter) {
    return mpr::glc::classify(focal, mpr::fit_to_array(focal, prototype<T>(letter, focal), f)).type;
  };
  CHECK(type_of('A') == mpr::glc::Type::pinhole);
  CHECK(type_of('G') == mpr::glc::Type::cross_slit);
  CHECK(type_of('H') == mpr::glc::Type::pencil);
  CHECK(type_of('I') == mpr::glc::Type::bilinear);
  // Orthographic rays (B) all get one scale: a pinhole behind the array.
  CHECK(type_of('B') == mpr::glc::Type::pinhole);
  const mpr::glc::Classification<T> b =
      mpr::glc::classify(focal, mpr::fit_to_array(focal, prototype<T>('B', focal), f));
  CHECK(b.centre.z() < 0);
}

TEMPLATE_TEST_CASE("fit_to_array: the nine gallery views of a grid render nine different images",
                   "[lightfield][array_view]", float, double) {
  using T = TestType;
  // Constant colour per camera: the nearest-camera image of a view is its map of camera choices.
  const auto frames = grid<T>(7, 5);
  const mpr::PinholeCamera<T> ref = mpr_test::camera_at<T>(mpr::Vec3<T>::Zero(), 64, 48, 60.0);
  const mpr::ArrayFootprint<T> f = mpr::array_footprint(*frames, ref);
  const mpr::PlanarSurface<T> focal = ref.image_plane(T(100));
  const mpr::CameraFrameSampler<mpr::NearestCamera, T, mpr::Color> sampler(frames);
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (const mpr::glc::GalleryEntry& e : mpr::glc::gallery) {
    const mpr::GlcSelector<T> glc = mpr::fit_to_array(focal, prototype<T>(e.id, focal), f);
    mpr::Image<mpr::Rgb8> image(32, 24);
    mpr::Renderer(focal, glc, sampler).render(image.view(), mpr::Region(0, 0, 32, 24));
    images.push_back(std::move(image));
  }
  for (std::size_t a = 0; a < images.size(); ++a)
    for (std::size_t b = a + 1; b < images.size(); ++b) {
      INFO("views " << mpr::glc::gallery[a].id << " and " << mpr::glc::gallery[b].id);
      int differing = 0;
      for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) differing += images[a](x, y) == images[b](x, y) ? 0 : 1;
      CHECK(differing > 32);
    }
}

TEMPLATE_TEST_CASE("fit_to_array: on a line of cameras every ray passes through the line", "[lightfield][array_view]",
                   float, double) {
  using T = TestType;
  const auto frames = grid<T>(9, 1);
  const mpr::PinholeCamera<T> ref = mpr_test::camera_at<T>(mpr::Vec3<T>::Zero(), 64, 48, 60.0);
  const mpr::ArrayFootprint<T> f = mpr::array_footprint(*frames, ref);
  REQUIRE(f.one_dimensional());
  const mpr::PlanarSurface<T> focal = ref.image_plane(T(100));
  for (const char letter : {'A', 'G', 'I'}) {
    const mpr::GlcSelector<T> glc = mpr::fit_to_array(focal, prototype<T>(letter, focal), f);
    for (const mpr::Vec2<T>& uv : {mpr::Vec2<T>(0, 0), mpr::Vec2<T>(1, 1), mpr::Vec2<T>(0.2, 0.7)}) {
      const mpr::Vec2<T> x = crossing_at(focal, glc, f, uv);
      CHECK(std::abs(x.y()) < T(1e-3));
      CHECK(std::abs(x.x()) <= f.half_u + T(1e-3));
    }
  }
  CHECK_THROWS_AS(mpr::fit_to_array(focal, prototype<T>('A', focal), f, T(0)), mpr::argument_error);
  CHECK_THROWS_AS(mpr::fit_to_array(focal, prototype<T>('A', focal), f, T(1.5)), mpr::argument_error);
}

TEMPLATE_TEST_CASE("array_coverage: the share outside counted by hand", "[lightfield][array_view]", float, double) {
  using T = TestType;
  const auto frames = grid<T>(7, 5);
  const mpr::PinholeCamera<T> ref = mpr_test::camera_at<T>(mpr::Vec3<T>::Zero(), 64, 48, 60.0);
  const mpr::ArrayFootprint<T> f = mpr::array_footprint(*frames, ref);
  // Orthographic rays along the axis from a focal rectangle 40 wide and 8 high centred on x = 10:
  // crossings at x in [-10, 30], y in [-4, 4]; inside (|x| <= 6 + 1): x in [-7, 7], 14 of 40.
  const mpr::PlanarSurface<T> focal =
      mpr::PlanarSurface<T>::centred(mpr::Vec3<T>(10, 0, 50), mpr::Vec3<T>(40, 0, 0), mpr::Vec3<T>(0, 8, 0));
  const mpr::GlcSelector<T> ortho(focal, mpr::Vec3<T>::UnitZ(), mpr::Vec3<T>::UnitZ(), mpr::Vec3<T>::UnitZ());
  const mpr::ArrayCoverage c = mpr::array_coverage(focal, ortho, f, 80);
  CHECK(c.outside == Approx(1 - 14.0 / 40).margin(1.0 / 80));
  CHECK(c.span_u == 1.0); // 14 of the array's 12 units: capped
  CHECK(c.span_v == Approx(8.0 / 8).margin(0.03));
}
