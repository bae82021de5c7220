#include <mpr/scene/bvh.hpp>
#include <mpr/scene/classroom.hpp>
#include <mpr/scene/shapes.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

namespace {

/// A height field of (n+1)^2 irregular vertices, 2 n^2 triangles sharing edges and vertices.
template <class T> mpr::scene::Scene<T> bumpy_grid(int n) {
  mpr::scene::Mesh<T> m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const T x = T(i) + T(0.3) * std::sin(T(1.7) * i + T(0.3) * j);
      const T z = T(j) + T(0.3) * std::cos(T(1.1) * j + T(0.7) * i);
      m.positions.emplace_back(x, T(0.4) * std::sin(T(0.9) * i) * std::cos(T(0.6) * j), z);
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  mpr::scene::Scene<T> s;
  s.add(m);
  return s;
}

} // namespace

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
        const bool boundary = (target.x() < T(0.5) || target.z() < T(0.5) || target.x() > n - T(0.5) ||
                               target.z() > n - T(0.5));
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

TEMPLATE_TEST_CASE("the BVH finds the same closest hit as brute force", "[scene][bvh]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  mpr::scene::Scene<T> s;
  s.add(mpr::scene::sphere<T>(V(0, 0, 0), T(1), mpr::Color(1, 0, 0), 10, 6));
  s.add(mpr::scene::box<T>(V(-2, -2, -3), V(2, 2, -2.5), mpr::Color(0, 1, 0)));
  s.add(mpr::scene::cylinder<T>(V(1.5, -1, 0), V(0, 2, 0), T(0.3), mpr::Color(0, 0, 1), 8));
  REQUIRE(s.size() < 255);
  const mpr::scene::Bvh<T> bvh(s);
  // One leaf holding every triangle: brute force over the same intersection test.
  const mpr::scene::Bvh<T> brute(s, {.bins = 16, .max_leaf = 255, .traversal_cost = 1e30f});
  REQUIRE(brute.nodes().size() == 1);
  REQUIRE(bvh.nodes().size() > 1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<T> uni(-1, 1);
  int hits = 0;
  for (int k = 0; k < 3000; ++k) {
    const V origin(uni(rng) * 4, uni(rng) * 4, 4 + uni(rng));
    const V target(uni(rng) * 2, uni(rng) * 2, uni(rng) * 2);
    const mpr::Ray<T> ray{origin, (target - origin) * (1 + 3 * std::abs(uni(rng)))}; // not unit length
    const auto a = bvh.closest_hit(ray);
    const auto b = brute.closest_hit(ray);
    REQUIRE(a.valid() == b.valid());
    if (!a.valid()) continue;
    ++hits;
    CHECK(a.t == b.t);
    CHECK(a.triangle == b.triangle);
  }
  CHECK(hits > 1500);
}

TEMPLATE_TEST_CASE("hit parameter, barycentrics and degenerate rays", "[scene][bvh][bad_input]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  mpr::scene::Mesh<T> m;
  m.positions = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
  m.triangles = {{0, 1, 2}};
  mpr::scene::Scene<T> s;
  s.add(m);
  const mpr::scene::Bvh<T> bvh(s);
  const auto hit = bvh.closest_hit({V(1, 2, 5), V(0, 0, -2)});
  REQUIRE(hit.valid());
  CHECK(hit.t == Approx(2.5)); // t in units of the (non-unit) direction
  CHECK(hit.b1 == Approx(0.25));
  CHECK(hit.b2 == Approx(0.5));
  CHECK(!bvh.closest_hit({V(1, 2, 5), V(0, 0, -2)}, T(2)).valid()); // beyond t_max
  CHECK(!bvh.closest_hit({V(1, 2, 5), V(0, 0, 2)}).valid());        // behind the origin
  const T nan = std::numeric_limits<T>::quiet_NaN();
  CHECK(!bvh.closest_hit({V(1, 2, 5), V(nan, 0, -1)}).valid());
  CHECK(!bvh.closest_hit({V(1, 2, 5), V(0, 0, 0)}).valid());
  CHECK(!bvh.closest_hit({V(nan, 2, 5), V(0, 0, -1)}).valid());
  const mpr::scene::Bvh<T> empty(mpr::scene::Scene<T>{});
  CHECK(!empty.closest_hit({V(0, 0, 0), V(0, 0, 1)}).valid());
}

TEST_CASE("the classroom BVH is shallow enough for the traversal stack", "[scene][bvh]") {
  const auto scene = mpr::scenes::classroom<float>();
  const mpr::scene::Bvh<float> bvh(scene);
  CHECK(scene.size() > 10000);
  CHECK(bvh.triangle_count() == scene.size());
  CHECK(bvh.depth() < 64);
  CHECK(scene.degenerate_skipped() == 0);
}
