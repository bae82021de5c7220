#include "scene/bvh/bvh_test_util.hpp"

#include <catch2/catch.hpp>

#include <mpr/scene/bvh/bvh.hpp>
#include <mpr/scene/bvh/kernels/walk_kernels.hpp>
#include <mpr/scene/bvh/slab.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <type_traits>

using namespace bvh_test;

TEMPLATE_TEST_CASE("4-wide box test: conservative, NaN-free, and the walk's kernel equals the portable one",
                   "[scene][bvh][simd]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  namespace d = mpr::scene::detail;
  std::mt19937 rng(11);
  std::uniform_real_distribution<T> uni(-4, 4), unit(0, 1);
  int entered = 0, compared = 0;
  for (int k = 0; k < 20000; ++k) {
    const V origin(uni(rng), uni(rng), uni(rng));
    const V dir = random_direction<T>(rng);
    int kinds[4];
    const d::WideNode<T> node = random_node<T>(rng, origin, dir, kinds);
    const T t_max = k % 3 == 0 ? std::numeric_limits<T>::infinity() : T(8) * unit(rng);
    const d::BoxRay<T> r = d::BoxRay<T>::make({origin, dir});
    alignas(16) T t_near[4];
    const unsigned mask = d::box4_portable(node, r, t_max, t_near);
    for (int lane = 0; lane < 4; ++lane) {
      const bool unused = node.bounds[0][lane] == std::numeric_limits<T>::infinity();
      if (unused) CHECK(!(mask >> lane & 1U)); // nothing enters an unused lane
      if (!unused) CHECK(!std::isnan(t_near[lane]));
      if (mask >> lane & 1U) {
        ++entered;
        CHECK(t_near[lane] >= 0);
        CHECK(t_near[lane] < t_max);
      }
      // Conservative: a box around the origin is entered at once, one around the point at
      // parameter 1 no later (its entry is below 1, its exit above).
      if (kinds[lane] == 6 && t_max > 0) CHECK((mask >> lane & 1U));
      if (kinds[lane] == 7 && t_max > 1) CHECK((mask >> lane & 1U));
    }
    {
      // The kernels the walk uses for T (SSE for float on x86-64) against the portable ones.
      using K = d::WalkKernels<T>;
      alignas(16) T t_simd[4];
      const unsigned mask_simd = K::box4(node, K::box_ray(r), t_max, t_simd);
      CHECK(mask_simd == mask);
      for (int lane = 0; lane < 4; ++lane) CHECK(same_bits(t_simd[lane], t_near[lane]));
      ++compared;
    }
  }
  CHECK(entered > 10000);
  CHECK(compared == 20000);
}

TEST_CASE("4-wide edge functions: the walk's kernel computes the portable values and rejects only mixed signs",
          "[scene][bvh][simd]") {
  namespace d = mpr::scene::detail;
  using K = d::WalkKernels<float>;
  using V = mpr::Vec3<float>;
  const auto scene = bumpy_grid<float>(6);
  const mpr::scene::Bvh<float> bvh(scene);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> uni(0, 6);
  int candidates_seen = 0, zero_seen = 0;
  for (int k = 0; k < 4000; ++k) {
    // Rays at grid vertices and edges (edge functions exactly zero) and at random points.
    const auto& tri = scene.triangles()[static_cast<std::size_t>(k) % scene.size()];
    const V target = k % 2 == 0 ? V(tri.p[static_cast<std::size_t>(k / 2) % 3]) : V(uni(rng), 0.0f, uni(rng));
    const V eye(uni(rng), 7.0f, uni(rng) - 3.0f);
    const V dir = target - eye;
    int kz = 0;
    const float ax = std::abs(dir[0]), ay = std::abs(dir[1]), az = std::abs(dir[2]);
    kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    int kx = kz + 1 == 3 ? 0 : kz + 1, ky = kx + 1 == 3 ? 0 : kx + 1;
    if (dir[kz] < 0) std::swap(kx, ky);
    d::Shear<float> sh{};
    REQUIRE(d::Shear<float>::make({eye, dir}, sh));
    REQUIRE((sh.kx == kx && sh.ky == ky && sh.kz == kz));
    const float sx = sh.sx, sy = sh.sy;
    for (const auto& block : bvh.triangle_blocks()) {
      typename K::EdgeValues e;
      const unsigned mask = K::edges4(block, sh, e);
      for (std::uint32_t lane = 0; lane < 4; ++lane) {
        if (lane >= block.count) {
          CHECK(!(mask >> lane & 1U));
          continue;
        }
        const d::Edges<float> p = d::edges_portable(block, lane, kx, ky, kz, sx, sy, eye[kx], eye[ky], eye[kz]);
        const bool zero = p.U == 0 || p.V == 0 || p.W == 0;
        const bool mixed = (p.U < 0 || p.V < 0 || p.W < 0) && (p.U > 0 || p.V > 0 || p.W > 0);
        const bool candidate = zero || !mixed;
        if (std::is_same_v<K, d::PortableKernels<float>>)
          CHECK(bool(mask >> lane & 1U)); // the portable kernel leaves every lane to the scalar test
        else
          CHECK(bool(mask >> lane & 1U) == candidate);
        zero_seen += zero ? 1 : 0;
        if (candidate) {
          ++candidates_seen;
          const d::Edges<float> s = e.lane(static_cast<int>(lane));
          // (the portable kernel's values are those of edges_portable by construction)
          CHECK((same_bits(s.U, p.U) && same_bits(s.V, p.V) && same_bits(s.W, p.W)));
          CHECK((same_bits(s.Ax, p.Ax) && same_bits(s.Ay, p.Ay) && same_bits(s.Bx, p.Bx) && same_bits(s.By, p.By) &&
                 same_bits(s.Cx, p.Cx) && same_bits(s.Cy, p.Cy)));
          CHECK((same_bits(s.az, p.az) && same_bits(s.bz, p.bz) && same_bits(s.cz, p.cz)));
        }
      }
    }
  }
  CHECK(candidates_seen > 4000);
  CHECK(zero_seen > 0); // the exact-fallback path was exercised
}
