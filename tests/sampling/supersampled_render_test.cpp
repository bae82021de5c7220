// Renderer under each pixel-sampling policy (include/mpr/sampling/supersampled_render.hpp).
#include <mpr/mpr.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <span>

namespace {

/// Colour (u, v, inside) of a ray starting on the unit plane z = 0 spanned by x and y: inside is
/// 1 when the origin lies in [0, 1]^2 and 1000 otherwise, so a sample outside the view shows.
template <class T>
struct OriginProbe {
  using scalar_type = T;
  mpr::Color sample(const mpr::Ray<T>& r) const noexcept {
    const bool inside = r.origin.x() >= 0 && r.origin.x() <= 1 && r.origin.y() >= 0 && r.origin.y() <= 1;
    return mpr::Color(static_cast<float>(r.origin.x()), static_cast<float>(r.origin.y()), inside ? 1.0f : 1000.0f);
  }
};
/// The same with a batch path.
template <class T>
struct OriginProbeBatch : OriginProbe<T> {
  void sample_rays(std::span<const mpr::Ray<T>> rays, std::span<mpr::Color> out) const noexcept {
    for (std::size_t i = 0; i < rays.size(); ++i) out[i] = this->sample(rays[i]);
  }
};
/// The same with batch and tile paths.
template <class T>
struct OriginProbeTile : OriginProbeBatch<T> {
  void sample_tile(std::span<const mpr::Ray<T>> rays, int, std::span<mpr::Color> out) const noexcept {
    this->sample_rays(rays, out);
  }
};
/// 1 left of the vertical line x = edge on the unit plane, 0 right of it.
template <class T>
struct Edge {
  using scalar_type = T;
  double edge;
  mpr::Color sample(const mpr::Ray<T>& r) const noexcept {
    return mpr::Color::Constant(r.origin.x() < edge ? 1.f : 0.f);
  }
};

/// Grey everywhere.
template <class T>
struct Grey {
  using scalar_type = T;
  mpr::Color sample(const mpr::Ray<T>&) const noexcept { return mpr::Color::Constant(0.5f); }
};

template <class T>
mpr::PlanarSurface<T> unit_plane() {
  return mpr::PlanarSurface<T>({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
}
template <class T>
mpr::GlcSelector<T> ortho(const mpr::PlanarSurface<T>& plane) {
  return mpr::GlcSelector<T>(plane, {0, 0, 1}, {0, 0, 1}, {0, 0, 1});
}

template <class T, class Sampler, class Sampling>
mpr::Image<mpr::Color> render(Sampler sampler, Sampling sampling, int w, int h, int threads,
                              mpr::Region region = mpr::Region(0, 0, 1, 1)) {
  const mpr::PlanarSurface<T> plane = unit_plane<T>();
  const mpr::Renderer renderer(plane, ortho(plane), sampler, sampling);
  mpr::Image<mpr::Color> image(w, h);
  renderer.render(image.view(), region.width == 1 ? mpr::Region(0, 0, w, h) : region, {threads});
  return image;
}

bool equal(const mpr::Image<mpr::Color>& a, const mpr::Image<mpr::Color>& b) {
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      if ((a(x, y) != b(x, y)).any()) return false;
  return true;
}

} // namespace

TEMPLATE_TEST_CASE("PixelCentre renders exactly the ray through each pixel centre", "[sampling]", float, double) {
  using T = TestType;
  const mpr::PlanarSurface<T> plane({-1, -0.75, 1}, {2, 0, 0}, {0, 1.5, 0});
  const mpr::GlcSelector<T> xslit(plane, {-0.5, -0.1, 1}, {0.5, -0.1, 1}, {-0.5, 0.3, 1});
  const OriginProbeTile<T> probe;
  const mpr::Renderer by_default(plane, xslit, probe);
  const mpr::Renderer centre(plane, xslit, probe, mpr::PixelCentre{});
  STATIC_REQUIRE(std::is_same_v<decltype(by_default), decltype(centre)>);
  const mpr::Region region(0, 0, 13, 7);
  mpr::Image<mpr::Color> image(13, 7);
  centre.render(image.view(), region, {2});
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 13; ++x) {
      const mpr::Vec2<T> uv = region.pixel_to_uv<T>({x, y});
      const mpr::Color expected = probe.sample(xslit.ray_at({x, y}, uv, plane.point_at(uv)));
      REQUIRE((image(x, y) == expected).all());
    }
}

TEMPLATE_TEST_CASE("supersampled images are identical for any thread count, path and tile", "[sampling]", float,
                   double) {
  using T = TestType;
  const int w = 23, h = 19; // more than two tiles of kTileRows rows, odd sizes
  const auto check = [&](const auto& sampling) {
    const mpr::Image<mpr::Color> reference = render<T>(OriginProbe<T>{}, sampling, w, h, 1);
    for (const int threads : {1, 2, 3}) {
      CHECK(equal(render<T>(OriginProbe<T>{}, sampling, w, h, threads), reference));
      CHECK(equal(render<T>(OriginProbeBatch<T>{}, sampling, w, h, threads), reference));
      CHECK(equal(render<T>(OriginProbeTile<T>{}, sampling, w, h, threads), reference));
    }
    // A view placed partly outside a smaller image renders the same pixels of the view.
    const mpr::Image<mpr::Color> part = render<T>(OriginProbeTile<T>{}, sampling, 11, 9, 2, mpr::Region(-5, -4, w, h));
    bool same = true;
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 11; ++x) same = same && (part(x, y) == reference(x + 5, y + 4)).all();
    CHECK(same);
  };
  check(mpr::Supersample(mpr::Stratified(3)));
  check(mpr::Supersample(mpr::OwenSobol(8), mpr::MitchellFilter()));
  check(mpr::Supersample(mpr::OwenSobol(5), mpr::AnyFilter(mpr::LanczosFilter())));
  check(mpr::Supersample(mpr::Stratified(2), mpr::GaussianFilter()));
}

