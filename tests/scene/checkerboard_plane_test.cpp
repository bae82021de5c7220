#include <mpr/mpr.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace {

/// Distance from x to the nearest integer.
template <class T>
T to_grid(T x) {
  return std::abs(x - std::round(x));
}

} // namespace

// A pinhole GLC through the analytic checkerboard must equal, pixel for pixel, the image obtained
// independently by mapping each pixel centre through the inverse of the board-to-image
// homography H = K [R | t] [cell_u cell_v origin; 0 0 1] (no rays, no plane intersection).
TEMPLATE_TEST_CASE("pinhole GLC render matches the 3x4 projection of the checkerboard", "[sampler]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const int width = 160, height = 120;

  // Camera: eye above and behind the board, looking down at it, rolled slightly.
  const Eigen::Matrix<double, 3, 1> eye(0.7, 3.1, -6.2);
  Eigen::Matrix<double, 3, 3> R; // world to camera
  R = Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.45, Eigen::Vector3d::UnitX()) *
      Eigen::AngleAxisd(-0.1, Eigen::Vector3d::UnitY());
  const Eigen::Vector3d t = -(R * eye);
  // Intrinsics in mpr's pixel convention: image coordinates run from 0 at the top-left corner of
  // the image to (width, height) at its bottom-right corner; pixel (x, y) is centred at (x+.5, y+.5).
  Eigen::Matrix3d K;
  K << 150, 0, 83, 0, 150, 57, 0, 0, 1;
  Eigen::Matrix<double, 3, 4> P;
  P << R, t;
  P = K * P;

  // The board: 8 x 8 cells of 0.9 x 1.1 units on the plane y = 0, turned by 20 degrees.
  typename mpr::CheckerboardPlane<T>::Config board;
  board.origin = V(T(-0.3), 0, T(0.8));
  board.cell_u = V(T(0.9 * std::cos(0.35)), 0, T(0.9 * std::sin(0.35)));
  board.cell_v = V(T(-1.1 * std::sin(0.35)), 0, T(1.1 * std::cos(0.35)));
  board.cells = 4;
  const mpr::CheckerboardPlane<T> sampler(board);

  // The render path: image plane at unit depth in front of the eye, corners through K^-1.
  const Eigen::Matrix3d K_inv = K.inverse();
  const auto plane_point = [&](double x, double y) {
    const Eigen::Vector3d cam = K_inv * Eigen::Vector3d(x, y, 1);
    return V((R.transpose() * cam + eye).template cast<T>());
  };
  const V origin = plane_point(0, 0);
  const mpr::PlanarSurface<T> plane(origin, V(plane_point(width, 0) - origin), V(plane_point(0, height) - origin));
  const V e = eye.cast<T>();
  const mpr::GlcSelector<T> pinhole(plane, V(plane.point_at({0, 0}) - e), V(plane.point_at({1, 0}) - e),
                                    V(plane.point_at({0, 1}) - e));
  const mpr::Renderer renderer(plane, pinhole, sampler);
  mpr::Image<mpr::Color> image(width, height);
  renderer.render(image.view(), mpr::Region(0, 0, width, height));

  // The independent path.
  Eigen::Matrix3d board_to_world_h;
  board_to_world_h.col(0) = board.cell_u.template cast<double>();
  board_to_world_h.col(1) = board.cell_v.template cast<double>();
  board_to_world_h.col(2) = board.origin.template cast<double>();
  Eigen::Matrix<double, 4, 3> lift = Eigen::Matrix<double, 4, 3>::Zero();
  lift.topRows<3>() = board_to_world_h;
  lift(3, 2) = 1;
  const Eigen::Matrix3d H = P * lift; // board (a, b, 1) -> image, homogeneous
  const Eigen::Matrix3d H_inv = H.inverse();

  const double margin = std::is_same_v<T, float> ? 2e-3 : 1e-7;
  int compared = 0, near_edge = 0, on_board = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Eigen::Vector3d ab = H_inv * Eigen::Vector3d(x + 0.5, y + 0.5, 1);
      const double a = ab.x() / ab.z(), b = ab.y() / ab.z();
      const Eigen::Vector3d world = board_to_world_h * Eigen::Vector3d(a, b, 1);
      const bool in_front = (R * world + t).z() > 0;
      mpr::Color expected = board.background;
      if (in_front) {
        if (to_grid(a) < margin || to_grid(b) < margin) {
          ++near_edge; // the two paths may legitimately round to different cells here
          continue;
        }
        const double fa = std::floor(a), fb = std::floor(b);
        if (std::abs(fa + 0.5) < board.cells && std::abs(fb + 0.5) < board.cells) {
          expected = sampler.cell_color(static_cast<long long>(fa), static_cast<long long>(fb));
          ++on_board;
        }
      }
      ++compared;
      INFO("pixel " << x << ", " << y << " board (" << a << ", " << b << ")");
      REQUIRE((image(x, y) == expected).all());
    }
  CHECK(on_board > width * height / 4);    // the board fills a good part of the view
  CHECK(near_edge < width * height / 100); // and almost every pixel was decided
  CHECK(compared + near_edge == width * height);
}

TEMPLATE_TEST_CASE("checkerboard misses: parallel, behind and off-board rays", "[sampler]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  typename mpr::CheckerboardPlane<T>::Config board;
  board.cells = 3;
  const mpr::CheckerboardPlane<T> sampler(board); // plane z = 0
  const auto is_background = [&](const mpr::Color& c) { return (c == board.background).all(); };
  CHECK(is_background(sampler.sample({V(0, 0, 1), V(1, 0, 0)})));  // parallel
  CHECK(is_background(sampler.sample({V(0, 0, 1), V(0, 0, 1)})));  // plane behind the ray
  CHECK(is_background(sampler.sample({V(5, 0, 1), V(0, 0, -1)}))); // off the 6 x 6 board
  CHECK((sampler.sample({V(T(0.5), T(0.5), 1), V(0, 0, -3)}) == board.light).all());
  CHECK((sampler.sample({V(T(1.5), T(0.5), 1), V(0, 0, -3)}) == board.dark).all());
  CHECK((sampler.sample({V(T(-0.5), T(-1.5), 1), V(0, 0, -3)}) == board.dark).all());
  CHECK((sampler.sample({V(T(-1.5), T(-1.5), 1), V(0, 0, -3)}) == board.light).all());
  CHECK((sampler.sample({V(T(1.5), T(1.5), 1), V(0, 0, -3)}) == board.light).all());
  CHECK((sampler.sample({V(T(2.5), T(0.5), 1), V(0, 0, -3)}) == board.light_alt).all());
  const T nan = std::numeric_limits<T>::quiet_NaN();
  CHECK(is_background(sampler.sample({V(nan, 0, 1), V(0, 0, -1)})));
  CHECK(is_background(sampler.sample({V(0, 0, 1), V(0, 0, 0)})));
  // Far away on an infinite board: no overflow in the cell index.
  const mpr::CheckerboardPlane<T> infinite;
  const mpr::Color far = infinite.sample({V(T(1e30), 0, 1), V(0, 0, -1)});
  CHECK(far.allFinite());
  CHECK_THROWS_WITH(mpr::CheckerboardPlane<T>([] {
                      typename mpr::CheckerboardPlane<T>::Config c;
                      c.cell_v = c.cell_u;
                      return c;
                    }()),
                    Catch::Contains("cell_v"));
}
