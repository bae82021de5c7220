#pragma once
/// \file
/// `mpr::CylinderAperture`: the light-field interpolation that blends the cameras within a
/// radius of the ray line, with linear falloff -- a finite synthetic aperture centred on the ray
/// (the aperture filtering of dynamically reparameterized light fields, Isaksen et al. 2000).

#include <mpr/core/concepts.hpp>
#include <mpr/core/error.hpp>
#include <mpr/lightfield/detail/kernels.hpp>
#include <mpr/lightfield/frame_runs.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/interpolation.hpp>
#include <mpr/lightfield/plane_rows.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

namespace mpr {

/// The cameras whose centres lie strictly within `radius` (world units) of the ray line,
/// weighted by the linear falloff `1 - d / radius` and renormalised over those that see the
/// point. When no such camera sees the point the nearest-camera answer is used, so the result
/// is never NaN.
///
/// Batch, on a planar array: the cameras that can reach a run are collected once from the run's
/// plane crossings. Tile, on a planar array: a row at a time, cameras outer, each tried only on
/// the 64-ray segments it can reach, weights vectorised (`detail::cylinder_weights`), weighted
/// shift-and-add. Equal to `sample` up to float rounding and the shift-and-add's 1e-3 pixel.
struct CylinderAperture {
  /// Radius of the aperture around the ray line, world units, positive and finite.
  double radius = 1.0;

  /// Throws `argument_error` ("radius") unless `radius` is positive and finite.
  void validate() const {
    if (!(radius > 0) || !std::isfinite(radius)) throw argument_error("radius", "must be positive and finite");
  }

  template <std::floating_point T, class Px>
  [[nodiscard]] Color sample(const FrameTable<T, Px>& table, const Ray<T>& ray) const noexcept {
    const Vec3<T> X = table.point_of(ray);
    const T r = static_cast<T>(radius);
    float acc[3] = {0, 0, 0};
    float weight = 0;
    table.index().within(ray.origin, ray.direction, r, [&](int i, T d) noexcept {
      const float w = static_cast<float>(T(1) - d / r);
      if (w > 0) table.add_seen(table.camera(static_cast<std::size_t>(i)), X, w, acc, weight);
    });
    if (!(weight > 0)) return table.camera_color(table.index().nearest(ray.origin, ray.direction), X);
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
    if (table.plane() && w > 0 && row_path(table, *table.plane(), rays, w, out)) return;
    for_each_row(rays, w, out, [&](std::span<const Ray<T>> r, std::span<Color> o) { sample_rays(table, r, o); });
  }

private:
  static constexpr int kMaxCandidates = 512;
  static constexpr std::size_t kSegment = 64;
  static constexpr std::size_t kMaxSegments = 64;

  // One run of at most kBatchRays rays: on a planar array, the cameras that can lie within the
  // radius of any ray of the run are those within radius / cos(theta_min) of the run's plane
  // crossings (bounding box), collected once; each ray then tests only those.
  template <std::floating_point T, class Px>
  void run(const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, std::span<Color> out) const noexcept {
    const std::size_t n = rays.size();
    const T r = static_cast<T>(radius);
    Vec3<T> lo = Vec3<T>::Constant(std::numeric_limits<T>::infinity()), hi = -lo;
    T cos_min = 1;
    bool ok = table.plane().has_value();
    for (std::size_t i = 0; i < n && ok; ++i) {
      Vec3<T> x = Vec3<T>::Zero();
      T cosine = 0;
      ok = table.plane()->hit(rays[i], x, cosine);
      if (!ok) break;
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
      cos_min = std::min(cos_min, cosine);
    }
    if (!ok) {
      for (std::size_t i = 0; i < n; ++i) out[i] = sample(table, rays[i]);
      return;
    }
    int candidates[kMaxCandidates];
    int count = 0;
    const T reach = r / cos_min * T(1.001) + T(1e-4) * table.plane()->extent;
    for (std::size_t k = 0; k < table.size(); ++k) {
      const Vec3<T>& centre = table.camera(k).centre;
      const Vec3<T> nearest_point = centre.cwiseMax(lo).cwiseMin(hi);
      if ((centre - nearest_point).norm() < reach) {
        if (count == kMaxCandidates) {
          for (std::size_t i = 0; i < n; ++i) out[i] = sample(table, rays[i]);
          return;
        }
        candidates[count++] = static_cast<int>(k);
      }
    }
    const T r2 = r * r;
    Vec3<T> points[kBatchRays];
    float acc[3 * kBatchRays];
    float weight[kBatchRays];
    T inverse_length2[kBatchRays];
    float ray_weight[kBatchRays];
    for (std::size_t i = 0; i < n; ++i) {
      points[i] = table.point_of(rays[i]);
      acc[3 * i] = acc[3 * i + 1] = acc[3 * i + 2] = 0;
      weight[i] = 0;
      const T dd = rays[i].direction.squaredNorm();
      inverse_length2[i] = dd > 0 && std::isfinite(dd) ? T(1) / dd : T(0);
    }
    const bool even = n >= 8 && table.config().filter == PixelFilter::bilinear && evenly_spaced(points, n);
    for (int j = 0; j < count; ++j) {
      const auto& c = table.camera(static_cast<std::size_t>(candidates[j]));
      // [first, last): the rays this camera weighs; shift-and-add covers just that sub-run.
      std::size_t first = n, last = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const T d2 = inverse_length2[i] > 0
                         ? line_distance2(c.centre, rays[i].origin, rays[i].direction, inverse_length2[i])
                         : r2;
        ray_weight[i] = d2 < r2 ? static_cast<float>(T(1) - std::sqrt(d2) / r) : 0.0f;
        if (ray_weight[i] > 0) {
          first = std::min(first, i);
          last = i + 1;
        }
      }
      if (first >= last) continue;
      add_run(table, c, points + first, last - first, even, acc + 3 * first, weight + first, ray_weight + first);
    }
    for (std::size_t i = 0; i < n; ++i)
      out[i] = weight[i] > 0 ? table.finish(acc + 3 * i, weight[i])
                             : table.camera_color(table.index().nearest(rays[i].origin, rays[i].direction), points[i]);
  }

