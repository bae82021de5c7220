#pragma once
/// \file
/// The nine views of the classic GLC gallery (Yu & McMillan, "General Linear Cameras", ECCV 2004,
/// Fig. 6), all on one image plane: (A) perspective, (B) orthographic, (C) oblique orthographic,
/// (D) pushbroom, (E) twisted orthographic, (F) twisted orthographic looking down, (G) cross-slit,
/// (H) pencil, (I) bilinear.

#include <mpr/core/error.hpp>
#include <mpr/glc/cameras.hpp>
#include <mpr/glc/classify.hpp>

#include <array>
#include <cmath>
#include <concepts>
#include <string>
#include <string_view>
#include <type_traits>

namespace mpr::glc {

/// One gallery entry: its letter, a short name and the GLC type the view has.
struct GalleryEntry {
  char id;
  std::string_view name;
  Type type;
};

/// The nine gallery views, A to I.
inline constexpr std::array<GalleryEntry, 9> gallery{{
    {'A', "perspective", Type::pinhole},
    {'B', "orthographic", Type::orthographic},
    {'C', "oblique orthographic", Type::orthographic},
    {'D', "pushbroom", Type::pushbroom},
    {'E', "twisted orthographic", Type::twisted_orthographic},
    {'F', "twisted orthographic, looking down", Type::twisted_orthographic},
    {'G', "cross-slit", Type::cross_slit},
    {'H', "pencil", Type::pencil},
    {'I', "bilinear", Type::bilinear},
}};

/// Gallery view `id` ('A'..'I', case-insensitive) on `plane`, looking at a scene of size `scale`
/// (world units) centred at `scene_centre`, which must lie in front of the plane (positive
/// depth along `plane.normal()`).
///
/// Every view looks along the axis a from the plane centre to `scene_centre`. The pinhole (A)
/// sits on that axis, behind the plane, at the distance e that makes about 1.2 * `scale` fill the
/// image width at the scene's depth (e = depth of the scene when the plane is already wider than
/// that). The others derive from it: (B) rays along a; (C) a tilted by atan(0.6) towards +u and
/// atan(0.3) towards +v (the scene slides off the image: rectify it); (D) slit along the width
/// direction through the pinhole, rays perpendicular to it; (E) rays along a whose slope along u
/// changes with v so that the scene is sheared by about scale / 2 from top to bottom; (F) the same
/// looking 30 degrees further down (+v); (G) a vertical slit at the pinhole and a horizontal one
/// four times farther back; (H) pencil with its slit at the pinhole along u, twist 1 / (2 e);
/// (I) bilinear with the pinhole's convergence and twist 1 / (2 e).
/// Throws `argument_error` for an unknown id ("id"), a scene behind the plane ("scene_centre")
/// or a non-positive scale ("scale").
template <std::floating_point T>
[[nodiscard]] GlcSelector<T> gallery_view(char id, const PlanarSurface<T>& plane,
                                          const std::type_identity_t<Vec3<T>>& scene_centre,
                                          std::type_identity_t<T> scale) {
  if (!scene_centre.allFinite()) throw argument_error("scene_centre", "not finite");
  if (!(scale > 0) || !std::isfinite(scale)) throw argument_error("scale", "must be positive and finite");
  const detail::PlaneFrame<T> fr(plane);
  const T zs = fr.depth(scene_centre);
  const T width = plane.width_vector().norm(), height = plane.height_vector().norm();
  if (!(zs > 1e-3 * std::max(width, height))) throw argument_error("scene_centre", "not in front of the image plane");
  const Vec3<T> axis = (scene_centre - fr.c) / zs; // unit component along n
  const T magnification = T(1.2) * scale / width;
  const T e = magnification > T(1.05) ? zs / (magnification - 1) : zs;
  const Vec3<T> eye = fr.c - e * axis;
  const T twist = 1 / (2 * e);
  switch (id) {
  case 'A':
  case 'a':
    return perspective(plane, eye);
  case 'B':
  case 'b':
    return orthographic(plane, axis);
  case 'C':
  case 'c':
    return orthographic(plane, Vec3<T>(axis + T(0.6) * fr.e1 + T(0.3) * fr.e2));
  case 'D':
  case 'd': {
    const Vec3<T> a = axis.normalized();
    return pushbroom(plane, Line<T>{eye, fr.e1}, Vec3<T>(fr.e1 - fr.e1.dot(a) * a));
  }
  case 'E':
  case 'e':
  case 'F':
  case 'f': {
    const Vec3<T> dir = (id == 'E' || id == 'e') ? axis : Vec3<T>(axis + T(0.57735026918962576) * fr.e2);
    const T shear = T(0.5) * std::max(scale, width) / (height * zs);
    return twisted_orthographic(plane, dir, fr.e1, shear);
  }
  case 'G':
  case 'g':
    return cross_slit(plane, Line<T>{eye, fr.e2}, Line<T>{Vec3<T>(fr.c - 4 * e * axis), fr.e1});
  case 'H':
  case 'h':
    return pencil(plane, Line<T>{eye, fr.e1}, twist);
  case 'I':
  case 'i':
    return bilinear(plane, axis, 1 / e, twist);
  default:
    throw argument_error("id", std::string("unknown gallery view '") + id + "' (use A..I)");
  }
}

} // namespace mpr::glc