TEMPLATE_TEST_CASE("no sample leaves the view, whatever the filter radius", "[sampling]", float, double) {
  using T = TestType;
  const auto check = [&](const auto& sampling) {
    const mpr::Image<mpr::Color> image = render<T>(OriginProbeTile<T>{}, sampling, 6, 5, 2);
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 6; ++x) REQUIRE(image(x, y)[2] == Approx(1).epsilon(1e-6));
  };
  check(mpr::Supersample(mpr::OwenSobol(16), mpr::TentFilter(2)));
  check(mpr::Supersample(mpr::OwenSobol(16), mpr::LanczosFilter(4)));
  check(mpr::Supersample(mpr::Stratified(4), mpr::BoxFilter(3)));
  check(mpr::Supersample(mpr::OwenSobol(1), mpr::MitchellFilter(8)));
}

TEMPLATE_TEST_CASE("the box filter integrates coverage: an edge through a pixel gives its area share", "[sampling]",
                   float, double) {
  using T = TestType;
  const int w = 8;
  for (const double share : {0.1, 0.37, 0.5, 0.93}) {
    const double edge = (3 + share) / w; // through pixel column 3
    const mpr::Image<mpr::Color> sobol = render<T>(Edge<T>{edge}, mpr::Supersample(mpr::OwenSobol(256)), w, 2, 1);
    const mpr::Image<mpr::Color> strata = render<T>(Edge<T>{edge}, mpr::Supersample(mpr::Stratified(16)), w, 2, 1);
    const mpr::Image<mpr::Color> centre = render<T>(Edge<T>{edge}, mpr::PixelCentre{}, w, 2, 1);
    for (int y = 0; y < 2; ++y) {
      // 256 net points: exactly one in each column strip of width 1/256, so the share is off by
      // at most one strip; 16 x 16 strata: at most one column of strata.
      CHECK(sobol(3, y)[0] == Approx(share).margin(1.0 / 256 + 1e-6));
      CHECK(strata(3, y)[0] == Approx(share).margin(1.0 / 16 + 1e-6));
      CHECK(centre(3, y)[0] == (share > 0.5 ? 1.0f : 0.0f));
      CHECK(sobol(2, y)[0] == 1);
      CHECK(sobol(4, y)[0] == 0);
    }
  }
}

TEMPLATE_TEST_CASE("negative lobes never blow up: a constant scene stays constant for every filter", "[sampling]",
                   float, double) {
  using T = TestType;
  const auto check = [&](const auto& sampling) {
    const mpr::Image<mpr::Color> image = render<T>(Grey<T>{}, sampling, 9, 7, 2);
    for (int y = 0; y < 7; ++y)
      for (int x = 0; x < 9; ++x) REQUIRE(image(x, y)[1] == Approx(0.5).epsilon(1e-5));
  };
  for (const int spp : {1, 2, 3, 16}) {
    check(mpr::Supersample(mpr::OwenSobol(spp), mpr::MitchellFilter()));
    check(mpr::Supersample(mpr::OwenSobol(spp), mpr::LanczosFilter()));
    check(mpr::Supersample(mpr::OwenSobol(spp), mpr::GaussianFilter()));
    check(mpr::Supersample(mpr::OwenSobol(spp), mpr::TentFilter()));
  }
}

