#pragma once
// mpr-render's framing: the image plane of a view (from the reference camera or --plane-centre,
// --look-at, --plane-size, --up), tilted per frame, with the view's GLC, a morph and the
// rectifying homography (--rectify) -> the surface+selector pair of one view.

#include "job.hpp"
#include "loading.hpp"
#include "view_spec.hpp"

#include <mpr/glc.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <variant>

namespace mpr_cli {

/// A GLC view on an image plane (no rectification).
template <std::floating_point T>
struct PlanarCamera {
  mpr::PlanarSurface<T> surface;
  mpr::GlcSelector<T> selector;
};

/// The surface+selector pair of one view: planar, or rectified through a homography.
template <std::floating_point T>
using CameraVariant = std::variant<PlanarCamera<T>, mpr::glc::Rectified<T>>;

/// The (untilted frame of the) image plane a view's GLC is defined on.
template <std::floating_point T>
const mpr::PlanarSurface<T>& plane_of(const CameraVariant<T>& camera) {
  return std::holds_alternative<PlanarCamera<T>>(camera) ? std::get<PlanarCamera<T>>(camera).surface
                                                         : std::get<mpr::glc::Rectified<T>>(camera).surface.plane();
}

/// The GLC of a view (before any rectifying homography).
template <std::floating_point T>
const mpr::GlcSelector<T>& glc_of(const CameraVariant<T>& camera) {
  return std::holds_alternative<PlanarCamera<T>>(camera) ? std::get<PlanarCamera<T>>(camera).selector
                                                         : std::get<mpr::glc::Rectified<T>>(camera).selector.selector();
}

/// The output size of one view.
template <std::floating_point T>
std::pair<int, int> view_size(const Job& job, const Loaded<T>& l) {
  if (!job.size_given && l.reference) return {l.reference->width(), l.reference->height()};
  return {job.width, job.height};
}

/// `full` (a light field's reference view on the focal plane) fitted to a `width` x `height`
/// output: the largest centred rectangle of the output's aspect ratio inside `full` (so square
/// things stay square whatever --size is, and no part of the view lies outside the reference
/// camera's), then scaled by 1 / `zoom` about its centre. Unchanged when the aspect ratios agree
/// (to 1e-9) and `zoom` is 1.
template <std::floating_point T>
mpr::PlanarSurface<T> fit_to_output(const mpr::PlanarSurface<T>& full, int width, int height, double zoom = 1) {
  const double fw = static_cast<double>(full.width_vector().norm());
  const double fh = static_cast<double>(full.height_vector().norm());
  const double want = static_cast<double>(width) / height, have = fw / fh;
  if (std::abs(want / have - 1) <= 1e-9 && zoom == 1) return full;
  double sx = 1, sy = 1; // scale of the width and height vectors
  if (want > have)
    sy = have / want; // the output is wider: keep the width, crop the height
  else
    sx = want / have; // the output is taller: keep the height, crop the width
  return mpr::PlanarSurface<T>::centred(full.centre(), static_cast<T>(sx / zoom) * full.width_vector(),
                                        static_cast<T>(sy / zoom) * full.height_vector());
}

/// The image plane of a frame, before tilting (see job.hpp for the defaults).
template <std::floating_point T>
mpr::PlanarSurface<T> base_plane(const Job& job, const Loaded<T>& l, const FrameParams& p, int width, int height) {
  if (l.reference)
    return fit_to_output(l.reference->image_plane(static_cast<T>(p.focal_depth)), width, height, job.zoom);
  using V = mpr::Vec3<T>;
  const V centre = (job.plane_centre ? *job.plane_centre : l.plane_centre).template cast<T>();
  const V look = (job.look_at ? *job.look_at : l.look_at).template cast<T>();
  const V up = job.up.template cast<T>();
  const T w = static_cast<T>(job.plane_size ? job.plane_size->first : l.plane_width);
  const T h =
      job.plane_size ? static_cast<T>(job.plane_size->second) : w * static_cast<T>(height) / static_cast<T>(width);
  if (!((look - centre).norm() > 0)) throw mpr::argument_error("--look-at", "equals the plane centre");
  // Far from the origin the plane's own extent drowns in rounding (then every view would fail
  // with a misleading "parallel" or "degenerate").
  if (!(std::min(w, h) > std::max(centre.stableNorm(), look.stableNorm()) * std::numeric_limits<T>::epsilon() * 64))
    throw mpr::argument_error(job.plane_size ? "--plane-size" : "--plane-centre",
                              std::string("the image plane is too small for its distance from the origin in ") +
                                  (std::is_same_v<T, float> ? "float; use --double or" : "double;") +
                                  " move the scene near the origin");
  const V forward = (look - centre) / (look - centre).stableNorm(); // no overflow for far points
  const V side = forward.cross(up);
  if (!(side.norm() > T(1e-6) * up.norm())) throw mpr::argument_error("--up", "parallel to the viewing direction");
  const V right = side.normalized();
  const V down = forward.cross(right);
  return mpr::PlanarSurface<T>::centred(centre, w * right, h * down);
}

template <std::floating_point T>
mpr::PlanarSurface<T> frame_plane(const mpr::PlanarSurface<T>& base, const FrameParams& p) {
  if (p.tilt_x == 0 && p.tilt_y == 0) return base;
  constexpr double deg = std::numbers::pi / 180;
  return base.tilted(static_cast<T>(p.tilt_x * deg), static_cast<T>(p.tilt_y * deg));
}

/// The camera of view `k` at frame parameters `p`.
template <std::floating_point T>
CameraVariant<T> make_camera(const Job& job, const Loaded<T>& l, const FrameParams& p, std::size_t k, int width,
                             int height) {
  const mpr::PlanarSurface<T> base = base_plane(job, l, p, width, height);
  const mpr::PlanarSurface<T> plane = frame_plane(base, p);
  mpr::GlcSelector<T> glc = make_selector<T>(job.views[k], "--view", plane, job, l, p);
  if (job.morph_to) {
    const mpr::GlcSelector<T> to = make_selector<T>(*job.morph_to, "--morph-to", plane, job, l, p);
    const T w = static_cast<T>(p.morph);
    const auto mix = [w](const mpr::Vec3<T>& a, const mpr::Vec3<T>& b) { return mpr::Vec3<T>((1 - w) * a + w * b); };
    try {
      glc = mpr::GlcSelector<T>(plane, mix(glc.d00(), to.d00()), mix(glc.d10(), to.d10()), mix(glc.d01(), to.d01()));
    } catch (const mpr::argument_error& e) {
      throw mpr::argument_error("--morph-to", "the two views look to opposite sides of the image plane (" +
                                                  e.parameter() + " of the morph)");
    }
  }
  if (job.rectify_to_plane) {
    // Where the view's rays through the untilted plane's corners cross the tilted plane.
    const mpr::GlcSelector<T> base_glc = make_selector<T>(job.views[k], "--view", base, job, l, p);
    std::array<mpr::Vec2<T>, 4> target;
    const std::array<mpr::Vec2<T>, 4> corners = {mpr::Vec2<T>(0, 0), mpr::Vec2<T>(1, 0), mpr::Vec2<T>(1, 1),
                                                 mpr::Vec2<T>(0, 1)};
    for (std::size_t i = 0; i < 4; ++i) {
      const mpr::Vec3<T> o = base.point_at(corners[i]);
      const mpr::Vec3<T> d = base_glc.direction_at(corners[i]);
      if (!(std::abs(d.dot(plane.normal())) > T(1e-6) * d.norm()))
        throw mpr::argument_error("--rectify", "a corner ray runs parallel to the tilted plane");
      target[i] = plane.uv_of(plane.plane().crossing(mpr::Ray<T>{o, d}));
    }
    try {
      return mpr::glc::rectify(plane, glc, target);
    } catch (const mpr::argument_error& e) {
      throw mpr::argument_error("--rectify", "view " + job.views[k] + ": " + detail::nested(e));
    }
  }
  if (job.rectify) {
    std::array<mpr::Vec3<T>, 4> quad;
    for (std::size_t i = 0; i < 4; ++i) quad[i] = (*job.rectify)[i].template cast<T>();
    // A quadrilateral on the image plane itself (e.g. on a light field's focal plane) is not in
    // front of it; the library would say "behind". Say what it is and what frames part of a plane.
    const T size = std::max(plane.width_vector().norm(), plane.height_vector().norm());
    bool on_plane = true;
    for (const mpr::Vec3<T>& q : quad)
      on_plane = on_plane && std::abs(plane.normal().dot(q - plane.centre())) <= T(1e-4) * size;
    if (on_plane)
      throw mpr::argument_error("--rectify", "the quadrilateral lies on the image plane itself, but must lie in front "
                                             "of it; to show part of the image plane use --zoom (light fields) or "
                                             "--plane-size (scenes)");
    try {
      return mpr::glc::rectify(plane, glc, mpr::glc::target_region(plane, glc, quad));
    } catch (const mpr::argument_error& e) {
      throw mpr::argument_error("--rectify", "view " + job.views[k] + ": " + detail::nested(e));
    }
  }
  return PlanarCamera<T>{plane, glc};
}

} // namespace mpr_cli
