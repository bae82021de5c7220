#pragma once
/// \file
/// The structure-of-arrays ray-plane crossing of the geometry module (`mpr::Plane` per ray): where
/// each ray of a row crosses a plane, in the plane's own axes, written once as plain C++ and
/// compiled per instruction set through `run_at` (core/simd.hpp). The light-field row paths of
/// planar camera arrays use it.

#include <mpr/core/simd.hpp>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace mpr::detail {

/// The rays of one output row seen from a plane (e.g. that of a planar camera array), structure
/// of arrays: ray i crosses the plane at (xu[i], xv[i]) (in-plane coordinates), its direction has
/// in-plane components (du[i], dv[i]) and squared length dd[i]; ok[i] is nonzero (all bits
/// set) when the crossing is well defined (the ray is not within ~0.06 degrees of the plane).
template <class T>
struct PlaneRays {
  using Flag = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;
  T *xu, *xv, *du, *dv, *dd;
  Flag* ok;
};

/// An orthonormal frame of a plane as the kernel reads it: a point on it, its unit normal and two
/// in-plane unit axes (`PlaneFrame` as plain scalars).
template <class T>
struct PlaneAxes {
  T px, py, pz, nx, ny, nz, ux, uy, uz, vx, vy, vz;
};

/// ok = all bits set where `good`, else 0; returns the squared cosine dn^2 / length2 where
/// `good`, else 1. The quotient is formed for every ray and replaced by its bits: under a select
/// the compiler moves the division into a branch wherever the level has no masked division
/// (AVX2, SSE2), and the loop no longer vectorises there.
template <class T, class Flag>
MPR_ALWAYS_INLINE T plane_cos2(bool good, T dn, T length2, Flag& ok) noexcept {
  static_assert(sizeof(Flag) == sizeof(T));
  const Flag mask = good ? Flag(-1) : Flag(0);
  ok = mask;
  const T quotient = dn * dn / length2;
  return std::bit_cast<T>((std::bit_cast<Flag>(quotient) & mask) | (std::bit_cast<Flag>(T(1)) & ~mask));
}

/// Fills `out` (n entries from each pointer) for rays given as structure of arrays (origin
/// o = (ox, oy, oz) relative to the frame's point, direction (dx, dy, dz)), and cos2[i], the
/// squared cosine between ray i and the normal. A ray crosses when (d . n)^2 > 1e-6 |d|^2 and
/// the crossing is finite; where it does not, ok[i] = 0, cos2[i] = 1 and the other outputs are
/// unspecified.
template <class T>
MPR_ALWAYS_INLINE void plane_rays_body(const T* MPR_RESTRICT ox, const T* MPR_RESTRICT oy, const T* MPR_RESTRICT oz,
                                       const T* MPR_RESTRICT dx, const T* MPR_RESTRICT dy, const T* MPR_RESTRICT dz,
                                       std::size_t n, const PlaneAxes<T>& f, T* MPR_RESTRICT xu, T* MPR_RESTRICT xv,
                                       T* MPR_RESTRICT du, T* MPR_RESTRICT dv, T* MPR_RESTRICT dd,
                                       typename PlaneRays<T>::Flag* MPR_RESTRICT ok, T* MPR_RESTRICT cos2) noexcept {
  // (Outputs are parameters: GCC honours `restrict` on parameters, not on local copies.)
  // The frame in locals: loads through `f` inside the loop could alias the outputs.
  const T nx = f.nx, ny = f.ny, nz = f.nz, ux = f.ux, uy = f.uy, uz = f.uz, vx = f.vx, vy = f.vy, vz = f.vz;
  for (std::size_t i = 0; i < n; ++i) {
    const T dn = nx * dx[i] + ny * dy[i] + nz * dz[i], on = nx * ox[i] + ny * oy[i] + nz * oz[i];
    const T length2 = dx[i] * dx[i] + dy[i] * dy[i] + dz[i] * dz[i];
    const T u = ux * dx[i] + uy * dy[i] + uz * dz[i], v = vx * dx[i] + vy * dy[i] + vz * dz[i];
    const T t = -on / dn;
    const T cu = ux * ox[i] + uy * oy[i] + uz * oz[i] + t * u;
    const T cv = vx * ox[i] + vy * oy[i] + vz * oz[i] + t * v;
    // Where ok[i] is 0 the other outputs are meaningless (possibly NaN); every reader masks them
    // with ok. No branches or float selects, so that the loop vectorises; x - x == 0 is false
    // exactly for infinities and NaN.
    const bool good =
        (dn * dn > T(1e-6) * length2) & (cu - cu == T(0)) & (cv - cv == T(0)) & (length2 - length2 == T(0));
    xu[i] = cu;
    xv[i] = cv;
    du[i] = u;
    dv[i] = v;
    dd[i] = length2;
    cos2[i] = plane_cos2(good, dn, length2, ok[i]);
  }
}

