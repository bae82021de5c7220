// Finite-aperture GLCs (include/mpr/glc/finite_aperture.hpp) against the thin lens.
#include <mpr/mpr.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {

using mpr::glc::FiniteAperture;

/// Image plane z = 0, 2 x 2 units about the axis, normal +z (the scene in front at z > 0); a
/// pinhole at (0, 0, -h) on the lens plane: the thin lens of aperture centre there.
template <class T>
struct ThinLens {
  T h = 1;
  mpr::PlanarSurface<T> plane{mpr::Vec3<T>(-1, -1, 0), mpr::Vec3<T>(2, 0, 0), mpr::Vec3<T>(0, 2, 0)};
  [[nodiscard]] mpr::GlcSelector<T> pinhole() const {
    const mpr::Vec3<T> c(0, 0, -h);
    return mpr::GlcSelector<T>(plane, plane.point_at({0, 0}) - c, plane.point_at({1, 0}) - c,
                               plane.point_at({0, 1}) - c);
  }
};

/// Where `r` crosses the plane z = depth.
template <class T>
mpr::Vec3<T> hit(const mpr::Ray<T>& r, T depth) {
  return r.at((depth - r.origin.z()) / r.direction.z());
}

/// 1 where the ray crosses the plane z = depth left of x = 0, else 0.
template <class T>
struct EdgeAt {
  using scalar_type = T;
  T depth;
  mpr::Color sample(const mpr::Ray<T>& r) const noexcept {
    return mpr::Color::Constant(hit(r, depth).x() < 0 ? 1.f : 0.f);
  }
};

/// Rays along the image plane.
struct Grazing {
  using scalar_type = double;
  mpr::Ray<double> ray_at(mpr::Pixel, const mpr::Vec2<double>&, const mpr::Vec3<double>& p) const noexcept {
    return {p, mpr::Vec3<double>(1, 0, 0)};
  }
};

} // namespace

TEMPLATE_TEST_CASE("F = 0: a pixel's rays pass through its image-plane point and fill the aperture disc", "[glc]",
                   float, double) {
  using T = TestType;
  const ThinLens<T> lens;
  const T radius = T(0.1);
  const FiniteAperture camera(lens.plane, lens.pinhole(), mpr::glc::DiscAperture{}, radius, lens.h);
  const mpr::OwenSobol pattern(256);
  const mpr::Vec2<T> uv(T(0.3), T(0.65));
  const mpr::Vec3<T> x = lens.plane.point_at(uv);
  const mpr::Ray<T> centre = camera.ray_at({}, uv, x);
  for (const T depth : {T(0.5), T(1), T(3), T(9)}) { // in front of the image plane
    const T d = lens.h + depth;                      // from the lens plane
    const mpr::Vec3<T> c = hit(centre, depth);
    T spread = 0;
    for (int i = 0; i < pattern.count(); ++i) {
      const mpr::Ray<T> r = camera.ray_at({}, uv, x, pattern.lens_point({}, i));
      REQUIRE((r.origin - x).norm() < T(1e-6));     // through the pixel's point
      const mpr::Vec3<T> on_lens = hit(r, -lens.h); // inside the disc on the lens plane
      REQUIRE(std::hypot(on_lens.x(), on_lens.y()) <= radius * T(1 + 1e-5));
      spread = std::max(spread, (hit(r, depth) - c).norm());
    }
    // The bundle is the cone from the disc through x: radius r |d - h| / h at distance d.
    const T expected = radius * std::fabs(d - lens.h) / lens.h;
    CHECK(spread <= expected * T(1 + 1e-4));
    CHECK(spread >= expected * T(0.97));
  }
}

