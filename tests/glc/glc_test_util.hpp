#pragma once
// Shared helpers of the GLC tests: the exact canonical examples of the reference note
// (glc-math.md sec. 5), written on the plane z = 0 with unit axes.
#include <mpr/glc.hpp>

#include <array>

namespace glc_test {

template <class T> mpr::PlanarSurface<T> unit_plane() {
  return mpr::PlanarSurface<T>(mpr::Vec3<T>::Zero(), mpr::Vec3<T>::UnitX(), mpr::Vec3<T>::UnitY());
}

/// The GLC whose generator at uv (0,0), (1,0), (0,1) goes to st points s0, s1, s2 on z = 1.
template <class T>
mpr::GlcSelector<T> from_st(const mpr::PlanarSurface<T>& plane, T s0x, T s0y, T s1x, T s1y, T s2x, T s2y) {
  return mpr::GlcSelector<T>(plane, mpr::Vec3<T>(s0x, s0y, 1), mpr::Vec3<T>(s1x - 1, s1y, 1),
                             mpr::Vec3<T>(s2x, s2y - 1, 1));
}

/// Three world rays from uv points to st points on z = 1.
template <class T> std::array<mpr::Ray<T>, 3> rays(const std::array<std::array<T, 4>, 3>& uvst) {
  std::array<mpr::Ray<T>, 3> out;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& r = uvst[k];
    out[k] = {mpr::Vec3<T>(r[0], r[1], 0), mpr::Vec3<T>(r[2] - r[0], r[3] - r[1], 1)};
  }
  return out;
}

} // namespace glc_test
