#include "lightfield/frame_test_scenes.hpp"
#include "render/ray_hash.hpp"

#include <mpr/render/policy_dispatch.hpp>

#include <catch2/catch.hpp>

#include <memory>
#include <variant>

namespace {

using mpr_test::RayHash;

/// A sampler of the squared slopes of the ray, (dx / dz)^2 and (dy / dz)^2: their mean over a
/// pixel grows with the spread of its rays' directions (a finite aperture's).
template <class T>
struct SlopeSquares {
  using scalar_type = T;
  mpr::Color sample(const mpr::Ray<T>& r) const noexcept {
    const T sx = r.direction.x() / r.direction.z(), sy = r.direction.y() / r.direction.z();
    return mpr::Color(static_cast<float>(sx * sx), static_cast<float>(sy * sy), 0);
  }
};

bool close(const mpr::Color& a, const mpr::Color& b, float tolerance) { return ((a - b).abs() <= tolerance).all(); }

} // namespace

TEMPLATE_TEST_CASE("policy dispatch: each interpolation choice builds its sampler", "[policy_dispatch]", float,
                   double) {
  using T = TestType;
  const auto cameras = mpr_test::grid_cameras<T>(2, 2, 1.0, 8, 6, 8.0);
  const auto frames =
      std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(cameras, mpr_test::constant_images(cameras));
  // The alternatives follow InterpolationChoice: nearest, synthetic, cylinder, depth.
  CHECK(mpr::make_frame_sampler(frames, mpr::InterpolationChoice::nearest, 1.0).index() == 0);
  CHECK(mpr::make_frame_sampler(frames, mpr::InterpolationChoice::synthetic, 1.0).index() == 1);
  const mpr::FrameSamplerVariant<T, mpr::Color> cylinder =
      mpr::make_frame_sampler(frames, mpr::InterpolationChoice::cylinder, 0.75);
  REQUIRE(cylinder.index() == 2);
  // The radius reaches the policy: a ray along camera 0's axis, from a point 5 in front of it,
  // sees only camera 0 within 0.75 (the neighbours are 1 apart), so its colour is camera 0's.
  CHECK(std::get<2>(cylinder).interpolation().radius == 0.75);
  const mpr::Ray<T> along_0{cameras[0].centre() + mpr::Vec3<T>(0, 0, 5), mpr::Vec3<T>(0, 0, 1)};
  CHECK(close(std::get<2>(cylinder).sample(along_0), mpr_test::constant_colour(0), 1e-5f));
  // The policies' own checks: a cylinder of radius 0, the depth proxy without depth maps.
  CHECK_THROWS_AS(mpr::make_frame_sampler(frames, mpr::InterpolationChoice::cylinder, 0.0), mpr::argument_error);
  CHECK_THROWS_AS(mpr::make_frame_sampler(frames, mpr::InterpolationChoice::depth, 1.0), mpr::argument_error);
}

TEST_CASE("policy dispatch: the pixel sampling of spp samples", "[policy_dispatch]") {
  CHECK(std::holds_alternative<mpr::PixelCentre>(mpr::make_pixel_sampling(1, mpr::BoxFilter(0.5))));
  CHECK(std::holds_alternative<mpr::PixelCentre>(mpr::make_pixel_sampling(0, mpr::BoxFilter(0.5))));
  const mpr::PixelSamplingVariant s = mpr::make_pixel_sampling(16, mpr::make_filter(mpr::FilterChoice::mitchell));
  REQUIRE(s.index() == 1);
  CHECK(std::get<1>(s).pattern().count() == 16);
  CHECK(std::get<1>(s).filter().radius() == 2); // mitchell's default
}

