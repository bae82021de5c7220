#include "glc_test_util.hpp"

#include <mpr/glc/two_plane.hpp>

#include <catch2/catch.hpp>

#include <limits>

TEMPLATE_TEST_CASE("two_plane: the generators of a GlcSelector in its plane's frame", "[glc][two_plane]", float,
                   double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  // A sheared, scaled plane: uv are affine plane coordinates, slopes are uv per unit depth.
  const mpr::PlanarSurface<T> plane(V(1, 2, 3), V(2, 0, 0), V(1, 4, 0));
  const mpr::GlcSelector<T> sel(plane, V(2, 4, 1), V(0, 0, 3), V(-1, 1, 2));
  const auto tp = mpr::glc::two_plane(plane, sel);
  CHECK(tp.normal() == V(0, 0, 1));
  CHECK(tp[0].u == 0);
  CHECK(tp[1].u == 1);
  CHECK(tp[2].v == 1);
  // d00 = (2, 4, 1) = sigma W + tau H + n: tau = 1, sigma = 0.5.
  CHECK(tp[0].sigma == Approx(0.5));
  CHECK(tp[0].tau == Approx(1));
  const T eps = 64 * std::numeric_limits<T>::epsilon();
  for (const auto& uv : {mpr::Vec2<T>(0, 0), mpr::Vec2<T>(0.3, 0.9), mpr::Vec2<T>(1, 1)}) {
    const mpr::Ray<T> a = tp.ray(uv.x(), uv.y());
    const mpr::Ray<T> b = sel.ray_at({0, 0}, uv, plane.point_at(uv));
    CHECK((a.origin - b.origin).norm() <= eps * 10);
    CHECK((a.direction - b.direction).norm() <= eps);
    // to_frame inverts point().
    const V f = tp.to_frame(a.at(T(2.5)));
    CHECK((tp.point(f.x(), f.y(), f.z()) - a.at(T(2.5))).norm() <= eps * 10);
    CHECK(f.z() == Approx(2.5));
  }
  CHECK(tp.scale() == Approx(std::sqrt(T(1 + 16))));
  // Rays to the other side: the frame's normal flips and depths stay positive along the rays.
  const mpr::GlcSelector<T> back(plane, V(0, 0, -1), V(0, 0, -1), V(0, 0, -1));
  CHECK(mpr::glc::two_plane(plane, back).normal() == V(0, 0, -1));
  CHECK(mpr::glc::two_plane(plane, back).to_frame(V(1, 2, 1)).z() == T(2)); // 2 below the plane at z = 3
}

TEMPLATE_TEST_CASE("two_plane: from three world rays, and validation", "[glc][two_plane]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto plane = glc_test::unit_plane<T>();
  // Rays given by any point on them: they are extended to the plane.
  const std::array<mpr::Ray<T>, 3> rays{mpr::Ray<T>{V(1, 1, 2), V(0.5, 0, 1)}, mpr::Ray<T>{V(0, 0, -1), V(0, 0, 2)},
                                        mpr::Ray<T>{V(0, 1, 0), V(0, 1, 1)}};
  const auto tp = mpr::glc::two_plane(plane, rays);
  CHECK(tp[0].u == 0);
  CHECK(tp[0].v == 1);
  CHECK(tp[0].sigma == T(0.5));
  CHECK(tp[1].u == 0);
  CHECK(tp[2].tau == 1);
  const std::array<mpr::Ray<T>, 3> mixed{rays[0], mpr::Ray<T>{V(0, 0, 0), V(0, 0, -1)}, rays[2]};
  CHECK_THROWS_WITH(mpr::glc::two_plane(plane, mixed), Catch::Contains("different sides"));
  const std::array<mpr::Ray<T>, 3> flat{rays[0], mpr::Ray<T>{V(0, 0, 0), V(1, 0, 0)}, rays[2]};
  CHECK_THROWS_WITH(mpr::glc::two_plane(plane, flat), Catch::Contains("parallel"));
  const std::array<mpr::Ray<T>, 3> nan{rays[0], mpr::Ray<T>{V(0, T(NAN), 0), V(0, 0, 1)}, rays[2]};
  CHECK_THROWS_WITH(mpr::glc::two_plane(plane, nan), Catch::Contains("not finite"));
  using G = mpr::glc::Generator<T>;
  CHECK_THROWS_WITH(mpr::glc::TwoPlane<T>(V::Zero(), V::UnitX(), V::UnitY(), 0, {G{}, G{}, G{}}),
                    Catch::Contains("side"));
  CHECK_THROWS_WITH(mpr::glc::TwoPlane<T>(V::Zero(), V::UnitX(), V::UnitX(), 1, {G{}, G{}, G{}}),
                    Catch::Contains("height_vector"));
  CHECK_THROWS_WITH(mpr::glc::TwoPlane<T>(V::Zero(), V::UnitX(), V::UnitY(), 1, {G{}, G{T(INFINITY), 0, 0, 0}, G{}}),
                    Catch::Contains("generators"));
}
