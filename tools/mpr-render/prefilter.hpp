#pragma once
// mpr-render's --prefilter: light-field frames box-filtered to the output's scale before the
// render (mpr::downsampled, lightfield/frame_prefilter.hpp), so that an output smaller than the
// cameras' images (the README's 700x400 Chess animations) reads a quarter of the texels and
// averages each pixel's footprint instead of point-sampling it.

#include "framing.hpp"
#include "job.hpp"
#include "loading.hpp"

#include <mpr/lightfield/frame_prefilter.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>

namespace mpr_cli {

/// The smallest distance, in the reference camera's pixels, between the focal-surface points of
/// neighbouring output pixels (a pixel's footprint on the frames), over a 5x5 grid of pixels of
/// every view of a `w` x `h` image at frame parameters `p`; +inf when no point projects into the
/// reference camera. Measured over up to 8 pixels (inside the image) and divided by their
/// number, so that float rounding of the points (about 1e-4 of a pixel over one pixel on Chess)
/// stays far below `auto_prefilter_factor`'s tolerance.
template <std::floating_point T>
[[nodiscard]] double footprint_at(const Job& job, const Loaded<T>& l, const FrameParams& p, int w, int h) {
  double smallest = std::numeric_limits<double>::infinity();
  if (!l.reference) return smallest;
  const int sx = std::min(8, w - 1), sy = std::min(8, h - 1); // the stencils, pixels
  for (std::size_t k = 0; k < job.views.size(); ++k) {
    const CameraVariant<T> camera = make_camera(job, l, p, k, w, h);
    std::visit(
        [&](const auto& cam) {
          const auto project = [&](double x, double y) {
            const mpr::Vec2<T> uv(static_cast<T>(x / w), static_cast<T>(y / h));
            return l.reference->project(mpr::Vec3<T>(cam.surface.point_at(uv)));
          };
          for (int j = 0; j < 5; ++j)
            for (int i = 0; i < 5; ++i) {
              const double x = 0.5 + (w - 1 - sx) * i / 4.0, y = 0.5 + (h - 1 - sy) * j / 4.0;
              const auto a = project(x, y);
              if (!a) continue;
              if (sx > 0)
                if (const auto b = project(x + sx, y))
                  smallest = std::min(smallest, static_cast<double>((*b - *a).norm()) / sx);
              if (sy > 0)
                if (const auto b = project(x, y + sy))
                  smallest = std::min(smallest, static_cast<double>((*b - *a).norm()) / sy);
            }
        },
        camera);
  }
  return smallest;
}

/// `footprint_at` at every frame of the job's animation, the smallest.
template <std::floating_point T>
[[nodiscard]] double smallest_footprint(const Job& job, const Loaded<T>& l, int w, int h) {
  double smallest = std::numeric_limits<double>::infinity();
  const int count = std::max(job.frames, 1);
  for (int f = 0; f < count; ++f)
    smallest =
        std::min(smallest, footprint_at(job, l, frame_params(job, l.default_focal_depth, frame_time(f, count)), w, h));
  return smallest;
}

/// Whether --prefilter auto considers the job: light fields under the nearest, synthetic or
/// cylinder interpolation, one sample per pixel. The depth proxy samples where its depth maps put
/// the surface, not on the focal surface, and supersampling (--spp) already integrates each
/// pixel's footprint: `auto` leaves both on the full frames.
template <std::floating_point T>
[[nodiscard]] bool auto_prefilter_applies(const Job& job, const Loaded<T>& l) noexcept {
  return l.frames && l.reference && job.interpolation != Interpolation::depth && job.spp == 1;
}

/// The factor of --prefilter auto for a footprint (`footprint_at`) on `frames`: the whole camera
/// pixels it spans (within 1e-3), 1 to 8 and at most the smallest camera's width and height (1:
/// the full frames).
template <std::floating_point T>
[[nodiscard]] int auto_prefilter_factor(double footprint, const mpr::CameraFrameSet<T>& frames) noexcept {
  if (!std::isfinite(footprint)) return 1;
  int most = 8;
  for (const mpr::PinholeCamera<T>& c : frames.cameras()) most = std::min({most, c.width(), c.height()});
  return std::clamp(static_cast<int>(std::floor(footprint * (1 + 1e-3))), 1, std::max(most, 1));
}

/// The downsampling factor of --prefilter: the given N, or for `auto` where
/// `auto_prefilter_applies` the `auto_prefilter_factor` of the footprint `measure()` returns
/// (also stored in `footprint`), else 1. The one decision of mpr-render and mpr-view, which
/// measure differently (a whole animation; one request at its preview's scale).
template <std::floating_point T, class Measure>
[[nodiscard]] int prefilter_factor(const Job& job, const Loaded<T>& l, const Measure& measure,
                                   double* footprint = nullptr) {
  if (job.prefilter) return *job.prefilter;
  if (!auto_prefilter_applies(job, l)) return 1;
  const double f = measure();
  if (footprint != nullptr) *footprint = f;
  return auto_prefilter_factor(f, *l.frames);
}

/// `prefilter_factor` of a job rendered at `w` x `h`: auto measures its `smallest_footprint`.
template <std::floating_point T>
[[nodiscard]] int prefilter_factor(const Job& job, const Loaded<T>& l, int w, int h, double* footprint = nullptr) {
  return prefilter_factor(
      job, l, [&] { return smallest_footprint(job, l, w, h); }, footprint);
}

/// `frames` prefiltered by `factor` on `threads` workers, or `frames` itself for factor 1.
/// Throws `argument_error` ("--prefilter") when the factor exceeds a camera's size.
template <std::floating_point T>
[[nodiscard]] std::shared_ptr<const mpr::CameraFrameSet<T>>
prefiltered_frames(std::shared_ptr<const mpr::CameraFrameSet<T>> frames, int factor, int threads) {
  if (factor <= 1 || !frames) return frames;
  try {
    return std::make_shared<const mpr::CameraFrameSet<T>>(mpr::downsampled(*frames, factor, threads));
  } catch (const mpr::argument_error& e) {
    throw mpr::argument_error("--prefilter", e.reason());
  }
}

/// `l` with its frames prefiltered for the job (see `prefilter_factor`); a line for the user in
/// its notes when they were. Throws `argument_error` ("--prefilter") when the factor exceeds a
/// camera's size.
template <std::floating_point T>
[[nodiscard]] Loaded<T> with_prefilter(const Job& job, Loaded<T> l, int w, int h) {
  double footprint = 0;
  const int factor = prefilter_factor(job, l, w, h, &footprint);
  if (factor <= 1 || !l.frames) return l;
  const auto start = std::chrono::steady_clock::now();
  l.frames = prefiltered_frames(l.frames, factor, job.threads);
  const mpr::PinholeCamera<T>& c = l.frames->camera(0);
  char head[160], why[96] = "";
  std::snprintf(head, sizeof head, "prefiltered the frames to 1/%d of their scale (%dx%d) in %.2f s", factor, c.width(),
                c.height(), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  if (!job.prefilter) std::snprintf(why, sizeof why, " (auto: an output pixel spans %.2f camera pixels)", footprint);
  const std::string note = std::string(head) + why + "; --prefilter 1 samples the full frames";
  l.notes.emplace_back(note);
  return l;
}

} // namespace mpr_cli
