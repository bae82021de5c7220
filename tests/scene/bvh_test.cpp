#include <mpr/scene/bvh.hpp>
#include <mpr/scene/classroom.hpp>
#include <mpr/scene/shapes.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace {

/// A height field of (n+1)^2 irregular vertices, 2 n^2 triangles sharing edges and vertices.
template <class T>
mpr::scene::Scene<T> bumpy_grid(int n) {
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
  const auto scene = mpr::scene::classroom<float>();
  const mpr::scene::Bvh<float> bvh(scene);
  CHECK(scene.size() > 10000);
  CHECK(bvh.triangle_count() == scene.size());
  CHECK(bvh.depth() < 64);
  CHECK(scene.degenerate_skipped() == 0);
}

namespace {

/// Bit-exact equality of two floats (NaN equal to the same NaN).
template <class T>
bool same_bits(T a, T b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

/// A random 4-wide node whose boxes include the awkward cases: flat boxes (lo == hi on an axis),
/// faces through the ray origin's coordinates, boxes around the origin (kind 6) or around the
/// point at parameter 1 (kind 7, with a margin far above rounding), and unused lanes
/// (lo = +inf, hi = -inf). `kinds` receives each lane's kind.
template <class T>
mpr::scene::detail::WideNode<T> random_node(std::mt19937& rng, const mpr::Vec3<T>& origin, const mpr::Vec3<T>& dir,
                                            int* kinds) {
  std::uniform_real_distribution<T> uni(-4, 4), margin(T(0.01), T(1));
  std::uniform_int_distribution<int> pick(0, 9);
  mpr::scene::detail::WideNode<T> node{};
  for (int lane = 0; lane < 4; ++lane) {
    const int kind = kinds[lane] = pick(rng);
    for (int a = 0; a < 3; ++a) {
      T lo = uni(rng), hi = uni(rng);
      if (kind == 1) hi = lo;
      if (kind == 2) lo = origin[a];
      if (kind == 3) hi = origin[a];
      if (kind == 4) lo = hi = origin[a];
      if (lo > hi) std::swap(lo, hi);
      if (kind == 5) {
        lo = std::numeric_limits<T>::infinity();
        hi = -std::numeric_limits<T>::infinity();
      }
      if (kind == 6) {
        lo = origin[a] - margin(rng);
        hi = origin[a] + margin(rng);
      }
      if (kind == 7) {
        lo = origin[a] + dir[a] - margin(rng);
        hi = origin[a] + dir[a] + margin(rng);
      }
      node.bounds[a][lane] = lo;
      node.bounds[a + 3][lane] = hi;
    }
  }
  return node;
}

/// A random direction that is often parallel to one or two slabs (zero components, either sign
/// of zero) or nearly so.
template <class T>
mpr::Vec3<T> random_direction(std::mt19937& rng) {
  std::uniform_real_distribution<T> uni(-1, 1);
  std::uniform_int_distribution<int> pick(0, 7);
  mpr::Vec3<T> d(uni(rng), uni(rng), uni(rng));
  for (int a = 0; a < 3; ++a) {
    const int kind = pick(rng);
    if (kind == 0) d[a] = T(0);
    if (kind == 1) d[a] = -T(0);
    if (kind == 2) d[a] = std::numeric_limits<T>::denorm_min() * (uni(rng) < 0 ? -1 : 1);
  }
  if (d.cwiseAbs().maxCoeff() == 0) d[1] = 1;
  return d;
}

} // namespace

TEMPLATE_TEST_CASE("4-wide box test: conservative, NaN-free, and the SIMD kernel equals the portable one",
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
#if MPR_BVH_SSE
    if constexpr (std::is_same_v<T, float>) {
      alignas(16) float t_sse[4];
      const unsigned mask_sse = d::box4_sse(node, d::BoxRaySse(r), t_max, t_sse);
      CHECK(mask_sse == mask);
      for (int lane = 0; lane < 4; ++lane) CHECK(same_bits(t_sse[lane], t_near[lane]));
      ++compared;
    }
#endif
  }
  CHECK(entered > 10000);
#if MPR_BVH_SSE
  if constexpr (std::is_same_v<T, float>) CHECK(compared == 20000);
#endif
  (void)compared;
}

#if MPR_BVH_SSE
TEST_CASE("4-wide edge functions: the SSE kernel computes the portable values and rejects only mixed signs",
          "[scene][bvh][simd]") {
  namespace d = mpr::scene::detail;
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
    const float sx = dir[kx] / dir[kz], sy = dir[ky] / dir[kz];
    for (const auto& block : bvh.triangle_blocks()) {
      d::EdgeValues4 e;
      const unsigned mask = d::edges4_sse(block, kx, ky, kz, sx, sy, eye[kx], eye[ky], eye[kz], e);
      for (std::uint32_t lane = 0; lane < 4; ++lane) {
        if (lane >= block.count) {
          CHECK(!(mask >> lane & 1U));
          continue;
        }
        const d::Edges<float> p = d::edges_portable(block, lane, kx, ky, kz, sx, sy, eye[kx], eye[ky], eye[kz]);
        const bool zero = p.U == 0 || p.V == 0 || p.W == 0;
        const bool mixed = (p.U < 0 || p.V < 0 || p.W < 0) && (p.U > 0 || p.V > 0 || p.W > 0);
        const bool candidate = zero || !mixed;
        CHECK(bool(mask >> lane & 1U) == candidate);
        zero_seen += zero ? 1 : 0;
        if (candidate) {
          ++candidates_seen;
          const d::Edges<float> s = e.lane(static_cast<int>(lane));
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
#endif

TEMPLATE_TEST_CASE("the 4-wide tree holds every triangle once and its SIMD query equals the portable one",
                   "[scene][bvh][simd]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto scene = mpr::scene::classroom<T>();
  const mpr::scene::Bvh<T> bvh(scene);
  std::vector<int> seen(scene.size(), 0);
  for (const auto& block : bvh.triangle_blocks()) {
    REQUIRE(block.count >= 1);
    REQUIRE(block.count <= 4);
    for (std::uint32_t lane = 0; lane < block.count; ++lane) ++seen[block.index[lane]];
  }
  CHECK(std::count(seen.begin(), seen.end(), 1) == static_cast<std::ptrdiff_t>(scene.size()));
  CHECK(bvh.wide_nodes().size() < bvh.nodes().size() / 2);
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
