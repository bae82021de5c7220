#pragma once
/// \file
/// The render loops of `mpr::Renderer` under a `SupersamplingPolicy` (used by renderer.hpp;
/// not a public interface). Each pixel gathers its own `count` samples in index order, so its
/// colour does not depend on the thread count, the tile size or the path taken (per pixel,
/// batch of a row, tile of rows): per sample index the rays of a whole span or tile go to the
/// sampler's batch or tile path together (rays one pixel apart, as coherent as at 1 spp).

#include <mpr/core/concepts.hpp>
#include <mpr/core/config.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/region.hpp>
#include <mpr/sampling/pixel_sampling.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <type_traits>
#include <vector>

namespace mpr::detail {

/// `fn(f)` with the concrete filter of `f`: `f` itself, or what an `AnyFilter`-like type holds
/// (one dispatch per call, not per sample).
template <class F, class Fn>
MPR_ALWAYS_INLINE decltype(auto) with_filter(const F& f, Fn&& fn) noexcept {
  if constexpr (requires { f.visit(fn); })
    return f.visit(std::forward<Fn>(fn));
  else
    return std::forward<Fn>(fn)(f);
}

/// The zero of a colour type (Eigen arrays and arithmetic types).
template <class C>
[[nodiscard]] MPR_ALWAYS_INLINE C zero_color() noexcept {
  if constexpr (requires { C::Zero(); })
    return C(C::Zero());
  else
    return C{};
}

/// Share of the total absolute weight below which a pixel's signed total weight is not trusted
/// (negative lobes nearly cancelling): the pixel then takes the |w|-weighted average instead.
inline constexpr float kMinWeightShare = 0.25f;

/// True when filter `F` declares `static constexpr bool nonnegative = true` (no negative lobes).
template <class F>
inline constexpr bool nonnegative_filter = requires {
  requires F::nonnegative;
};

/// The running sums of one pixel: sum w f, sum |w| f (only when weights may be negative,
/// `Signed`) and sum f, with sum w and sum |w|.
template <class C, bool Signed = true>
struct FilterSums {
  C weighted = zero_color<C>();
  C absolute = zero_color<C>();
  C plain = zero_color<C>();
  float w = 0;
  float w_abs = 0;

