#pragma once
/// \file
/// The watertight ray/triangle test of Woop, Benthin and Wald ("Watertight Ray/Triangle
/// Intersection", JCGT 2(1), 2013): the ray is sheared so that it runs along +z from the
/// origin, and the triangle's 2-D edge functions U, V, W decide the hit; a zero edge function is
/// recomputed in higher precision. A ray that crosses a shared edge or vertex hits at least one
/// of the triangles (no cracks), and a closest-hit query reports exactly one of them. This is
/// the portable reference; bvh/kernels/triangle_edges4_sse.hpp computes the edge functions of four triangles
/// at once.

#include <mpr/core/config.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/scene/bvh/node.hpp>

#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

namespace mpr::scene::detail {

MPR_EXACT_FP_BEGIN

/// Per-ray set-up of the watertight test (Woop et al. section 3): the axis permutation
/// (kx, ky, kz) and shear (sx, sy, sz), and the origin in the permuted frame.
template <std::floating_point T>
struct Shear {
  int kx, ky, kz;
  T sx, sy, sz;
  T ox, oy, oz;

  /// The set-up for `ray`; false (and `out` unspecified) when its direction is zero or NaN,
  /// such a ray hits nothing.
  [[nodiscard]] static bool make(const Ray<T>& ray, Shear& out) noexcept {
    const T* d = ray.direction.data();
    const T* o = ray.origin.data();
    Shear& sh = out;
    // The dimension where |d| is largest becomes z; swap x, y to keep the winding.
    {
      const T ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
      sh.kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    }
    if (!(std::abs(d[sh.kz]) > 0)) return false; // zero or NaN direction
    sh.kx = sh.kz + 1 == 3 ? 0 : sh.kz + 1;
    sh.ky = sh.kx + 1 == 3 ? 0 : sh.kx + 1;
    if (d[sh.kz] < 0) std::swap(sh.kx, sh.ky);
    sh.sx = d[sh.kx] / d[sh.kz];
    sh.sy = d[sh.ky] / d[sh.kz];
    sh.sz = T(1) / d[sh.kz];
    sh.ox = o[sh.kx];
    sh.oy = o[sh.ky];
    sh.oz = o[sh.kz];
    return true;
  }
};

/// The edge functions of one triangle in the ray's sheared frame (Woop et al. fig. 2): vertices
/// relative to the origin (A, B, C; z unsheared) and U, V, W.
template <std::floating_point T>
struct Edges {
  T Ax, Ay, Bx, By, Cx, Cy, az, bz, cz, U, V, W;
};

/// `Edges` of lane `lane` of `block`; (kx, ky, kz) the axis permutation, (sx, sy) the shear and
/// (ox, oy, oz) the permuted origin.
template <std::floating_point T>
[[nodiscard]] Edges<T> edges_portable(const TriBlock<T>& block, std::uint32_t lane, int kx, int ky, int kz, T sx, T sy,
                                      T ox, T oy, T oz) noexcept {
  Edges<T> e;
  const T ax = block.p[0][kx][lane] - ox, ay = block.p[0][ky][lane] - oy;
  const T bx = block.p[1][kx][lane] - ox, by = block.p[1][ky][lane] - oy;
  const T cx = block.p[2][kx][lane] - ox, cy = block.p[2][ky][lane] - oy;
  e.az = block.p[0][kz][lane] - oz;
  e.bz = block.p[1][kz][lane] - oz;
  e.cz = block.p[2][kz][lane] - oz;
  e.Ax = ax - sx * e.az;
  e.Ay = ay - sy * e.az;
  e.Bx = bx - sx * e.bz;
  e.By = by - sy * e.bz;
  e.Cx = cx - sx * e.cz;
  e.Cy = cy - sy * e.cz;
  e.U = e.Cx * e.By - e.Cy * e.Bx;
  e.V = e.Ax * e.Cy - e.Ay * e.Cx;
  e.W = e.Bx * e.Ay - e.By * e.Ax;
  return e;
}

/// 1 + 2^-12 (float), 1 + 2^-26 (double): the margin of `watertight_finish`'s early rejection.
template <std::floating_point T>
inline constexpr T kRejectMargin = T(1) +
                                   T(1) / static_cast<T>(std::uint64_t(1) << (std::numeric_limits<T>::digits / 2));

/// Woop, Benthin & Wald 2013, fig. 2 and 3, from the edge functions on: the higher-precision
/// fallback for edge hits, the sign test, and the hit distance. Updates `hit` when triangle
/// `triangle` is hit at a t > 0 that is closer than `hit`: t < hit.t, or t == hit.t with a lower
/// triangle index than a valid `hit` (so that ties, e.g. a ray through an edge shared by two
/// triangles of different leaves, go to the same triangle whatever order the leaves are tested
/// in: the closest hit is the least (t, index) pair, which single rays and packets agree on).
template <std::floating_point T>
inline void watertight_finish(const Edges<T>& e, T sz, std::uint32_t triangle, Hit<T>& hit) noexcept {
  T U = e.U, V = e.V, W = e.W;
  if (U == 0 || V == 0 || W == 0) {
    using W_t = std::conditional_t<std::is_same_v<T, float>, double, long double>;
    U = static_cast<T>(static_cast<W_t>(e.Cx) * e.By - static_cast<W_t>(e.Cy) * e.Bx);
    V = static_cast<T>(static_cast<W_t>(e.Ax) * e.Cy - static_cast<W_t>(e.Ay) * e.Cx);
    W = static_cast<T>(static_cast<W_t>(e.Bx) * e.Ay - static_cast<W_t>(e.By) * e.Ax);
  }
  if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return;
  const T det = U + V + W;
  if (det == 0) return;
  const T t_scaled = U * (sz * e.az) + V * (sz * e.bz) + W * (sz * e.cz);
  // t = t_scaled / det must be positive, and not beyond hit.t: rejected here without dividing
  // only when t_scaled / det exceeds hit.t by a margin (2^-12 for float, 2^-26 for double) far
  // above the rounding of the division, so the rejected t would have failed the exact test
  // below too and the result does not depend on the order triangles are tested in.
  if (det > 0 ? t_scaled <= 0 : t_scaled >= 0) return;
  const T bound = hit.t * det * kRejectMargin<T>;
  if (det > 0 ? t_scaled > bound : t_scaled < bound) return;
  const T rcp = T(1) / det;
  const T t = t_scaled * rcp;
  if (!(t < hit.t || (t == hit.t && hit.valid() && triangle < hit.triangle))) return;
  hit.t = t;
  hit.b1 = V * rcp;
  hit.b2 = W * rcp;
  hit.triangle = triangle;
}

MPR_EXACT_FP_END

} // namespace mpr::scene::detail
