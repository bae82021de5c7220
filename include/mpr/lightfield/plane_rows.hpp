#pragma once
/// \file
/// One output row of rays seen from the plane of a planar camera array: where each ray crosses
/// the plane (in-plane coordinates, structure of arrays, vectorised), the least cosine to the
/// normal, and whether the row's points are evenly spaced. The row paths of `NearestCamera` and
/// `CylinderAperture` start here, from the rays of a row or from a `RayGrid`.

#include <mpr/core/ray_grid.hpp>
#include <mpr/lightfield/array_plane.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>
#include <mpr/lightfield/frame_runs.hpp>
#include <mpr/lightfield/frame_table.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace mpr {

/// Per-thread working memory of the row paths, sized for one output row.
template <std::floating_point T>
struct PlaneRowScratch {
  using Flag = typename detail::PlaneRays<T>::Flag;
  std::vector<Vec3<T>> points;
  std::vector<float> acc, weight, ray_weight;
  std::vector<T> soa[6]; // ray origins relative to the plane point, then directions
  std::vector<T> at[3];  // the points relative to the plane point, when a focal depth is set
  std::vector<T> xu, xv, du, dv, dd, cos2, inv_dd;
  std::vector<Flag> ok;

  /// Room for rows of `w` rays; false when memory runs out.
  [[nodiscard]] bool reserve(std::size_t w) noexcept {
    try {
      if (points.size() < w) {
        points.resize(w);
        for (std::vector<float>* v : {&acc, &weight, &ray_weight}) v->resize(v == &acc ? 3 * w : w);
        for (std::vector<T>& v : soa) v.resize(w);
        for (std::vector<T>& v : at) v.resize(w);
        for (std::vector<T>* v : {&xu, &xv, &du, &dv, &dd, &cos2, &inv_dd}) v->resize(w);
        ok.resize(w);
      }
      return true;
    } catch (...) {
      return false;
    }
  }

  /// The crossings from ray `offset` on.
  [[nodiscard]] detail::PlaneRays<T> plane_rays(std::size_t offset = 0) noexcept {
    return {xu.data() + offset, xv.data() + offset, du.data() + offset,
            dv.data() + offset, dd.data() + offset, ok.data() + offset};
  }
};

/// Fills `scratch` for the w rays of `row`: their points (`FrameTable::point_of`) and where they
/// cross `plane` (`scratch.xu` ..., see `detail::PlaneRays`). Returns the least cosine between a
/// crossing ray and the plane normal (1 when none crosses); `all_cross` tells whether every ray
/// crosses, `even` whether the points are evenly spaced (only asked for bilinear filtering and
/// w >= 8). Precondition: `scratch.reserve(w)` succeeded.
template <std::floating_point T, class Px>
T prepare_plane_row(const FrameTable<T, Px>& table, const ArrayPlane<T>& plane, const Ray<T>* row, std::size_t w,
                    PlaneRowScratch<T>& scratch, bool& all_cross, bool& even) noexcept {
  const detail::PlaneAxes<T> frame{plane.point.x(),  plane.point.y(),  plane.point.z(),  plane.normal.x(),
                                   plane.normal.y(), plane.normal.z(), plane.axis_u.x(), plane.axis_u.y(),
                                   plane.axis_u.z(), plane.axis_v.x(), plane.axis_v.y(), plane.axis_v.z()};
  T* const soa[6] = {scratch.soa[0].data(), scratch.soa[1].data(), scratch.soa[2].data(),
                     scratch.soa[3].data(), scratch.soa[4].data(), scratch.soa[5].data()};
  for (std::size_t i = 0; i < w; ++i) {
    const Ray<T>& ray = row[i];
    soa[0][i] = ray.origin.x() - frame.px;
    soa[1][i] = ray.origin.y() - frame.py;
    soa[2][i] = ray.origin.z() - frame.pz;
    soa[3][i] = ray.direction.x();
    soa[4][i] = ray.direction.y();
    soa[5][i] = ray.direction.z();
    scratch.points[i] = table.point_of(ray);
  }
  const T* const soa_in[6] = {soa[0], soa[1], soa[2], soa[3], soa[4], soa[5]};
  detail::plane_rays(soa_in, w, frame, scratch.plane_rays(), scratch.cos2.data());
  all_cross = std::find(scratch.ok.begin(), scratch.ok.begin() + static_cast<std::ptrdiff_t>(w), 0) ==
              scratch.ok.begin() + static_cast<std::ptrdiff_t>(w);
  even = false;
  if (table.config().filter == PixelFilter::bilinear && w >= 8) {
    const T* p[3] = {soa[0], soa[1], soa[2]};
    if (table.config().depth) {
      const T depth = *table.config().depth;
      for (int k = 0; k < 3; ++k) {
        T* q = scratch.at[k].data();
        for (std::size_t i = 0; i < w; ++i) q[i] = soa[k][i] + depth * soa[k + 3][i];
        p[k] = q;
      }
    }
    even = evenly_spaced(scratch.points.data(), p, w);
  }
  return std::sqrt(std::min(T(1), detail::min_of(scratch.cos2.data(), w)));
}

