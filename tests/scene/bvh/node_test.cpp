#include "scene/bvh/bvh_test_util.hpp"

#include <catch2/catch.hpp>

#include <mpr/scene/bvh/node.hpp>

#include <cstddef>
#include <type_traits>

TEMPLATE_TEST_CASE("BVH data layout: aligned lanes for the 4-wide kernels", "[scene][bvh]", float, double) {
  using T = TestType;
  namespace d = mpr::scene::detail;
  STATIC_REQUIRE(alignof(d::WideNode<T>) == 64);
  STATIC_REQUIRE(alignof(d::TriBlock<T>) >= 16);
  STATIC_REQUIRE(offsetof(d::WideNode<T>, bounds) == 0);
  STATIC_REQUIRE(sizeof(d::WideNode<T>::bounds) == 24 * sizeof(T));
  STATIC_REQUIRE(std::is_trivially_copyable_v<d::TriBlock<T>>);
  STATIC_REQUIRE((d::kLeafRef & (d::kLeafRef - 1)) == 0); // one bit
  STATIC_REQUIRE(!std::is_same_v<mpr::scene::Hit<float>, mpr::scene::Hit<double>>);
  const mpr::scene::Hit<T> none;
  CHECK(!none.valid());
  CHECK(none.t == std::numeric_limits<T>::infinity());
  const mpr::scene::BvhTree<T> empty;
  CHECK(empty.nodes.empty());
  CHECK(empty.triangle_count == 0);
}
