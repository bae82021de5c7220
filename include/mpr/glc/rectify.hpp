#pragma once
/// \file
/// Rectification of GLC images: steep or twisted rays push the useful part of a GLC image off
/// the image plane's rectangle; Yu & McMillan ("Multiperspective Projection and Collineation",
/// ICCV 2005) resample the image plane through a homography so that a chosen target region
/// fills the output again. Here: the selector that evaluates the GLC at the warped uv, the target
/// region of a scene quadrilateral, and `rectify`, which puts the pieces together.

#include <mpr/core/error.hpp>
#include <mpr/core/pixel.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/glc/project.hpp>
#include <mpr/selector/glc_selector.hpp>
#include <mpr/surface/homography_surface.hpp>

#include <array>
#include <concepts>
#include <optional>
#include <string>
#include <type_traits>

namespace mpr::glc {

/// A `GlcSelector` read through a homography of uv: `ray_at(px, uv, point)` is the GLC ray at
/// plane uv `H(uv)`. Pair it with the `HomographySurface` of the same H (then `point` is that
/// ray's start); `rectify` does.
template <std::floating_point T>
class RectifiedSelector {
public:
  using scalar_type = T;
  /// Throws like `HomographySurface` for a bad homography.
  RectifiedSelector(const GlcSelector<T>& selector, const Mat3<T>& homography) : selector_(selector), h_(homography) {
    if (!homography.allFinite()) throw argument_error("homography", "not finite");
  }
  [[nodiscard]] Ray<T> ray_at(Pixel px, const Vec2<T>& uv, const Vec3<T>& point) const noexcept {
    const Vec3<T> p = h_ * Vec3<T>(uv.x(), uv.y(), T(1));
    return selector_.ray_at(px, Vec2<T>(p.x() / p.z(), p.y() / p.z()), point);
  }
  [[nodiscard]] const GlcSelector<T>& selector() const noexcept { return selector_; }

private:
  GlcSelector<T> selector_;
  Mat3<T> h_;
};

/// A rectified GLC view: render it as `Renderer(r.surface, r.selector, sampler)`.
template <std::floating_point T>
struct Rectified {
  HomographySurface<T> surface;
  RectifiedSelector<T> selector;
};

/// The rectified view of (`plane`, `selector`) in which the plane-uv quadrilateral `target`
/// (corners in the order top-left, top-right, bottom-right, bottom-left of the output) fills the
/// output. Throws `argument_error("quad", ...)` for a non-convex target.
template <std::floating_point T>
[[nodiscard]] Rectified<T> rectify(const PlanarSurface<T>& plane, const GlcSelector<T>& selector,
                                   const std::array<Vec2<T>, 4>& target) {
  const Mat3<T> h = homography_from_unit_square(target);
  return {HomographySurface<T>(plane, h), RectifiedSelector<T>(selector, h)};
}

/// The plane-uv quadrilateral in which the camera shows the world quadrilateral `corners`
/// (projected corner by corner with `project`). Throws `argument_error("corners", ...)` when a
/// corner is seen by no ray or lies behind the image plane.
template <std::floating_point T>
[[nodiscard]] std::array<Vec2<T>, 4> target_region(const PlanarSurface<T>& plane, const GlcSelector<T>& selector,
                                                   const std::array<Vec3<T>, 4>& corners) {
  const TwoPlane<T> glc = two_plane(plane, selector);
  std::array<Vec2<T>, 4> out;
  for (std::size_t k = 0; k < 4; ++k) {
    if (glc.to_frame(corners[k]).z() <= 0)
      throw argument_error("corners", "corner " + std::to_string(k) + " lies behind the image plane");
    const std::optional<Vec2<T>> uv = project(glc, corners[k], Vec2<T>(T(0.5), T(0.5)));
    if (!uv) throw argument_error("corners", "corner " + std::to_string(k) + " is seen by no ray of the camera");
    out[k] = *uv;
  }
  return out;
}

} // namespace mpr::glc
