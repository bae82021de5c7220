#pragma once
// mpr-render's checks before the first pixel is rendered, so that a job that cannot finish
// fails at once with one line and writes nothing: every value given must be representable in
// the render's scalar type; a rasterized virtual array (--raster) must fit the memory budget
// below (its estimate, with a time estimate, is in the message); and every frame's cameras (and
// sampler settings) of an animation are built once, so that a sweep that becomes impossible
// partway (a tilt at which a corner ray runs parallel to the plane, a focal depth that
// overflows, a finite aperture whose rays cannot reach its lens plane) is refused before frame 1
// is written.

#include "framing.hpp"
#include "job.hpp"
#include "loading.hpp"
#include "samplers.hpp"
#include "view_spec.hpp"

#include <mpr/lightfield.hpp>
#include <mpr/scene/rasterized_sampler.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>

namespace mpr_cli {

/// The --raster budget: the bytes a virtual array may take, and the cost figures of the
/// estimate, measured with mpr-render itself on a 2-core x86-64 machine (one thread): 170 KB
/// and 4-5 ms per 160x120 camera, for the classroom and for a 20,000-triangle OBJ
/// (docs/reliability.md).
struct RasterBudget {
  std::uint64_t max_bytes = std::uint64_t(1) << 30; ///< 1 GiB (about 6,000 cameras)
  double bytes_per_pixel = 8.9;                     ///< frame, rasterizer and sampler data
  double bytes_per_camera = 2048;                   ///< camera model and bookkeeping
  double seconds_per_camera_triangle = 1e-8;        ///< rasterizing, per camera and triangle
  double seconds_per_camera_pixel = 2e-7;           ///< clearing, shading, converting
  double bytes_per_point = 16;                      ///< --raster-samples > 1: one camera's points
  double max_seconds = 1800;                        ///< 30 minutes on one core, all frames together
};

/// The limits on the output of a job (lifted by --no-budget): the image's pixels (3 bytes each,
/// 4 more with --write-depth; 2^28 pixels is 768 MiB) and the rays of the whole run (pixels x
/// --spp x frames; 2^34 rays is about an hour at 5 Mrays/s, one core of docs/mpr-render.md's
/// machine).
struct OutputBudget {
  std::uint64_t max_pixels = std::uint64_t(1) << 28;
  std::uint64_t max_rays = std::uint64_t(1) << 34;
};

/// Estimated memory and time of building one virtual array.
struct RasterEstimate {
  double bytes = 0;
  double seconds = 0;
};

/// The estimate for `columns` x `rows` cameras of `width` x `height` pixels, `samples` x
/// `samples` points a pixel (--raster-samples, >= 1): the points' buffers are held for one camera
/// at a time, the per-pixel work grows with the points, the per-triangle work does not.
[[nodiscard]] inline RasterEstimate estimate_raster(int columns, int rows, int width, int height, std::size_t triangles,
                                                    const RasterBudget& budget = {}, int samples = 1) {
  const double cameras = static_cast<double>(columns) * rows;
  const double pixels = static_cast<double>(width) * height;
  const double points = pixels * samples * samples;
  RasterEstimate e;
  e.bytes = cameras * (pixels * budget.bytes_per_pixel + budget.bytes_per_camera) +
            (samples > 1 ? budget.bytes_per_point * points : 0);
  e.seconds = cameras * (static_cast<double>(triangles) * budget.seconds_per_camera_triangle +
                         points * budget.seconds_per_camera_pixel);
  return e;
}

namespace detail {

inline std::string format_g(const char* format, double v) {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

/// Throws argument_error naming `option` unless `v` is 0 or its magnitude lies between the
/// square roots of T's smallest normal and largest numbers (float: about 1.1e-19 to 1.8e19), so
/// that the squares and products the cameras form from it stay normal and finite: 1e-30 as a
/// focal depth would otherwise surface as "invalid width_vector" deep in the library.
template <std::floating_point T>
void require_in_range(double v, const char* option) {
  const double a = std::abs(v);
  const double lo = std::sqrt(static_cast<double>(std::numeric_limits<T>::min()));
  const double hi = std::sqrt(static_cast<double>(std::numeric_limits<T>::max()));
  if (a == 0 || (a >= lo && a <= hi)) return;
  throw mpr::argument_error(option, format_g("%g", v) + " is outside the range of " +
                                        (std::is_same_v<T, float> ? "float" : "double") + " (" + format_g("%.3g", lo) +
                                        " to " + format_g("%.3g", hi) + " in magnitude)" +
                                        (std::is_same_v<T, float> ? "; use --double" : ""));
}

template <std::floating_point T>
void require_in_range(const mpr::Vec3<double>& v, const char* option) {
  for (int i = 0; i < 3; ++i) require_in_range<T>(v[i], option);
}

template <std::floating_point T>
void require_in_range(const Track& track, const char* option) {
  for (const Track::Key& k : track.keys()) require_in_range<T>(k.value, option);
}

/// Every number of the job, checked against T's range.
template <std::floating_point T>
void check_value_ranges(const Job& job) {
  require_in_range<T>(job.radius, "--radius");
  if (job.focal_depth) require_in_range<T>(*job.focal_depth, "--focal-depth");
  require_in_range<T>(job.tilt_x, "--tilt-x");
  require_in_range<T>(job.tilt_y, "--tilt-y");
  require_in_range<T>(job.morph, "--morph");
  require_in_range<T>(job.reference_depth, "--reference-depth");
  require_in_range<T>(job.position_scale, "--position-scale");
  require_in_range<T>(job.obj_scale, "--obj-scale");
  require_in_range<T>(job.zoom, "--zoom");
  if (job.plane_centre) require_in_range<T>(*job.plane_centre, "--plane-centre");
  if (job.look_at) require_in_range<T>(*job.look_at, "--look-at");
  if (job.plane_size) {
    require_in_range<T>(job.plane_size->first, "--plane-size");
    require_in_range<T>(job.plane_size->second, "--plane-size");
  }
  require_in_range<T>(job.up, "--up");
  if (job.rectify)
    for (const mpr::Vec3<double>& p : *job.rectify) require_in_range<T>(p, "--rectify");
  if (job.scene_centre) require_in_range<T>(*job.scene_centre, "--scene-centre");
  if (job.scene_scale) require_in_range<T>(*job.scene_scale, "--scene-scale");
  if (job.aperture) {
    require_in_range<T>(job.aperture->size, "--aperture");
    if (job.aperture->distance) require_in_range<T>(*job.aperture->distance, "--lens-distance");
    for (const double d : job.aperture->focus) require_in_range<T>(d, "--focus");
  }
}

/// "frame 7 of 24: " for animations, "" for a single image.
inline std::string frame_label(int f, int count) {
  return count > 1 ? "frame " + std::to_string(f + 1) + " of " + std::to_string(count) + ": " : std::string();
}

} // namespace detail

/// Every number of `job` checked against T's range (require_in_range): before loading, so that no
/// loader sees a value out of range (an OBJ scaled by 1e308), and again in preflight.
template <std::floating_point T>
void check_ranges(const Job& job) {
  detail::check_value_ranges<T>(job);
}

/// Throws argument_error("--raster") when the virtual array of `job` would exceed `budget`.
template <std::floating_point T>
void check_raster_budget(const Job& job, const Loaded<T>& l, const RasterBudget& budget = {}) {
  if (!job.raster || !l.scene) return;
  const mpr::scene::VirtualArrayConfig<T> config = raster_config<T>(job);
  const RasterEstimate e = estimate_raster(config.columns, config.rows, config.width, config.height, l.scene->size(),
                                           budget, config.samples);
  const int frames = std::max(job.frames, 1);
  if (job.no_budget || (e.bytes <= static_cast<double>(budget.max_bytes) && e.seconds * frames <= budget.max_seconds))
    return;
  throw mpr::argument_error(
      "--raster",
      std::to_string(job.raster->first) + "x" + std::to_string(job.raster->second) + " cameras of " +
          std::to_string(config.width) + "x" + std::to_string(config.height) + " pixels" +
          (job.raster_samples > 1 ? " (" + std::to_string(job.raster_samples * job.raster_samples) + " points a pixel)"
                                  : std::string()) +
          " need about " + detail::format_g("%.0f", e.bytes / (1 << 20)) + " MiB (limit " +
          std::to_string(budget.max_bytes >> 20) + " MiB) and roughly " + detail::format_g("%.0f", e.seconds * frames) +
          " s on one core to rasterize " + std::to_string(l.scene->size()) + " triangles" +
          (frames > 1 ? " for " + std::to_string(frames) + " frames" : std::string()) + " (limit " +
          detail::format_g("%.0f", budget.max_seconds) +
          " s); use fewer cameras or --raster-samples, or --no-budget to lift the limits");
}

/// Throws argument_error naming --size (or --spp) when the image of `job` (views of `w` x `h`
/// pixels tiled by --layout) or the rays of the whole run exceed `budget`, unless --no-budget.
inline void check_output_budget(const Job& job, int w, int h, const OutputBudget& budget = {}) {
  if (job.no_budget) return;
  const std::uint64_t pixels = std::uint64_t(job.cols) * std::uint64_t(w) * std::uint64_t(job.rows) * std::uint64_t(h);
  const std::string image = std::to_string(job.cols * w) + "x" + std::to_string(job.rows * h);
  if (pixels > budget.max_pixels)
    throw mpr::argument_error(
        "--size", "the image of " + image + " pixels (" + std::to_string(job.cols) + "x" + std::to_string(job.rows) +
                      " views of " + std::to_string(w) + "x" + std::to_string(h) + ") exceeds the limit of " +
                      std::to_string(budget.max_pixels) + " pixels; use a smaller --size or --layout, or --no-budget");
  const double rays = static_cast<double>(pixels) * job.spp * std::max(job.frames, 1);
  if (rays > static_cast<double>(budget.max_rays))
    throw mpr::argument_error(job.spp > 1 ? "--spp" : "--size",
                              detail::format_g("%.3g", rays) + " rays (" + image + " pixels x " +
                                  std::to_string(job.spp) + " samples x " + std::to_string(std::max(job.frames, 1)) +
                                  " frames) exceed the limit of " +
                                  detail::format_g("%.3g", static_cast<double>(budget.max_rays)) +
                                  " rays (about an hour on one core); use fewer samples, pixels or frames, or "
                                  "--no-budget");
}

/// Builds every frame's cameras and sampler settings once (see the file comment); throws
/// argument_error naming the option (and the frame of an animation) for the first that fails.
template <std::floating_point T>
void preflight(const Job& job, const Loaded<T>& l) {
  detail::check_value_ranges<T>(job);
  check_raster_budget(job, l);
  const auto [w, h] = view_size(job, l);
  check_output_budget(job, w, h);
  const int count = std::max(job.frames, 1);
  for (int f = 0; f < count; ++f) {
    const FrameParams p = frame_params(job, l.default_focal_depth, frame_time(f, count));
    try {
      detail::require_in_range<T>(p.focal_depth, "--focal-depth");
      try {
        (void)base_plane(job, l, p, w, h);
      } catch (const mpr::argument_error& e) {
        if (e.parameter().rfind("--", 0) == 0) throw;
        // A library parameter (e.g. the plane's "depth") stands for the option that set it.
        throw mpr::argument_error(l.reference ? "--focal-depth" : "--plane-size",
                                  (l.reference ? detail::format_g("%g", p.focal_depth) + " gives no image plane: "
                                               : std::string("no image plane: ")) +
                                      detail::nested(e));
      }
      for (std::size_t k = 0; k < job.views.size(); ++k) {
        const CameraVariant<T> camera = make_camera(job, l, p, k, w, h);
        // The lens of every view and frame (the focus, rays parallel to the image plane).
        if (job.aperture)
          std::visit(
              [&](const auto& cam) {
                (void)with_aperture(*job.aperture, p.aperture_size, plane_of(camera), cam.selector);
              },
              camera);
      }
      if (job.raster) {
        (void)mpr::scene::virtual_array_cameras(base_plane(job, l, p, w, h), raster_config<T>(job));
        if (job.interpolation == Interpolation::cylinder) (void)mpr::CylinderAperture{p.radius};
        if (job.interpolation == Interpolation::depth) job.depth_proxy(p.radius).validate();
      } else if (!l.scene_sampler && job.interpolation == Interpolation::cylinder) {
        (void)mpr::CameraFrameSampler<mpr::CylinderAperture, T>(l.frames, mpr::CylinderAperture{p.radius});
      } else if (!l.scene_sampler && job.interpolation == Interpolation::depth) {
        (void)mpr::CameraFrameSampler<mpr::DepthProxy, T>(l.frames, job.depth_proxy(p.radius));
      }
    } catch (const mpr::argument_error& e) {
      if (count == 1) throw;
      // "invalid --tilt-x: frame 7 of 24: <reason> (nothing was written ...)".
      const bool option = e.parameter().rfind("--", 0) == 0;
      std::string reason = detail::nested(e);
      if (option && reason.rfind(e.parameter() + ": ", 0) == 0) reason.erase(0, e.parameter().size() + 2);
      throw mpr::argument_error(option ? e.parameter() : std::string("animation"),
                                detail::frame_label(f, count) + reason +
                                    " (nothing was written: every frame is checked first)");
    }
  }
}

// Compiled once, in mpr_tools (tools/dispatch/run_float.cpp, run_double.cpp).
extern template void preflight<float>(const Job&, const Loaded<float>&);
extern template void preflight<double>(const Job&, const Loaded<double>&);

} // namespace mpr_cli
