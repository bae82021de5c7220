#pragma once
// Shared by the BVH tests: a crack-prone mesh, bit-exact comparison and awkward rays and boxes.

#include <mpr/core/vec.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/scene.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <utility>

namespace bvh_test {

/// A height field of (n+1)^2 irregular vertices, 2 n^2 triangles sharing edges and vertices.
template <class T>
inline mpr::scene::Scene<T> bumpy_grid(int n) {
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

} // namespace bvh_test
