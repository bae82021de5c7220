#pragma once
/// \file
/// The compile-time contracts of the four roles. Each policy names its scalar type
/// (`float` or `double`) as a nested `scalar_type`, and every call the renderer makes on it is
/// `noexcept` and `const` (policies are read-only while rendering, so threads can share them).

#include <mpr/core/color.hpp>
#include <mpr/core/pixel.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>

#include <concepts>
#include <type_traits>

namespace mpr {

/// `P` declares a floating-point `scalar_type`.
template <class P>
concept HasScalar = requires {
  typename P::scalar_type;
}
&&std::floating_point<typename P::scalar_type>;

/// Image surface: `point_at(uv)` is the point of the manifold where the ray of `uv` starts.
template <class S>
concept ImageSurface = HasScalar<S> && requires(const S& s, const Vec2<typename S::scalar_type>& uv) {
  { s.point_at(uv) }
  noexcept->std::same_as<Vec3<typename S::scalar_type>>;
};

/// Ray selector: `ray_at(pixel, uv, point)` is the ray shown at `pixel` (region coordinates
/// `uv`, surface point `point`). A selector may ignore any of the three arguments.
template <class R>
concept RaySelector = HasScalar<R> && requires(const R& r, Pixel px, const Vec2<typename R::scalar_type>& uv,
                                               const Vec3<typename R::scalar_type>& point) {
  { r.ray_at(px, uv, point) }
  noexcept->std::same_as<Ray<typename R::scalar_type>>;
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
  { m.sample(ray) }
  noexcept->std::same_as<sampler_color_t<M>>;
};

/// A surface, selector and sampler that can be composed: each satisfies its concept and all
/// three use the same scalar type.
template <class Surface, class Selector, class Sampler>
concept ComposablePolicies = ImageSurface<Surface> && RaySelector<Selector> && RaySampler<Sampler> &&
    std::same_as<typename Surface::scalar_type, typename Selector::scalar_type> &&
    std::same_as<typename Surface::scalar_type, typename Sampler::scalar_type>;

} // namespace mpr
