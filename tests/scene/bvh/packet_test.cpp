#include "scene/bvh/bvh_test_util.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/core/region.hpp>
#include <mpr/glc/gallery.hpp>
#include <mpr/scene/bvh/bvh.hpp>
#include <mpr/scene/bvh/kernels/packet_closest_hits.hpp>
#include <mpr/scene/bvh/packet.hpp>
#include <mpr/scene/classroom.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <span>
#include <vector>

using namespace bvh_test;
namespace sd = mpr::scene::detail;

namespace {

/// Rays of a `size` x `size` view in 4 x 4 pixel blocks (16 consecutive rays per block, the
/// order `Bvh::closest_hits_coherent` expects), row-major within each block.
template <class T>
std::vector<mpr::Ray<T>> block_rays(const mpr::PlanarSurface<T>& plane, const mpr::GlcSelector<T>& glc, int size) {
  const mpr::Region region(0, 0, size, size);
  std::vector<mpr::Ray<T>> rays;
  for (int by = 0; by < size; by += 4)
    for (int bx = 0; bx < size; bx += 4)
      for (int y = by; y < by + 4; ++y)
        for (int x = bx; x < bx + 4; ++x) {
          const mpr::Vec2<T> uv = region.pixel_to_uv<T>({x, y});
          rays.push_back(glc.ray_at({x, y}, uv, plane.point_at(uv)));
        }
  return rays;
}

/// Which packet kernels `packet_hits` runs: those of a SIMD level (portable, AVX2, AVX-512;
/// the x86 ones for float only, called directly whatever `MPR_SIMD` says), or `Bvh`'s choice.
struct KernelSet {
  bool bvh_choice = false;
  mpr_test::SimdLevel level = mpr_test::SimdLevel::portable;
};

/// The hits of `rays` in packets of `sd::kPacketRays` with the kernels of `set`.
template <class T>
std::vector<mpr::scene::Hit<T>> packet_hits(const mpr::scene::Bvh<T>& bvh, const std::vector<mpr::Ray<T>>& rays,
                                            KernelSet set, T t_max) {
  std::vector<mpr::scene::Hit<T>> hits(rays.size());
  for (std::size_t i = 0; i < rays.size(); i += sd::kPacketRays) {
    const std::size_t n = std::min<std::size_t>(sd::kPacketRays, rays.size() - i);
    const std::span<const mpr::Ray<T>> r(rays.data() + i, n);
    const std::span<mpr::scene::Hit<T>> h(hits.data() + i, n);
    if (set.bvh_choice) {
      bvh.closest_hits_coherent(r, h, t_max);
    } else if (set.level == mpr_test::SimdLevel::portable || !std::is_same_v<T, float>) {
      sd::packet_closest_hits_with<sd::PortablePacketKernels<T>, sd::WalkKernels<T>>(bvh.tree(), r, h, t_max);
    } else {
#if MPR_BVH_PACKET_AVX2
      if constexpr (std::is_same_v<T, float>) {
        for (auto& x : h) x = mpr::scene::Hit<T>{t_max};
        // Both set-ups: the portable one (any axes) and the level's own (falls back more often).
        const bool avx512 = set.level >= mpr_test::SimdLevel::avx512;
        sd::RayPacket<T> p;
        bool formed = false;
        if ((i / sd::kPacketRays) % 2 == 0)
          formed = sd::RayPacket<T>::make(r, h.data(), p);
        else
          formed = avx512 ? sd::Avx512PacketKernels::make(r, t_max, p) : sd::Avx2PacketKernels::make(r, t_max, p);
        if (!formed)
          for (std::size_t k = 0; k < n; ++k) h[k] = bvh.closest_hit(r[k], t_max);
        else if (avx512)
          sd::packet_walk_avx512(bvh.tree(), p, h.data());
        else
          sd::packet_walk_avx2(bvh.tree(), p, h.data());
      }
#endif
    }
  }
  return hits;
}

/// Packets give every ray the single-ray hit bit for bit, with `Bvh`'s choice of kernels and
/// those of every SIMD level this machine runs; returns the number of hits.
template <class T>
int check_same_hits(const mpr::scene::Bvh<T>& bvh, const std::vector<mpr::Ray<T>>& rays,
                    T t_max = std::numeric_limits<T>::infinity()) {
  std::vector<mpr::scene::Hit<T>> want(rays.size());
  int hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    want[i] = bvh.closest_hit(rays[i], t_max);
    hits += want[i].valid();
  }
  const auto check = [&](KernelSet set) {
    const std::vector<mpr::scene::Hit<T>> got = packet_hits(bvh, rays, set, t_max);
    int wrong = 0;
    for (std::size_t i = 0; i < rays.size(); ++i)
      if (got[i].triangle != want[i].triangle || !same_bits(got[i].t, want[i].t) || !same_bits(got[i].b1, want[i].b1) ||
          !same_bits(got[i].b2, want[i].b2))
        ++wrong;
    CHECK(wrong == 0);
  };
  {
    INFO("packet kernels: Bvh's choice");
    check({.bvh_choice = true});
  }
  mpr_test::for_each_simd_level([&](mpr_test::SimdLevel level) { check({.level = level}); });
  return hits;
}

} // namespace

