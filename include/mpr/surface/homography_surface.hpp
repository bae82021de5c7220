#pragma once
/// \file
/// `mpr::HomographySurface`: an image plane sampled through a 3x3 homography of its uv, the
/// rectification used for multiperspective images by Yu & McMillan ("Multiperspective
/// Projection and Collineation", ICCV 2005), and `homography_from_unit_square`, which builds the
/// homography that makes a chosen quadrilateral of the plane fill the output.

#include <mpr/core/error.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <array>
#include <cmath>
#include <concepts>
#include <limits>

namespace mpr {

/// The homography H (3x3, acting on homogeneous uv) that maps the output's unit square to the
/// quadrilateral `quad` of plane uv: (0,0) -> quad[0], (1,0) -> quad[1], (1,1) -> quad[2],
/// (0,1) -> quad[3] (Heckbert, "Fundamentals of Texture Mapping and Image Warping", 1989,
/// sec. 2.2.3). Throws `argument_error("quad", ...)` for non-finite corners or a quadrilateral
/// that is not strictly convex (three corners collinear, a fold or a self-intersection).
template <std::floating_point T>
[[nodiscard]] Mat3<T> homography_from_unit_square(const std::array<Vec2<T>, 4>& quad) {
  for (const Vec2<T>& q : quad)
    if (!q.allFinite()) throw argument_error("quad", "corner not finite");
  // Strict convexity: every consecutive corner triple turns the same way, by a margin.
  T size = 0;
  for (std::size_t i = 0; i < 4; ++i) size = std::max(size, (quad[(i + 1) % 4] - quad[i]).norm());
  int sign = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec2<T> a = quad[(i + 1) % 4] - quad[i], b = quad[(i + 2) % 4] - quad[(i + 1) % 4];
    const T turn = a.x() * b.y() - a.y() * b.x();
    if (!(std::abs(turn) > T(1e-9) * size * size)) throw argument_error("quad", "degenerate (collinear corners)");
    const int s = turn > 0 ? 1 : -1;
    if (sign != 0 && s != sign) throw argument_error("quad", "not convex");
    sign = s;
  }
  const Vec2<T> d1 = quad[1] - quad[2], d2 = quad[3] - quad[2];
  const Vec2<T> sum = quad[0] - quad[1] + quad[2] - quad[3];
  const T den = d1.x() * d2.y() - d1.y() * d2.x();
  const T g = (sum.x() * d2.y() - sum.y() * d2.x()) / den;
  const T h = (d1.x() * sum.y() - d1.y() * sum.x()) / den;
  Mat3<T> H;
  H << quad[1].x() - quad[0].x() + g * quad[1].x(), quad[3].x() - quad[0].x() + h * quad[3].x(), quad[0].x(),
      quad[1].y() - quad[0].y() + g * quad[1].y(), quad[3].y() - quad[0].y() + h * quad[3].y(), quad[0].y(), g, h, T(1);
  return H;
}

/// A `PlanarSurface` whose uv is first mapped by a homography:
/// `point_at(uv) = plane.point_at(warp(uv))`, `warp(uv) = (H (u, v, 1))` dehomogenised.
/// Satisfies `mpr::ImageSurface`. A GLC selector must be evaluated at `warp(uv)` too (see
/// `mpr::glc::rectify`), since a homography of the image is not affine.
template <std::floating_point T>
class HomographySurface {
public:
  using scalar_type = T;

  /// Throws `argument_error("homography", ...)` when H is not finite, singular, or sends part of
  /// the unit square to infinity (its third row changes sign or vanishes on [0,1]^2).
  HomographySurface(const PlanarSurface<T>& plane, const Mat3<T>& homography) : plane_(plane), h_(homography) {
    if (!homography.allFinite()) throw argument_error("homography", "not finite");
    const T det = homography.determinant();
    if (!(std::abs(det) > 1024 * std::numeric_limits<T>::epsilon() * std::pow(homography.norm(), T(3))))
      throw argument_error("homography", "singular");
    // w is affine in uv, so its sign on the square is decided at the corners.
    int sign = 0;
    for (const T u : {T(0), T(1)})
      for (const T v : {T(0), T(1)}) {
        const T w = homography(2, 0) * u + homography(2, 1) * v + homography(2, 2);
        const T bound = 64 * std::numeric_limits<T>::epsilon() * homography.row(2).cwiseAbs().sum();
        if (!(std::abs(w) > bound)) throw argument_error("homography", "maps part of the image to infinity");
        const int s = w > 0 ? 1 : -1;
        if (sign != 0 && s != sign) throw argument_error("homography", "maps part of the image to infinity");
        sign = s;
      }
  }

  /// The plane uv shown at output uv.
  [[nodiscard]] Vec2<T> warp(const Vec2<T>& uv) const noexcept {
    const Vec3<T> p = h_ * Vec3<T>(uv.x(), uv.y(), T(1));
    return {p.x() / p.z(), p.y() / p.z()};
  }

  [[nodiscard]] Vec3<T> point_at(const Vec2<T>& uv) const noexcept { return plane_.point_at(warp(uv)); }

  [[nodiscard]] const PlanarSurface<T>& plane() const noexcept { return plane_; }
  [[nodiscard]] const Mat3<T>& homography() const noexcept { return h_; }

private:
  PlanarSurface<T> plane_;
  Mat3<T> h_;
};

} // namespace mpr