namespace detail {
/// Row `j` of a `RayGrid` as the samplers use it: anchored at the renderer's exact rays of the
/// row's first and last pixels (so that the grid's own rounding, large far from the world
/// origin, does not move the row), with the steps per pixel between them (zero for one pixel).
template <std::floating_point T>
struct GridRow {
  Ray<T> first;
  Vec3<T> origin_step = Vec3<T>::Zero(), direction_step = Vec3<T>::Zero();
  Vec3<T> point, point_step = Vec3<T>::Zero(); ///< `FrameTable::point_of` of the first ray, and its step
  /// The exact rays may lie off the row's line by more than 1/100 of a pixel step (far from the
  /// world origin in float): the row's points and crossings must come from the exact rays.
  bool rough = false;
};

template <std::floating_point T, class Px, class ExactRay>
[[nodiscard]] GridRow<T> grid_row(const FrameTable<T, Px>& table, const RayGrid<T, ExactRay>& grid, int j) noexcept {
  GridRow<T> row;
  row.first = grid.ray(0, j);
  row.point = table.point_of(row.first);
  if (grid.width < 2) return row;
  const Ray<T> last = grid.ray(grid.width - 1, j);
  const T inv = T(1) / static_cast<T>(grid.width - 1);
  row.origin_step = (last.origin - row.first.origin) * inv;
  row.direction_step = (last.direction - row.first.direction) * inv;
  row.point_step = (table.point_of(last) - row.point) * inv;
  const std::optional<T>& depth = table.config().depth;
  const T off = grid.origin_error + (depth ? std::abs(*depth) * grid.direction_error : T(0));
  row.rough = !(2 * off <= T(0.01) * row.point_step.cwiseAbs().maxCoeff());
  return row;
}

/// points[i] = p + i step for i in [0, n).
template <std::floating_point T>
void affine_points(const Vec3<T>& p, const Vec3<T>& step, int n, Vec3<T>* points) noexcept {
  // (int indices: their conversion to T vectorises, a size_t's does not.)
  for (int i = 0; i < n; ++i) {
    const T t = static_cast<T>(i);
    points[i] = Vec3<T>(p.x() + t * step.x(), p.y() + t * step.y(), p.z() + t * step.z());
  }
}
} // namespace detail

