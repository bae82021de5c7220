#pragma once
/// \file
/// GLC views of a camera array in two-plane terms. On a light field, a General Linear Camera is
/// a linear 2-D family of the array's rays: each ray joins a point of the focal plane (the image
/// surface, where the sampler takes colour) to a point of the camera plane, the two affine in the
/// image coordinates uv (the two-plane parametrisation of Yu & McMillan, "General Linear
/// Cameras", ECCV 2004, sec. 3). A ray whose camera-plane crossing lies outside the array has no
/// camera behind it: the interpolation answers it from the edge cameras (or not at all).
///
/// `ArrayFootprint` is where the cameras lie (`array_footprint`), `fit_to_array` maps any GLC on
/// the focal plane to the GLC with the same focal-plane points whose camera-plane crossings span
/// the array, and `array_coverage` measures how much of a view's ray field falls inside.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/pixel.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/selector/glc_selector.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

namespace mpr {

/// Where the cameras of an array lie, as a GLC view of its light field needs it: the camera
/// plane and the bounding rectangle of the camera centres in it (world frame, world units).
template <std::floating_point T>
struct ArrayFootprint {
  Vec3<T> centre = Vec3<T>::Zero();  ///< centre of the rectangle, on the plane
  Vec3<T> normal = Vec3<T>::UnitZ(); ///< unit normal of the camera plane
  Vec3<T> axis_u = Vec3<T>::UnitX(); ///< unit in-plane axis along the reference image's rows
  Vec3<T> axis_v = Vec3<T>::UnitY(); ///< unit in-plane axis, `normal` x `axis_u`
  T half_u = 0;                      ///< half size of the rectangle along `axis_u`, >= 0
  T half_v = 0;                      ///< half size of the rectangle along `axis_v`, >= 0
  T spacing = 0;                     ///< median distance from a camera to its nearest neighbour
  std::size_t cameras = 0;           ///< cameras in the footprint
  bool planar = true;                ///< false: a ring or unstructured set projected on the plane

  /// True when the cameras lie (nearly) on a line or a ring seen edge-on: the shorter side of the
  /// rectangle is under 5% of the longer one. Such an array samples a 3-D subset of the rays, so
  /// every view of it passes through the camera line.
  [[nodiscard]] bool one_dimensional() const noexcept {
    return std::min(half_u, half_v) <= T(0.05) * std::max(half_u, half_v);
  }

  /// The world point at in-plane coordinates `st` (along `axis_u`, `axis_v`, from `centre`).
  [[nodiscard]] Vec3<T> point(const Vec2<T>& st) const noexcept {
    return Vec3<T>(centre + st.x() * axis_u + st.y() * axis_v);
  }

  /// In-plane coordinates where the *line* of `ray` meets the camera plane; nullopt when the ray
  /// is parallel to the plane (within about 0.06 degrees) or the crossing is not finite.
  [[nodiscard]] std::optional<Vec2<T>> crossing(const Ray<T>& ray) const noexcept {
    const T dn = ray.direction.dot(normal);
    if (!(std::abs(dn) > T(1e-3) * ray.direction.norm())) return std::nullopt;
    const Vec3<T> x = ray.origin + ((centre - ray.origin).dot(normal) / dn) * ray.direction;
    const Vec2<T> st((x - centre).dot(axis_u), (x - centre).dot(axis_v));
    if (!st.allFinite()) return std::nullopt;
    return st;
  }

