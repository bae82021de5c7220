#pragma once
/// \file
/// The compile-time contracts of the four roles. Each policy names its scalar type
/// (`float` or `double`) as a nested `scalar_type`, and every call the renderer makes on it is
/// `noexcept` and `const` (policies are read-only while rendering, so threads can share them).

#include <mpr/core/color.hpp>
#include <mpr/core/pixel.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/ray_grid.hpp>
#include <mpr/core/vec.hpp>

#include <concepts>
#include <cstddef>
#include <span>
#include <type_traits>

namespace mpr {

// (clang-format 14 would spell the return-type requirements "noexcept->".)
// clang-format off

/// `P` declares a floating-point `scalar_type`.
template <class P>
concept HasScalar = requires {
  typename P::scalar_type;
}
&&std::floating_point<typename P::scalar_type>;

/// Image surface: `point_at(uv)` is the point of the manifold where the ray of `uv` starts.
template <class S>
concept ImageSurface = HasScalar<S> && requires(const S& s, const Vec2<typename S::scalar_type>& uv) {
  { s.point_at(uv) } noexcept -> std::same_as<Vec3<typename S::scalar_type>>;
};

/// Ray selector: `ray_at(pixel, uv, point)` is the ray shown at `pixel` (region coordinates
/// `uv`, surface point `point`). A selector may ignore any of the three arguments.
template <class R>
concept RaySelector = HasScalar<R> && requires(const R& r, Pixel px, const Vec2<typename R::scalar_type>& uv,
                                               const Vec3<typename R::scalar_type>& point) {
  { r.ray_at(px, uv, point) } noexcept -> std::same_as<Ray<typename R::scalar_type>>;
};

/// Optional interface of an image surface whose points are affine in uv (a plane):
/// `affine_points()` gives `point_at` as an `AffineField3`.
template <class S>
concept AffineSurface = ImageSurface<S> && requires(const S& s) {
  { s.affine_points() } noexcept -> std::same_as<AffineField3<typename S::scalar_type>>;
};

/// Optional interface of a ray selector whose rays are affine in uv whenever the surface points
/// are: `affine_rays(points)` gives the rays `ray_at` returns over the surface `points`.
template <class R>
concept AffineSelector = RaySelector<R> && requires(const R& r, const AffineField3<typename R::scalar_type>& points) {
  { r.affine_rays(points) } noexcept -> std::same_as<AffineRays<typename R::scalar_type>>;
};

namespace detail {
template <class M>
struct SamplerColor {
  using type = Color;
};
template <class M>
requires requires { typename M::color_type; }
struct SamplerColor<M> {
  using type = typename M::color_type;
};
} // namespace detail

/// The colour type a sampler returns: its nested `color_type` if it declares one, else `Color`.
template <class M>
using sampler_color_t = typename detail::SamplerColor<M>::type;

/// Ray sampler: `sample(ray)` is the colour the data set shows along `ray`.
template <class M>
concept RaySampler = HasScalar<M> && requires(const M& m, const Ray<typename M::scalar_type>& ray) {
  { m.sample(ray) } noexcept -> std::same_as<sampler_color_t<M>>;
};

/// Optional batch interface of a ray sampler: `sample_rays(rays, out)` writes the colour of
/// every ray of a span (equal lengths), the same colours as `sample` per ray, but free to walk
/// its data in a better order (e.g. cameras in the outer loop). `Renderer::render_row` uses it
/// when present, on chunks of one row; `sample(ray)` stays the contract.
template <class M>
concept BatchRaySampler = RaySampler<M> &&
    requires(const M& m, std::span<const Ray<typename M::scalar_type>> rays, std::span<sampler_color_t<M>> out) {
  { m.sample_rays(rays, out) } noexcept;
};

/// Optional tile interface of a ray sampler: `sample_tile(rays, width, out)` gets the rays of
/// `rays.size() / width` consecutive image rows of `width` pixels each (row-major, one pixel
/// after the other; precondition: `width > 0`, `rays.size()` a multiple of it and equal to
/// `out.size()`) and writes the colour of every ray, the same colours as `sample` per ray (to
/// rounding), but free to walk its data once per tile (e.g. each camera's image rows once for
/// several output rows, which share most of them). `mpr::render` then hands each thread whole
/// tiles of `kTileRows` rows (fixed, so the image is still the same for every thread count);
/// `sample(ray)` stays the contract.
template <class M>
concept TileRaySampler = RaySampler<M> && requires(const M& m, std::span<const Ray<typename M::scalar_type>> rays,
                                                   int width, std::span<sampler_color_t<M>> out) {
  { m.sample_tile(rays, width, out) } noexcept;
};

/// Optional grid interface of a tile sampler: `sample_grid(grid, out)` gets a tile whose rays are
/// affine in the pixel (`RayGrid`: the tile's first ray, its steps per column and per row, and
/// the renderer's exact ray of any pixel) and writes the colour of every pixel, row-major, the
/// same colours as `sample_tile` would (to rounding), without the renderer building one ray per
/// pixel. It returns false, writing nothing, when it has no grid path for this tile (the
/// renderer then hands it the rays). `Renderer::render_tile` uses it when the surface models
/// `AffineSurface` and the selector `AffineSelector`; `sample(ray)` stays the contract.
template <class M>
concept GridRaySampler = TileRaySampler<M> &&
    requires(const M& m, const RayGrid<typename M::scalar_type, detail::ExactRayProbe<typename M::scalar_type>>& grid,
             std::span<sampler_color_t<M>> out) {
  { m.sample_grid(grid, out) } noexcept -> std::same_as<bool>;
};

/// Rays per call of a `BatchRaySampler`'s `sample_rays` from the renderer (at most), and the
/// chunk the light-field batch paths work in.
inline constexpr std::size_t kBatchRays = 256;

/// Rows per tile for `TileRaySampler`s (fixed, so an image is the same for every thread count).
inline constexpr int kTileRows = 8;

/// A surface, selector and sampler that can be composed: each satisfies its concept and all
/// three use the same scalar type.
template <class Surface, class Selector, class Sampler>
concept ComposablePolicies = ImageSurface<Surface> && RaySelector<Selector> && RaySampler<Sampler> &&
    std::same_as<typename Surface::scalar_type, typename Selector::scalar_type> &&
    std::same_as<typename Surface::scalar_type, typename Sampler::scalar_type>;

// clang-format on

} // namespace mpr