TEMPLATE_TEST_CASE("packets: every gallery GLC on the classroom gets the single-ray hits bit for bit",
                   "[scene][bvh][packet]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const mpr::scene::Bvh<T> bvh(mpr::scene::classroom<T>());
  // The ray-cast benchmark's image plane, 8 x 6 m, looking into the room.
  const V centre(0, T(3.1), T(3));
  const V forward = V(V(0, T(1.6), -8) - centre).normalized();
  const V right = forward.cross(V::UnitY()).normalized();
  const V down = forward.cross(right);
  const auto plane = mpr::PlanarSurface<T>::centred(centre, T(8) * right, T(6) * down);
  for (const auto& entry : mpr::glc::gallery) {
    INFO("gallery view " << entry.id << " " << entry.name);
    const auto glc = mpr::glc::gallery_view<T>(entry.id, plane, V(0, T(1.5), -4), T(9));
    const auto rays = block_rays(plane, glc, 64);
    CHECK(check_same_hits(bvh, rays) > 1000);
    CHECK(check_same_hits(bvh, rays, T(6)) > 100); // t_max cuts some hits
  }
}

TEMPLATE_TEST_CASE("packets: ties on shared edges and vertices go to the single-ray triangle", "[scene][bvh][packet]",
                   float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  // A flat grid (every triangle in its boxes' faces: equal t on both sides of an edge) and a
  // bumpy one, one triangle per leaf so that the two sides of an edge lie in different leaves.
  for (const bool flat : {true, false}) {
    INFO((flat ? "flat grid" : "bumpy grid"));
    mpr::scene::Scene<T> scene;
    const int n = 12;
    if (flat) {
      mpr::scene::Mesh<T> m;
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.positions.emplace_back(T(i), T(0), T(j));
      const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
          m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
      scene.add(m);
    } else {
      scene = bumpy_grid<T>(n);
    }
    const mpr::scene::Bvh<T> bvh(scene, {.bins = 16, .max_leaf = 1, .traversal_cost = 1.0f});
    // Packets of 16 rays from one eye (a pinhole) or from parallel origins (orthographic) through
    // vertices and edge points, neighbours in the mesh neighbours in the packet.
    std::vector<mpr::Ray<T>> rays;
    for (const bool ortho : {false, true})
      for (const auto& tri : scene.triangles())
        for (int j = 0; j < 3; ++j)
          for (T s : {T(0), T(0.5), T(1) / T(3)}) {
            const V target = tri.p[j] + s * (tri.p[(j + 1) % 3] - tri.p[j]);
            const V eye = ortho ? V(target + V(T(0.3), T(7), T(-0.2))) : V(T(5.3), T(9), T(-3.1));
            rays.push_back({eye, target - eye});
          }
    CHECK(check_same_hits(bvh, rays) > 2000);
  }
}