  /// True when `st` lies in the rectangle grown by `margin` world units on every side.
  [[nodiscard]] bool contains(const Vec2<T>& st, T margin) const noexcept {
    return std::abs(st.x()) <= half_u + margin && std::abs(st.y()) <= half_v + margin;
  }
};

/// The footprint of `frames` as views from `reference` (a camera of the set or a virtual one at
/// the array centre) see it. A planar array (`frames.array_plane()` set by its loader) keeps its
/// plane and all its cameras. Otherwise (a ring such as the Middlebury sets, or any unstructured
/// set) the camera plane is the plane through `reference.centre()` perpendicular to its optical
/// axis, and the cameras are those looking within 60 degrees of the reference's direction,
/// projected onto it. `axis_u` follows the reference image's rows. Throws `argument_error`
/// ("frames") for an empty set or when no camera looks within 60 degrees of the reference.
template <std::floating_point T, class Px>
[[nodiscard]] ArrayFootprint<T> array_footprint(const CameraFrameSet<T, Px>& frames,
                                                const PinholeCamera<T>& reference) {
  if (frames.size() == 0) throw argument_error("frames", "no cameras");
  ArrayFootprint<T> f;
  f.planar = frames.array_plane().has_value();
  const Vec3<T> forward = reference.forward();
  f.normal = f.planar ? Vec3<T>(frames.array_plane()->normal.normalized()) : forward;
  if (f.normal.dot(forward) < 0) f.normal = -f.normal;
  const Vec3<T> origin = f.planar ? frames.array_plane()->point : reference.centre();
  // The reference image's row direction, projected onto the plane (else any in-plane axis).
  Vec3<T> row = reference.R().row(0).transpose();
  row -= row.dot(f.normal) * f.normal;
  if (!(row.norm() > T(1e-3))) row = f.normal.unitOrthogonal();
  f.axis_u = row.normalized();
  f.axis_v = f.normal.cross(f.axis_u);
  std::vector<Vec2<T>> st;
  const T cos_limit = T(0.5); // 60 degrees
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const PinholeCamera<T>& c = frames.camera(i);
    if (!f.planar && c.forward().dot(forward) < cos_limit) continue;
    const Vec3<T> p = c.centre() - origin;
    st.emplace_back(p.dot(f.axis_u), p.dot(f.axis_v));
  }
  if (st.empty()) throw argument_error("frames", "no camera looks within 60 degrees of the reference camera");
  Vec2<T> lo = st.front(), hi = st.front();
  for (const Vec2<T>& p : st) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec2<T> mid = T(0.5) * (lo + hi);
  f.centre = Vec3<T>(origin + mid.x() * f.axis_u + mid.y() * f.axis_v);
  f.half_u = T(0.5) * (hi.x() - lo.x());
  f.half_v = T(0.5) * (hi.y() - lo.y());
  f.cameras = st.size();
  // Median nearest-neighbour distance in the plane (quadratic: arrays have at most thousands).
  std::vector<T> nearest;
  for (std::size_t i = 0; i < st.size(); ++i) {
    T best = std::numeric_limits<T>::infinity();
    for (std::size_t j = 0; j < st.size(); ++j)
      if (j != i && (st[j] - st[i]).norm() > 0) best = std::min(best, (st[j] - st[i]).norm());
    if (std::isfinite(best)) nearest.push_back(best);
  }
  if (!nearest.empty()) {
    std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2), nearest.end());
    f.spacing = nearest[nearest.size() / 2];
  }
  return f;
}