  MPR_ALWAYS_INLINE void add(const C& c, float weight) noexcept {
    weighted += c * weight;
    if constexpr (Signed) {
      absolute += c * std::fabs(weight);
      w_abs += std::fabs(weight);
    }
    plain += c;
    w += weight;
  }
  /// sum(w f) / sum(w) when sum(w) > kMinWeightShare sum(|w|); else sum(|w| f) / sum(|w|); when
  /// every weight is 0, the plain mean of the `count` samples. Never divides by 0.
  [[nodiscard]] MPR_ALWAYS_INLINE C resolve(int count) const noexcept {
    if constexpr (Signed) {
      if (w > kMinWeightShare * w_abs) return C(weighted / w);
      if (w_abs > 0) return C(absolute / w_abs);
    } else {
      if (w > 0) return C(weighted / w);
    }
    return C(plain / static_cast<float>(count));
  }
};

/// Where sample `p` of the region pixel `local` lands: uv in the region and the offset (dx, dy)
/// in pixels from the pixel centre. The domain is the filter's footprint, the square of
/// half-width `radius` about the centre, clipped to the region (so no sample leaves the view).
template <class T>
struct Placement {
  Vec2<T> uv;
  double dx, dy;
};
template <class T>
[[nodiscard]] MPR_ALWAYS_INLINE Placement<T> place_sample(const Region& region, double radius, Pixel local,
                                                          SamplePoint p) noexcept {
  const double cx = local.x + 0.5, cy = local.y + 0.5;
  const double x0 = std::max(cx - radius, 0.0), x1 = std::min(cx + radius, static_cast<double>(region.width));
  const double y0 = std::max(cy - radius, 0.0), y1 = std::min(cy + radius, static_cast<double>(region.height));
  const double x = x0 + p.x * (x1 - x0), y = y0 + p.y * (y1 - y0);
  // Reciprocals (the same expression on every path, so paths still agree bit for bit).
  const double inv_w = 1.0 / region.width, inv_h = 1.0 / region.height;
  return {Vec2<T>(static_cast<T>(x * inv_w), static_cast<T>(y * inv_h)), x - cx, y - cy};
}

/// The ray of sample `i` of pixel `px` (region pixel `local`) at `uv`: a `LensRaySelector` also
/// gets the sample's lens point (the pattern must then be a `LensSamplePattern`).
template <class R, class T>
[[nodiscard]] MPR_ALWAYS_INLINE Ray<T> sample_ray(const R& r, Pixel px, Pixel local, int i,
                                                  const Vec2<T>& uv) noexcept {
  using Selector = typename R::selector_type;
  if constexpr (LensRaySelector<Selector>) {
    using Pattern = std::remove_cvref_t<decltype(r.pixel_sampling().pattern())>;
    static_assert(LensSamplePattern<Pattern>, "a finite-aperture selector needs a pattern with lens points");
    return r.selector().ray_at(px, uv, r.surface().point_at(uv), r.pixel_sampling().pattern().lens_point(local, i));
  } else {
    return r.selector().ray_at(px, uv, r.surface().point_at(uv));
  }
}

/// row[i] = colors[i] stored as Px, for i in [0, n).
template <class Px, class C>
MPR_FLATTEN void store_colors(Px* row, const C* colors, int n) noexcept {
  if constexpr (requires { PixelTraits<Px>::from_colors(colors, row, std::size_t{}); }) {
    PixelTraits<Px>::from_colors(colors, row, static_cast<std::size_t>(n));
  } else {
    for (int i = 0; i < n; ++i) row[i] = PixelTraits<Px>::from_color(colors[i]);
  }
}

/// The filtered colour of `px` by one `sample` call per sample.
template <class R>
[[nodiscard]] typename R::color_type shade_supersampled(const R& r, Pixel px, const Region& region) noexcept {
  using T = typename R::scalar_type;
  using C = typename R::color_type;
  const auto& pattern = r.pixel_sampling().pattern();
  const double radius = r.pixel_sampling().filter().radius();
  const Pixel local{px.x - region.x, px.y - region.y};
  const int n = pattern.count();
  using Filter = std::remove_cvref_t<decltype(r.pixel_sampling().filter())>;
  FilterSums<C, !nonnegative_filter<Filter>> sums;
  with_filter(r.pixel_sampling().filter(), [&](const auto& f) noexcept {
    for (int i = 0; i < n; ++i) {
      const Placement<T> s = place_sample<T>(region, radius, local, pattern.point(local, i));
      sums.add(r.sampler().sample(sample_ray(r, px, local, i, s.uv)), static_cast<float>(f.evaluate(s.dx, s.dy)));
    }
  });
  return sums.resolve(n);
}

/// Buffers of one span or tile of `n` pixels.
template <class T, class C, bool Signed>
struct SupersampleBuffers {
  std::vector<Ray<T>> rays;
  std::vector<C> colors;
  std::vector<double> dx, dy;
  std::vector<FilterSums<C, Signed>> sums;
  /// Grows every buffer to `n`; false if memory runs out.
  bool reserve(std::size_t n) noexcept {
    try {
      if (rays.size() < n) rays.resize(n);
      if (colors.size() < n) colors.resize(n);
      if (dx.size() < n) dx.resize(n), dy.resize(n);
      if (sums.size() < n) sums.resize(n);
      return true;
    } catch (...) {
      return false;
    }
  }
};

/// Filtered colours of pixels [x_begin, x_end) x [y_begin, y_end) into `out`: per sample index,
/// all rays of the rectangle in one `sample_tile` (TileRaySampler, rows of `x_end - x_begin`) or
/// `sample_rays` (BatchRaySampler) call. False (nothing written) if the buffers cannot grow.
template <class R, class Px>
bool render_supersampled(const R& r, ImageView<Px> out, const Region& region, int y_begin, int y_end, int x_begin,
                         int x_end) noexcept {
  using T = typename R::scalar_type;
  using C = typename R::color_type;
  using Sampler = typename R::sampler_type;
  const int width = x_end - x_begin, rows = y_end - y_begin;
  if (width <= 0 || rows <= 0) return true;
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(rows);
  using Filter = std::remove_cvref_t<decltype(r.pixel_sampling().filter())>;
  constexpr bool kSigned = !nonnegative_filter<Filter>;
  thread_local SupersampleBuffers<T, C, kSigned> buf;
  if (!buf.reserve(n)) return false;
  const auto& pattern = r.pixel_sampling().pattern();
  const double radius = r.pixel_sampling().filter().radius();
  const int count = pattern.count();
  std::fill(buf.sums.begin(), buf.sums.begin() + static_cast<std::ptrdiff_t>(n), FilterSums<C, kSigned>{});
  for (int i = 0; i < count; ++i) {
    std::size_t k = 0;
    for (int y = y_begin; y < y_end; ++y)
      for (int x = x_begin; x < x_end; ++x, ++k) {
        const Pixel local{x - region.x, y - region.y};
        const Placement<T> s = place_sample<T>(region, radius, local, pattern.point(local, i));
        buf.rays[k] = sample_ray(r, Pixel{x, y}, local, i, s.uv);
        buf.dx[k] = s.dx;
        buf.dy[k] = s.dy;
      }
    const std::span<const Ray<T>> rays(buf.rays.data(), n);
    const std::span<C> colors(buf.colors.data(), n);
    if constexpr (TileRaySampler<Sampler>)
      r.sampler().sample_tile(rays, width, colors);
    else if constexpr (BatchRaySampler<Sampler>)
      r.sampler().sample_rays(rays, colors);
    else
      for (std::size_t j = 0; j < n; ++j) colors[j] = r.sampler().sample(rays[j]);
    with_filter(r.pixel_sampling().filter(), [&](const auto& f) noexcept {
      for (std::size_t j = 0; j < n; ++j)
        buf.sums[j].add(buf.colors[j], static_cast<float>(f.evaluate(buf.dx[j], buf.dy[j])));
    });
  }
  for (std::size_t j = 0; j < n; ++j) buf.colors[j] = buf.sums[j].resolve(count);
  for (int y = y_begin; y < y_end; ++y)
    store_colors(out.row(y) + x_begin, buf.colors.data() + static_cast<std::size_t>(y - y_begin) * width, width);
  return true;
}

} // namespace mpr::detail
