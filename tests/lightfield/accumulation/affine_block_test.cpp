#include <catch2/catch.hpp>

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/lightfield/accumulation/affine_block.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

namespace {

// Row q of an nrows x n block on p(i, q) = origin + i si + q sq, rounded to T.
template <class T>
std::vector<std::vector<mpr::Vec3<T>>> block(const mpr::Vec3<double>& origin, const mpr::Vec3<double>& si,
                                             const mpr::Vec3<double>& sq, std::size_t nrows, std::size_t n) {
  std::vector<std::vector<mpr::Vec3<T>>> rows(nrows, std::vector<mpr::Vec3<T>>(n));
  for (std::size_t q = 0; q < nrows; ++q)
    for (std::size_t i = 0; i < n; ++i)
      rows[q][i] = (origin + static_cast<double>(i) * si + static_cast<double>(q) * sq).template cast<T>();
  return rows;
}

template <class T>
std::vector<const mpr::Vec3<T>*> pointers(const std::vector<std::vector<mpr::Vec3<T>>>& rows) {
  std::vector<const mpr::Vec3<T>*> out;
  for (const auto& r : rows) out.push_back(r.data());
  return out;
}

// The camera's 3x4 projection, row-major, in T (as `FrameTable::Camera::P`).
template <class T>
std::vector<T> projection(const mpr::PinholeCamera<double>& c) {
  Eigen::Matrix<double, 3, 4> Rt;
  Rt.leftCols<3>() = c.R();
  Rt.col(3) = c.t();
  const Eigen::Matrix<double, 3, 4> P = c.K() * Rt;
  std::vector<T> out(12);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 4; ++k) out[static_cast<std::size_t>(4 * r + k)] = static_cast<T>(P(r, k));
  return out;
}

// The exact projection (double) of p by P.
template <class T>
mpr::Vec2<double> project_exact(const std::vector<T>& P, const mpr::Vec3<double>& p) {
  double h[3];
  for (int r = 0; r < 3; ++r)
    h[r] = static_cast<double>(P[static_cast<std::size_t>(4 * r)]) * p.x() +
           static_cast<double>(P[static_cast<std::size_t>(4 * r + 1)]) * p.y() +
           static_cast<double>(P[static_cast<std::size_t>(4 * r + 2)]) * p.z() +
           static_cast<double>(P[static_cast<std::size_t>(4 * r + 3)]);
  return {h[0] / h[2], h[1] / h[2]};
}

// How far (pixels, the larger coordinate) the sight places grid point (i, q) from pixel x.
double off_by(const mpr::detail::AffineSight& sight, double i, double q, const mpr::Vec2<double>& x) {
  double px = 0, py = 0;
  sight.at(i, q, px, py);
  return std::max(std::abs(px - x.x()), std::abs(py - x.y()));
}

// The largest distance (pixels, both coordinates) between the sight and the exact projection
// (double) of the grid's points.
template <class T>
double sight_error(const mpr::detail::AffineSight& sight, const std::vector<T>& P, const mpr::detail::AffineGrid& g,
                   std::size_t nrows, std::size_t n) {
  double worst = 0;
  for (std::size_t q = 0; q < nrows; ++q)
    for (std::size_t i = 0; i < n; ++i) {
      const mpr::Vec3<double> p = g.origin + static_cast<double>(i) * g.step_i + static_cast<double>(q) * g.step_q;
      worst = std::max(worst, off_by(sight, static_cast<double>(i), static_cast<double>(q), project_exact(P, p)));
    }
  return worst;
}

mpr::PinholeCamera<double> camera_at(const mpr::Vec3<double>& centre, double yaw) {
  mpr::Mat3<double> K = mpr::Mat3<double>::Identity();
  K(0, 0) = K(1, 1) = 640;
  K(0, 2) = 319.5;
  K(1, 2) = 239.5;
  const mpr::Mat3<double> R = Eigen::AngleAxisd(yaw, mpr::Vec3<double>::UnitY()).toRotationMatrix();
  return mpr::PinholeCamera<double>(K, R, -R * centre, 640, 480);
}

} // namespace

