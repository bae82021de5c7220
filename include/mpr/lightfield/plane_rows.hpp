#pragma once
/// \file
/// One output row of rays seen from the plane of a planar camera array: where each ray crosses
/// the plane (in-plane coordinates, structure of arrays, vectorised), the least cosine to the
/// normal, and whether the row's points are evenly spaced. The row paths of `NearestCamera` and
/// `CylinderAperture` start here.

#include <mpr/lightfield/array_plane.hpp>
#include <mpr/lightfield/detail/kernels.hpp>
#include <mpr/lightfield/frame_runs.hpp>
#include <mpr/lightfield/frame_table.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace mpr {

/// Per-thread working memory of the row paths, sized for one output row.
template <std::floating_point T>
struct PlaneRowScratch {
  using Flag = typename detail::PlaneRays<T>::Flag;
  std::vector<Vec3<T>> points;
  std::vector<float> acc, weight, ray_weight;
  std::vector<int> camera;
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
        camera.resize(w);
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

} // namespace mpr