/// The points (`FrameTable::point_of`) of every pixel of a `RayGrid`, row-major: each row evenly
/// spaced between the points of its first and last pixels' exact rays (`even[j]` true for
/// bilinear filtering and rows of at least 8 pixels), or, on a rough row (`detail::GridRow`),
/// the exact rays' points, `even[j]` telling whether they are evenly spaced (`evenly_spaced`).
template <std::floating_point T, class Px, class ExactRay>
void fill_grid_points(const FrameTable<T, Px>& table, const RayGrid<T, ExactRay>& grid, Vec3<T>* points,
                      unsigned char* even) noexcept {
  const std::size_t w = static_cast<std::size_t>(grid.width);
  const bool bilinear = table.config().filter == PixelFilter::bilinear && w >= 8;
  for (int j = 0; j < grid.rows; ++j) {
    Vec3<T>* p = points + static_cast<std::size_t>(j) * w;
    const detail::GridRow<T> row = detail::grid_row(table, grid, j);
    if (!row.rough) {
      detail::affine_points(row.point, row.point_step, grid.width, p);
      even[j] = bilinear ? 1 : 0;
      continue;
    }
    for (int i = 0; i < grid.width; ++i) p[i] = table.point_of(grid.ray(i, j));
    even[j] = bilinear && evenly_spaced(p, w) ? 1 : 0;
  }
}

/// `prepare_plane_row` for row `j` of a tile whose rays are affine in the pixel: the origins,
/// directions and points of the row's `grid.width` pixels are evaluated between the exact rays of
/// its first and last pixels (no ray per pixel, no transposition), so they are evenly spaced by
/// construction (`even` is true for bilinear filtering and rows of at least 8 pixels). `slack`:
/// a bound on how far a crossing computed here may lie from the one of the pixel's exact ray
/// (in-plane world units; the rays' rounding, magnified by the distance to the array plane and
/// the slant), for proofs that must hold for the exact rays. A rough row (`detail::GridRow`) is
/// prepared from its exact rays by `prepare_plane_row` (slack 0). Precondition:
/// `scratch.reserve(grid.width)` succeeded, 0 <= j < grid.rows.
template <std::floating_point T, class Px, class ExactRay>
T prepare_plane_grid_row(const FrameTable<T, Px>& table, const ArrayPlane<T>& plane, const RayGrid<T, ExactRay>& grid,
                         int j, PlaneRowScratch<T>& scratch, bool& all_cross, bool& even, T& slack) noexcept {
  const std::size_t w = static_cast<std::size_t>(grid.width);
  const int n = grid.width;
  const detail::GridRow<T> row = detail::grid_row(table, grid, j);
  if (row.rough) { // the exact rays, as `prepare_plane_row` takes them
    thread_local std::vector<Ray<T>> rays;
    try {
      if (rays.size() < w) rays.resize(w);
    } catch (...) {
      all_cross = false; // the caller then takes the row ray by ray
      even = false;
      slack = std::numeric_limits<T>::infinity();
      return 0;
    }
    for (int i = 0; i < n; ++i) rays[static_cast<std::size_t>(i)] = grid.ray(i, j);
    slack = 0;
    return prepare_plane_row(table, plane, rays.data(), w, scratch, all_cross, even);
  }
  const Vec3<T> rel = row.first.origin - plane.point;
  const Vec3<T>& d = row.first.direction;
  const T first[6] = {rel.x(), rel.y(), rel.z(), d.x(), d.y(), d.z()};
  const T step[6] = {row.origin_step.x(),    row.origin_step.y(),    row.origin_step.z(),
                     row.direction_step.x(), row.direction_step.y(), row.direction_step.z()};
  T reach[6]; // per coordinate, a bound on the terms its evaluation a + i b over the row adds
  for (int k = 0; k < 6; ++k) reach[k] = std::abs(first[k]) + static_cast<T>(n - 1) * std::abs(step[k]);
  detail::affine_points(row.point, row.point_step, n, scratch.points.data());
  const detail::PlaneAxes<T> frame{plane.point.x(),  plane.point.y(),  plane.point.z(),  plane.normal.x(),
                                   plane.normal.y(), plane.normal.z(), plane.axis_u.x(), plane.axis_u.y(),
                                   plane.axis_u.z(), plane.axis_v.x(), plane.axis_v.y(), plane.axis_v.z()};
  detail::plane_rays_affine(first, step, w, frame, scratch.plane_rays(), scratch.cos2.data());
  unsigned crossing = 1;
  for (int i = 0; i < n; ++i) crossing &= scratch.ok[static_cast<std::size_t>(i)] != 0 ? 1u : 0u;
  all_cross = crossing != 0;
  // The crossings' largest in-plane coordinate: when every ray crosses, the crossings of an
  // evenly spaced row lie on a segment between those of its ends (a projective image of one).
  const std::size_t end = w - 1;
  const T span = std::max(
      {std::abs(scratch.xu[0]), std::abs(scratch.xv[0]), std::abs(scratch.xu[end]), std::abs(scratch.xv[end])});
  even = table.config().filter == PixelFilter::bilinear && w >= 8;
  const T cos_min = std::sqrt(std::min(T(1), detail::min_of(scratch.cos2.data(), w)));
  // How far an exact ray may lie from its evaluation here, per coordinate: its own rounding
  // against the grid's affine form, and that of the two anchors the row interpolates (2x the
  // grid's bound); this evaluation and the subtraction of the plane point (4 eps of the
  // magnitudes). A ray moved by e_o at its origin and e_d in its direction crosses the plane up
  // to (|e_o| + t |e_d|) / cos away (t |d| the distance to the crossing; 2-norms, sqrt(3) of the
  // per-coordinate bounds).
  constexpr T eps = std::numeric_limits<T>::epsilon();
  const T o_mag = std::max({reach[0], reach[1], reach[2]}), d_mag = std::max({reach[3], reach[4], reach[5]});
  const T e_origin = 2 * grid.origin_error + 4 * eps * (o_mag + plane.point.cwiseAbs().maxCoeff());
  const T e_direction = 2 * grid.direction_error + 4 * eps * d_mag;
  const T d_min =
      std::min(row.first.direction.cwiseAbs().maxCoeff(),
               Vec3<T>(row.first.direction + static_cast<T>(n - 1) * row.direction_step).cwiseAbs().maxCoeff());
  const T distance = T(1.5) * span + T(1.8) * o_mag; // from a ray's origin to its crossing, at most
  slack = d_min > 0 && cos_min > 0 ? T(1.8) * (e_origin + distance * e_direction / d_min) / cos_min
                                   : std::numeric_limits<T>::infinity();
  return cos_min;
}