TEMPLATE_TEST_CASE("affine_grid: a block of evenly spaced rows is one grid; a row off it is not",
                   "[camera_frame_kernels]", float, double) {
  using T = TestType;
  const std::size_t nrows = 8, n = 300;
  const mpr::Vec3<double> origin(-3.25, 1.5, 10), si(0.0125, 0.0003, 0), sq(0.0002, -0.0125, 0);
  auto rows = block<T>(origin, si, sq, nrows, n);
  mpr::detail::AffineGrid g;
  REQUIRE(mpr::detail::affine_grid(pointers(rows).data(), nrows, n, g));
  const double tol = 64 * static_cast<double>(std::numeric_limits<T>::epsilon()) * 20;
  CHECK((g.origin - origin).cwiseAbs().maxCoeff() <= tol);
  CHECK((g.step_i - si).cwiseAbs().maxCoeff() * static_cast<double>(n - 1) <= 2 * tol);
  CHECK((g.step_q - sq).cwiseAbs().maxCoeff() * static_cast<double>(nrows - 1) <= 2 * tol);
  CHECK_FALSE(mpr::detail::affine_grid(pointers(rows).data(), 1, n, g));
  CHECK_FALSE(mpr::detail::affine_grid(pointers(rows).data(), nrows, 1, g));

  // A middle row moved across (its start, its end, both) by a twentieth of a row step: off the
  // grid, although each row alone stays evenly spaced.
  for (const int which : {0, 1, 2}) {
    auto moved = rows;
    for (std::size_t i = 0; i < n; ++i) {
      const double t = which == 0   ? 1.0 - static_cast<double>(i) / static_cast<double>(n - 1)
                       : which == 1 ? static_cast<double>(i) / static_cast<double>(n - 1)
                                    : 1.0;
      moved[3][i] = (moved[3][i].template cast<double>() + t * 0.05 * sq).template cast<T>();
    }
    INFO("moved end " << which);
    CHECK_FALSE(mpr::detail::affine_grid(pointers(moved).data(), nrows, n, g));
  }
  // Rows spaced unevenly across (the last row twice as far).
  auto uneven = block<T>(origin, si, sq, nrows, n);
  for (std::size_t i = 0; i < n; ++i)
    uneven[nrows - 1][i] = (uneven[nrows - 1][i].template cast<double>() + sq).template cast<T>();
  CHECK_FALSE(mpr::detail::affine_grid(pointers(uneven).data(), nrows, n, g));
  // A non-finite point.
  auto bad = rows;
  bad[5][n - 1].x() = std::numeric_limits<T>::quiet_NaN();
  CHECK_FALSE(mpr::detail::affine_grid(pointers(bad).data(), nrows, n, g));
}

