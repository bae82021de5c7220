#pragma once
/// \file
/// `mpr::SyntheticAperture`: the light-field interpolation that averages every camera seeing the
/// ray's point -- a synthetic aperture as wide as the array, focused on the point (dynamically
/// reparameterized light fields, Isaksen, McMillan & Gortler 2000; synthetic-aperture
/// photography, Vaish et al. 2004).

#include <mpr/core/concepts.hpp>
#include <mpr/core/ray_grid.hpp>
#include <mpr/lightfield/frame_runs.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/frame_tiles.hpp>
#include <mpr/lightfield/interpolation.hpp>
#include <mpr/lightfield/plane_rows.hpp>

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

namespace mpr {

/// The unweighted average over every camera that sees the ray's point (in front of it and inside
/// its image). No camera sees it: the background colour.
///
/// Batch and tile: cameras in the outer loop; a run of evenly spaced points that a camera sees
/// one pixel apart is added by shift-and-add (`mpr::shift_add`), and a tile walks each camera
/// once for all its rows, so camera rows shared by neighbouring output rows are read while still
/// in cache. Equal to `sample` up to float rounding and the shift-and-add's 1e-3 pixel.
struct SyntheticAperture {
  template <std::floating_point T, class Px>
  [[nodiscard]] Color sample(const FrameTable<T, Px>& table, const Ray<T>& ray) const noexcept {
    const Vec3<T> X = table.point_of(ray);
    float acc[3] = {0, 0, 0};
    float weight = 0;
    for (const auto& c : table.cameras()) table.add_seen(c, X, 1.0f, acc, weight);
    return table.finish(acc, weight);
  }

  template <std::floating_point T, class Px>
  void sample_rays(const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, std::span<Color> out) const noexcept {
    for_each_chunk(rays, kBatchRays, out, [&](std::span<const Ray<T>> r, std::span<Color> o) { run(table, r, o); });
  }

  template <std::floating_point T, class Px>
  void sample_tile(const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, int width,
                   std::span<Color> out) const noexcept {
    const std::size_t w = tile_width(rays.size(), width);
    const auto fill = [&](Vec3<T>* points, unsigned char* even) noexcept {
      for (std::size_t i = 0; i < rays.size(); ++i) points[i] = table.point_of(rays[i]);
      for (std::size_t r = 0; r < rays.size() / w; ++r)
        even[r] = table.config().filter == PixelFilter::bilinear && w >= 8 && evenly_spaced(points + r * w, w);
    };
    if (w > 0 && tile(table, rays.size(), w, out, fill)) return;
    for_each_row(rays, w, out, [&](std::span<const Ray<T>> r, std::span<Color> o) { sample_rays(table, r, o); });
  }

  /// The tile path for a tile whose rays are affine in the pixel (`GridRaySampler`): the points
  /// come from the grid, evenly spaced along each row by construction.
  template <std::floating_point T, class Px, class ExactRay>
  [[nodiscard]] bool sample_grid(const FrameTable<T, Px>& table, const RayGrid<T, ExactRay>& grid,
                                 std::span<Color> out) const noexcept {
    if (grid.width <= 0 || grid.rows <= 0) return false;
    const std::size_t w = static_cast<std::size_t>(grid.width), rows = static_cast<std::size_t>(grid.rows);
    const auto fill = [&](Vec3<T>* points, unsigned char* even) noexcept {
      fill_grid_points(table, grid, points, even);
    };
    return tile(table, w * rows, w, out, fill);
  }

private:
  // One run of at most kBatchRays rays, cameras in the outer loop.
  template <std::floating_point T, class Px>
  static void run(const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, std::span<Color> out) noexcept {
    const std::size_t n = rays.size();
    float acc[3 * kBatchRays];
    float weight[kBatchRays];
    Vec3<T> points[kBatchRays];
    for (std::size_t i = 0; i < n; ++i) {
      points[i] = table.point_of(rays[i]);
      weight[i] = 0;
    }
    std::fill(acc, acc + 3 * n, 0.0f);
    const bool even = table.config().filter == PixelFilter::bilinear && n >= 8 && evenly_spaced(points, n);
    for (const auto& c : table.cameras()) add_run(table, c, points, n, even, acc, weight);
    table.finish_all(acc, weight, n, out.data());
  }

  // Per-thread working memory of `tile`.
  template <std::floating_point T>
  struct TileScratch {
    std::vector<Vec3<T>> points;
    std::vector<float> acc; // 3 per ray (r g b), the layout of the texel rows
    std::vector<float> weight;
    std::vector<float> weight_steps; // of `shift_add_tile`: rows (w + 1)
    std::vector<unsigned char> even;
    LerpRowCache rows;
    TileWork tiles;
    detail::ShiftBatch shifted;        // the cameras' whole-pixel shifts, added together
    detail::SharedWeightsBatch shared; // the cameras' resampled blocks that share their weights
  };

