#include "scene/bvh/bvh_test_util.hpp"

#include <catch2/catch.hpp>

#include <mpr/scene/bvh/build.hpp>
#include <mpr/scene/classroom.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

using namespace bvh_test;

TEST_CASE("the classroom BVH is shallow enough for the traversal stack", "[scene][bvh]") {
  const auto scene = mpr::scene::classroom<float>();
  const mpr::scene::BvhTree<float> tree = mpr::scene::build_bvh(scene);
  CHECK(scene.size() > 10000);
  CHECK(tree.triangle_count == scene.size());
  CHECK(tree.depth < 64);
  CHECK(scene.degenerate_skipped() == 0);
}

TEMPLATE_TEST_CASE("the 4-wide tree holds every triangle once", "[scene][bvh]", float, double) {
  using T = TestType;
  const auto scene = mpr::scene::classroom<T>();
  const mpr::scene::BvhTree<T> tree = mpr::scene::build_bvh(scene);
  std::vector<int> seen(scene.size(), 0);
  for (const auto& block : tree.blocks) {
    REQUIRE(block.count >= 1);
    REQUIRE(block.count <= 4);
    for (std::uint32_t lane = 0; lane < block.count; ++lane) ++seen[block.index[lane]];
  }
  CHECK(std::count(seen.begin(), seen.end(), 1) == static_cast<std::ptrdiff_t>(scene.size()));
  CHECK(tree.wide.size() < tree.nodes.size() / 2);
}

TEMPLATE_TEST_CASE("binary SAH tree: every triangle in one leaf, children inside their parent", "[scene][bvh]", float,
                   double) {
  using T = TestType;
  const auto scene = bumpy_grid<T>(9);
  for (const mpr::scene::BvhConfig config : {mpr::scene::BvhConfig{}, mpr::scene::BvhConfig{.bins = 1, .max_leaf = 0},
                                             mpr::scene::BvhConfig{.bins = 1000, .max_leaf = 1000}}) {
    const mpr::scene::BvhTree<T> tree = mpr::scene::build_bvh(scene, config);
    REQUIRE(!tree.nodes.empty());
    CHECK(tree.triangle_count == scene.size());
    std::size_t in_leaves = 0;
    for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
      const auto& node = tree.nodes[i];
      if (node.count > 0) {
        in_leaves += node.count;
        CHECK(node.count <= 255); // max_leaf is clamped to [1, 255]
        continue;
      }
      for (const std::size_t child : {i + 1, static_cast<std::size_t>(node.index)}) {
        REQUIRE(child < tree.nodes.size());
        for (int a = 0; a < 3; ++a) {
          CHECK(tree.nodes[child].bounds[a] >= node.bounds[a]);
          CHECK(tree.nodes[child].bounds[a + 3] <= node.bounds[a + 3]);
        }
      }
    }
    CHECK(in_leaves == scene.size());
  }
  const mpr::scene::BvhTree<T> empty = mpr::scene::build_bvh(mpr::scene::Scene<T>{});
  CHECK(empty.nodes.empty());
  CHECK(empty.wide.empty());
  CHECK(empty.blocks.empty());
  CHECK(empty.depth == 0);
}
