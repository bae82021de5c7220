#pragma once
// mpr-render's views of camera arrays (light fields and --raster): the interpolation and radius
// a view gets when none is given, and the warnings a view earns before it is rendered -- rays
// that miss the array, a focal surface outside every camera's frame, a ray-independent
// interpolation under a non-pinhole view, a gallery view whose type the array cannot hold
// (lightfield/array_view.hpp, docs/mpr-render.md).

#include "framing.hpp"
#include "job.hpp"
#include "loading.hpp"
#include "view_spec.hpp"

#include <mpr/glc.hpp>
#include <mpr/lightfield/array_view.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>
#include <string>
#include <variant>

namespace mpr_cli {

namespace detail {

/// True when a view spec is the light field's own reference view (refocusing).
inline bool refocusing_view(const std::string& spec) { return spec == "default"; }

inline bool any_other_view(const Job& job) {
  for (const std::string& v : job.views)
    if (!refocusing_view(v)) return true;
  return job.morph_to.has_value() && !refocusing_view(*job.morph_to);
}

} // namespace detail

/// How the rays of a view (planar or rectified) meet the camera array.
template <std::floating_point T>
mpr::ArrayCoverage view_coverage(const CameraVariant<T>& camera, const mpr::ArrayFootprint<T>& array) {
  return std::visit([&](const auto& cam) { return mpr::array_coverage(cam.surface, cam.selector, array); }, camera);
}

/// The spacing of the array's cameras, world units: a light field's median nearest-neighbour
/// distance, or the --raster grid's cell width on the first frame's image plane (0 for a scene).
template <std::floating_point T>
double camera_spacing(const Job& job, const Loaded<T>& l) {
  if (l.footprint) return static_cast<double>(l.footprint->spacing);
  if (!job.raster) return 0;
  const auto [w, h] = view_size(job, l);
  const FrameParams p = frame_params(job, l.default_focal_depth, 0);
  return static_cast<double>(base_plane(job, l, p, w, h).width_vector().norm()) / job.raster->first;
}

/// The job with the array defaults filled in: without --interp, the reference view (refocusing)
/// of a planar array gets the synthetic aperture and any other view a cylinder aperture; every
/// view of a ring or unstructured set gets the nearest camera (its reference view is the
/// reference camera's image, where the synthetic aperture would average cameras that see the
/// object from angles far apart into ghosts); without --radius, the cylinder's radius is the
/// camera spacing (a light field's median nearest-neighbour distance, or the --raster grid's cell
/// width; twice that for the depth proxy), so a ray blends the few cameras around its crossing.
/// The radius is set under every interpolation (one default radius: mpr-view's cylinder key
/// starts from it).
template <std::floating_point T>
Job with_array_defaults(const Job& job, const Loaded<T>& l) {
  const bool array = l.frames != nullptr || job.raster.has_value();
  if (!array) return job;
  Job out = job;
  // A ring or unstructured set is sparse in angle (Middlebury's sparse rings: 22.5 degrees between
  // cameras): blending neighbours at one focal plane ghosts, the nearest camera shows seams instead.
  const bool ring = l.footprint && !l.footprint->planar;
  if (!job.interpolation_given && !job.radius_given && (ring || detail::any_other_view(job)))
    out.interpolation = ring ? Interpolation::nearest : Interpolation::cylinder;
  // Every interpolation gets the spacing radius, so that one switched to the cylinder later (the
  // viewer's keys) starts from the same default radius as --interp cylinder.
  if (!job.radius_given) {
    double spacing = camera_spacing(job, l);
    // The depth proxy weighs cameras by angle itself: it considers the two rings around the ray.
    if (out.interpolation == Interpolation::depth) spacing *= 2;
    if (spacing > 0 && std::isfinite(spacing)) out.radius = Track(spacing);
  }
  return out;
}

/// Warnings about the job as a whole, before anything is rendered.
template <std::floating_point T>
void warn_job(std::ostream& warn, const Job& job, const Loaded<T>& l) {
  const bool array = l.frames != nullptr || job.raster.has_value();
  if (!array) return;
  if (job.interpolation == Interpolation::synthetic && detail::any_other_view(job))
    warn << "mpr-render: warning: --interp synthetic averages every camera at the focal-plane point and ignores "
            "the ray, so all views on one focal plane render alike; use --interp nearest or cylinder\n";
  if (l.footprint && !l.footprint->planar && job.interpolation == Interpolation::synthetic)
    warn << "mpr-render: warning: the cameras stand on a ring or around the scene: --interp synthetic averages "
            "cameras that see it from angles far apart, so it renders ghosts; use --interp nearest, or --interp depth "
            "with --depth-maps estimate\n";
  if (l.footprint && detail::any_other_view(job)) {
    // Neighbouring cameras as seen from the focal plane: beyond a couple of degrees, whatever lies
    // off that plane lands in different places in neighbouring cameras.
    const double depth = frame_params(job, l.default_focal_depth, 0).focal_depth;
    const double angle =
        2 * std::atan(0.5 * static_cast<double>(l.footprint->spacing) / depth) * 180 / std::numbers::pi;
    if (angle > 2) {
      char line[256];
      std::snprintf(line, sizeof line,
                    "mpr-render: warning: neighbouring cameras are %.1f degrees apart seen from the focal plane: "
                    "what lies off that plane is doubled (blending) or cut where the camera changes (nearest)\n",
                    angle);
      warn << line;
    }
  }
  if (l.footprint && l.footprint->one_dimensional() && detail::any_other_view(job))
    warn << "mpr-render: warning: the cameras lie on a " << (l.footprint->planar ? "line" : "ring")
         << ": every view's rays pass through it, so views differ only along it\n";
}

/// --raster under views other than the reference view, with the nearest camera or the cylinder
/// aperture: warns when neighbouring cameras are more than 2 degrees apart seen from the focal
/// plane `focal_depth` in front of the image plane (the array's: the median scene depth unless
/// --focal-depth), naming --interp depth, which takes each ray's depth from the rasterizer.
template <std::floating_point T>
void warn_raster(std::ostream& warn, const Job& job, const Loaded<T>& l, double focal_depth) {
  if (!job.raster || job.all_in_focus || !detail::any_other_view(job) ||
      (job.interpolation != Interpolation::cylinder && job.interpolation != Interpolation::nearest))
    return;
  const double spacing = camera_spacing(job, l);
  const double angle = 2 * std::atan(0.5 * spacing / focal_depth) * 180 / std::numbers::pi;
  if (!(focal_depth > 0) || !(angle > 2)) return;
  char line[320];
  std::snprintf(line, sizeof line,
                "mpr-render: warning: --raster %dx%d: neighbouring cameras are %.1f degrees apart seen from the focal "
                "plane (depth %.3g): what lies off that plane is %s; --interp depth uses the rasterizer's depth "
                "instead\n",
                job.raster->first, job.raster->second, angle, focal_depth,
                job.interpolation == Interpolation::nearest ? "cut where the camera changes" : "doubled");
  warn << line;
}

/// Warnings about one view (frame 0): rays that cross the camera plane off the array, and a
/// gallery view that is another GLC type on this array than in the gallery.
template <std::floating_point T>
void warn_view(std::ostream& warn, const Job& job, const Loaded<T>& l, const std::string& spec,
               const CameraVariant<T>& camera) {
  if (!l.footprint || job.raster) return;
  const mpr::ArrayCoverage c = view_coverage(camera, *l.footprint);
  char line[256];
  if (c.outside > 0.01) {
    std::snprintf(line, sizeof line,
                  "mpr-render: warning: view %s: %.0f%% of its rays cross the camera plane off the array (those "
                  "pixels show the edge cameras or nothing)\n",
                  spec.c_str(), 100 * c.outside);
    warn << line;
  }
  const char letter = detail::gallery_letter(spec);
  if (letter == 0) return;
  const mpr::glc::GalleryEntry& entry = mpr::glc::gallery[static_cast<std::size_t>(letter - 'A')];
  const mpr::glc::Type type = mpr::glc::classify(plane_of(camera), glc_of(camera)).type;
  if (type == entry.type) return;
  const std::string now(mpr::glc::to_string(type));
  const bool parallel = entry.type == mpr::glc::Type::orthographic || entry.type == mpr::glc::Type::pushbroom ||
                        entry.type == mpr::glc::Type::twisted_orthographic;
  const double width = static_cast<double>(plane_of(camera).width_vector().norm());
  const double array_width = 2 * static_cast<double>(std::max(l.footprint->half_u, l.footprint->half_v));
  if (l.footprint->one_dimensional())
    std::snprintf(line, sizeof line,
                  "mpr-render: note: view %s (%s) is a %s on this array: every ray passes through the %s of cameras\n",
                  spec.c_str(), std::string(entry.name).c_str(), now.c_str(), l.footprint->planar ? "line" : "ring");
  else if (parallel && width > array_width)
    std::snprintf(line, sizeof line,
                  "mpr-render: note: view %s (%s) is a %s on this array: rays parallel across a view %.3g wide "
                  "cannot all meet an array %.3g wide\n",
                  spec.c_str(), std::string(entry.name).c_str(), now.c_str(), width, array_width);
  else
    std::snprintf(line, sizeof line, "mpr-render: note: view %s (%s) is a %s on this array\n", spec.c_str(),
                  std::string(entry.name).c_str(), now.c_str());
  warn << line;
}

/// The share of a view's focal surface (its image surface, at a samples x samples grid of uv cell
/// centres) that no camera of `frames` sees: the nearest camera, the synthetic and the cylinder
/// aperture have nothing to show there (black).
template <std::floating_point T>
double unseen_share(const CameraVariant<T>& camera, const mpr::CameraFrameSet<T>& frames, int samples = 48) {
  return std::visit(
      [&](const auto& cam) {
        int unseen = 0;
        for (int j = 0; j < samples; ++j)
          for (int i = 0; i < samples; ++i) {
            const mpr::Vec2<T> uv((T(i) + T(0.5)) / T(samples), (T(j) + T(0.5)) / T(samples));
            const mpr::Vec3<T> X = cam.surface.point_at(uv);
            const auto& cams = frames.cameras();
            unseen += std::none_of(cams.begin(), cams.end(), [&](const auto& c) { return c.project(X).has_value(); });
          }
        return static_cast<double>(unseen) / (static_cast<double>(samples) * samples);
      },
      camera);
}

/// The warning for a view whose focal surface lies partly outside every camera's frame (share of
/// its surface, at `frame` of `count` frames, counted from 0; `tilted`: its plane is tilted there).
inline void warn_unseen(std::ostream& warn, const Job& job, const std::string& spec, double share, int frame, int count,
                        bool tilted) {
  char line[320];
  const std::string at =
      count > 1 ? " at frame " + std::to_string(frame + 1) + " of " + std::to_string(count) : std::string();
  std::snprintf(line, sizeof line,
                "mpr-render: warning: view %s: %.0f%% of its focal surface%s lies outside every camera's frame: "
                "those pixels have nothing to show (black)%s\n",
                spec.c_str(), 100 * share, at.c_str(),
                tilted && !job.rectify_to_plane && !job.rectify
                    ? "; --rectify plane keeps a tilted plane inside the untilted framing"
                    : "");
  warn << line;
}

// Compiled once, in mpr_tools (tools/dispatch/run_float.cpp, run_double.cpp).
extern template Job with_array_defaults<float>(const Job&, const Loaded<float>&);
extern template void warn_job<float>(std::ostream&, const Job&, const Loaded<float>&);
extern template Job with_array_defaults<double>(const Job&, const Loaded<double>&);
extern template void warn_job<double>(std::ostream&, const Job&, const Loaded<double>&);

} // namespace mpr_cli
