// A tile of runs as one block (mpr/lightfield/frame_tiles.hpp): the same sums and weights as the
// runs added one by one (`shift_add`, then ray by ray), for 2-D shifts and resampled grids inside
// a camera's image, across its edges and past them; tiles that are no such grid are declined
// with nothing added.

#include "lightfield/frame_test_scenes.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/frame_tiles.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <random>
#include <vector>

namespace {

// `rows` runs of n points on the plane z = depth: run r from (x0, y0 + r dy) in steps of dx, or,
// with `shear`, each run also shifted by shear r in x.
template <class T>
std::vector<mpr::Vec3<T>> tile_points(T x0, T y0, T dx, T dy, T shear, T depth, std::size_t rows, std::size_t n) {
  std::vector<mpr::Vec3<T>> p;
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t i = 0; i < n; ++i)
      p.emplace_back(x0 + shear * static_cast<T>(r) + dx * static_cast<T>(i), y0 + dy * static_cast<T>(r), depth);
  return p;
}

} // namespace

TEMPLATE_TEST_CASE("shift_add_tile adds what the runs add one by one, edges included, or declines", "[frame_tiles]",
                   float, double) {
  using T = TestType;
  // Two cameras 0.5 apart, 200 x 60 pixels, focal length 200: on the plane z = 10 one camera
  // pixel is 0.05 world units.
  const auto cams = mpr_test::grid_cameras<T>(2, 1, 0.5, 200, 60, 200.0);
  auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(
      cams, mpr_test::with_detail(mpr_test::plane_images(cams, 10.0), 17, 31, 63, 0));
  const mpr::FrameTable<T> table(frames);
  const T pixel = T(0.05), depth = T(10);
  constexpr std::size_t rows = 8;
  struct Case {
    const char* name;
    T x0, y0; // the tile's first point, in camera pixels of the first camera from its centre
    std::size_t n;
    bool qualifies;
    T dx = 1, dy = 1, shear = 0; // in camera pixels
    float tolerance = 2e-6f;     // on each sum (within 1e-4 pixel of a texel the tile snaps)
  };
  const Case cases[] = {
      {"inside the image", -40.3, -10.6, 64, true},
      {"an integer shift (texels added uninterpolated)", -40.5, -10.5, 64, true},
      {"within 1e-4 pixel of an integer shift", -40.50004, -10.49996, 64, true, 1, 1, 0, 1e-4f},
      {"an integer shift across the edges", -105.5, -33.5, 220, true},
      {"across the left and right edges", -105.2, -3.25, 220, true},
      {"across the top edge", 7.7, -33.4, 50, true},
      {"across the bottom edge", -20.1, 25.9, 50, true},
      {"wholly below the image", 0.4, 31.2, 40, true},
      {"half the cameras' scale, across the edges", -101.3, -29.6, 60, true, 2, 2},
      {"a 960x540 view of 1400x800 cameras", -60.2, -11.1, 90, true, 1.4583333, 1.4583333},
      {"twice the cameras' scale", -30.7, -2.2, 100, true, 0.5, 0.5},
      {"1.5x the cameras' scale", -30.7, -2.2, 100, true, T(2) / 3, T(2) / 3},
      {"1.5x the cameras' scale, across the edges", -105.2, -33.4, 330, true, T(2) / 3, T(2) / 3},
      {"rows two camera pixels apart", 0.3, -5.2, 40, true, 1, 2},
      {"pixels three camera pixels apart", 0.3, -5.2, 40, false, 3, 3},
      {"rows sheared", 0.3, -5.2, 40, false, 1, 1, 0.5},
  };
  mpr::TileWork work;
  std::size_t deferred = 0; // blocks a batch took
  for (const Case& k : cases) {
    INFO(k.name);
    const auto points =
        tile_points<T>(k.x0 * pixel, k.y0 * pixel, k.dx * pixel, k.dy * pixel, k.shear * pixel, depth, rows, k.n);
    const std::size_t total = rows * k.n;
    for (const auto& c : table.cameras()) {
      std::vector<float> acc(3 * total, 0.25f), weight(total, 0.5f), steps(rows * (k.n + 1), 0.0f);
      std::vector<float> acc_runs = acc, weight_runs = weight;
      const bool added =
          mpr::shift_add_tile(table, c, points.data(), rows, k.n, acc.data(), weight.data(), steps.data(), work);
      CHECK(added == k.qualifies);
      if (!added) {
        CHECK(acc == acc_runs);
        CHECK(weight == weight_runs);
        CHECK(std::all_of(steps.begin(), steps.end(), [](float s) { return s == 0; }));
        continue;
      }
      // With a batch: a whole-pixel shift over whole rows is deferred, and added with
      // `add_shifted_blocks` it gives the same sums; the edges and weights are the same at once.
      {
        std::vector<float> acc_b(3 * total, 0.25f), weight_b(total, 0.5f), steps_b(rows * (k.n + 1), 0.0f);
        mpr::detail::ShiftBatch batch;
        batch.blocks.reserve(1);
        batch.rows.resize(1);
        CHECK(mpr::shift_add_tile(table, c, points.data(), rows, k.n, acc_b.data(), weight_b.data(), steps_b.data(),
                                  work, nullptr, &batch));
        deferred += batch.blocks.size();
        mpr::detail::add_shifted_blocks(batch, rows, k.n, mpr::Srgb8Texel::linear16(), mpr::Srgb8Texel::scale,
                                        acc_b.data(), 3 * static_cast<std::ptrdiff_t>(k.n));
        CHECK(weight_b == weight);
        CHECK(steps_b == steps);
        int apart = 0;
        for (std::size_t j = 0; j < acc.size(); ++j) apart += std::abs(acc_b[j] - acc[j]) <= 1e-6f ? 0 : 1;
        CHECK(apart == 0);
      }
      mpr::add_weight_steps(steps.data(), rows, k.n, weight.data());
      for (std::size_t r = 0; r < rows; ++r) {
        const std::size_t o = r * k.n;
        if (!mpr::shift_add(table, c, points.data() + o, k.n, acc_runs.data() + 3 * o, weight_runs.data() + o))
          table.add_per_ray(c, points.data() + o, k.n, acc_runs.data() + 3 * o, weight_runs.data() + o);
      }
      int worse = 0;
      for (std::size_t i = 0; i < total; ++i) {
        worse += weight[i] != weight_runs[i] ? 1 : 0;
        for (std::size_t j = 0; j < 3; ++j)
          worse += std::abs(acc[3 * i + j] - acc_runs[3 * i + j]) <= k.tolerance ? 0 : 1;
      }
      CHECK(worse == 0);
    }
  }
  CHECK(deferred > 0);
}

