#pragma once
/// \file
/// `mpr::pinhole_glc(camera, plane)`: the General Linear Camera of a pinhole camera on an image
/// plane -- the bridge from the camera model to the ray selector, kept apart so that
/// `PinholeCamera` itself does not depend on the selector.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/selector/glc_selector.hpp>
#include <mpr/surface/planar_surface.hpp>

namespace mpr {

/// The GLC whose corner rays run from the camera centre through the plane's corners (a
/// perspective GLC with its centre at `camera.centre()`); with `camera.image_plane(depth)` it
/// shows exactly the camera's pixels. Distortion is ignored.
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> pinhole_glc(const PinholeCamera<T>& camera, const PlanarSurface<T>& plane) {
  const Vec3<T>& c = camera.centre();
  return GlcSelector<T>(plane, Vec3<T>(plane.point_at({0, 0}) - c), Vec3<T>(plane.point_at({1, 0}) - c),
                        Vec3<T>(plane.point_at({0, 1}) - c));
}

} // namespace mpr
