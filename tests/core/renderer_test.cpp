#include <mpr/mpr.hpp>

#include <catch2/catch.hpp>

#include <atomic>

namespace {

using T = double;

/// A sampler whose colour encodes the ray exactly, so any change to any ray shows.
struct RayHash {
  using scalar_type = T;
  mpr::Color sample(const mpr::Ray<T>& r) const noexcept {
    return mpr::Color(static_cast<float>(r.origin.x() * 7 + r.direction.x()),
                      static_cast<float>(r.origin.y() * 7 + r.direction.y()),
                      static_cast<float>(r.origin.z() + r.direction.z() * 3));
  }
};

/// A sampler that reports the constant it was given (to tell views apart).
struct Constant {
  using scalar_type = float;
  float value;
  using color_type = float;
  float sample(const mpr::Ray<float>&) const noexcept { return value; }
};

auto make_renderer() {
  const mpr::PlanarSurface<T> plane({-1, -0.75, 1}, {2, 0, 0}, {0, 1.5, 0});
  const mpr::GlcSelector<T> xslit(plane, {-0.5, -0.1, 1}, {0.5, -0.1, 1}, {-0.5, 0.3, 1});
  return mpr::Renderer(plane, xslit, RayHash{});
}

auto constant_renderer(float value) {
  const mpr::PlanarSurface<float> plane({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const mpr::GlcSelector<float> ortho(plane, {0, 0, 1}, {0, 0, 1}, {0, 0, 1});
  return mpr::Renderer(plane, ortho, Constant{value});
}

} // namespace

TEST_CASE("render equals shade at every pixel", "[renderer]") {
  const auto renderer = make_renderer();
  const mpr::Region region(0, 0, 37, 23);
  mpr::Image<mpr::Color> image(37, 23);
  renderer.render(image.view(), region, {1});
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 37; ++x) REQUIRE((image(x, y) == renderer.shade({x, y}, region)).all());
}

TEST_CASE("the image is identical for 1, 2 and 7 threads", "[renderer]") {
  const auto renderer = make_renderer();
  const mpr::Region region(0, 0, 101, 67);
  mpr::Image<mpr::Color> one(101, 67), two(101, 67), seven(101, 67), threads_std(101, 67);
  renderer.render(one.view(), region, {1});
  renderer.render(two.view(), region, {2});
  renderer.render(seven.view(), region, {7});
  // The std::thread back end directly (the OpenMP one is used by default when available).
  mpr::detail::parallel_rows_std(0, 67, 2,
                                 [&](int y) noexcept { renderer.render_row(threads_std.view(), region, y, 0, 101); });
  CHECK(one == two);
  CHECK(one == seven);
  CHECK(one == threads_std);
}

TEST_CASE("a region offset inside a larger image renders the same pixels", "[renderer]") {
  const auto renderer = make_renderer();
  mpr::Image<mpr::Color> alone(40, 30);
  renderer.render(alone.view(), mpr::Region(0, 0, 40, 30), {1});
  const mpr::Color sentinel(-1, -2, -3);
  mpr::Image<mpr::Color> big(100, 80, sentinel);
  renderer.render(big.view(), mpr::Region(33, 21, 40, 30), {2});
  for (int y = 0; y < 80; ++y)
    for (int x = 0; x < 100; ++x) {
      const bool inside = x >= 33 && x < 73 && y >= 21 && y < 51;
      if (inside)
        REQUIRE((big(x, y) == alone(x - 33, y - 21)).all());
      else
        REQUIRE((big(x, y) == sentinel).all());
    }
}

TEST_CASE("a region partly outside the image renders only the overlap", "[renderer]") {
  const auto renderer = make_renderer();
  mpr::Image<mpr::Color> full(40, 30);
  renderer.render(full.view(), mpr::Region(0, 0, 40, 30), {1});
  mpr::Image<mpr::Color> small(25, 20);
  renderer.render(small.view(), mpr::Region(-15, -10, 40, 30), {2});
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 25; ++x) REQUIRE((small(x, y) == full(x + 15, y + 10)).all());
}

TEST_CASE("several views of different types render into one image in one call", "[renderer]") {
  const auto left = make_renderer();       // double, Color
  const auto right = constant_renderer(5); // float, float colour
  const auto top = constant_renderer(9);
  mpr::Image<float> image(60, 20, -1.0f);
  mpr::render(image.view(), mpr::RenderOptions{2}, mpr::view(mpr::Region(0, 0, 30, 20), left),
              mpr::view(mpr::Region(30, 0, 30, 20), right), mpr::view(mpr::Region(40, 0, 10, 5), top));
  mpr::Image<mpr::Color> reference(30, 20);
  left.render(reference.view(), mpr::Region(0, 0, 30, 20), {1});
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 30; ++x) REQUIRE(image(x, y) == mpr::PixelTraits<float>::from_color(reference(x, y)));
    for (int x = 30; x < 60; ++x) {
      const bool in_top = x >= 40 && x < 50 && y < 5; // the later view wins where they overlap
      REQUIRE(image(x, y) == (in_top ? 9.0f : 5.0f));
    }
  }
}

TEST_CASE("thread count resolution", "[renderer]") {
  CHECK(mpr::detail::resolve_thread_count(4, 2) == 2);
  CHECK(mpr::detail::resolve_thread_count(-3, 100) >= 1);
  CHECK(mpr::detail::resolve_thread_count(1, 0) == 1);
  std::atomic<int> rows{0};
  mpr::detail::parallel_rows(5, 105, 3, [&](int y) noexcept { rows += y; });
  CHECK(rows.load() == (5 + 104) * 100 / 2);
}