  // A row at a time on a planar array, cameras in the outer loop. A camera can weigh only rays
  // whose plane crossing lies within radius / cos_min of its centre, so each camera is tried
  // only on the segments whose crossings' bounding box is that close; there its weights are
  // computed for all rays at once, and the rays it weighs are added by a weighted shift-and-add
  // (or per ray). Rays that no camera weighs get the nearest camera, as in `sample`. A row with a
  // ray that does not cross the plane goes through `sample_rays`.
  template <std::floating_point T, class Px>
  bool row_path(const FrameTable<T, Px>& table, const ArrayPlane<T>& plane, std::span<const Ray<T>> rays, std::size_t w,
                std::span<Color> out) const noexcept {
    const std::size_t nrows = rays.size() / w;
    thread_local PlaneRowScratch<T> scratch;
    if (!scratch.reserve(w)) return false;
    const T r = static_cast<T>(radius), inv_radius = T(1) / r;
    const T margin = T(1e-4) * plane.extent;
    const std::size_t segments = (w + kSegment - 1) / kSegment;
    if (segments > kMaxSegments) return false;
    T lo_u[kMaxSegments], hi_u[kMaxSegments], lo_v[kMaxSegments], hi_v[kMaxSegments];
    for (std::size_t row_index = 0; row_index < nrows; ++row_index) {
      const Ray<T>* row = rays.data() + row_index * w;
      Color* o = out.data() + row_index * w;
      bool all_cross = true, even = false;
      const T cos_min = prepare_plane_row(table, plane, row, w, scratch, all_cross, even);
      if (!all_cross) {
        sample_rays(table, std::span<const Ray<T>>(row, w), std::span<Color>(o, w));
        continue;
      }
      for (std::size_t i = 0; i < w; ++i) scratch.inv_dd[i] = T(1) / scratch.dd[i];
      for (std::size_t g = 0; g < segments; ++g) {
        lo_u[g] = lo_v[g] = std::numeric_limits<T>::infinity();
        hi_u[g] = hi_v[g] = -std::numeric_limits<T>::infinity();
        for (std::size_t i = g * kSegment; i < std::min(w, (g + 1) * kSegment); ++i) {
          lo_u[g] = std::min(lo_u[g], scratch.xu[i]);
          hi_u[g] = std::max(hi_u[g], scratch.xu[i]);
          lo_v[g] = std::min(lo_v[g], scratch.xv[i]);
          hi_v[g] = std::max(hi_v[g], scratch.xv[i]);
        }
      }
      const T reach = r / cos_min * T(1.001) + margin;
      const Vec3<T>* points = scratch.points.data();
      float* acc = scratch.acc.data();
      float* weight = scratch.weight.data();
      float* ray_weight = scratch.ray_weight.data();
      std::fill(acc, acc + 3 * w, 0.0f);
      std::fill(weight, weight + w, 0.0f);
      T row_lo_u = lo_u[0], row_hi_u = hi_u[0], row_lo_v = lo_v[0], row_hi_v = hi_v[0];
      for (std::size_t g = 1; g < segments; ++g) {
        row_lo_u = std::min(row_lo_u, lo_u[g]);
        row_hi_u = std::max(row_hi_u, hi_u[g]);
        row_lo_v = std::min(row_lo_v, lo_v[g]);
        row_hi_v = std::max(row_hi_v, hi_v[g]);
      }
      for (std::size_t k = 0; k < table.size(); ++k) {
        const T cu = plane.centre_u[k], cv = plane.centre_v[k];
        // Most cameras are out of reach of the whole row.
        if (cu < row_lo_u - reach || cu > row_hi_u + reach || cv < row_lo_v - reach || cv > row_hi_v + reach) continue;
        std::size_t first = segments, last = 0;
        for (std::size_t g = 0; g < segments; ++g) {
          const T gu = std::max({lo_u[g] - cu, cu - hi_u[g], T(0)}), gv = std::max({lo_v[g] - cv, cv - hi_v[g], T(0)});
          if (gu * gu + gv * gv < reach * reach) {
            first = std::min(first, g);
            last = g + 1;
          }
        }
        if (first >= last) continue;
        const std::size_t b0 = first * kSegment, b1 = std::min(w, last * kSegment);
        detail::cylinder_weights(scratch.xu.data() + b0, scratch.xv.data() + b0, scratch.du.data() + b0,
                                 scratch.dv.data() + b0, scratch.inv_dd.data() + b0, b1 - b0, cu, cv, inv_radius,
                                 ray_weight + b0);
        // The rays the camera weighs: from the first to the last positive weight (a scan from
        // each end, which stops at the cylinder's edge).
        std::size_t lo = b0, hi = b1;
        while (lo < hi && !(ray_weight[lo] > 0)) ++lo;
        while (hi > lo && !(ray_weight[hi - 1] > 0)) --hi;
        if (lo >= hi) continue;
        add_run(table, table.camera(k), points + lo, hi - lo, even, acc + 3 * lo, weight + lo, ray_weight + lo);
      }
      for (std::size_t i = 0; i < w; ++i)
        o[i] = weight[i] > 0 ? table.finish(acc + 3 * i, weight[i])
                             : table.camera_color(table.index().nearest(row[i].origin, row[i].direction), points[i]);
    }
    return true;
  }
};

} // namespace mpr
