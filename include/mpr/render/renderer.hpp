#pragma once
/// \file
/// `mpr::Renderer<Surface, Selector, Sampler, Sampling>`: the composition of the four roles and
/// the pixel sampling, and `mpr::render`, which fills several views of one output image in a
/// single call. render/ sits above core/ and sampling/ (core/ includes neither).

#include <mpr/core/color.hpp>
#include <mpr/core/concepts.hpp>
#include <mpr/core/config.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/parallel.hpp>
#include <mpr/core/region.hpp>
#include <mpr/sampling/pixel_sampling.hpp>
#include <mpr/sampling/supersampled_render.hpp>

#include <algorithm>
#include <span>
#include <utility>
#include <vector>

namespace mpr {

/// Settings of one render call.
struct RenderOptions {
  /// Worker threads, the calling thread included; 0 or less means all hardware threads.
  /// The image is identical for every thread count.
  int threads = 0;
};

template <class R>
struct View;
template <class Px, class... R>
void render(ImageView<Px> out, const RenderOptions& options, const View<R>&... views) noexcept;

/// The renderer of one view: surface, selector and sampler, held by value, and the pixel
/// sampling (sampling/pixel_sampling.hpp; default `PixelCentre`, one ray through each pixel
/// centre). Empty (stateless) policies take no storage. The inner loop is exactly: uv from pixel
/// (or sample), point from surface, ray from selector, colour from sampler; every call is
/// resolved at compile time. Under a `SupersamplingPolicy` each pixel is the filter-weighted
/// average of its samples (sampling/supersampled_render.hpp).
template <class Surface, class Selector, class Sampler, class Sampling = PixelCentre>
requires ComposablePolicies<Surface, Selector, Sampler> && PixelSampling<Sampling>
class Renderer {
public:
  using scalar_type = typename Surface::scalar_type;
  using color_type = sampler_color_t<Sampler>;
  using surface_type = Surface;
  using selector_type = Selector;
  using sampler_type = Sampler;
  using sampling_type = Sampling;

  Renderer() = default;
  Renderer(Surface surface, Selector selector, Sampler sampler)
      : surface_(std::move(surface)), selector_(std::move(selector)), sampler_(std::move(sampler)) {}
  Renderer(Surface surface, Selector selector, Sampler sampler, Sampling sampling)
      : surface_(std::move(surface)), selector_(std::move(selector)), sampler_(std::move(sampler)),
        sampling_(std::move(sampling)) {}

  [[nodiscard]] const Surface& surface() const noexcept { return surface_; }
  [[nodiscard]] const Selector& selector() const noexcept { return selector_; }
  [[nodiscard]] const Sampler& sampler() const noexcept { return sampler_; }
  [[nodiscard]] const Sampling& pixel_sampling() const noexcept { return sampling_; }

  /// The colour of one pixel of the view that fills `region`.
  [[nodiscard]] color_type shade(Pixel px, const Region& region) const noexcept {
    if constexpr (SupersamplingPolicy<Sampling>) return detail::shade_supersampled(*this, px, region);
    const Vec2<scalar_type> uv = region.pixel_to_uv<scalar_type>(px);
    const Vec3<scalar_type> point = surface_.point_at(uv);
    const Ray<scalar_type> ray = selector_.ray_at(px, uv, point);
    return sampler_.sample(ray);
  }

  /// The ray shown at the centre of `px` (for diagnostics and projection checks).
  [[nodiscard]] Ray<scalar_type> ray_at(Pixel px, const Region& region) const noexcept {
    const Vec2<scalar_type> uv = region.pixel_to_uv<scalar_type>(px);
    return selector_.ray_at(px, uv, surface_.point_at(uv));
  }

  /// Renders pixels [x_begin, x_end) of row `y` into `out` (image coordinates). A sampler that
  /// models `BatchRaySampler` gets the rays of up to `kBatchRays` pixels per call.
  /// Preconditions: the span lies inside both `out` and `region`.
  template <class Px>
  requires StorableAs<Px, color_type>
  void render_row(ImageView<Px> out, const Region& region, int y, int x_begin, int x_end) const noexcept {
    Px* row = out.row(y);
    if constexpr (SupersamplingPolicy<Sampling> && BatchRaySampler<Sampler>) {
      if (detail::render_supersampled(*this, out, region, y, y + 1, x_begin, x_end)) return;
      for (int x = x_begin; x < x_end; ++x) row[x] = PixelTraits<Px>::from_color(shade(Pixel{x, y}, region));
    } else if constexpr (BatchRaySampler<Sampler>) {
      // Rays of up to kBatchRays pixels, then one batch call to the sampler.
      constexpr int kBatch = static_cast<int>(kBatchRays);
      Ray<scalar_type> rays[kBatch];
      color_type colors[kBatch];
      for (int x0 = x_begin; x0 < x_end; x0 += kBatch) {
        const int n = std::min(kBatch, x_end - x0);
        rays_of_row(region, y, x0, x0 + n, nullptr, rays);
        sampler_.sample_rays(std::span<const Ray<scalar_type>>(rays, static_cast<std::size_t>(n)),
                             std::span<color_type>(colors, static_cast<std::size_t>(n)));
        store_row(row + x0, colors, n);
      }
    } else {
      for (int x = x_begin; x < x_end; ++x) row[x] = PixelTraits<Px>::from_color(shade(Pixel{x, y}, region));
    }
  }

