#pragma once
// A ray sampler for renderer tests: its colour encodes the ray exactly, so any change to any ray
// (origin or direction, any pixel) shows in the image.

#include <mpr/core/color.hpp>
#include <mpr/core/ray.hpp>

namespace mpr_test {

/// Colour (7 ox + dx, 7 oy + dy, oz + 3 dz) of ray (o, d), in float.
template <class T>
struct RayHash {
  using scalar_type = T;
  mpr::Color sample(const mpr::Ray<T>& r) const noexcept {
    return mpr::Color(static_cast<float>(r.origin.x() * 7 + r.direction.x()),
                      static_cast<float>(r.origin.y() * 7 + r.direction.y()),
                      static_cast<float>(r.origin.z() + r.direction.z() * 3));
  }
};

} // namespace mpr_test
