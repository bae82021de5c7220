#include "scene/bvh/bvh_test_util.hpp"

#include <catch2/catch.hpp>

#include <mpr/scene/bvh/bvh.hpp>
#include <mpr/scene/bvh/traverse.hpp>
#include <mpr/scene/classroom.hpp>

#include <random>

using namespace bvh_test;

TEMPLATE_TEST_CASE("the walk with the x86 kernels equals the portable walk bit for bit", "[scene][bvh][simd]", float,
                   double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto scene = mpr::scene::classroom<T>();
  const mpr::scene::Bvh<T> bvh(scene);
  // Rays from inside the room in every direction, and from outside through it.
  std::mt19937 rng(3);
  std::uniform_real_distribution<T> uni(-1, 1);
  int hits = 0;
  for (int k = 0; k < 20000; ++k) {
    const V origin = k % 2 == 0 ? V(uni(rng) * 4, T(1.5) + uni(rng), uni(rng) * 6 - 4) : V(uni(rng) * 20, 10, 20);
    const V target(uni(rng) * 5, T(1.5) + uni(rng) * 2, uni(rng) * 8 - 4);
    const mpr::Ray<T> ray{origin, k % 3 == 0 ? random_direction<T>(rng) : V(target - origin)};
    const auto a = bvh.closest_hit(ray);
    const auto b = bvh.closest_hit_portable(ray);
    REQUIRE(a.triangle == b.triangle);
    if (!a.valid()) continue;
    ++hits;
    CHECK(same_bits(a.t, b.t));
    CHECK(same_bits(a.b1, b.b1));
    CHECK(same_bits(a.b2, b.b2));
  }
  CHECK(hits > 10000);
}
