#pragma once
/// \file
/// One output row of rays seen from the plane of a planar camera array: where each ray crosses
/// the plane (in-plane coordinates, structure of arrays, vectorised), the least cosine to the
/// normal, and whether the row's points are evenly spaced. The row paths of `NearestCamera` and
/// `CylinderAperture` start here, from the rays of a row or from a `RayGrid`.

#include <mpr/core/ray_grid.hpp>
#include <mpr/lightfield/array_plane.hpp>
#include <mpr/lightfield/detail/kernels.hpp>
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

/// The points (`FrameTable::point_of`) of every pixel of a `RayGrid`, row-major, from the grid's
/// affine form: `ray.at(depth)` or the origin, evenly spaced along each row.
template <std::floating_point T, class Px, class ExactRay>
void fill_grid_points(const FrameTable<T, Px>& table, const RayGrid<T, ExactRay>& grid, Vec3<T>* points) noexcept {
  const std::optional<T>& depth = table.config().depth;
  const Vec3<T> dx = depth ? Vec3<T>(grid.origin_dx + *depth * grid.direction_dx) : grid.origin_dx;
  const Vec3<T> dy = depth ? Vec3<T>(grid.origin_dy + *depth * grid.direction_dy) : grid.origin_dy;
  const Vec3<T> p0 = depth ? Vec3<T>(grid.origin + *depth * grid.direction) : grid.origin;
  for (int j = 0; j < grid.rows; ++j) {
    const T row = static_cast<T>(j);
    const Vec3<T> p(p0.x() + row * dy.x(), p0.y() + row * dy.y(), p0.z() + row * dy.z());
    Vec3<T>* q = points + static_cast<std::size_t>(j) * static_cast<std::size_t>(grid.width);
    for (int i = 0; i < grid.width; ++i) {
      const T t = static_cast<T>(i);
      q[i] = Vec3<T>(p.x() + t * dx.x(), p.y() + t * dx.y(), p.z() + t * dx.z());
    }
  }
}

/// `prepare_plane_row` for row `j` of a tile whose rays are affine in the pixel: the origins,
/// directions and points of the row's `grid.width` pixels are evaluated from the grid (no ray
/// per pixel, no transposition), so they are evenly spaced by construction (`even` is true for
/// bilinear filtering and rows of at least 8 pixels). Precondition: `scratch.reserve(grid.width)`
/// succeeded, 0 <= j < grid.rows.
template <std::floating_point T, class Px, class ExactRay>
T prepare_plane_grid_row(const FrameTable<T, Px>& table, const ArrayPlane<T>& plane, const RayGrid<T, ExactRay>& grid,
                         int j, PlaneRowScratch<T>& scratch, bool& all_cross, bool& even) noexcept {
  const std::size_t w = static_cast<std::size_t>(grid.width);
  const T row = static_cast<T>(j);
  const Vec3<T> o = grid.origin + row * grid.origin_dy;
  const Vec3<T> d = grid.direction + row * grid.direction_dy;
  const Vec3<T> rel = o - plane.point;
  const T first[6] = {rel.x(), rel.y(), rel.z(), d.x(), d.y(), d.z()};
  const T step[6] = {grid.origin_dx.x(),    grid.origin_dx.y(),    grid.origin_dx.z(),
                     grid.direction_dx.x(), grid.direction_dx.y(), grid.direction_dx.z()};
  // (int indices: their conversion to T vectorises, a size_t's does not.)
  const int n = grid.width;
  for (int k = 0; k < 6; ++k) {
    T* q = scratch.soa[k].data();
    const T a = first[k], b = step[k];
    for (int i = 0; i < n; ++i) q[i] = a + static_cast<T>(i) * b;
  }
  const std::optional<T>& depth = table.config().depth;
  const Vec3<T> p = depth ? Vec3<T>(o + *depth * d) : o;
  const Vec3<T> dp = depth ? Vec3<T>(grid.origin_dx + *depth * grid.direction_dx) : grid.origin_dx;
  Vec3<T>* points = scratch.points.data();
  for (int i = 0; i < n; ++i) {
    const T t = static_cast<T>(i);
    points[i] = Vec3<T>(p.x() + t * dp.x(), p.y() + t * dp.y(), p.z() + t * dp.z());
  }
  const detail::PlaneAxes<T> frame{plane.point.x(),  plane.point.y(),  plane.point.z(),  plane.normal.x(),
                                   plane.normal.y(), plane.normal.z(), plane.axis_u.x(), plane.axis_u.y(),
                                   plane.axis_u.z(), plane.axis_v.x(), plane.axis_v.y(), plane.axis_v.z()};
  const T* const soa_in[6] = {scratch.soa[0].data(), scratch.soa[1].data(), scratch.soa[2].data(),
                              scratch.soa[3].data(), scratch.soa[4].data(), scratch.soa[5].data()};
  detail::plane_rays(soa_in, w, frame, scratch.plane_rays(), scratch.cos2.data());
  unsigned crossing = 1;
  for (int i = 0; i < n; ++i) crossing &= scratch.ok[static_cast<std::size_t>(i)] != 0 ? 1u : 0u;
  all_cross = crossing != 0;
  even = table.config().filter == PixelFilter::bilinear && w >= 8;
  return std::sqrt(std::min(T(1), detail::min_of(scratch.cos2.data(), w)));
}

} // namespace mpr
