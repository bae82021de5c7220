#include <mpr/camera/pinhole_camera.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <limits>

TEMPLATE_TEST_CASE("PinholeCamera projects and back-projects consistently", "[camera]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const T tol = std::is_same_v<T, float> ? T(2e-3) : T(1e-9);
  mpr::Mat3<T> K;
  K << 500, 0, 319.5, 0, 510, 239.5, 0, 0, 1;
  const mpr::Mat3<T> R = Eigen::AngleAxis<T>(T(0.3), V(1, 2, 3).normalized()).toRotationMatrix();
  const V t(T(0.1), T(-0.2), T(4));
  for (const auto distortion :
       {typename mpr::PinholeCamera<T>::Distortion{}, typename mpr::PinholeCamera<T>::Distortion{T(-0.1), T(0.02)}}) {
    const mpr::PinholeCamera<T> camera(K, R, t, 640, 480, distortion);
    CHECK((camera.camera_from_world(camera.centre())).norm() < tol);
    for (int i = 0; i < 9; ++i) {
      const mpr::Vec2<T> pixel(T(20 + 70 * i), T(15 + 50 * i));
      const mpr::Ray<T> ray = camera.ray_through(pixel);
      const auto back = camera.project(ray.at(T(3)));
      REQUIRE(back.has_value());
      REQUIRE((*back - pixel).norm() < tol * 100);
      // Unit camera-z component: at(3) is 3 units in front of the camera.
      REQUIRE(camera.camera_from_world(ray.at(T(3))).z() == Approx(3).epsilon(tol));
    }
    CHECK_FALSE(camera.project(V(camera.centre() - camera.forward())).has_value()); // behind
  }
}

TEMPLATE_TEST_CASE("PinholeCamera rejects malformed calibration", "[camera]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const mpr::Mat3<T> K = (mpr::Mat3<T>() << 500, 0, 320, 0, 500, 240, 0, 0, 1).finished();
  const mpr::Mat3<T> I = mpr::Mat3<T>::Identity();
  const V t(0, 0, 1);
  CHECK_THROWS_WITH(mpr::PinholeCamera<T>(K, T(2) * I, t, 640, 480),
                    Catch::Contains("R") && Catch::Contains("rotation"));
  CHECK_THROWS_WITH(mpr::PinholeCamera<T>(K, V(1, 1, -1).asDiagonal(), t, 640, 480), Catch::Contains("reflection"));
  mpr::Mat3<T> singular = K;
  singular(1, 1) = 0;
  CHECK_THROWS_WITH(mpr::PinholeCamera<T>(singular, I, t, 640, 480), Catch::Contains("focal"));
  mpr::Mat3<T> not_upper = K;
  not_upper(2, 0) = 1;
  CHECK_THROWS_WITH(mpr::PinholeCamera<T>(not_upper, I, t, 640, 480), Catch::Contains("upper triangular"));
  CHECK_THROWS_WITH(mpr::PinholeCamera<T>(K, I, V(0, std::numeric_limits<T>::quiet_NaN(), 0), 640, 480),
                    Catch::Contains("t"));
  CHECK_THROWS_WITH(mpr::PinholeCamera<T>(K, I, t, 0, 480), Catch::Contains("width"));
  CHECK_THROWS_WITH(mpr::PinholeCamera<T>::look_at({0, 0, 0}, {0, 1, 0}, {0, 1, 0}, T(1), 8, 8), Catch::Contains("up"));
}