TEMPLATE_TEST_CASE("packets: coincident triangles tie at equal t, and the lowest index wins", "[scene][bvh][packet]",
                   float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  // Three copies of a bumpy grid: every hit is a tie between three triangles with the same t
  // bit for bit, in different leaves (one triangle per leaf) or in one leaf (four per leaf).
  const mpr::scene::Scene<T> grid = bumpy_grid<T>(10);
  mpr::scene::Mesh<T> copy;
  for (const auto& tri : grid.triangles()) {
    const auto first = static_cast<std::uint32_t>(copy.positions.size());
    for (int j = 0; j < 3; ++j) copy.positions.push_back(tri.p[j]);
    copy.triangles.push_back({first, first + 1, first + 2});
  }
  mpr::scene::Scene<T> scene;
  for (int k = 0; k < 3; ++k) scene.add(copy);
  std::mt19937 rng(3);
  std::uniform_real_distribution<T> uni(0, 1);
  std::vector<mpr::Ray<T>> rays;
  for (const bool ortho : {false, true})
    for (const auto& tri : grid.triangles()) {
      const T a = uni(rng), b = uni(rng) * (1 - a);
      const V target = tri.p[0] + a * (tri.p[1] - tri.p[0]) + b * (tri.p[2] - tri.p[0]);
      const V eye = ortho ? V(target + V(T(0.3), T(7), T(-0.2))) : V(T(4.3), T(9), T(-3.1));
      rays.push_back({eye, target - eye});
    }
  for (const int leaf : {1, 4}) {
    INFO("max_leaf " << leaf);
    const mpr::scene::Bvh<T> bvh(scene, {.bins = 16, .max_leaf = leaf, .traversal_cost = 1.0f});
    CHECK(check_same_hits(bvh, rays) > 300);
    // The reference itself: the first copy's triangle (the least index of the three).
    int first_copy = 0;
    for (const auto& ray : rays) {
      const auto hit = bvh.closest_hit(ray);
      first_copy += hit.valid() && hit.triangle < grid.triangles().size();
    }
    CHECK(first_copy > 300);
  }
}

TEMPLATE_TEST_CASE("packets: mixed signs, degenerate rays and partial packets fall back or drop out",
                   "[scene][bvh][packet][bad_input]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const mpr::scene::Bvh<T> bvh(mpr::scene::classroom<T>());
  std::mt19937 rng(16);
  std::uniform_real_distribution<T> uni(-1, 1);
  const T nan = std::numeric_limits<T>::quiet_NaN();
  std::vector<mpr::Ray<T>> rays;
  for (int k = 0; k < 4000; ++k) {
    const V origin(uni(rng) * 4, T(1.5) + uni(rng), uni(rng) * 6 - 4);
    V d = k % 5 == 0 ? random_direction<T>(rng) : V(T(0.3) + T(0.05) * uni(rng), T(-0.1) + T(0.05) * uni(rng), T(-1));
    if (k % 97 == 0) d = V(0, 0, 0);
    if (k % 89 == 0) d = V(nan, 0, 1);
    rays.push_back({origin, d});
  }
  CHECK(check_same_hits(bvh, rays) > 2000);
  // A run shorter than a packet, and an empty one.
  const std::vector<mpr::Ray<T>> few(rays.begin(), rays.begin() + 5);
  CHECK(check_same_hits(bvh, few) >= 0);
  std::vector<mpr::scene::Hit<T>> none;
  bvh.closest_hits_coherent({}, none);
  // Signs that differ within the packet: no packet is formed.
  sd::RayPacket<T> p;
  std::vector<mpr::scene::Hit<T>> h(2);
  const mpr::Ray<T> mixed[2] = {{V(0, 0, 0), V(1, 1, 1)}, {V(0, 0, 0), V(-1, 1, 1)}};
  CHECK_FALSE(sd::RayPacket<T>::make(mixed, h.data(), p));
  const mpr::Ray<T> same[2] = {{V(0, 0, 0), V(1, 1, 1)}, {V(0, 0, 0), V(0, 0, 0)}};
  REQUIRE(sd::RayPacket<T>::make(same, h.data(), p));
  CHECK(p.active == 1U); // the zero direction hits nothing and is left out
}