  // Every camera once per tile of n points in rows of w; `fill(points, even)` gives the points
  // and tells per row whether they are evenly spaced. False when working memory cannot grow.
  template <std::floating_point T, class Px, class Fill>
  static bool tile(const FrameTable<T, Px>& table, std::size_t n, std::size_t w, std::span<Color> out,
                   const Fill& fill) noexcept {
    const std::size_t rows = n / w;
    thread_local TileScratch<T> scratch;
    try {
      if (scratch.points.size() < n) scratch.points.resize(n);
      if (scratch.acc.size() < 3 * n) scratch.acc.resize(3 * n);
      if (scratch.weight.size() < n) scratch.weight.resize(n);
      if (scratch.weight_steps.size() < n + rows) scratch.weight_steps.resize(n + rows);
      if (scratch.even.size() < rows) scratch.even.resize(rows);
    } catch (...) {
      return false;
    }
    detail::ShiftBatch* batch = &scratch.shifted;
    batch->blocks.clear();
    try {
      batch->blocks.reserve(table.size());
      if (batch->rows.size() < table.size()) batch->rows.resize(table.size());
      if (batch->rows16.size() < table.size()) batch->rows16.resize(table.size());
    } catch (...) {
      batch = nullptr; // each camera's shift added by itself
    }
    detail::SharedWeightsBatch* shared = &scratch.shared;
    shared->blocks.clear();
    try {
      shared->blocks.reserve(table.size());
    } catch (...) {
      shared = nullptr; // each camera's block resampled by itself
    }
    scratch.rows.clear(); // rows kept from another tile may belong to frames since freed
    Vec3<T>* points = scratch.points.data();
    float* acc = scratch.acc.data();
    float* weight = scratch.weight.data();
    fill(points, scratch.even.data());
    std::fill(weight, weight + n, 0.0f);
    float* steps = scratch.weight_steps.data();
    std::fill(steps, steps + n + rows, 0.0f);
    std::fill(acc, acc + 3 * n, 0.0f);
    const bool all_even = std::all_of(scratch.even.begin(), scratch.even.begin() + static_cast<std::ptrdiff_t>(rows),
                                      [](unsigned char e) { return e != 0; });
    for (const auto& c : table.cameras()) {
      // The next camera's rows are asked for while this one's are read (`shift_add`).
      const auto* ahead = &c != &table.cameras().back() && !(&c + 1)->distorted ? &c + 1 : nullptr;
      // The tile as one 2-D shift of the camera's image, when it is one.
      if (all_even &&
          shift_add_tile(table, c, points, rows, w, acc, weight, steps, scratch.tiles, ahead, batch, shared))
        continue;
      for (std::size_t r = 0; r < rows; ++r) {
        const std::size_t o = r * w;
        if (scratch.even[r] && !c.distorted) {
          if (shift_add(table, c, points + o, w, acc + 3 * o, weight + o, nullptr, &scratch.rows, ahead)) continue;
          // Rows off the camera's rows (a tilted plane): the whole tile at once when it can.
          if (r == 0 && rows > 1 && all_even && add_tile(table, c, points, rows, w, acc, weight)) break;
          if (add_projective(table, c, points + o, w, acc + 3 * o, weight + o)) continue;
        }
        table.add_per_ray(c, points + o, w, acc + 3 * o, weight + o);
      }
    }
    if (batch != nullptr && !batch->blocks.empty()) {
      using texel_type = typename FrameTable<T, Px>::texel_type;
      detail::add_shifted_blocks(*batch, rows, w, texel_decode_table<texel_type>(), texel_type::scale, acc,
                                 3 * static_cast<std::ptrdiff_t>(w));
    }
    if (shared != nullptr && !shared->blocks.empty()) {
      using texel_type = typename FrameTable<T, Px>::texel_type;
      detail::add_shared_weights(*shared, texel_decode_table<texel_type>(), texel_type::scale, acc,
                                 3 * static_cast<std::ptrdiff_t>(w));
    }
    add_weight_steps(steps, rows, w, weight);
    table.finish_all(acc, weight, n, out.data());
    return true;
  }

  // Camera c's contribution to all `rows` rows of w points of the tile at once, unweighted
  // (`add_projective_tile`); false (nothing added) as there.
  template <std::floating_point T, class Px>
  static bool add_tile(const FrameTable<T, Px>& table, const typename FrameTable<T, Px>::Camera& c,
                       const Vec3<T>* points, std::size_t rows, std::size_t w, float* acc, float* weight) noexcept {
    if (rows > kMaxTileRuns) return false;
    const Vec3<T>* run[kMaxTileRuns];
    detail::TileRowOut out[kMaxTileRuns];
    for (std::size_t r = 0; r < rows; ++r) {
      run[r] = points + r * w;
      out[r] = {acc + 3 * r * w, weight + r * w, nullptr};
    }
    return add_projective_tile(table, c, std::span<const Vec3<T>* const>(run, rows),
                               std::span<const detail::TileRowOut>(out, rows), w);
  }
};

} // namespace mpr
