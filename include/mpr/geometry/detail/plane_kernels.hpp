#pragma once
/// \file
/// The structure-of-arrays ray-plane crossing of the geometry module (`mpr::Plane` per ray): where
/// each ray of a row crosses a plane, in the plane's own axes, written once as plain C++ and
/// compiled per instruction set through `run_at` (core/simd.hpp). The light-field row paths of
/// planar camera arrays use it.

#include <mpr/core/simd.hpp>

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
  using Flag = typename PlaneRays<T>::Flag;
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
    ok[i] = good ? Flag(-1) : Flag(0);
    cos2[i] = good ? dn * dn / length2 : T(1);
  }
}

/// `plane_rays_body` compiled for `level`; `soa` = {ox, oy, oz, dx, dy, dz}.
template <class T>
inline void plane_rays(const T* const (&soa)[6], std::size_t n, const PlaneAxes<T>& f, const PlaneRays<T>& out, T* cos2,
                       SimdLevel level = simd_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA {
    plane_rays_body(soa[0], soa[1], soa[2], soa[3], soa[4], soa[5], n, f, out.xu, out.xv, out.du, out.dv, out.dd,
                    out.ok, cos2);
  });
}

} // namespace mpr::detail