TEMPLATE_TEST_CASE("packet beam: conservative for every ray, and the AVX2 and AVX-512 kernels equal the portable ones",
                   "[scene][bvh][packet][simd]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  std::mt19937 rng(5);
  std::uniform_real_distribution<T> uni(-1, 1);
  int entered = 0, culled = 0;
  for (int k = 0; k < 3000; ++k) {
    const V origin(uni(rng) * 3, uni(rng) * 3, uni(rng) * 3);
    const V d0 = random_direction<T>(rng);
    const T spread = k % 3 == 0 ? T(0.001) : T(0.2);
    std::vector<mpr::Ray<T>> rays;
    for (int r = 0; r < sd::kPacketRays; ++r) {
      V d = d0;
      for (int a = 0; a < 3; ++a)
        if (d0[a] != 0) d[a] = d0[a] * (1 + spread * std::abs(uni(rng)));
      rays.push_back({V(origin + spread * V(uni(rng), uni(rng), uni(rng))), d});
    }
    std::vector<mpr::scene::Hit<T>> hits(rays.size(), mpr::scene::Hit<T>{T(1) + T(3) * std::abs(uni(rng))});
    sd::RayPacket<T> p;
    if (!sd::RayPacket<T>::make(rays, hits.data(), p)) continue;
    int kinds[4];
    const auto node = random_node<T>(rng, origin, d0, kinds);
    const T cull_max = p.max_cull();
    const unsigned beam = sd::PortablePacketKernels<T>::beam4(node, p, cull_max);
    for (int lane = 0; lane < 4; ++lane) {
      T t_min;
      const std::uint32_t m = sd::PortablePacketKernels<T>::rays(node, lane, p, p.active, t_min);
      INFO("lane kind " << kinds[lane]);
      if (m != 0) CHECK((beam >> lane & 1U) == 1U);
      entered += m != 0;
      culled += (beam >> lane & 1U) == 0;
#if MPR_BVH_PACKET_AVX2
      if constexpr (std::is_same_v<T, float>) {
        if (mpr_test::runs(mpr_test::SimdLevel::avx2)) {
          INFO("AVX2");
          sd::Avx2PacketKernels::Least entry;
          CHECK(sd::Avx2PacketKernels::rays(node, lane, p, p.active, entry) == m);
          if (m != 0) CHECK(sd::Avx2PacketKernels::least_value(entry) == t_min);
        }
        if (mpr_test::runs(mpr_test::SimdLevel::avx512)) {
          INFO("AVX-512");
          sd::Avx512PacketKernels::Least entry;
          CHECK(sd::Avx512PacketKernels::rays(node, lane, p, p.active, entry) == m);
          if (m != 0) CHECK(sd::Avx512PacketKernels::least_value(entry) == t_min);
        }
      }
#endif
    }
#if MPR_BVH_PACKET_AVX2
    if constexpr (std::is_same_v<T, float>) {
      if (mpr_test::runs(mpr_test::SimdLevel::avx2)) CHECK(sd::Avx2PacketKernels::beam4(node, p, cull_max) == beam);
      if (mpr_test::runs(mpr_test::SimdLevel::avx512)) CHECK(sd::Avx512PacketKernels::beam4(node, p, cull_max) == beam);
    }
#endif
  }
  CHECK(entered > 1000);
  CHECK(culled > 1000);
}

