#include "scene/bvh/bvh_test_util.hpp"

#include <catch2/catch.hpp>

#include <mpr/scene/bvh/bvh.hpp>
#include <mpr/scene/bvh/watertight.hpp>

#include <limits>

using namespace bvh_test;

TEMPLATE_TEST_CASE("watertight: rays through shared edges and vertices never fall through", "[scene][bvh]", float,
                   double) {
  using T = TestType;
  const int n = 12;
  const auto scene = bumpy_grid<T>(n);
  const mpr::scene::Bvh<T> bvh(scene);
  const mpr::Vec3<T> eye(T(5.3), T(9), T(-3.1));
  int misses = 0, rays = 0;
  for (const auto& tri : scene.triangles()) {
    // Through each vertex exactly, and through points on each edge (interior edges are shared).
    for (int j = 0; j < 3; ++j) {
      const mpr::Vec3<T>& a = tri.p[j];
      const mpr::Vec3<T>& b = tri.p[(j + 1) % 3];
      for (T s : {T(0), T(0.5), T(1) / T(3), T(0.123456)}) {
        const mpr::Vec3<T> target = a + s * (b - a);
        const bool boundary =
            (target.x() < T(0.5) || target.z() < T(0.5) || target.x() > n - T(0.5) || target.z() > n - T(0.5));
        if (boundary) continue;
        ++rays;
        if (!bvh.closest_hit({eye, target - eye}).valid()) ++misses;
      }
    }
  }
  INFO(misses << " of " << rays << " rays through shared edges/vertices missed");
  CHECK(rays > 1000);
  CHECK(misses == 0);
}

TEMPLATE_TEST_CASE("watertight test of one triangle: parameter, barycentrics, t range, winding", "[scene][bvh]", float,
                   double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  namespace d = mpr::scene::detail;
  d::TriBlock<T> block{};
  const V p[3] = {V(0, 0, 0), V(4, 0, 0), V(0, 4, 0)};
  for (int v = 0; v < 3; ++v)
    for (int a = 0; a < 3; ++a) block.p[v][a][0] = p[v][a];
  block.count = 1;
  const auto query = [&](const mpr::Ray<T>& ray, T t_max) {
    mpr::scene::Hit<T> hit;
    hit.t = t_max;
    d::Shear<T> sh{};
    if (!d::Shear<T>::make(ray, sh)) return hit;
    d::watertight_finish(d::edges_portable(block, 0, sh.kx, sh.ky, sh.kz, sh.sx, sh.sy, sh.ox, sh.oy, sh.oz), sh.sz, 7,
                         hit);
    return hit;
  };
  const T inf = std::numeric_limits<T>::infinity();
  for (const T dz : {T(-2), T(2)}) { // both windings: the test is two-sided
    const mpr::Ray<T> ray{V(1, 2, -dz * T(2.5)), V(0, 0, dz)};
    const auto hit = query(ray, inf);
    REQUIRE(hit.valid());
    CHECK(hit.triangle == 7);
    CHECK(hit.t == Approx(2.5));
    CHECK(hit.b1 == Approx(0.25));
    CHECK(hit.b2 == Approx(0.5));
    CHECK(!query(ray, T(2.5)).valid()); // t must be below t_max
  }
  CHECK(!query({V(1, 2, 5), V(0, 0, 1)}, inf).valid());  // behind the origin
  CHECK(!query({V(3, 3, 5), V(0, 0, -1)}, inf).valid()); // outside the hypotenuse
  d::Shear<T> sh{};
  CHECK(!d::Shear<T>::make({V(0, 0, 0), V(0, 0, 0)}, sh));
  CHECK(!d::Shear<T>::make({V(0, 0, 0), V(0, 0, std::numeric_limits<T>::quiet_NaN())}, sh));
}
