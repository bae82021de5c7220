#pragma once
// A linear render for the writers' round-trip tests: a cross-slit GLC view whose sampler's colour
// is an affine function of the ray, so the image spans values below 0, inside [0, 1] and above
// 1 (which only the float formats keep), rendered with mpr::Renderer in the scalar type T.

#include <mpr/mpr.hpp>

namespace mpr_test {

/// Colour (0.6 dx + 0.5, 2 dy + 0.3 ox, 0.2 + 4 oy) of a ray with origin o and direction d.
template <std::floating_point T>
struct AffineRayColour {
  using scalar_type = T;
  mpr::Color sample(const mpr::Ray<T>& r) const noexcept {
    return mpr::Color(static_cast<float>(0.6 * r.direction.x() + 0.5),
                      static_cast<float>(2 * r.direction.y() + 0.3 * r.origin.x()),
                      static_cast<float>(0.2 + 4 * r.origin.y()));
  }
};

/// The render of AffineRayColour through a cross-slit view, `width` x `height` pixels.
template <std::floating_point T>
mpr::Image<mpr::Color> linear_render(int width = 24, int height = 16) {
  const mpr::PlanarSurface<T> plane({-1, -0.75, 1}, {2, 0, 0}, {0, 1.5, 0});
  const mpr::GlcSelector<T> xslit(plane, {-0.5, -0.1, 1}, {0.5, -0.1, 1}, {-0.5, 0.3, 1});
  mpr::Image<mpr::Color> image(width, height);
  mpr::Renderer(plane, xslit, AffineRayColour<T>{}).render(image.view(), mpr::Region(0, 0, width, height), {1});
  return image;
}

} // namespace mpr_test