#if MPR_BVH_PACKET_AVX2
namespace {

/// The AVX2 (`level` avx2) or AVX-512 (avx512) set-up against `RayPacket<float>::make`.
void check_simd_setup(mpr_test::SimdLevel level) {
  using T = float;
  using V = mpr::Vec3<T>;
  std::mt19937 rng(11);
  std::uniform_real_distribution<T> uni(-1, 1);
  const T nan = std::numeric_limits<T>::quiet_NaN();
  int formed = 0, refused = 0;
  for (int k = 0; k < 5000; ++k) {
    const V d0 = random_direction<T>(rng);
    const T spread = k % 4 == 0 ? T(1) : T(0.01);
    const std::size_t n = 1 + static_cast<std::size_t>(k % sd::kPacketRays);
    std::vector<mpr::Ray<T>> rays;
    for (std::size_t r = 0; r < n; ++r) {
      V d = d0 + spread * V(uni(rng), uni(rng), uni(rng));
      if (k % 7 == 0 && r == 2) d = V(0, 0, 0);
      if (k % 11 == 0 && r == 1) d = V(nan, 0, 1);
      if (k % 13 == 0 && r == 0) d = V(1, nan, 0);
      rays.push_back({V(uni(rng), uni(rng), uni(rng)) * T(5), d});
    }
    const T t_max = k % 2 == 0 ? std::numeric_limits<T>::infinity() : T(3);
    std::vector<mpr::scene::Hit<T>> hits(n, mpr::scene::Hit<T>{t_max});
    sd::RayPacket<T> a, b;
    const bool ok_avx = level >= mpr_test::SimdLevel::avx512 ? sd::Avx512PacketKernels::make(rays, t_max, b)
                                                             : sd::Avx2PacketKernels::make(rays, t_max, b);
    const bool ok_portable = sd::RayPacket<T>::make(rays, hits.data(), a);
    if (level >= mpr_test::SimdLevel::avx512) {
      sd::RayPacket<T> c;
      CHECK(ok_avx == sd::Avx2PacketKernels::make(rays, t_max, c)); // the same packets refused
    }
    if (!ok_avx) {
      ++refused;
      continue;
    }
    REQUIRE(ok_portable);
    ++formed;
    REQUIRE(a.active == b.active);
    if (a.active == 0) continue;
    CHECK(a.same_axes);
    CHECK(a.kx == b.kx);
    CHECK(a.ky == b.ky);
    CHECK(a.kz == b.kz);
    CHECK(a.near == b.near);
    CHECK(a.far == b.far);
    for (int ax = 0; ax < 3; ++ax) {
      CHECK(a.inv_lo[ax] == b.inv_lo[ax]);
      CHECK(a.inv_hi[ax] == b.inv_hi[ax]);
      CHECK(a.off_lo[ax] == b.off_lo[ax]);
      CHECK(a.off_hi[ax] == b.off_hi[ax]);
    }
    for (int r = 0; r < sd::kPacketRays; ++r) {
      CHECK(same_bits(a.cull[r], b.cull[r]));
      if (!(a.active >> r & 1U)) continue;
      for (int ax = 0; ax < 3; ++ax) {
        CHECK(same_bits(a.inv[ax][r], b.inv[ax][r]));
        CHECK(same_bits(a.offset[ax][r], b.offset[ax][r]));
      }
      CHECK(same_bits(a.sx[r], b.sx[r]));
      CHECK(same_bits(a.sy[r], b.sy[r]));
      CHECK(same_bits(a.sz[r], b.sz[r]));
      CHECK(same_bits(a.ox[r], b.ox[r]));
      CHECK(same_bits(a.oy[r], b.oy[r]));
      CHECK(same_bits(a.oz[r], b.oz[r]));
      CHECK(same_bits(a.best[r], b.best[r]));
    }
  }
  CHECK(formed > 1000);
  CHECK(refused > 100);
}

} // namespace

TEST_CASE("packet set-up: the AVX2 and AVX-512 ones compute the portable values", "[scene][bvh][packet][simd]") {
  if (!mpr_test::runs(mpr_test::SimdLevel::avx2))
    SUCCEED("no AVX2 on this CPU (or MPR_SIMD=portable): only the portable set-up runs");
  mpr_test::for_each_simd_level([](mpr_test::SimdLevel level) {
    if (level == mpr_test::SimdLevel::portable) return;
    check_simd_setup(level);
  });
}
#endif