TEMPLATE_TEST_CASE("policy dispatch: render_chosen renders the hand-worked pixels", "[policy_dispatch]", float,
                   double) {
  using T = TestType;
  // renderer_test.cpp's view: plane point(u, v) = (-1 + 2u, -0.75 + 1.5v, 1); GLC direction
  // d(u, v) = (-0.5 + u, -0.1 + 0.4v, 1); RayHash = (7 ox + dx, 7 oy + dy, oz + 3 dz); in the
  // 4 x 2 region at (2, 1) pixel (x, y) has u = (x + 0.5) / 4, v = (y + 0.5) / 2.
  const mpr::PlanarSurface<T> plane({-1, -0.75, 1}, {2, 0, 0}, {0, 1.5, 0});
  const mpr::GlcSelector<T> xslit(plane, {-0.5, -0.1, 1}, {0.5, -0.1, 1}, {-0.5, 0.3, 1});
  const mpr::Region region(2, 1, 4, 2);
  // u = 0.375, v = 0.25 and u = 0.875, v = 0.75 (region pixels (1, 0) and (3, 1)).
  const mpr::Color at_3_1(-1.875f, -2.625f, 4), at_5_2(5.625f, 2.825f, 4);
  const mpr::LensChoice<T> lens{mpr::glc::DiscAperture{}, T(0.2), T(1), mpr::glc::Mat2<T>::Zero()};

  mpr::Image<mpr::Color> centre(7, 4);
  // The pixel centre ignores the lens.
  mpr::render_chosen(plane, xslit, plane, RayHash<T>{}, mpr::make_pixel_sampling(1, mpr::BoxFilter(0.5)), &lens,
                     centre.view(), region, {1});
  CHECK(close(centre(3, 1), at_3_1, 1e-5f));
  CHECK(close(centre(5, 2), at_5_2, 1e-5f));
  CHECK(close(centre(0, 0), mpr::Color(0, 0, 0), 0)); // outside the region: untouched

  // 64 box-filtered samples of a colour linear in (u, v): the pixel's mean, its centre value
  // to within the samples' spread (the colour changes 3.75 per pixel in x, 10.75 in y).
  const mpr::PixelSamplingVariant box64 = mpr::make_pixel_sampling(64, mpr::BoxFilter(0.5));
  mpr::Image<mpr::Color> pinhole(7, 4);
  mpr::render_chosen(plane, xslit, plane, RayHash<T>{}, box64, nullptr, pinhole.view(), region, {1});
  CHECK(close(pinhole(3, 1), at_3_1, 0.2f));
  CHECK(close(pinhole(5, 2), at_5_2, 0.2f));

  // With supersampling the lens is used: each sample's ray leaves its own point of the disc of
  // radius 0.2 on the lens plane 1 behind the image plane, so the squared slopes grow by the
  // disc's variance per axis, 0.2^2 / 4 = 0.01, over the pinhole's (the image is in focus:
  // every ray of a sample crosses the same image-plane point).
  mpr::Image<mpr::Color> pinhole_spread(7, 4), lens_spread(7, 4);
  mpr::render_chosen(plane, xslit, plane, SlopeSquares<T>{}, box64, nullptr, pinhole_spread.view(), region, {1});
  mpr::render_chosen(plane, xslit, plane, SlopeSquares<T>{}, box64, &lens, lens_spread.view(), region, {1});
  for (int y = 1; y < 3; ++y)
    for (int x = 2; x < 6; ++x) {
      INFO("pixel " << x << ", " << y);
      CHECK(lens_spread(x, y)(0) - pinhole_spread(x, y)(0) == Approx(0.01).margin(0.003));
      CHECK(lens_spread(x, y)(1) - pinhole_spread(x, y)(1) == Approx(0.01).margin(0.003));
    }
  CHECK(close(lens_spread(0, 0), mpr::Color(0, 0, 0), 0));
}

TEST_CASE("policy dispatch: a lens whose focal plane the rays cannot reach throws before rendering",
          "[policy_dispatch]") {
  using T = double;
  const mpr::PlanarSurface<T> plane({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  // Rays nearly parallel to the image plane (glc::FiniteAperture names "focus").
  const mpr::GlcSelector<T> grazing(plane, {1, 0, 1e-8}, {1, 0, 1e-8}, {1, 0, 1e-8});
  const mpr::LensChoice<T> lens{mpr::glc::DiscAperture{}, T(0.1), T(1), mpr::glc::Mat2<T>::Zero()};
  mpr::Image<mpr::Color> out(2, 2);
  CHECK_THROWS_AS(mpr::render_chosen(plane, grazing, plane, RayHash<T>{},
                                     mpr::make_pixel_sampling(4, mpr::BoxFilter(0.5)), &lens, out.view(),
                                     mpr::Region(0, 0, 2, 2), {1}),
                  mpr::argument_error);
}
