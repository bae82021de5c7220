// pinhole_glc: the GLC of a pinhole camera on its image plane shows exactly the camera's pixels.
#include <mpr/camera/pinhole_glc.hpp>

#include <catch2/catch.hpp>

#include <type_traits>

TEMPLATE_TEST_CASE("pinhole_glc on image_plane maps uv onto pixel centres", "[camera]", float, double) {
  using T = TestType;
  const T tol = std::is_same_v<T, float> ? T(2e-3) : T(1e-9);
  const auto camera = mpr::PinholeCamera<T>::look_at({1, 2, -5}, {0, 0, 0}, {0, 1, 0}, T(0.7), 64, 48);
  const mpr::PlanarSurface<T> plane = camera.image_plane(T(2));
  const mpr::GlcSelector<T> glc = mpr::pinhole_glc(camera, plane);
  for (int y = 0; y < 48; y += 7)
    for (int x = 0; x < 64; x += 9) {
      const mpr::Vec2<T> uv((x + T(0.5)) / 64, (y + T(0.5)) / 48);
      const mpr::Ray<T> ray = glc.ray_at({x, y}, uv, plane.point_at(uv));
      const auto p = camera.project(ray.at(T(1)));
      REQUIRE(p.has_value());
      REQUIRE((*p - mpr::Vec2<T>(T(x), T(y))).norm() < tol);
    }
  // look_at: the target projects to the principal point.
  const auto centre = camera.project({0, 0, 0});
  REQUIRE(centre.has_value());
  CHECK((*centre - mpr::Vec2<T>(T(31.5), T(23.5))).norm() < tol);
}
