// Runs of one camera by shift-and-add (mpr/lightfield/frame_runs.hpp) where they cross the
// image's edge rows: in the half-pixel border above the first row and below the last, a run's
// pixels read the edge row twice (the bilinear pixel clamps it), and are added so, at the
// cameras' scale and resampled; a run within the model's tolerance of the border's outer edge,
// whose points may fall either side, is declined with nothing added. Offsets within 1e-4 pixel of
// a texel are snapped to it.

#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/frame_runs.hpp>

#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

namespace {
// One camera at the origin, 200 x 60 pixels, focal length 200: on the plane z = 10, camera pixel
// (x, y) is the point (x - 99.5, y - 29.5) / 20.
template <class T>
mpr::FrameTable<T> one_camera() {
  const auto cams = mpr_test::grid_cameras<T>(1, 1, 0.5, 200, 60, 200.0);
  return mpr::FrameTable<T>(std::make_shared<const mpr::CameraFrameSet<T>>(
      cams, mpr_test::with_detail(mpr_test::plane_images(cams, 10.0), 5, 31, 63, 15)));
}
} // namespace

TEMPLATE_TEST_CASE("shift_add adds runs in the image's half-pixel border rows as the rays do", "[frame_runs]", float,
                   double) {
  using T = TestType;
  const mpr::FrameTable<T> table = one_camera<T>();
  const auto& c = table.camera(0);
  struct Case {
    const char* name;
    double x0, y, step; // the run in camera pixels: (x0 + step i, y)
    bool added;
  };
  const Case cases[] = {
      {"the top border row", 10.3, -0.3, 1, true},
      {"the top border row at whole-pixel x", 10.0, -0.25, 1, true},
      {"the bottom border row", 10.3, 59.2, 1, true},
      {"the top border row, resampled (step 1.5)", 3.7, -0.2, 1.5, true},
      {"the bottom border row at half scale", 3.7, 59.4, 2, true},
      {"the first row", 10.3, 0.0, 1, true},
      // Offsets within 1e-4 pixel of a texel are taken as on it: the nearer texel, below or above.
      {"just short of whole pixels both ways", 10.99999, 20.99999, 1, true},
      {"just past whole pixels both ways", 10.00001, 20.00001, 1, true},
      {"just short of the first row", 10.99999, -0.00001, 1, true},
      {"the last row", 10.3, 59.0, 1, true},
      {"within the tolerance of the top edge", 10.3, -0.4995, 1, false},
      {"within the tolerance of the bottom edge", 10.3, 59.4995, 1, false},
  };
  constexpr std::size_t n = 60;
  for (const Case& k : cases) {
    INFO(k.name);
    std::vector<mpr::Vec3<T>> points;
    for (std::size_t i = 0; i < n; ++i)
      points.emplace_back(static_cast<T>((k.x0 + k.step * static_cast<double>(i) - 99.5) / 20),
                          static_cast<T>((k.y - 29.5) / 20), T(10));
    std::vector<float> acc(3 * n, 0.25f), weight(n, 0.5f);
    std::vector<float> acc_rays = acc, weight_rays = weight;
    const bool added = mpr::shift_add(table, c, points.data(), n, acc.data(), weight.data());
    CHECK(added == k.added);
    if (!added) {
      CHECK(acc == acc_rays);
      CHECK(weight == weight_rays);
      continue;
    }
    table.add_per_ray(c, points.data(), n, acc_rays.data(), weight_rays.data());
    int worse = 0;
    for (std::size_t i = 0; i < n; ++i) {
      worse += weight[i] != weight_rays[i] ? 1 : 0;
      for (std::size_t j = 0; j < 3; ++j) worse += std::abs(acc[3 * i + j] - acc_rays[3 * i + j]) <= 2e-5f ? 0 : 1;
    }
    CHECK(worse == 0);
  }
}

TEMPLATE_TEST_CASE("ahead_rows points at the next camera's texel rows from a known position or a projection",
                   "[frame_runs]", float, double) {
  using T = TestType;
  const mpr::FrameTable<T> table = one_camera<T>(); // pixel (x, y) sees ((x, y) - (99.5, 29.5)) / 20
  const auto& c = table.camera(0);
  const auto channels = [&](int x, int y) { return c.texels[static_cast<std::ptrdiff_t>(y) * c.width + x].c; };
  const mpr::Vec3<T> X(static_cast<T>((12.5 - 99.5) / 20), static_cast<T>((7.5 - 29.5) / 20), T(10));
  using Rows = decltype(mpr::detail::ahead_rows<T, mpr::Rgb8>(&c, X));
  const Rows projected = mpr::detail::ahead_rows<T, mpr::Rgb8>(&c, X);
  CHECK(projected[0] == channels(12, 7));
  CHECK(projected[1] == channels(12, 8));
  // A known position for point i stands in for the projection (here a different one, to tell).
  mpr::RunSight<T> sight{};
  sight.ahead_x = T(40.25);
  sight.ahead_y = T(20.5);
  sight.ahead_dx = T(2);
  sight.ahead_dy = T(0.25);
  const Rows known = mpr::detail::ahead_rows<T, mpr::Rgb8>(&c, X, &sight, 3); // (46.25, 21.25)
  CHECK(known[0] == channels(46, 21));
  CHECK(known[1] == channels(46, 22));
  // Outside the image it is clamped to the last texel pair; NaN means unknown (projected).
  sight.ahead_x = T(500);
  sight.ahead_y = T(-7);
  CHECK(mpr::detail::ahead_rows<T, mpr::Rgb8>(&c, X, &sight, 0)[0] == channels(199, 0));
  sight.ahead_x = std::numeric_limits<T>::quiet_NaN();
  CHECK(mpr::detail::ahead_rows<T, mpr::Rgb8>(&c, X, &sight, 3) == projected);
  // No camera, or a position too large for the texel arithmetic: nothing.
  CHECK(mpr::detail::ahead_rows<T, mpr::Rgb8>(nullptr, X) == Rows{});
  sight.ahead_x = std::numeric_limits<T>::infinity();
  CHECK(mpr::detail::ahead_rows<T, mpr::Rgb8>(&c, X, &sight, 0) == Rows{});
  sight.ahead_x = T(1e9);
  CHECK(mpr::detail::ahead_rows<T, mpr::Rgb8>(&c, X, &sight, 0) == Rows{});
}
