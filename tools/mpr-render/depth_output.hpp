#pragma once
// mpr-render's depth of a view (issue 12): the depth sampler of a job -- for a light field the
// surface its cameras' depth maps show along each ray (mpr::FrameDepthSampler), for a scene the
// ray cast's hit (mpr::HitDepth) -- rendered for every view by --write-depth (a PFM and a
// colour-mapped preview), and read under one pixel by --focus-at to set the focal depth.

#include "framing.hpp"
#include "job.hpp"
#include "loading.hpp"
#include "publish.hpp"

#include <mpr/render/renderer.hpp>
#include <mpr/io/depth_maps.hpp>
#include <mpr/io/pfm.hpp>
#include <mpr/lightfield/view_depth.hpp>
#include <mpr/scene/scene_sampler.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <variant>

namespace mpr_cli {

template <std::floating_point T>
using DepthSamplerVariant =
    std::variant<mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast, mpr::HitDepth>, mpr::FrameDepthSampler<T>>;

/// The radius of a light field's surface search: --radius under --interp depth (the depth
/// interpolation's own candidates), else twice the camera spacing (its default).
template <std::floating_point T>
double depth_search_radius(const Job& job, const Loaded<T>& l, const FrameParams& p) {
  if (job.interpolation == Interpolation::depth || !l.footprint) return p.radius;
  const double spacing = static_cast<double>(l.footprint->spacing);
  return spacing > 0 && std::isfinite(spacing) ? 2 * spacing : p.radius;
}

/// The depth sampler of a job. Light fields (precondition: --depth-maps): the surface the depth
/// maps show, as its depth along the reference camera's axis, or as the ray parameter (the
/// signed distance in front of the view's image plane) with `ray_parameter`. Scenes (also
/// --raster): the ray cast's hit, in front of the image plane.
template <std::floating_point T>
DepthSamplerVariant<T> make_depth_sampler(const Job& job, const Loaded<T>& l, const FrameParams& p,
                                          bool ray_parameter = false) {
  if (l.frames) {
    const mpr::FrameDepthSampler<T> s(l.frames, job.depth_proxy(depth_search_radius(job, l, p)));
    if (ray_parameter) return s;
    return s.along_axis(*l.reference);
  }
  return mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast, mpr::HitDepth>(l.scene);
}

/// Renders the depth of one view into `out` (one ray through each pixel centre).
template <std::floating_point T>
void render_depth(const CameraVariant<T>& camera, const DepthSamplerVariant<T>& sampler, mpr::ImageView<float> out,
                  const mpr::Region& region, const mpr::RenderOptions& options) {
  std::visit([&](const auto& cam,
                 const auto& smp) { mpr::Renderer(cam.surface, cam.selector, smp).render(out, region, options); },
             camera, sampler);
}

/// The depth under output pixel `px` of the view that fills `region`.
template <std::floating_point T>
float depth_at(const CameraVariant<T>& camera, const DepthSamplerVariant<T>& sampler, mpr::Pixel px,
               const mpr::Region& region) {
  return std::visit(
      [&](const auto& cam, const auto& smp) { return mpr::Renderer(cam.surface, cam.selector, smp).shade(px, region); },
      camera, sampler);
}

namespace detail {
inline std::string format_depth(double d) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", d);
  return text;
}
} // namespace detail