  /// Renders pixels [x_begin, x_end) of rows [y_begin, y_end) into `out`. A sampler that models
  /// `GridRaySampler`, under an `AffineSurface` and an `AffineSelector`, gets the tile as a
  /// `RayGrid` (no ray per pixel) and may decline it; a `TileRaySampler` gets all their rays in
  /// one call (the rays are kept in a per-thread buffer that grows to the largest tile seen; if
  /// it cannot grow, the rows are rendered one by one). Preconditions: the rectangle lies inside
  /// both `out` and `region`.
  template <class Px>
  requires StorableAs<Px, color_type>
  void render_tile(ImageView<Px> out, const Region& region, int y_begin, int y_end, int x_begin,
                   int x_end) const noexcept {
    if constexpr (SupersamplingPolicy<Sampling> && TileRaySampler<Sampler>) {
      if (detail::render_supersampled(*this, out, region, y_begin, y_end, x_begin, x_end)) return;
    } else if constexpr (TileRaySampler<Sampler>) {
      const int width = x_end - x_begin, rows = y_end - y_begin;
      if (width <= 0 || rows <= 0) return;
      const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(rows);
      thread_local std::vector<Ray<scalar_type>> rays;
      thread_local std::vector<color_type> colors;
      thread_local std::vector<scalar_type> u_of_column;
      bool room = true;
      try {
        if (rays.size() < n) rays.resize(n);
        if (colors.size() < n) colors.resize(n);
        if (u_of_column.size() < static_cast<std::size_t>(width)) u_of_column.resize(static_cast<std::size_t>(width));
      } catch (...) {
        room = false;
      }
      if (room) {
        if constexpr (GridRaySampler<Sampler> && AffineSurface<Surface> && AffineSelector<Selector>) {
          if (sample_grid(region, y_begin, x_begin, width, rows, std::span<color_type>(colors.data(), n))) {
            for (int y = y_begin; y < y_end; ++y)
              store_row(out.row(y) + x_begin,
                        colors.data() + static_cast<std::size_t>(y - y_begin) * static_cast<std::size_t>(width), width);
            return;
          }
        }
        // u depends on the column only: one division per column for the whole tile.
        for (int x = x_begin; x < x_end; ++x)
          u_of_column[static_cast<std::size_t>(x - x_begin)] = region.column_to_u<scalar_type>(x);
        for (int y = y_begin; y < y_end; ++y)
          rays_of_row(region, y, x_begin, x_end, u_of_column.data(),
                      rays.data() + static_cast<std::size_t>(y - y_begin) * static_cast<std::size_t>(width));
        sampler_.sample_tile(std::span<const Ray<scalar_type>>(rays.data(), n), width,
                             std::span<color_type>(colors.data(), n));
        for (int y = y_begin; y < y_end; ++y)
          store_row(out.row(y) + x_begin,
                    colors.data() + static_cast<std::size_t>(y - y_begin) * static_cast<std::size_t>(width), width);
        return;
      }
    }
    for (int y = y_begin; y < y_end; ++y) render_row(out, region, y, x_begin, x_end);
  }

