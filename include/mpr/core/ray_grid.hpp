#pragma once
/// \file
/// Rays that are affine in the pixel: `mpr::AffineField3` (a surface point or a direction as an
/// affine function of uv), `mpr::AffineRays` (the rays of a view in that form) and
/// `mpr::RayGrid` (the rays of one render tile, per pixel step). A planar surface with a General
/// Linear Camera's selector gives such rays; a sampler that models `GridRaySampler` then gets the
/// tile's row structure instead of one ray per pixel (Yu & McMillan, ECCV 2004: a GLC's rays are
/// affine in the image plane's coordinates).

#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>

#include <concepts>
#include <limits>

namespace mpr {

/// `value(u, v) = at + u * du + v * dv`: a 3-vector that is affine in normalized region
/// coordinates (a planar surface's point, a GLC's direction).
template <std::floating_point T>
struct AffineField3 {
  Vec3<T> at = Vec3<T>::Zero(); ///< the value at uv (0, 0)
  Vec3<T> du = Vec3<T>::Zero(); ///< change per unit u
  Vec3<T> dv = Vec3<T>::Zero(); ///< change per unit v

  /// The value at (u, v), per component as `PlanarSurface::point_at` computes it.
  [[nodiscard]] Vec3<T> value(T u, T v) const noexcept {
    return Vec3<T>(at.x() + u * du.x() + v * dv.x(), at.y() + u * du.y() + v * dv.y(),
                   at.z() + u * du.z() + v * dv.z());
  }

  /// A bound on the rounding of `value(u, v)` for u, v in [0, 1], per coordinate: two products
  /// and two sums, each off by at most half an ulp of a partial sum no larger than |at| + |du| +
  /// |dv| (4 eps of it, with room for a fused multiply-add).
  [[nodiscard]] T rounding() const noexcept {
    return 4 * std::numeric_limits<T>::epsilon() *
           (at.cwiseAbs().maxCoeff() + du.cwiseAbs().maxCoeff() + dv.cwiseAbs().maxCoeff());
  }
};

/// The rays of a view as affine functions of uv: the ray at (u, v) starts at `origin.value(u, v)`
/// and runs along `direction.value(u, v)` (not normalized).
template <std::floating_point T>
struct AffineRays {
  AffineField3<T> origin;
  AffineField3<T> direction;
};

/// The rays of a tile of `width` x `rows` pixels whose origins and directions are affine in the
/// pixel. In real arithmetic the ray of pixel (i, j) of the tile (column i, row j, counted from
/// the tile's first pixel) starts at `origin + i * origin_dx + j * origin_dy` and runs along
/// `direction + i * direction_dx + j * direction_dy`; evaluated in floating point it differs
/// from the renderer's own ray by rounding, by at most `origin_error` and `direction_error` in
/// any coordinate. `ray(i, j)` gives the renderer's ray exactly (the ray `sample` would get):
/// a sampler anchors its rows there, and asks for it where a decision must not depend on
/// rounding (e.g. a near tie between two cameras). Far from the world origin in float, the
/// rounding is a visible fraction of a pixel: a sampler that evaluated the affine form alone
/// would then draw another image than `sample` does.
template <std::floating_point T, class ExactRay>
struct RayGrid {
  int width = 0; ///< pixels per row, > 0
  int rows = 0;  ///< rows, > 0
  Vec3<T> origin = Vec3<T>::Zero(), origin_dx = Vec3<T>::Zero(), origin_dy = Vec3<T>::Zero();
  Vec3<T> direction = Vec3<T>::Zero(), direction_dx = Vec3<T>::Zero(), direction_dy = Vec3<T>::Zero();
  /// Bounds on |ray(i, j) - the affine form| per coordinate (world units), origin and direction.
  T origin_error = 0, direction_error = 0;
  ExactRay exact; ///< exact(i, j) -> Ray<T>, the renderer's ray of pixel (i, j)

  /// The renderer's ray of pixel (i, j) of the tile. Precondition: 0 <= i < width, 0 <= j < rows.
  [[nodiscard]] Ray<T> ray(int i, int j) const noexcept { return exact(i, j); }
};

namespace detail {
/// A stand-in for the renderer's exact-ray callable, for checking `GridRaySampler`.
template <std::floating_point T>
struct ExactRayProbe {
  [[nodiscard]] Ray<T> operator()(int, int) const noexcept { return {}; }
};
} // namespace detail

} // namespace mpr
