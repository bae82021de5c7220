#pragma once
/// \file
/// Fixed-size Eigen vector aliases used throughout mpr.

#include <Eigen/Core>
#include <concepts>

namespace mpr {

/// A 2-vector of scalar `T`, e.g. normalized image coordinates `uv`.
template <std::floating_point T>
using Vec2 = Eigen::Matrix<T, 2, 1>;

/// A 3-vector of scalar `T`: points and directions in world units.
template <std::floating_point T>
using Vec3 = Eigen::Matrix<T, 3, 1>;

/// A 3x3 matrix of scalar `T` (rotations, intrinsics, homographies).
template <std::floating_point T>
using Mat3 = Eigen::Matrix<T, 3, 3>;

/// True when every component of `v` is finite (neither NaN nor infinite).
template <class Derived>
[[nodiscard]] bool all_finite(const Eigen::MatrixBase<Derived>& v) noexcept {
  return v.allFinite();
}

} // namespace mpr
