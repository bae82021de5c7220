#pragma once
/// \file
/// The ray type that selectors produce and samplers consume.

#include <mpr/core/vec.hpp>

namespace mpr {

/// A ray `origin + t * direction`, `t >= 0`, in world units.
///
/// `direction` is *not* required to be unit length: the GLC selector, for example, scales it so
/// that its component along the image-plane normal is exactly 1, which makes `t` the depth in
/// front of the image plane. Samplers must not assume a unit direction.
template <std::floating_point T>
struct Ray {
  using scalar_type = T;
  Vec3<T> origin;
  Vec3<T> direction;

  /// The point at parameter `t` along the ray.
  [[nodiscard]] Vec3<T> at(T t) const noexcept { return origin + t * direction; }
};

} // namespace mpr
