#pragma once
/// \file
/// The contract of a light-field interpolation: which cameras of a `FrameTable` answer a ray and
/// with what weights. An interpolation is a type of its own (`NearestCamera`,
/// `SyntheticAperture`, `CylinderAperture`, or one of the user's) with a per-ray `sample` and,
/// optionally, a batch `sample_rays`, a tile `sample_tile` and a grid `sample_grid` that fall back to its own per-ray
/// function; `CameraFrameSampler<Interpolation>` offers to the renderer exactly the interfaces
/// the interpolation has. An optional `validate()` const member throws `argument_error` for bad
/// parameters, and an optional `validate(table)` for frames it cannot use (e.g. `DepthProxy`
/// without depth maps); the sampler calls both at construction.

#include <mpr/core/color.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/ray_grid.hpp>
#include <mpr/lightfield/frame_table.hpp>

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <span>

namespace mpr {

// (clang-format 14 would spell the return-type requirements "noexcept->".)
// clang-format off

/// `I` answers one ray from the frames of a `FrameTable<T, Px>`: `sample(table, ray)`, const and
/// noexcept, returning linear `Color`.
template <class I, class T, class Px>
concept FrameInterpolation = std::copy_constructible<I> &&
    requires(const I& i, const FrameTable<T, Px>& table, const Ray<T>& ray) {
  { i.sample(table, ray) } noexcept -> std::same_as<Color>;
};

/// Optional batch path: `sample_rays(table, rays, out)` writes `out[k] = sample(table, rays[k])`
/// (to float rounding) for spans of equal length.
template <class I, class T, class Px>
concept BatchFrameInterpolation = FrameInterpolation<I, T, Px> &&
    requires(const I& i, const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, std::span<Color> out) {
  { i.sample_rays(table, rays, out) } noexcept;
};

/// Optional tile path: `sample_tile(table, rays, width, out)` for the rays of consecutive output
/// rows of `width` pixels (the preconditions of `TileRaySampler`).
template <class I, class T, class Px>
concept TileFrameInterpolation = FrameInterpolation<I, T, Px> &&
    requires(const I& i, const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, int width,
             std::span<Color> out) {
  { i.sample_tile(table, rays, width, out) } noexcept;
};

/// Optional grid path: `sample_grid(table, grid, out)` for a tile whose rays are affine in the
/// pixel (`RayGrid`, the preconditions of `GridRaySampler`); returns false, writing nothing,
/// where it has no such path (the renderer then hands `sample_tile` the rays).
template <class I, class T, class Px>
concept GridFrameInterpolation = TileFrameInterpolation<I, T, Px> &&
    requires(const I& i, const FrameTable<T, Px>& table, const RayGrid<T, detail::ExactRayProbe<T>>& grid,
             std::span<Color> out) {
  { i.sample_grid(table, grid, out) } noexcept -> std::same_as<bool>;
};

// clang-format on

/// The row length of a tile call: `width`, or the whole span when `width <= 0`.
[[nodiscard]] inline std::size_t tile_width(std::size_t rays, int width) noexcept {
  return width > 0 ? static_cast<std::size_t>(width) : rays;
}

/// Calls `f(row_rays, row_out)` for each row of `w` rays (the last may be shorter): the fallback
/// of a tile path to an interpolation's own batch or per-ray function.
template <std::floating_point T, class F>
void for_each_row(std::span<const Ray<T>> rays, std::size_t w, std::span<Color> out, F&& f) noexcept {
  for (std::size_t start = 0; start < rays.size(); start += std::max<std::size_t>(w, 1))
    f(rays.subspan(start, std::min(w, rays.size() - start)), out.subspan(start));
}

/// Calls `f(chunk_rays, chunk_out)` for chunks of at most `chunk` rays.
template <std::floating_point T, class F>
void for_each_chunk(std::span<const Ray<T>> rays, std::size_t chunk, std::span<Color> out, F&& f) noexcept {
  for (std::size_t start = 0; start < rays.size(); start += chunk)
    f(rays.subspan(start, std::min(chunk, rays.size() - start)), out.subspan(start));
}

} // namespace mpr