TEMPLATE_TEST_CASE("F = f I refocuses: every ray of a pixel meets at the chosen depth", "[glc]", float, double) {
  using T = TestType;
  const ThinLens<T> lens;
  for (const T depth : {T(0.5), T(2), T(7)}) {
    const FiniteAperture camera(lens.plane, lens.pinhole(), mpr::glc::PolygonAperture(6), T(0.2), lens.h,
                                mpr::glc::focus_at_depth(lens.h, depth));
    const mpr::Vec2<T> uv(T(0.8), T(0.1));
    const mpr::Vec3<T> target = hit(camera.ray_at({}, uv, lens.plane.point_at(uv)), depth);
    for (int i = 0; i < 64; ++i) {
      const mpr::Ray<T> r = camera.ray_at({}, uv, lens.plane.point_at(uv), mpr::OwenSobol(64).lens_point({3, 4}, i));
      REQUIRE((hit(r, depth) - target).norm() < T(2e-5) * (1 + depth));
    }
  }
}

TEMPLATE_TEST_CASE("astigmatic focus: two focal lines at the two depths of F's eigenvalues", "[glc]", float, double) {
  using T = TestType;
  const ThinLens<T> lens;
  const T du = 1, dv = 4;
  const FiniteAperture camera(lens.plane, lens.pinhole(), mpr::glc::SquareAperture{}, T(0.2), lens.h,
                              mpr::glc::astigmatic_focus(lens.h, du, dv));
  const mpr::Vec2<T> uv(T(0.4), T(0.55));
  const mpr::Vec3<T> x = lens.plane.point_at(uv);
  T u_spread_at_du = 0, v_spread_at_du = 0, u_spread_at_dv = 0, v_spread_at_dv = 0;
  const mpr::Vec3<T> c1 = hit(camera.ray_at({}, uv, x), du), c2 = hit(camera.ray_at({}, uv, x), dv);
  for (int i = 0; i < 64; ++i) {
    const mpr::Ray<T> r = camera.ray_at({}, uv, x, mpr::OwenSobol(64).lens_point({1, 1}, i));
    u_spread_at_du = std::max(u_spread_at_du, std::fabs(hit(r, du).x() - c1.x()));
    v_spread_at_du = std::max(v_spread_at_du, std::fabs(hit(r, du).y() - c1.y()));
    u_spread_at_dv = std::max(u_spread_at_dv, std::fabs(hit(r, dv).x() - c2.x()));
    v_spread_at_dv = std::max(v_spread_at_dv, std::fabs(hit(r, dv).y() - c2.y()));
  }
  // At depth du the u direction is in focus: a focal line along v; at dv the other way round.
  CHECK(u_spread_at_du < T(1e-5));
  CHECK(v_spread_at_du > T(0.05));
  CHECK(v_spread_at_dv < T(1e-5));
  CHECK(u_spread_at_dv > T(0.05));
  const mpr::glc::FocusClassification<T> f = mpr::glc::classify_focus(camera.focus(), lens.h);
  CHECK(f.type == mpr::glc::FocusType::astigmatic);
  CHECK(f.depths[0] == Approx(du).epsilon(1e-5));
  CHECK(f.depths[1] == Approx(dv).epsilon(1e-5));
}

