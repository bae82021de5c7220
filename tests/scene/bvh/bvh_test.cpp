#include "scene/bvh/bvh_test_util.hpp"

#include <catch2/catch.hpp>

#include <mpr/scene/bvh/bvh.hpp>
#include <mpr/scene/shapes.hpp>

#include <cmath>
#include <random>

using namespace bvh_test;

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
  // A point's three draws last coordinate first, in statements of their own (the order of a
  // call's arguments differs between compilers): every compiler traces the same rays.
  const auto draw = [&](T xy, T z_scale, T z_offset) {
    const T z = uni(rng), y = uni(rng), x = uni(rng);
    return V(x * xy, y * xy, z_offset + z * z_scale);
  };
  for (int k = 0; k < 3000; ++k) {
    const V origin = draw(4, 1, 4);
    const V target = draw(2, 2, 0);
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

TEMPLATE_TEST_CASE("Bvh holds what build_bvh builds", "[scene][bvh]", float, double) {
  using T = TestType;
  const auto scene = bumpy_grid<T>(5);
  const mpr::scene::Bvh<T> bvh(scene);
  const mpr::scene::BvhTree<T> tree = mpr::scene::build_bvh(scene);
  CHECK(bvh.triangle_count() == scene.size());
  CHECK(bvh.nodes().size() == tree.nodes.size());
  CHECK(bvh.wide_nodes().size() == tree.wide.size());
  CHECK(bvh.triangle_blocks().size() == tree.blocks.size());
  CHECK(bvh.tree().root == tree.root);
  CHECK(bvh.depth() == tree.depth);
  STATIC_REQUIRE(std::is_same_v<typename mpr::scene::Bvh<T>::Node, mpr::scene::BvhNode<T>>);
  STATIC_REQUIRE(std::is_nothrow_default_constructible_v<mpr::scene::Bvh<T>>);
}
