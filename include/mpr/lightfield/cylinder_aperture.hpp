#pragma once
/// \file
/// `mpr::CylinderAperture`: the light-field interpolation that blends the cameras within a
/// radius of the ray line, with linear falloff -- a finite synthetic aperture centred on the ray
/// (the aperture filtering of dynamically reparameterized light fields, Isaksen et al. 2000).

#include <mpr/core/concepts.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/ray_grid.hpp>
#include <mpr/lightfield/accumulation/affine_block.hpp>
#include <mpr/lightfield/frame_runs.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/interpolation.hpp>
#include <mpr/lightfield/kernels/cylinder_weights.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>
#include <mpr/lightfield/plane_rows.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

namespace mpr {

/// The cameras whose centres lie strictly within `radius` (world units) of the ray line,
/// weighted by the linear falloff `1 - d / radius` and renormalised over those that see the
/// point. When no such camera sees the point the nearest-camera answer is used, so the result
/// is never NaN.
///
/// Batch, on a planar array: the cameras that can reach a run are collected once from the run's
/// plane crossings. Tile, on a planar array: eight rows at a time, each camera tried only on the
/// 64-ray segments it can reach, weights vectorised (`detail::cylinder_weights`), weighted
/// shift-and-add; cameras outer over the rows' common span, each camera row interpolated once,
/// or, where every run reads one camera row and the rows are short, rows outer (each row's sums
/// stay in cache); a camera whose rows are not shifts of its image (a tilted plane) takes all of
/// them at once (`add_projective_tile`). Equal to `sample` up to float rounding and the
/// shift-and-add's 1e-3 pixel.
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
    if (table.plane() && w > 0 &&
        row_path(table, *table.plane(), rays.size() / w, w, out,
                 TileRows<T, Px>{table, *table.plane(), rays.data(), w}))
      return;
    for_each_row(rays, w, out, [&](std::span<const Ray<T>> r, std::span<Color> o) { sample_rays(table, r, o); });
  }

  /// The tile path for a tile whose rays are affine in the pixel (`GridRaySampler`): the same row
  /// groups, their crossings from the grid. False on a non-planar array.
  template <std::floating_point T, class Px, class ExactRay>
  [[nodiscard]] bool sample_grid(const FrameTable<T, Px>& table, const RayGrid<T, ExactRay>& grid,
                                 std::span<Color> out) const noexcept {
    if (!table.plane() || grid.width <= 0 || grid.rows <= 0) return false;
    return row_path(table, *table.plane(), static_cast<std::size_t>(grid.rows), static_cast<std::size_t>(grid.width),
                    out, GridRows<T, Px, ExactRay>{table, *table.plane(), grid});
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

  // Rows taken together by `row_path` (the renderer's tiles have kTileRows).
  static constexpr std::size_t kGroupRows = 8;
  // How far (pixels) a camera's affine map of a group may place the rows' points from their
  // projections for it to stand in for projecting the runs (`detail::affine_sight`): a tenth of
  // the shift-and-add's 1e-3 pixel.
  static constexpr double kSightTolerance = 1e-4;
  // The most a row of the group may hold of crossings, weights and sums (5 scalars and 5 floats a
  // ray) for its cameras to be added rows outer: within 32 KiB it stays in the L1 data cache while
  // every camera is added to it (819 rays in float, 546 in double). Longer rows take cameras
  // outer, which also reads each camera's rows one after another (where rows outer was measured
  // to lose: docs/performance.md).
  static constexpr std::size_t kRowsOuterBytes = 32 * 1024;

  // Per-thread working memory of `row_path`: each row's crossings and sums, the bounding boxes
  // of its segments' crossings, the cameras within reach of the group.
  template <std::floating_point T>
  struct GroupScratch {
    PlaneRowScratch<T> row[kGroupRows];
    T lo_u[kGroupRows][kMaxSegments], hi_u[kGroupRows][kMaxSegments];
    T lo_v[kGroupRows][kMaxSegments], hi_v[kGroupRows][kMaxSegments];
    T reach[kGroupRows];
    bool crosses[kGroupRows], even[kGroupRows];
    std::size_t lo[kGroupRows], hi[kGroupRows]; // the rays a camera weighs, [lo, hi) per row
    // The rays it was weighed on (`weigh`), around [lo, hi); set only when lo < hi.
    std::size_t tried_lo[kGroupRows], tried_hi[kGroupRows];
    std::vector<int> cameras;
    std::vector<detail::AffineSight> sights; // per entry of `cameras`: its affine map, when `seen`
    std::vector<unsigned char> seen;
    LerpRowCache rows; // camera rows interpolated once for the two output rows that read them

    [[nodiscard]] bool reserve(std::size_t w, std::size_t cameras_in_table) noexcept {
      for (PlaneRowScratch<T>& r : row)
        if (!r.reserve(w)) return false;
      try {
        cameras.reserve(cameras_in_table);
        sights.resize(cameras_in_table);
        seen.resize(cameras_in_table);
      } catch (...) {
        return false;
      }
      return true;
    }
  };

  // Up to kGroupRows rows at a time on a planar array. A camera can weigh only rays whose plane
  // crossing lies within radius / cos_min of its centre, so each camera is tried only on the
  // 64-ray segments whose crossings' bounding box is that close; there its weights are computed
  // for all rays at once (`detail::cylinder_weights`). Cameras outer, the rays a camera weighs in
  // any row of the group give one span, added in every such row by a weighted shift-and-add
  // (weight 0 outside the row's own rays): each camera row is then interpolated once for the two
  // output rows that read it; a camera with no affine map of the group (a tilted plane) adds all
  // those rows at once through the projective tile's decoded boxes. Rows outer (every run one
  // camera row, short rows), each row gets each camera on its own rays. The next camera's texels
  // are fetched meanwhile. Rays that no camera weighs get the nearest camera, as in `sample`. A
  // row with a ray that does not cross the plane goes ray by ray through `sample`.
  //
  // `source` gives the rows (`TileRows` or `GridRows`).
  template <std::floating_point T, class Px, class Rows>
  bool row_path(const FrameTable<T, Px>& table, const ArrayPlane<T>& plane, std::size_t nrows, std::size_t w,
                std::span<Color> out, const Rows& source) const noexcept {
    thread_local GroupScratch<T> scratch;
    if ((w + kSegment - 1) / kSegment > kMaxSegments || !scratch.reserve(w, table.size())) return false;
    for (std::size_t r0 = 0; r0 < nrows; r0 += kGroupRows) {
      const std::size_t rows = std::min(kGroupRows, nrows - r0);
      group(table, plane, r0, rows, w, out.subspan(r0 * w, rows * w), scratch, source);
    }
    return true;
  }

  // `row_path` for at most kGroupRows rows from row r0 of `source`: the rows' crossings, then
  // each camera in reach.
  template <std::floating_point T, class Px, class Rows>
  void group(const FrameTable<T, Px>& table, const ArrayPlane<T>& plane, std::size_t r0, std::size_t nrows,
             std::size_t w, std::span<Color> out, GroupScratch<T>& s, const Rows& source) const noexcept {
    const T r = static_cast<T>(radius), margin = T(1e-4) * plane.extent;
    constexpr T kInf = std::numeric_limits<T>::infinity();
    T box[4] = {kInf, -kInf, kInf, -kInf}; // the group's crossings: u from, to; v from, to
    T reach_max = 0;
    for (std::size_t q = 0; q < nrows; ++q) {
      PlaneRowScratch<T>& row = s.row[q];
      bool all_cross = true, even = false;
      T slack = 0;
      const T cos_min = source.prepare(r0 + q, row, all_cross, even, slack);
      s.crosses[q] = all_cross;
      s.even[q] = even;
      if (!all_cross) {
        for (std::size_t i = 0; i < w; ++i) out[q * w + i] = sample(table, source.ray(r0 + q, i));
        continue;
      }
      for (std::size_t i = 0; i < w; ++i) row.inv_dd[i] = T(1) / row.dd[i];
      for (std::size_t g = 0; g * kSegment < w; ++g) {
        T lu = kInf, hu = -kInf, lv = kInf, hv = -kInf;
        const std::size_t i0 = g * kSegment, count = std::min(w, i0 + kSegment) - i0;
        detail::widen_bounds(row.xu.data() + i0, count, lu, hu);
        detail::widen_bounds(row.xv.data() + i0, count, lv, hv);
        s.lo_u[q][g] = lu;
        s.hi_u[q][g] = hu;
        s.lo_v[q][g] = lv;
        s.hi_v[q][g] = hv;
        box[0] = std::min(box[0], lu);
        box[1] = std::max(box[1], hu);
        box[2] = std::min(box[2], lv);
        box[3] = std::max(box[3], hv);
      }
      s.reach[q] = r / cos_min * T(1.001) + margin + 2 * slack;
      reach_max = std::max(reach_max, s.reach[q]);
      std::fill(row.acc.begin(), row.acc.begin() + static_cast<std::ptrdiff_t>(3 * w), 0.0f);
      std::fill(row.weight.begin(), row.weight.begin() + static_cast<std::ptrdiff_t>(w), 0.0f);
    }
    // Most cameras are out of reach of the whole group.
    s.cameras.clear();
    for (std::size_t k = 0; k < table.size(); ++k) {
      const T cu = plane.centre_u[k], cv = plane.centre_v[k];
      if (cu >= box[0] - reach_max && cu <= box[1] + reach_max && cv >= box[2] - reach_max && cv <= box[3] + reach_max)
        s.cameras.push_back(static_cast<int>(k));
    }
    s.rows.clear(); // rows kept from another group may belong to frames since freed
    // When the rows' points form one affine grid, a camera that sees it at one depth gives every
    // run's pixel positions from one map instead of three projections a run.
    const Vec3<T>* points[kGroupRows];
    bool block = nrows >= 2 && table.config().filter == PixelFilter::bilinear;
    for (std::size_t q = 0; q < nrows; ++q) {
      points[q] = s.row[q].points.data();
      block = block && s.crosses[q] && s.even[q];
    }
    detail::AffineGrid grid;
    block = block && detail::affine_grid(points, nrows, w, grid);
    // Every camera's map, in one loop before any is added: a camera's runs are placed by its own
    // map, and the next camera's texels for them, prefetched meanwhile, by the next one's.
    for (std::size_t j = 0; j < s.cameras.size(); ++j) {
      const auto& c = table.camera(static_cast<std::size_t>(s.cameras[j]));
      s.seen[j] = block && !c.distorted && detail::affine_sight(c.P, grid, w, nrows, kSightTolerance, s.sights[j]);
    }
    const std::size_t ncam = s.cameras.size();
    bool one_row = block && w * (5 * sizeof(T) + 5 * sizeof(float)) <= kRowsOuterBytes;
    for (std::size_t j = 0; j < ncam && one_row; ++j)
      one_row = s.seen[j] && detail::one_row_runs(s.sights[j], w, nrows);
    if (one_row) {
      // Rows outer: each run is added in one pass (no camera row shared between output rows), so
      // nothing is lost by visiting a camera's rows apart, and the row stays in cache meanwhile.
      for (std::size_t q = 0; q < nrows; ++q)
        for (std::size_t j = 0; j < ncam; ++j) {
          weigh(plane, static_cast<std::size_t>(s.cameras[j]), w, q, s);
          if (s.lo[q] >= s.hi[q]) continue;
          // At least `kShortestRun` rays, padded with weights of 0 inside the rays weighed.
          const std::size_t hi = std::min(s.tried_hi[q], std::max(s.hi[q], s.lo[q] + kShortestRun));
          const std::size_t lo = std::max(s.tried_lo[q], std::min(s.lo[q], hi > kShortestRun ? hi - kShortestRun : 0));
          const bool last = j + 1 == ncam;
          add_camera(table, s, j, q, lo, hi, last ? 0 : j + 1, last ? q + 1 : q, nrows);
        }
    } else {
      for (std::size_t j = 0; j < ncam; ++j) {
        std::size_t span_lo = w, span_hi = 0;
        for (std::size_t q = 0; q < nrows; ++q) {
          weigh(plane, static_cast<std::size_t>(s.cameras[j]), w, q, s);
          if (s.lo[q] < s.hi[q]) {
            span_lo = std::min(span_lo, s.lo[q]);
            span_hi = std::max(span_hi, s.hi[q]);
          }
        }
        if (span_lo >= span_hi) continue;
        for (std::size_t q = 0; q < nrows; ++q) {
          if (s.lo[q] >= s.hi[q]) continue;
          float* ray_weight = s.row[q].ray_weight.data();
          std::fill(ray_weight + span_lo, ray_weight + s.lo[q], 0.0f);
          std::fill(ray_weight + s.hi[q], ray_weight + span_hi, 0.0f);
        }
        if (add_tile(table, s, j, span_lo, span_hi, nrows)) continue;
        for (std::size_t q = 0; q < nrows; ++q)
          if (s.lo[q] < s.hi[q]) add_camera(table, s, j, q, span_lo, span_hi, j + 1, q, nrows);
      }
    }
    for (std::size_t q = 0; q < nrows; ++q) {
      if (!s.crosses[q]) continue;
      const PlaneRowScratch<T>& row = s.row[q];
      Color* o = out.data() + q * w;
      if (table.finish_all(row.acc.data(), row.weight.data(), w, o)) continue; // every ray weighed
      for (std::size_t i = 0; i < w; ++i) {
        if (!(row.weight[i] > 0)) {
          const Ray<T> ray = source.ray(r0 + q, i);
          o[i] = table.camera_color(table.index().nearest(ray.origin, ray.direction), row.points[i]);
        }
      }
    }
  }

  // Camera j of the group (entry j of `s.cameras`) added to rays [lo, hi) of row q, each weighed
  // by its `ray_weight` (set there), its pixel positions from its map when it has one. The camera
  // added next is entry next_j on row next_q (none past the group): its texels for the run are
  // prefetched meanwhile, placed by its own map where it has one.
  template <std::floating_point T, class Px>
  void add_camera(const FrameTable<T, Px>& table, GroupScratch<T>& s, std::size_t j, std::size_t q, std::size_t lo,
                  std::size_t hi, std::size_t next_j, std::size_t next_q, std::size_t nrows) const noexcept {
    const bool has_next = next_j < s.cameras.size() && next_q < nrows;
    const auto* ahead = has_next ? &table.camera(static_cast<std::size_t>(s.cameras[next_j])) : nullptr;
    const detail::AffineSight* sight = s.seen[j] ? &s.sights[j] : nullptr;
    const detail::AffineSight* next = has_next && s.seen[next_j] ? &s.sights[next_j] : nullptr;
    RunSight<T> at;
    if (sight != nullptr) {
      const double dq = static_cast<double>(q), mid = static_cast<double>(lo + (hi - lo) / 2);
      sight->at(static_cast<double>(lo), dq, at.x0, at.y0);
      sight->at(mid, dq, at.xm, at.ym);
      sight->at(static_cast<double>(hi - 1), dq, at.x1, at.y1);
      if (next != nullptr) {
        next->at(static_cast<double>(lo), static_cast<double>(next_q), at.ahead_x, at.ahead_y);
        at.ahead_dx = static_cast<T>(next->x[1]);
        at.ahead_dy = static_cast<T>(next->y[1]);
      }
    }
    PlaneRowScratch<T>& row = s.row[q];
    add_run(table, table.camera(static_cast<std::size_t>(s.cameras[j])), row.points.data() + lo, hi - lo, s.even[q],
            row.acc.data() + 3 * lo, row.weight.data() + lo, row.ray_weight.data() + lo, &s.rows, ahead,
            sight != nullptr ? &at : nullptr);
  }

  // Camera j added to rays [lo, hi) of the group's rows it weighs, all at once when it has no
  // affine map of the group and its rows are not shifts of its image (a plane tilted off the
  // cameras' rows): `add_projective_tile` decodes their texels once. False: nothing added.
  template <std::floating_point T, class Px>
  bool add_tile(const FrameTable<T, Px>& table, GroupScratch<T>& s, std::size_t j, std::size_t lo, std::size_t hi,
                std::size_t nrows) const noexcept {
    const auto& c = table.camera(static_cast<std::size_t>(s.cameras[j]));
    if (s.seen[j] || c.distorted || hi - lo < kShortestRun) return false;
    const Vec3<T>* points[kGroupRows];
    detail::TileRowOut out[kGroupRows];
    std::size_t rows = 0, first = nrows;
    for (std::size_t q = 0; q < nrows; ++q) {
      if (s.lo[q] >= s.hi[q]) continue;
      if (!s.even[q]) return false;
      first = std::min(first, q);
      PlaneRowScratch<T>& row = s.row[q];
      points[rows] = row.points.data() + lo;
      out[rows++] = {row.acc.data() + 3 * lo, row.weight.data() + lo, row.ray_weight.data() + lo};
    }
    if (rows < 2) return false;
    if (shift_add(table, c, points[0], hi - lo, out[0].acc, out[0].seen, out[0].rw, &s.rows)) {
      for (std::size_t q = first + 1; q < nrows; ++q)
        if (s.lo[q] < s.hi[q]) add_camera(table, s, j, q, lo, hi, j + 1, q, nrows);
      return true;
    }
    return add_projective_tile(table, c, std::span<const Vec3<T>* const>(points, rows),
                               std::span<const detail::TileRowOut>(out, rows), hi - lo);
  }

  // Camera k's weights for row q of the group, on the segments within the row's reach of its
  // centre ([s.tried_lo[q], s.tried_hi[q]) of `ray_weight`, each >= 0; elsewhere untouched), and
  // the rays it weighs, [s.lo[q], s.hi[q]) (empty: none, and `tried_*` not set), from the span of
  // positive weights the weights kernel returns.
  template <std::floating_point T>
  void weigh(const ArrayPlane<T>& plane, std::size_t k, std::size_t w, std::size_t q,
             GroupScratch<T>& s) const noexcept {
    s.lo[q] = s.hi[q] = 0;
    if (!s.crosses[q]) return;
    const T cu = plane.centre_u[k], cv = plane.centre_v[k], reach2 = s.reach[q] * s.reach[q];
    // The squared distance from the centre to each segment's box (a loop the compiler
    // vectorises), then the first and last segment within reach.
    const std::size_t segments = (w + kSegment - 1) / kSegment;
    T gap2[kMaxSegments];
    for (std::size_t g = 0; g < segments; ++g) {
      const T gu = std::max(std::max(s.lo_u[q][g] - cu, cu - s.hi_u[q][g]), T(0));
      const T gv = std::max(std::max(s.lo_v[q][g] - cv, cv - s.hi_v[q][g]), T(0));
      gap2[g] = gu * gu + gv * gv;
    }
    std::size_t g0 = 0, g1 = segments;
    while (g0 < segments && !(gap2[g0] < reach2)) ++g0;
    if (g0 == segments) return;
    while (!(gap2[g1 - 1] < reach2)) --g1;
    const std::size_t first = g0 * kSegment, last = std::min(w, g1 * kSegment);
    s.tried_lo[q] = first;
    s.tried_hi[q] = last;
    PlaneRowScratch<T>& row = s.row[q];
    float* ray_weight = row.ray_weight.data();
    const std::array<std::size_t, 2> positive = detail::cylinder_weights(
        row.xu.data() + first, row.xv.data() + first, row.du.data() + first, row.dv.data() + first,
        row.inv_dd.data() + first, last - first, cu, cv, T(1) / static_cast<T>(radius), ray_weight + first);
    if (positive[0] >= positive[1]) return;
    s.lo[q] = first + positive[0];
    s.hi[q] = first + positive[1];
  }
};

} // namespace mpr