/// --focus-at X,Y: the job with the focus set to the depth seen at that output pixel, printed to
/// `info` (when not null). Light fields: --focal-depth, the depth along the reference camera's
/// axis at which the focal plane (with the first frame's tilt) contains the surface point the
/// pixel's ray meets; the plane is moved until it does (one step for a pinhole view of an
/// untilted plane; other views' rays move with the plane). --raster: --focal-depth, the ray
/// cast's depth in front of the image plane (where the rasterized array takes the colour). A
/// ray-cast scene with --aperture: --focus, likewise. Throws argument_error("--focus-at") for a
/// pixel outside the output, nothing seen there, or a surface behind the camera or plane.
template <std::floating_point T>
Job with_focus_at(const Job& job, const Loaded<T>& l, std::ostream* info) {
  if (!job.focus_at) return job;
  const std::pair<int, int> size = view_size(job, l); // not structured bindings: a lambda below
  const int w = size.first, h = size.second, x = job.focus_at->first, y = job.focus_at->second; // (Clang 14)
  const std::string pixel = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
  if (x >= job.cols * w || y >= job.rows * h)
    throw mpr::argument_error("--focus-at", pixel + " lies outside the " + std::to_string(job.cols * w) + "x" +
                                                std::to_string(job.rows * h) + " output");
  const std::size_t k = static_cast<std::size_t>((y / h) * job.cols + x / w);
  const mpr::Region region((x / w) * w, (y / h) * h, w, h);
  const mpr::Pixel px{x, y};
  FrameParams p = frame_params(job, l.default_focal_depth, 0);
  const DepthSamplerVariant<T> sampler = make_depth_sampler(job, l, p, true);
  const auto depth_here = [&](const FrameParams& q) {
    return static_cast<double>(depth_at(make_camera(job, l, q, k, w, h), sampler, px, region));
  };
  double t = depth_here(p);
  if (!std::isfinite(t))
    throw mpr::argument_error(
        "--focus-at", "nothing is seen at " + pixel + " of view " + job.views[k] + " (" +
                          (l.frames ? "the depth maps show no surface along its ray" : "its ray meets no surface") +
                          "); choose another pixel");
  Job out = job;
  std::string set;
  double chosen = t;
  if (l.frames) {
    // The plane's centre moves along the reference axis a; the plane itself by (n . a) per unit.
    const mpr::Vec3<double> axis = l.reference->R().row(2).transpose().template cast<double>();
    const mpr::Vec3<double> normal =
        frame_plane(base_plane(job, l, p, w, h), p).normal().template cast<double>().normalized();
    const double along = normal.dot(axis);
    double depth = p.focal_depth;
    for (int step = 0; step < 20 && std::isfinite(t) && std::abs(t) > 1e-6 * std::abs(depth); ++step) {
      depth += t / along;
      if (!(depth > 0))
        throw mpr::argument_error("--focus-at", "the surface at " + pixel + " lies behind the reference camera");
      p.focal_depth = depth;
      t = depth_here(p);
    }
    chosen = depth;
    out.focal_depth = Track(depth);
    set = "--focal-depth";
  } else {
    if (!(t > 0)) throw mpr::argument_error("--focus-at", "the surface at " + pixel + " lies behind the image plane");
    if (job.raster) {
      out.focal_depth = Track(t);
      set = "--focal-depth";
    } else {
      out.aperture->focus = {t};
      set = "--focus";
    }
  }
  if (info != nullptr)
    *info << "focus at " << pixel << " of view " << job.views[k] << ": depth " << detail::format_depth(chosen) << " ("
          << set << " " << detail::format_depth(chosen) << ")\n";
  return out;
}

/// --write-depth FILE.pfm: the depth of every view of the first frame, tiled as the image is
/// (see make_depth_sampler for the depth measured), written as a PFM and as a colour-mapped
/// preview (depth_preview_path); a line for each to `info` (when not null). With `publish`, both
/// files are staged there (published with the run's other files, publish.hpp); without, they are
/// published together at once.
template <std::floating_point T>
void write_view_depth(const Job& job, const Loaded<T>& l, std::ostream* info, Publication* publish = nullptr) {
  if (!job.write_depth) return;
  const auto [w, h] = view_size(job, l);
  const FrameParams p = frame_params(job, l.default_focal_depth, 0);
  const DepthSamplerVariant<T> sampler = make_depth_sampler(job, l, p);
  mpr::Image<float> depth(job.cols * w, job.rows * h);
  for (std::size_t k = 0; k < job.views.size(); ++k) {
    const int col = static_cast<int>(k) % job.cols, row = static_cast<int>(k) / job.cols;
    render_depth(make_camera(job, l, p, k, w, h), sampler, depth.view(), mpr::Region(col * w, row * h, w, h),
                 mpr::RenderOptions{job.threads});
  }
  check_output_folder(*job.write_depth, "--write-depth");
  Publication own;
  Publication& files = publish != nullptr ? *publish : own;
  files.stage(*job.write_depth, mpr::encode_pfm(depth.view()));
  const std::filesystem::path preview = depth_preview_path(*job.write_depth);
  const mpr::Image<mpr::Rgb8> colours = mpr::depth_preview(depth.view());
  files.stage(preview, mpr::encode_png(colours.view()));
  if (info != nullptr) {
    const mpr::DepthRange range = mpr::depth_range(depth.view());
    long unseen = 0;
    for (int y = 0; y < depth.height(); ++y)
      for (int x = 0; x < depth.width(); ++x) unseen += std::isfinite(depth(x, y)) ? 0 : 1;
    std::ostringstream line;
    line << "wrote " << job.write_depth->string() << " (depth "
         << (range.valid() ? detail::format_depth(range.near) + " to " + detail::format_depth(range.far)
                           : std::string("nowhere"))
         << ", " << unseen << " of " << depth.width() * depth.height() << " pixels see nothing) and "
         << preview.string() << "\n";
    files.note(info, line.str()); // printed when the files are published, not before
  }
  if (publish == nullptr) own.commit();
}

// Compiled once, in mpr_tools (tools/dispatch/depth_float.cpp, depth_double.cpp).
extern template Job with_focus_at<float>(const Job&, const Loaded<float>&, std::ostream*);
extern template void write_view_depth<float>(const Job&, const Loaded<float>&, std::ostream*, Publication*);
extern template Job with_focus_at<double>(const Job&, const Loaded<double>&, std::ostream*);
extern template void write_view_depth<double>(const Job&, const Loaded<double>&, std::ostream*, Publication*);

} // namespace mpr_cli