/// The GLC view of a light field that `prototype` (any GLC on the focal plane `focal`) stands
/// for: the same focal-plane points, with camera-plane crossings rescaled so that they span the
/// array. The prototype's crossings at the image corners are extended to an affine map of uv;
/// that map, taken relative to the foot of the focal-plane centre on the camera plane, is moved
/// to the array centre and scaled by one factor (keeping its shape and its offset, so an oblique
/// prototype looks from one side) until pattern and offset reach `fill` of the array's rectangle. On a one-dimensional
/// array (a line or a ring) the crossings are put on the camera line. The result's ray at uv runs from that crossing
/// through `focal.point_at(uv)`, so ray-dependent interpolations (nearest camera, cylinder
/// aperture) see the view; when the prototype's crossings are all one point, every ray passes
/// through the array centre (a pinhole there).
///
/// Scaling the crossings keeps pinholes, cross-slits, pencils and bilinear cameras of their type
/// but turns rays that were parallel along a direction (orthographic, pushbroom, twisted
/// orthographic views) into converging ones: parallel rays a view wide cannot all meet an array
/// narrower than the view. `glc::classify` of the result names what the view now is.
/// Preconditions: `fill` in (0, 1]. Throws `argument_error` ("fill"; "view" when a corner ray of
/// the prototype runs parallel to the camera plane).
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> fit_to_array(const PlanarSurface<T>& focal, const GlcSelector<T>& prototype,
                                          const ArrayFootprint<T>& array, T fill = T(0.9)) {
  if (!(fill > 0 && fill <= 1)) throw argument_error("fill", "must be in (0, 1]");
  const std::array<Vec2<T>, 3> corners{Vec2<T>(0, 0), Vec2<T>(1, 0), Vec2<T>(0, 1)};
  std::array<Vec2<T>, 4> c;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::optional<Vec2<T>> x =
        array.crossing(Ray<T>{focal.point_at(corners[i]), prototype.direction_at(corners[i])});
    if (!x) throw argument_error("view", "a corner ray runs parallel to the camera plane");
    c[i] = *x;
  }
  c[3] = c[1] + c[2] - c[0]; // the affine map's (1, 1) corner
  Vec2<T> lo = c[0], hi = c[0];
  for (const Vec2<T>& p : c) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // The pattern's offset from the foot of the focal-plane centre on the camera plane: an oblique
  // prototype looks from one side, and so does its fitted view.
  const Vec3<T> foot = focal.centre() - array.centre;
  const Vec2<T> mid = T(0.5) * (lo + hi), half = T(0.5) * (hi - lo);
  const Vec2<T> offset = mid - Vec2<T>(foot.dot(array.axis_u), foot.dot(array.axis_v));
  const bool line = array.one_dimensional();
  const bool along_u = array.half_u >= array.half_v;
  // One scale for both axes, the largest that keeps pattern and offset within the array; an axis
  // the crossings neither spread nor move along does not limit it.
  const T tiny = T(1e-9) * std::max({array.half_u, array.half_v, array.spacing, T(1)});
  const Vec2<T> reach(half.x() + std::abs(offset.x()), half.y() + std::abs(offset.y()));
  T k = std::numeric_limits<T>::infinity();
  if (reach.x() > tiny && (!line || along_u)) k = std::min(k, array.half_u / reach.x());
  if (reach.y() > tiny && (!line || !along_u)) k = std::min(k, array.half_v / reach.y());
  if (!std::isfinite(k)) k = 0; // every crossing one point (or across a line array): its centre
  k *= fill;
  std::array<Vec3<T>, 3> d;
  for (std::size_t i = 0; i < 3; ++i) {
    Vec2<T> s = k * (c[i] - mid + offset);
    if (line) (along_u ? s.y() : s.x()) = 0;
    const Vec3<T> p = focal.point_at(corners[i]);
    d[i] = p - array.point(s);
    // Keep the prototype's side of the image plane (the side the scene is on).
    if (d[i].dot(focal.normal()) * prototype.direction_at(corners[i]).dot(focal.normal()) < 0) d[i] = -d[i];
  }
  return GlcSelector<T>(focal, d[0], d[1], d[2]);
}

/// How a view's rays meet an array (see `array_coverage`).
struct ArrayCoverage {
  double outside = 0; ///< share of the rays crossing the camera plane off the array (or parallel to it)
  double span_u = 0;  ///< extent of the crossings along `axis_u` over the array's extent (1: edge to edge)
  double span_v = 0;  ///< the same along `axis_v` (0 on a one-dimensional array's short side)
};

/// The coverage of the array by the rays of a view (any image surface and ray selector) over a
/// `samples` x `samples` grid of uv cell centres. A ray counts as outside when its line meets
/// the camera plane farther than half the camera spacing beyond the rectangle of centres, i.e.
/// where no camera lies nearer to it than an edge camera. Preconditions: `samples` >= 2.
template <class Surface, class Selector, std::floating_point T>
[[nodiscard]] ArrayCoverage array_coverage(const Surface& surface, const Selector& selector,
                                           const ArrayFootprint<T>& array, int samples = 48) {
  samples = std::max(samples, 2);
  const T margin = T(0.5) * array.spacing;
  std::size_t outside = 0;
  Vec2<T> lo = Vec2<T>::Constant(std::numeric_limits<T>::infinity()), hi = -lo;
  for (int j = 0; j < samples; ++j)
    for (int i = 0; i < samples; ++i) {
      const Vec2<T> uv((T(i) + T(0.5)) / T(samples), (T(j) + T(0.5)) / T(samples));
      const std::optional<Vec2<T>> x = array.crossing(selector.ray_at(Pixel{i, j}, uv, surface.point_at(uv)));
      if (!x || !array.contains(*x, margin)) {
        ++outside;
        continue;
      }
      lo = lo.cwiseMin(*x);
      hi = hi.cwiseMax(*x);
    }
  ArrayCoverage out;
  out.outside = static_cast<double>(outside) / (static_cast<double>(samples) * samples);
  if (lo.x() <= hi.x()) {
    const auto share = [](T span, T half) {
      return half > 0 ? std::min(1.0, static_cast<double>(span / (2 * half))) : 0.0;
    };
    out.span_u = share(hi.x() - lo.x(), array.half_u);
    out.span_v = share(hi.y() - lo.y(), array.half_v);
  }
  return out;
}

} // namespace mpr