TEST_CASE("FilterSums: signed average, |w| average when lobes cancel, plain mean when all weights are 0",
          "[sampling]") {
  using Sums = mpr::detail::FilterSums<float>;
  Sums a;
  a.add(2, 1);
  a.add(4, 3);
  CHECK(a.resolve(2) == Approx(3.5));
  Sums b; // w = 0.1 of |w| = 2.1: below the 1/4 share, so the |w|-weighted mean
  b.add(2, -1);
  b.add(4, 1.1f);
  CHECK(b.resolve(2) == Approx((2 * 1 + 4 * 1.1) / 2.1));
  Sums c;
  c.add(2, 0);
  c.add(6, 0);
  CHECK(c.resolve(2) == Approx(4));
  Sums d; // negative total weight
  d.add(1, -2);
  d.add(3, 0.5f);
  CHECK(d.resolve(2) == Approx((1 * 2 + 3 * 0.5) / 2.5));
}

TEST_CASE("supersampling removes staircase error on a checkerboard", "[sampling]") {
  using T = double;
  const auto plane = mpr::PlanarSurface<T>::centred({0, 0, 1}, {2, 0, 0}, {0, 2, 0});
  const mpr::Vec3<T> eye(0, 0, 0);
  const mpr::GlcSelector<T> pinhole(plane, plane.point_at({0, 0}) - eye, plane.point_at({1, 0}) - eye,
                                    plane.point_at({0, 1}) - eye);
  mpr::CheckerboardPlane<T>::Config board;
  board.origin = {0, 0, 4};
  board.cell_u = {0.6, 0.35, 0}; // turned and 0.7 units wide: edges cross pixels at all angles
  board.cell_v = {-0.35, 0.6, 0};
  const mpr::CheckerboardPlane<T> scene(board);
  const auto image = [&](const auto& sampling) {
    mpr::Image<mpr::Color> out(48, 48);
    mpr::Renderer(plane, pinhole, scene, sampling).render(out.view(), mpr::Region(0, 0, 48, 48), {2});
    return out;
  };
  const mpr::Image<mpr::Color> truth = image(mpr::Supersample(mpr::OwenSobol(1024)));
  const auto mse = [&](const mpr::Image<mpr::Color>& a) {
    double sum = 0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x) sum += (a(x, y) - truth(x, y)).square().sum();
    return sum / (48.0 * 48 * 3);
  };
  const double centre = mse(image(mpr::PixelCentre{}));
  const double sobol16 = mse(image(mpr::Supersample(mpr::OwenSobol(16))));
  const double strata16 = mse(image(mpr::Supersample(mpr::Stratified(4))));
  INFO("mse centre " << centre << ", OwenSobol 16 " << sobol16 << ", stratified 4x4 " << strata16);
  CHECK(centre > 0);
  CHECK(sobol16 < centre / 8);
  CHECK(strata16 < centre / 8);
}

TEST_CASE("filters without negative lobes say so; the unsigned sums average the same", "[sampling]") {
  STATIC_REQUIRE(mpr::detail::nonnegative_filter<mpr::BoxFilter>);
  STATIC_REQUIRE(mpr::detail::nonnegative_filter<mpr::TentFilter>);
  STATIC_REQUIRE(mpr::detail::nonnegative_filter<mpr::GaussianFilter>);
  STATIC_REQUIRE_FALSE(mpr::detail::nonnegative_filter<mpr::MitchellFilter>);
  STATIC_REQUIRE_FALSE(mpr::detail::nonnegative_filter<mpr::LanczosFilter>);
  STATIC_REQUIRE_FALSE(mpr::detail::nonnegative_filter<mpr::AnyFilter>);
  mpr::detail::FilterSums<float, false> u;
  u.add(2, 1);
  u.add(4, 3);
  CHECK(u.resolve(2) == Approx(3.5));
  mpr::detail::FilterSums<float, false> z;
  z.add(2, 0);
  z.add(6, 0);
  CHECK(z.resolve(2) == Approx(4));
}