TEMPLATE_TEST_CASE("affine_sight: a camera that sees a block at one depth maps every row's ends within the "
                   "tolerance; a turned one, or rows off the grid by more than it allows, are refused",
                   "[camera_frame_kernels]", float, double) {
  using T = TestType;
  const std::size_t nrows = 8, n = 400;
  // A block on the plane z = 10 in front of cameras on z = 0 looking along +z.
  const auto rows = block<T>({-3, -0.2, 10}, {0.015, 0, 0}, {0, 0.015, 0}, nrows, n);
  mpr::detail::AffineGrid g;
  REQUIRE(mpr::detail::affine_grid(pointers(rows).data(), nrows, n, g));
  const double tolerance = 1e-4;
  int accepted = 0, refused = 0, close = 0;
  // Turned cameras: yaw from 1e-9 to about 2e-3 in steps of a factor 2, so that the largest
  // accepted yaw lies within a factor 2 of what the tolerance allows.
  for (int k = -1; k < 22; ++k) {
    const double yaw = k < 0 ? 0.0 : 1e-9 * std::pow(2.0, k);
    for (const double cx : {-1.0, 0.0, 2.5}) {
      const mpr::PinholeCamera<double> cam = camera_at({cx, 0.3, 0}, yaw);
      const std::vector<T> P = projection<T>(cam);
      mpr::detail::AffineSight sight;
      const bool ok = mpr::detail::affine_sight(P.data(), g, n, nrows, tolerance, sight);
      INFO("yaw " << yaw << ", camera x " << cx);
      if (yaw == 0.0) CHECK(ok); // a rectified camera: exactly one depth
      if (yaw >= 1e-3) CHECK_FALSE(ok);
      if (ok) {
        ++accepted;
        const double error = sight_error(sight, P, g, nrows, n);
        CHECK(error <= tolerance);
        close += error > tolerance / 16 ? 1 : 0;
        // `at` gives the positions in the sampler's scalar.
        T x, y;
        sight.at(2.0, 3.0, x, y);
        CHECK(static_cast<double>(x) == Approx(sight.x[0] + 2 * sight.x[1] + 3 * sight.x[2]).margin(1e-3));
        CHECK(static_cast<double>(y) == Approx(sight.y[0] + 2 * sight.y[1] + 3 * sight.y[2]).margin(1e-3));
      } else {
        ++refused;
      }
    }
  }
  CHECK(accepted >= 20);
  CHECK(refused >= 20);
  CHECK(close >= 1); // the bound is not much looser than the error it bounds

  // A middle row moved off the grid by up to the 64 ulp affine_grid lets through, seen by a
  // camera of a long focal length: the map must place that row's ends (the points themselves,
  // projected exactly) within the tolerance, or refuse the camera.
  mpr::Mat3<double> K = mpr::Mat3<double>::Identity();
  K(0, 0) = K(1, 1) = 4000;
  K(0, 2) = K(1, 2) = 200;
  const mpr::PinholeCamera<double> tele(K, mpr::Mat3<double>::Identity(), mpr::Vec3<double>(-0.1, 0.2, 0), 400, 400);
  const std::vector<T> P = projection<T>(tele);
  int moved_accepted = 0, moved_refused = 0;
  for (const double ulps : {0.0, 1.0, 4.0, 16.0, 60.0}) {
    auto moved = rows;
    const double step = ulps * static_cast<double>(std::numeric_limits<T>::epsilon()) * 20;
    for (std::size_t i = 0; i < n; ++i)
      moved[3][i] = (moved[3][i].template cast<double>() + mpr::Vec3<double>(step, -step, step)).template cast<T>();
    mpr::detail::AffineGrid gm;
    if (!mpr::detail::affine_grid(pointers(moved).data(), nrows, n, gm)) continue;
    mpr::detail::AffineSight sight;
    if (!mpr::detail::affine_sight(P.data(), gm, n, nrows, tolerance, sight)) {
      ++moved_refused;
      continue;
    }
    ++moved_accepted;
    double worst = 0;
    for (std::size_t q = 0; q < nrows; ++q)
      for (const std::size_t i : {std::size_t(0), n - 1}) {
        const mpr::Vec3<double> p = moved[q][i].template cast<double>();
        worst = std::max(worst, off_by(sight, static_cast<double>(i), static_cast<double>(q), project_exact(P, p)));
      }
    INFO("row moved by " << ulps << " ulp");
    CHECK(worst <= tolerance);
  }
  CHECK(moved_accepted >= 1);
  if (std::is_same_v<T, float>) CHECK(moved_refused >= 1);

  // Behind the camera, or with the block reaching behind it: refused.
  const auto behind = block<T>({-3, -0.2, -10}, {0.015, 0, 0}, {0, 0.015, 0}, nrows, n);
  mpr::detail::AffineGrid gb;
  REQUIRE(mpr::detail::affine_grid(pointers(behind).data(), nrows, n, gb));
  mpr::detail::AffineSight sight;
  CHECK_FALSE(mpr::detail::affine_sight(projection<T>(camera_at({0, 0, 0}, 0)).data(), gb, n, nrows, 1.0, sight));
  const auto across = block<T>({-3, -0.2, -1}, {0, 0, 0.01}, {0.015, 0, 0}, nrows, n);
  mpr::detail::AffineGrid ga;
  REQUIRE(mpr::detail::affine_grid(pointers(across).data(), nrows, n, ga));
  CHECK_FALSE(mpr::detail::affine_sight(projection<T>(camera_at({0, 0, 0}, 0)).data(), ga, n, nrows, 1e9, sight));
}

TEMPLATE_TEST_CASE("snap_to_texel: within 1e-4 pixel of a texel, or within T's rounding of the coordinate, is on it",
                   "[lightfield][snap]", float, double) {
  using T = TestType;
  const auto snapped = [](T x, long expect_i, T expect_a) {
    long i = -1;
    T a = -1;
    mpr::detail::snap_to_texel(x, i, a);
    INFO("x = " << static_cast<double>(x));
    CHECK(i == expect_i);
    CHECK(a == expect_a);
  };
  snapped(T(40.3), 40, T(40.3) - T(40)); // a fraction is kept
  snapped(T(-40.5), -41, T(0.5));
  snapped(T(40.00005), 40, 0); // within 1e-4 pixel, above and below
  snapped(T(40.99995), 41, 0);
  snapped(T(-10.99996), -11, 0);
  // Two units in the last place above 800 in float (1.2e-4 pixel, as a float projection lands
  // off a texel it should hit) snap in float; in double the same offset is a real fraction.
  const T off = std::nextafter(std::nextafter(T(800), T(1e4)), T(1e4)) - T(800);
  if constexpr (std::is_same_v<T, float>) {
    CHECK(off > T(1e-4));
    snapped(T(800) + off, 800, 0);
    snapped(T(1400) - T(4) * std::numeric_limits<T>::epsilon() * T(1400) / T(2), 1400, 0);
  } else {
    snapped(T(800) + T(1.22e-4), 800, T(800) + T(1.22e-4) - T(800));
  }
  snapped(T(800.001), 800, T(800.001) - T(800)); // a thousandth of a pixel is a fraction at any scale
  CHECK(mpr::detail::texel_snap(T(1400)) <= T(6.7e-4));
  CHECK(mpr::detail::texel_snap(T(3)) == T(1e-4));
}