/// `plane_rays_body` compiled for `level`; `soa` = {ox, oy, oz, dx, dy, dz}.
template <class T>
inline void plane_rays(const T* const (&soa)[6], std::size_t n, const PlaneAxes<T>& f, const PlaneRays<T>& out, T* cos2,
                       SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA {
    plane_rays_body(soa[0], soa[1], soa[2], soa[3], soa[4], soa[5], n, f, out.xu, out.xv, out.du, out.dv, out.dd,
                    out.ok, cos2);
  });
}

/// `plane_rays_body` for the n rays of an evenly spaced row: ray i has origin `first[0..2] + i
/// step[0..2]` (relative to the frame's point) and direction `first[3..5] + i step[3..5]`. The
/// projections onto the frame's axes are affine in i too, so they are formed once from the
/// row's first ray and step, not per ray: no ray arrays are read. Same outputs and rules as
/// `plane_rays_body`, to rounding.
template <class T>
MPR_ALWAYS_INLINE void plane_rays_affine_body(const T (&first)[6], const T (&step)[6], std::size_t n,
                                              const PlaneAxes<T>& f, T* MPR_RESTRICT xu, T* MPR_RESTRICT xv,
                                              T* MPR_RESTRICT du, T* MPR_RESTRICT dv, T* MPR_RESTRICT dd,
                                              typename PlaneRays<T>::Flag* MPR_RESTRICT ok,
                                              T* MPR_RESTRICT cos2) noexcept {
  const auto dot = [](T ax, T ay, T az, T bx, T by, T bz) { return ax * bx + ay * by + az * bz; };
  // Each per-ray quantity as q0 + i q1: the origin's and direction's projections on n, u, v,
  // and the direction's components (for its length).
  const T on0 = dot(f.nx, f.ny, f.nz, first[0], first[1], first[2]),
          on1 = dot(f.nx, f.ny, f.nz, step[0], step[1], step[2]);
  const T ou0 = dot(f.ux, f.uy, f.uz, first[0], first[1], first[2]),
          ou1 = dot(f.ux, f.uy, f.uz, step[0], step[1], step[2]);
  const T ov0 = dot(f.vx, f.vy, f.vz, first[0], first[1], first[2]),
          ov1 = dot(f.vx, f.vy, f.vz, step[0], step[1], step[2]);
  const T dn0 = dot(f.nx, f.ny, f.nz, first[3], first[4], first[5]),
          dn1 = dot(f.nx, f.ny, f.nz, step[3], step[4], step[5]);
  const T du0 = dot(f.ux, f.uy, f.uz, first[3], first[4], first[5]),
          du1 = dot(f.ux, f.uy, f.uz, step[3], step[4], step[5]);
  const T dv0 = dot(f.vx, f.vy, f.vz, first[3], first[4], first[5]),
          dv1 = dot(f.vx, f.vy, f.vz, step[3], step[4], step[5]);
  const T dx0 = first[3], dx1 = step[3], dy0 = first[4], dy1 = step[4], dz0 = first[5], dz1 = step[5];
  // (An int index: its conversion to T vectorises, a size_t's does not; rows are short.)
  const int count = static_cast<int>(n);
  for (int i = 0; i < count; ++i) {
    const T k = static_cast<T>(i);
    const T dn = dn0 + k * dn1, on = on0 + k * on1, u = du0 + k * du1, v = dv0 + k * dv1;
    const T x = dx0 + k * dx1, y = dy0 + k * dy1, z = dz0 + k * dz1;
    const T length2 = x * x + y * y + z * z;
    const T t = -on / dn;
    const T cu = ou0 + k * ou1 + t * u;
    const T cv = ov0 + k * ov1 + t * v;
    const bool good =
        (dn * dn > T(1e-6) * length2) & (cu - cu == T(0)) & (cv - cv == T(0)) & (length2 - length2 == T(0));
    xu[i] = cu;
    xv[i] = cv;
    du[i] = u;
    dv[i] = v;
    dd[i] = length2;
    cos2[i] = plane_cos2(good, dn, length2, ok[i]);
  }
}

/// `plane_rays_affine_body` compiled for `level`. Precondition: n fits an int.
template <class T>
inline void plane_rays_affine(const T (&first)[6], const T (&step)[6], std::size_t n, const PlaneAxes<T>& f,
                              const PlaneRays<T>& out, T* cos2, SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA {
    plane_rays_affine_body(first, step, n, f, out.xu, out.xv, out.du, out.dv, out.dd, out.ok, cos2);
  });
}

} // namespace mpr::detail
