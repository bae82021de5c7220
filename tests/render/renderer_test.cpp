#include "render/ray_hash.hpp"

#include <mpr/mpr.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <span>

namespace {

using T = double;

/// A sampler whose colour encodes the ray exactly, so any change to any ray shows.
using RayHash = mpr_test::RayHash<T>;

/// RayHash with a batch and a tile path (each ray hashed on its own), so the renderer takes its
/// row-batch (`render_row`) and tile (`render`) paths; counts the tile calls.
struct RayHashTiles : RayHash {
  std::atomic<int>* tiles = nullptr;
  void sample_rays(std::span<const mpr::Ray<T>> rays, std::span<mpr::Color> out) const noexcept {
    for (std::size_t i = 0; i < rays.size(); ++i) out[i] = sample(rays[i]);
  }
  void sample_tile(std::span<const mpr::Ray<T>> rays, int, std::span<mpr::Color> out) const noexcept {
    if (tiles != nullptr) ++*tiles;
    sample_rays(rays, out);
  }
};

/// RayHashTiles with a grid path: each pixel's ray evaluated from the grid's affine form (so the
/// image shows a wrong origin or step), and `grid.ray` checked against it: the largest
/// difference is kept in `gap`. Declines every tile when `decline` is set.
struct RayHashGrid : RayHashTiles {
  std::atomic<int>* grids = nullptr;
  double* gap = nullptr;
  bool decline = false;
  template <class ExactRay>
  bool sample_grid(const mpr::RayGrid<T, ExactRay>& grid, std::span<mpr::Color> out) const noexcept {
    if (decline) return false;
    ++*grids;
    for (int j = 0; j < grid.rows; ++j)
      for (int i = 0; i < grid.width; ++i) {
        const mpr::Ray<T> affine{mpr::Vec3<T>(grid.origin + i * grid.origin_dx + j * grid.origin_dy),
                                 mpr::Vec3<T>(grid.direction + i * grid.direction_dx + j * grid.direction_dy)};
        const mpr::Ray<T> exact = grid.ray(i, j);
        // Within the grid's stated rounding of the affine form (and this evaluation's own).
        const T origin_gap = (affine.origin - exact.origin).cwiseAbs().maxCoeff();
        const T direction_gap = (affine.direction - exact.direction).cwiseAbs().maxCoeff();
        if (!(grid.origin_error > 0 && origin_gap <= 2 * grid.origin_error &&
              direction_gap <= 2 * grid.direction_error))
          *gap = 1;
        *gap = std::max({*gap, (affine.origin - exact.origin).norm(), (affine.direction - exact.direction).norm()});
        out[static_cast<std::size_t>(j * grid.width + i)] = sample(affine);
      }
    return true;
  }
};

/// A sampler that reports the constant it was given (to tell views apart).
struct Constant {
  using scalar_type = float;
  float value;
  using color_type = float;
  float sample(const mpr::Ray<float>&) const noexcept { return value; }
};

template <class Sampler = RayHash>
auto make_renderer(Sampler sampler = {}) {
  const mpr::PlanarSurface<T> plane({-1, -0.75, 1}, {2, 0, 0}, {0, 1.5, 0});
  const mpr::GlcSelector<T> xslit(plane, {-0.5, -0.1, 1}, {0.5, -0.1, 1}, {-0.5, 0.3, 1});
  return mpr::Renderer(plane, xslit, sampler);
}

auto constant_renderer(float value) {
  const mpr::PlanarSurface<float> plane({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const mpr::GlcSelector<float> ortho(plane, {0, 0, 1}, {0, 0, 1}, {0, 0, 1});
  return mpr::Renderer(plane, ortho, Constant{value});
}

} // namespace

TEST_CASE("pixels worked out by hand: uv, surface point, ray and colour", "[renderer]") {
  // make_renderer(): plane point(u, v) = (-1 + 2u, -0.75 + 1.5v, 1); GLC direction
  // d(u, v) = (-0.5 + u, -0.1 + 0.4v, 1); RayHash = (7 ox + dx, 7 oy + dy, oz + 3 dz).
  // In a 4 x 2 region pixel (x, y) has u = (x + 0.5) / 4, v = (y + 0.5) / 2.
  struct Expected {
    int x, y;
    double u, v;
    mpr::Vec3<double> point, direction;
    mpr::Color colour;
  };
  const Expected cases[] = {
      // u = 0.375, v = 0.25: point (-0.25, -0.375, 1), d (-0.125, 0, 1).
      {1, 0, 0.375, 0.25, {-0.25, -0.375, 1}, {-0.125, 0, 1}, mpr::Color(-1.875f, -2.625f, 4)},
      // u = 0.875, v = 0.75: point (0.75, 0.375, 1), d (0.375, 0.2, 1).
      {3, 1, 0.875, 0.75, {0.75, 0.375, 1}, {0.375, 0.2, 1}, mpr::Color(5.625f, 2.825f, 4)},
      // u = 0.125, v = 0.75: point (-0.75, 0.375, 1), d (-0.375, 0.2, 1).
      {0, 1, 0.125, 0.75, {-0.75, 0.375, 1}, {-0.375, 0.2, 1}, mpr::Color(-5.625f, 2.825f, 4)},
  };
  const auto renderer = make_renderer();
  std::atomic<int> tiles{0};
  const auto tiled = make_renderer(RayHashTiles{{}, &tiles});
  // The region at (2, 1) of a 7 x 4 image: pixel (x, y) of the region is image pixel (x + 2, y + 1).
  const mpr::Region region(2, 1, 4, 2);
  mpr::Image<mpr::Color> rows(7, 4), batches(7, 4), tiled_image(7, 4);
  renderer.render(rows.view(), region, {1});
  for (int y = 1; y < 3; ++y) tiled.render_row(batches.view(), region, y, 2, 6);
  tiled.render(tiled_image.view(), region, {2});
  CHECK(tiles.load() >= 1);
  for (const Expected& e : cases) {
    INFO("pixel " << e.x << ", " << e.y);
    const mpr::Pixel px{e.x + 2, e.y + 1};
    const mpr::Vec2<double> uv = region.pixel_to_uv<double>(px);
    CHECK(uv.x() == Approx(e.u).margin(1e-15));
    CHECK(uv.y() == Approx(e.v).margin(1e-15));
    const mpr::Ray<double> ray = renderer.ray_at(px, region);
    CHECK((ray.origin - e.point).norm() <= 1e-12);
    CHECK((ray.direction - e.direction).norm() <= 1e-12);
    CHECK(((renderer.shade(px, region) - e.colour).abs() <= 1e-6f).all());
    CHECK(((rows(px.x, px.y) - e.colour).abs() <= 1e-6f).all());
    CHECK(((batches(px.x, px.y) - e.colour).abs() <= 1e-6f).all());
    CHECK(((tiled_image(px.x, px.y) - e.colour).abs() <= 1e-6f).all());
  }
}

TEST_CASE("render equals shade at every pixel", "[renderer]") {
  const auto renderer = make_renderer();
  const mpr::Region region(0, 0, 37, 23);
  mpr::Image<mpr::Color> image(37, 23);
  renderer.render(image.view(), region, {1});
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 37; ++x) REQUIRE((image(x, y) == renderer.shade({x, y}, region)).all());
}

TEST_CASE("the image is identical for 1, 2, 3 and 7 threads, by rows and by tiles, OpenMP and std::thread",
          "[renderer]") {
  const mpr::Region region(0, 0, 101, 67);
  const auto renderer = make_renderer();
  std::atomic<int> tiles{0};
  const auto tiled = make_renderer(RayHashTiles{{}, &tiles});
  mpr::Image<mpr::Color> reference(101, 67);
  renderer.render(reference.view(), region, {1});
  // The reference is the per-pixel image (checked against hand-worked pixels above).
  for (int y = 0; y < 67; y += 11)
    for (int x = 0; x < 101; x += 13) REQUIRE((reference(x, y) == renderer.shade({x, y}, region)).all());
  for (const int threads : {1, 2, 3, 7}) {
    INFO(threads << " threads");
    mpr::Image<mpr::Color> rows(101, 67), tile_image(101, 67), rows_std(101, 67), tiles_std(101, 67);
    renderer.render(rows.view(), region, {threads});
    tiles = 0;
    tiled.render(tile_image.view(), region, {threads});
    CHECK(tiles.load() == (67 + mpr::kTileRows - 1) / mpr::kTileRows); // the tile path, every tile once
    // The std::thread back end directly (the OpenMP one is used by default when available).
    mpr::detail::parallel_rows_std(0, 67, threads,
                                   [&](int y) noexcept { renderer.render_row(rows_std.view(), region, y, 0, 101); });
    mpr::detail::parallel_rows_std(0, (67 + 4) / 5, threads, [&](int t) noexcept {
      tiled.render_tile(tiles_std.view(), region, 5 * t, std::min(5 * t + 5, 67), 0, 101);
    });
    CHECK(rows == reference);
    CHECK(tile_image == reference);
    CHECK(rows_std == reference);
    CHECK(tiles_std == reference);
  }
}

TEST_CASE("a grid sampler gets each tile's rays in affine form, or the rays when it declines", "[renderer]") {
  STATIC_REQUIRE(mpr::GridRaySampler<RayHashGrid>);
  STATIC_REQUIRE_FALSE(mpr::GridRaySampler<RayHashTiles>);
  // A region offset inside a larger image, tiles that do not start at the region's first row.
  const mpr::Region region(5, 3, 61, 29);
  const auto renderer = make_renderer();
  std::atomic<int> grids{0}, tiles{0};
  double gap = 0;
  const auto gridded = make_renderer(RayHashGrid{{{}, &tiles}, &grids, &gap, false});
  const auto declining = make_renderer(RayHashGrid{{{}, &tiles}, &grids, &gap, true});
  mpr::Image<mpr::Color> image(70, 40, mpr::Color(9, 9, 9)), fallback(70, 40, mpr::Color(9, 9, 9));
  gridded.render(image.view(), region, {2});
  CHECK(grids.load() == (29 + mpr::kTileRows - 1) / mpr::kTileRows);
  CHECK(tiles.load() == 0);
  CHECK(gap < 1e-14); // grid.ray(i, j) is the renderer's ray; the affine form differs by rounding
  float worst = 0;
  int untouched = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 70; ++x) {
      if (!region.contains({x, y})) {
        untouched += (image(x, y) == mpr::Color(9, 9, 9)).all() ? 1 : 0;
        continue;
      }
      worst = std::max(worst, (image(x, y) - renderer.shade({x, y}, region)).abs().maxCoeff());
    }
  CHECK(worst < 1e-5f);
  CHECK(untouched == 70 * 40 - 61 * 29);
  grids = 0;
  declining.render(fallback.view(), region, {2});
  CHECK(grids.load() == 0);
  CHECK(tiles.load() == (29 + mpr::kTileRows - 1) / mpr::kTileRows);
  for (int y = region.y; y < region.y + region.height; ++y)
    for (int x = region.x; x < region.x + region.width; ++x)
      REQUIRE((fallback(x, y) == renderer.shade({x, y}, region)).all());
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