TEMPLATE_TEST_CASE("shift_add_tile defers whole-pixel resampled blocks that share their weights; added together "
                   "they give the per-camera sums",
                   "[frame_tiles]", float, double) {
  using T = TestType;
  // Two cameras 0.5 apart, focal length 200: on the plane z = 10 the second sees every point 10
  // whole pixels from where the first does, at the same fractional offset.
  const auto cams = mpr_test::grid_cameras<T>(2, 1, 0.5, 200, 60, 200.0);
  auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(
      cams, mpr_test::with_detail(mpr_test::plane_images(cams, 10.0), 17, 31, 63, 0));
  const mpr::FrameTable<T> table(frames);
  const T pixel = T(0.05), depth = T(10);
  constexpr std::size_t rows = 8;
  struct Case {
    const char* name;
    T x0, y0, step; // the tile's first point (camera pixels of the first camera from its centre), step
    std::size_t n;
    std::size_t taken; // blocks the batch takes
  };
  const Case cases[] = {
      {"magnified 2x", -30.7, -2.2, 0.5, 100, 2},
      {"magnified 1.5x", -20.35, -6.6, T(2) / 3, 90, 2},
      {"a 960x540 view of 1400x800 cameras", -40.2, -11.1, 1.4583333, 40, 2},
      // Blocks over part of the tile: the same part for both cameras (taken), or not (the first
      // camera's taken, the other's added by itself).
      {"across the top edge", 7.7, -31.4, 0.5, 50, 2},
      {"across the left and right edges", -105.2, -3.25, 0.5, 420, 1},
      {"wholly above the image", 7.7, -40.4, 0.5, 50, 0},
  };
  mpr::TileWork work;
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    for (const Case& k : cases) {
      INFO(k.name);
      const auto points =
          tile_points<T>(k.x0 * pixel, k.y0 * pixel, k.step * pixel, k.step * pixel, T(0), depth, rows, k.n);
      const std::size_t total = rows * k.n;
      std::vector<float> acc(3 * total, 0.25f), weight(total, 0.5f), steps(rows * (k.n + 1), 0.0f);
      std::vector<float> acc_b = acc, weight_b = weight, steps_b = steps;
      mpr::detail::SharedWeightsBatch batch;
      batch.blocks.reserve(table.size());
      for (const auto& c : table.cameras()) {
        REQUIRE(mpr::shift_add_tile(table, c, points.data(), rows, k.n, acc.data(), weight.data(), steps.data(), work));
        REQUIRE(mpr::shift_add_tile(table, c, points.data(), rows, k.n, acc_b.data(), weight_b.data(), steps_b.data(),
                                    work, nullptr, nullptr, &batch));
      }
      CHECK(batch.blocks.size() == k.taken);
      mpr::detail::add_shared_weights(batch, mpr::Srgb8Texel::linear16(), mpr::Srgb8Texel::scale, acc_b.data(),
                                      3 * static_cast<std::ptrdiff_t>(k.n), level);
      CHECK(batch.blocks.empty());
      CHECK(weight_b == weight);
      CHECK(steps_b == steps);
      int apart = 0;
      float worst = 0;
      for (std::size_t j = 0; j < acc.size(); ++j) {
        worst = std::max(worst, std::abs(acc_b[j] - acc[j]));
        apart += std::abs(acc_b[j] - acc[j]) <= 2e-5f ? 0 : 1;
      }
      INFO("largest difference " << worst);
      CHECK(apart == 0);
    }
  });
}

TEST_CASE("add_weight_steps folds the step rows into running counts at every SIMD level", "[frame_tiles]") {
  // Rows of every length up to two vectors and beyond, steps of whole camera counts (starts and
  // ends of runs, several on one pixel), onto weights that are not whole.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> count(-3, 3);
  for (const std::size_t n : {1u, 2u, 15u, 16u, 17u, 31u, 32u, 33u, 100u}) {
    INFO("n = " << n);
    const std::size_t rows = 3;
    std::vector<float> steps(rows * (n + 1)), start(rows * n);
    for (float& s : steps) s = static_cast<float>(count(rng));
    for (std::size_t i = 0; i < start.size(); ++i) start[i] = 0.25f + static_cast<float>(i % 7);
    std::vector<float> expected = start;
    for (std::size_t r = 0; r < rows; ++r) {
      float running = 0;
      for (std::size_t i = 0; i < n; ++i) expected[r * n + i] += running += steps[r * (n + 1) + i];
    }
    mpr_test::for_each_simd_level([&](mpr_test::SimdLevel level) {
      std::vector<float> weight = start;
      mpr::add_weight_steps(steps.data(), rows, n, weight.data(), level);
      CHECK(weight == expected);
    });
  }
}