TEST_CASE("rendered circle of confusion matches the thin-lens formula on a plane at known depth", "[glc]") {
  using T = double;
  const ThinLens<T> lens;
  const T radius = 0.05, depth = 3, d = lens.h + depth; // object 4 units from the lens, focus on the image plane
  const FiniteAperture camera(lens.plane, lens.pinhole(), mpr::glc::DiscAperture{}, radius, lens.h);
  const int w = 400;
  // Thin lens: c = A |S2 - S1| / S2 on the focus (image) plane, A = 2 radius, S1 = h, S2 = d.
  const double coc_pixels = 2 * radius * std::fabs(d - lens.h) / d * w / 2.0; // plane is 2 units wide
  REQUIRE(coc_pixels == Approx(15));
  mpr::Image<mpr::Color> image(w, 2);
  mpr::Renderer(lens.plane, camera, EdgeAt<T>{depth}, mpr::Supersample(mpr::OwenSobol(1024)))
      .render(image.view(), mpr::Region(0, -w / 2, w, w), {2});
  // The edge profile's derivative is the disc's chord-length density, of variance rho^2 / 4
  // (rho the blur radius); the pixel's box adds 1/12 pixel^2.
  double sum = 0, mean = 0, second = 0;
  for (int x = 0; x + 1 < w; ++x) {
    const double step = image(x, 0)[0] - image(x + 1, 0)[0], at = x + 1.0;
    sum += step;
    mean += step * at;
    second += step * at * at;
  }
  mean /= sum;
  const double variance = second / sum - mean * mean - 1.0 / 12;
  const double measured = 4 * std::sqrt(variance); // diameter = 2 rho = 4 sigma
  CHECK(sum == Approx(1).margin(1e-6));
  CHECK(mean == Approx(w / 2.0).margin(0.2));
  CHECK(measured == Approx(coc_pixels).epsilon(0.05));
  // In focus (F chosen for the plane's depth) the edge is sharp: the pixel's own width only.
  mpr::Image<mpr::Color> sharp(w, 2);
  const FiniteAperture focused(lens.plane, lens.pinhole(), mpr::glc::DiscAperture{}, radius, lens.h,
                               mpr::glc::focus_at_depth(lens.h, depth));
  mpr::Renderer(lens.plane, focused, EdgeAt<T>{depth}, mpr::Supersample(mpr::OwenSobol(256)))
      .render(sharp.view(), mpr::Region(0, -w / 2, w, w), {2});
  int blurred = 0;
  for (int x = 0; x < w; ++x) blurred += (sharp(x, 0)[0] > 0.001f && sharp(x, 0)[0] < 0.999f) ? 1 : 0;
  CHECK(blurred <= 1);
}

TEST_CASE("a finite aperture renders its pinhole at the pixel centre and at size 0", "[glc]") {
  using T = float;
  const ThinLens<T> lens;
  const EdgeAt<T> scene{2};
  const auto render = [&](const auto& selector, const auto& sampling) {
    mpr::Image<mpr::Color> image(40, 30);
    mpr::Renderer(lens.plane, selector, scene, sampling).render(image.view(), mpr::Region(0, 0, 40, 30), {2});
    return image;
  };
  const FiniteAperture wide(lens.plane, lens.pinhole(), mpr::glc::DiscAperture{}, 0.2f, lens.h);
  const FiniteAperture none(lens.plane, lens.pinhole(), mpr::glc::DiscAperture{}, 0.0f, lens.h);
  CHECK(render(wide, mpr::PixelCentre{}) == render(lens.pinhole(), mpr::PixelCentre{}));
  const auto ss = mpr::Supersample(mpr::OwenSobol(8));
  CHECK(render(none, ss) == render(lens.pinhole(), ss));
  CHECK_FALSE(render(wide, ss) == render(lens.pinhole(), ss));
}

TEST_CASE("finite-aperture bad input: one error naming the parameter", "[glc]") {
  using T = double;
  const ThinLens<T> lens;
  const auto parameter = [](auto make) {
    try {
      make();
    } catch (const mpr::argument_error& e) {
      return e.parameter();
    }
    return std::string("none");
  };
  CHECK(parameter([&] { FiniteAperture(lens.plane, lens.pinhole(), mpr::glc::DiscAperture{}, -0.1, 1.0); }) ==
        "aperture size");
  CHECK(parameter([&] { FiniteAperture(lens.plane, lens.pinhole(), mpr::glc::DiscAperture{}, 0.1, 0.0); }) ==
        "aperture distance");
  CHECK(parameter([&] {
          FiniteAperture(lens.plane, lens.pinhole(), mpr::glc::DiscAperture{}, 0.1, 1.0,
                         mpr::glc::Mat2<T>::Constant(std::numeric_limits<T>::quiet_NaN()));
        }) == "focus matrix");
  CHECK(parameter([&] { (void)mpr::glc::focus_at_depth(1.0, -2.0); }) == "focus depth");
  CHECK(parameter([&] { mpr::glc::PolygonAperture(2); }) == "aperture blades");
  // Rays parallel to the image plane have no focal-plane crossing.
  CHECK(parameter([&] { FiniteAperture(lens.plane, Grazing{}, mpr::glc::DiscAperture{}, 0.1, 1.0); }) == "focus");
}