  /// Renders the view into the part of `region` that lies inside `out`.
  /// (Defined here, not out of line: Clang 14 matches no out-of-line definition of a
  /// constrained member template of a constrained class template.)
  template <class Px>
  requires StorableAs<Px, color_type>
  void render(ImageView<Px> out, const Region& region, const RenderOptions& options = {}) const noexcept {
    mpr::render(out, options, View<Renderer>{region, this});
  }

private:
  // The tile's rays as a `RayGrid` for a `GridRaySampler`: the affine rays of surface and
  // selector stepped per pixel (u and v grow by 1 / width and 1 / height per column and row),
  // with `ray_at`'s own ray for the pixels the sampler asks for exactly.
  bool sample_grid(const Region& region, int y_begin, int x_begin, int width, int rows,
                   std::span<color_type> colors) const noexcept {
    using T = scalar_type;
    const AffineRays<T> field = selector_.affine_rays(surface_.affine_points());
    const T u0 = region.column_to_u<T>(x_begin), v0 = region.row_to_v<T>(y_begin);
    const T su = T(1) / static_cast<T>(region.width), sv = T(1) / static_cast<T>(region.height);
    const auto exact = [this, &region, x_begin, y_begin](int i, int j) noexcept {
      const Vec2<T> uv(region.column_to_u<T>(x_begin + i), region.row_to_v<T>(y_begin + j));
      return selector_.ray_at(Pixel{x_begin + i, y_begin + j}, uv, surface_.point_at(uv));
    };
    const RayGrid<T, decltype(exact)> grid{width,
                                           rows,
                                           field.origin.value(u0, v0),
                                           Vec3<T>(su * field.origin.du),
                                           Vec3<T>(sv * field.origin.dv),
                                           field.direction.value(u0, v0),
                                           Vec3<T>(su * field.direction.du),
                                           Vec3<T>(sv * field.direction.dv),
                                           field.origin.rounding(),
                                           field.direction.rounding(),
                                           exact};
    return sampler_.sample_grid(grid, colors);
  }

  // rays[i] = the ray of pixel (x_begin + i, y): the same rays as `ray_at`, with the row's v
  // computed once and u taken from `u` (u[i] = region.column_to_u(x_begin + i)) when given.
  MPR_FLATTEN void rays_of_row(const Region& region, int y, int x_begin, int x_end, const scalar_type* u,
                               Ray<scalar_type>* rays) const noexcept {
    const scalar_type v = region.row_to_v<scalar_type>(y);
    for (int x = x_begin; x < x_end; ++x) {
      const Vec2<scalar_type> uv(u != nullptr ? u[x - x_begin] : region.column_to_u<scalar_type>(x), v);
      rays[x - x_begin] = selector_.ray_at(Pixel{x, y}, uv, surface_.point_at(uv));
    }
  }

  // row[i] = colors[i] stored as Px, for i in [0, n).
  template <class Px>
  MPR_FLATTEN static void store_row(Px* row, const color_type* colors, int n) noexcept {
    detail::store_colors(row, colors, n);
  }

  [[no_unique_address]] Surface surface_{};
  [[no_unique_address]] Selector selector_{};
  [[no_unique_address]] Sampler sampler_{};
  [[no_unique_address]] Sampling sampling_{};
};

/// One view of a multi-view render: a region of the output and the renderer that fills it.
/// Holds the renderer by reference; it must outlive the `render` call.
template <class R>
struct View {
  Region region;
  const R* renderer;
};

/// Pairs a region with a renderer for `mpr::render`.
template <class R>
[[nodiscard]] View<R> view(const Region& region, const R& renderer) noexcept {
  return {region, &renderer};
}

/// Renders every view into `out` in one pass over the rows, spread over threads. Views may have
/// different surface, selector and sampler types. Where regions overlap, the later view wins.
/// Pixels of `out` covered by no view are left unchanged.
template <class Px, class... R>
void render(ImageView<Px> out, const RenderOptions& options, const View<R>&... views) noexcept {
  int y_begin = out.height(), y_end = 0;
  ((y_begin = std::min(y_begin, std::max(views.region.y, 0)),
    y_end = std::max(y_end, std::min(views.region.y + views.region.height, out.height()))),
   ...);
  if constexpr ((TileRaySampler<typename R::sampler_type> || ...)) {
    // Tiles of kTileRows rows counted from y_begin (fixed, whatever the thread count); each
    // view renders its part of the tile, later views over earlier ones as for rows.
    if (y_end <= y_begin) return;
    const auto tile = [&](int t) noexcept {
      const int ty0 = y_begin + t * kTileRows, ty1 = std::min(ty0 + kTileRows, y_end);
      const auto one = [&](const auto& v) noexcept {
        const Region& r = v.region;
        const int y0 = std::max(ty0, r.y), y1 = std::min(ty1, r.y + r.height);
        const int x0 = std::max(r.x, 0), x1 = std::min(r.x + r.width, out.width());
        if (y0 < y1 && x0 < x1) v.renderer->render_tile(out, r, y0, y1, x0, x1);
      };
      (one(views), ...);
    };
    detail::parallel_rows(0, (y_end - y_begin + kTileRows - 1) / kTileRows, options.threads, tile);
  } else {
    const auto row = [&](int y) noexcept {
      const auto one = [&](const auto& v) noexcept {
        const Region& r = v.region;
        if (y < r.y || y >= r.y + r.height) return;
        const int x0 = std::max(r.x, 0), x1 = std::min(r.x + r.width, out.width());
        if (x0 < x1) v.renderer->render_row(out, r, y, x0, x1);
      };
      (one(views), ...);
    };
    detail::parallel_rows(y_begin, y_end, options.threads, row);
  }
}

} // namespace mpr
