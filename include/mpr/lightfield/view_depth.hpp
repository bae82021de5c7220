#pragma once
/// \file
/// `mpr::FrameDepthSampler<T, Px>`: the depth of any view of a light field, the light-field
/// counterpart of the scene sampler's `HitDepth` output. Each ray is answered with where the
/// surface that the cameras' depth maps describe meets it -- the surface point `DepthProxy` finds
/// and blends the cameras at -- as a `float`, +inf where no camera's depth map shows a surface
/// along the ray. Rendered like any sampler (into an `Image<float>`), it gives the depth map of
/// any GLC view, tilted plane or rectified view; its value under one pixel is the focal depth
/// that brings that pixel into focus (autofocus).
///
/// Example (the depth of the reference view of a light field with depth maps, along the
/// reference camera's axis, i.e. in the units of the focal depth):
///
///     const mpr::FrameDepthSampler<float> depth =
///         mpr::FrameDepthSampler<float>(frames).along_axis(reference);
///     mpr::Image<float> map(w, h);
///     mpr::Renderer(plane, mpr::pinhole_glc(reference, plane), depth).render(map.view(), {0, 0, w, h});

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/depth_proxy.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/frame_table.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <utility>

namespace mpr {

/// Answers each ray with the depth of the surface point the depth maps give it (see the file
/// comment).
///
/// Output: by default the ray parameter t of the point `DepthProxy::surface` finds -- the
/// convention of `HitDepth`: with a GLC ray (direction of unit normal component) t is the signed
/// distance of the point in front of the view's image plane, negative for a point between the
/// cameras and a focal plane inside the scene. After `along_axis(camera)`: the depth of the point
/// along that camera's optical axis (`camera.R() X + camera.t()`, third coordinate), the
/// convention of the depth maps and of a light field's focal depth. +inf where the search finds
/// no surface (the ray leaves every tried camera's view, or every such camera saw nothing there).
///
/// Requirements: the frame set carries depth maps (throws otherwise, as `DepthProxy`). The
/// search is `DepthProxy`'s (its radius, march cameras, tolerance and `whole_line` apply); the
/// blend is skipped. Copies share the table (`shared_ptr`), so the sampler is cheap to copy into
/// a `Renderer`. Its batch path (`sample_rays`) walks sixteen rays at a time where
/// `DepthProxy::sample_rays` does.
template <std::floating_point T, class Px = Rgb8>
class FrameDepthSampler {
public:
  using scalar_type = T;
  using color_type = float;
  using table_type = FrameTable<T, Px>;
  using frame_set_type = CameraFrameSet<T, Px>;

  /// Over an existing table (e.g. `CameraFrameSampler::shared_table()`, or the rasterized-scene
  /// sampler's `frame_sampler().shared_table()`). Throws `argument_error` naming "table" (null)
  /// or what `DepthProxy::validate` names ("radius", ..., "depth maps" when there are none).
  explicit FrameDepthSampler(std::shared_ptr<const table_type> table, DepthProxy proxy = {})
      : table_(std::move(table)), proxy_(proxy) {
    if (!table_) throw argument_error("table", "null");
    proxy_.validate();
    proxy_.validate(*table_);
  }

  /// Over a frame set (a table with the default `FrameSamplerConfig` is built). Throws as above,
  /// and `argument_error` ("frames") for a null or empty set.
  explicit FrameDepthSampler(std::shared_ptr<const frame_set_type> frames, DepthProxy proxy = {})
      : FrameDepthSampler(std::make_shared<const table_type>(std::move(frames)), proxy) {}

  /// A copy that answers the depth along `camera`'s optical axis instead of the ray parameter.
  [[nodiscard]] FrameDepthSampler along_axis(const PinholeCamera<T>& camera) const {
    FrameDepthSampler out = *this;
    out.axis_ = Axis{Vec3<T>(camera.R().row(2).transpose()), camera.t().z()};
    return out;
  }

  [[nodiscard]] const table_type& table() const noexcept { return *table_; }
  [[nodiscard]] const DepthProxy& proxy() const noexcept { return proxy_; }

  /// The depth along `ray` (see the class comment), never NaN for a finite ray.
  [[nodiscard]] float sample(const Ray<T>& ray) const noexcept { return depth_of(ray, proxy_.surface(*table_, ray)); }

  /// `out[i] = sample(rays[i])` for every i (precondition: equal lengths): the depth proxy's
  /// batch surface search (`DepthProxy::surface_rays`), 64 rays at a time.
  void sample_rays(std::span<const Ray<T>> rays, std::span<float> out) const noexcept {
    std::optional<T> t[64];
    for (std::size_t s = 0; s < rays.size(); s += 64) {
      const std::size_t n = std::min<std::size_t>(64, rays.size() - s);
      proxy_.surface_rays(*table_, rays.subspan(s, n), std::span<std::optional<T>>(t, n));
      for (std::size_t i = 0; i < n; ++i) out[s + i] = depth_of(rays[s + i], t[i]);
    }
  }

private:
  [[nodiscard]] float depth_of(const Ray<T>& ray, const std::optional<T>& t) const noexcept {
    if (!t) return std::numeric_limits<float>::infinity();
    if (!axis_) return static_cast<float>(*t);
    const Vec3<T> X = ray.at(*t);
    const T depth = axis_->row.dot(X) + axis_->offset;
    if (!std::isnan(depth)) return static_cast<float>(depth);
    // A point beyond the scalar's range (a map of FLT_MAX depths): X holds an infinity that a
    // zero of the axis row multiplies. The depth along the axis is linear in t instead; NaN only
    // for an infinite t along a ray parallel to the image plane, where no depth is defined.
    const T linear = (axis_->row.dot(ray.origin) + axis_->offset) + *t * axis_->row.dot(ray.direction);
    return std::isnan(linear) ? std::numeric_limits<float>::infinity() : static_cast<float>(linear);
  }

  struct Axis {
    Vec3<T> row; ///< third row of the camera's R
    T offset;    ///< third coordinate of its t
  };
  std::shared_ptr<const table_type> table_;
  DepthProxy proxy_;
  std::optional<Axis> axis_;
};

} // namespace mpr