/// The rows of a row path (`NearestCamera`, `CylinderAperture`) given as the rays of a tile,
/// `width` to a row: `prepare` fills the scratch for row r by `prepare_plane_row` (slack 0: the
/// crossings are the exact rays' own), `ray(r, i)` is the ray of pixel i of row r.
template <std::floating_point T, class Px>
struct TileRows {
  const FrameTable<T, Px>& table;
  const ArrayPlane<T>& plane;
  const Ray<T>* rays;
  std::size_t width;

  T prepare(std::size_t r, PlaneRowScratch<T>& scratch, bool& all_cross, bool& even, T& slack) const noexcept {
    slack = 0;
    return prepare_plane_row(table, plane, rays + r * width, width, scratch, all_cross, even);
  }
  [[nodiscard]] const Ray<T>& ray(std::size_t r, std::size_t i) const noexcept { return rays[r * width + i]; }
};

/// The rows of a row path given as a `RayGrid`: `prepare` by `prepare_plane_grid_row`, `ray(r,
/// i)` the renderer's exact ray.
template <std::floating_point T, class Px, class ExactRay>
struct GridRows {
  const FrameTable<T, Px>& table;
  const ArrayPlane<T>& plane;
  const RayGrid<T, ExactRay>& grid;

  T prepare(std::size_t r, PlaneRowScratch<T>& scratch, bool& all_cross, bool& even, T& slack) const noexcept {
    return prepare_plane_grid_row(table, plane, grid, static_cast<int>(r), scratch, all_cross, even, slack);
  }
  [[nodiscard]] Ray<T> ray(std::size_t r, std::size_t i) const noexcept {
    return grid.ray(static_cast<int>(i), static_cast<int>(r));
  }
};

} // namespace mpr
