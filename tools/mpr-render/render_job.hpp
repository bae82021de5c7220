#pragma once
// mpr-render's run loop: a Job -> loaded data -> per frame and per view a camera (surface +
// selector, framing.hpp) and a sampler (samplers.hpp), each a std::variant, combined per view
// render into a fully typed mpr::Renderer (render_view: one visit of the sampler here, one of
// the camera and pixel sampling in render_dispatch.hpp's render_with_sampler). No per-pixel dispatch: inside the
// visit the inner loop is the same template instantiation a C++ user writes by hand
// (benchmarks/cli_dispatch.cpp).

#include "depth_output.hpp"
#include "framing.hpp"
#include "job.hpp"
#include "labels.hpp"
#include "light_field_views.hpp"
#include "loading.hpp"
#include "output.hpp"
#include "prefilter.hpp"
#include "preflight.hpp"
#include "print_camera.hpp"
#include "render_dispatch.hpp"
#include "samplers.hpp"

#include <mpr/mpr.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <ostream>
#include <type_traits>
#include <utility>
#include <vector>

namespace mpr_cli {

/// Renders one view with the pixel sampling of --spp / --filter into the linear image `out`: the
/// only run-time dispatch of a render. The visit here picks the sampler; render_with_sampler
/// (render_dispatch.hpp, compiled in mpr_tools) visits the camera and the pixel sampling. With
/// `aperture` (and a supersampling policy: make_job requires --spp N > 1), the view's selector
/// integrates over that finite aperture (aperture.hpp), opened to `aperture_size`.
template <std::floating_point T>
void render_view(const CameraVariant<T>& camera, const SamplerVariant<T>& sampler, const PixelSamplingVariant& sampling,
                 mpr::ImageView<mpr::Color> out, const mpr::Region& region, const mpr::RenderOptions& options,
                 const ApertureSpec* aperture = nullptr, double aperture_size = 0) {
  const ViewTarget target{out, region, options, &sampling, aperture, aperture_size};
  std::visit([&](const auto& smp) { render_with_sampler(camera, smp, target); }, sampler);
}

/// render_view into 8-bit sRGB pixels: the view is rendered into a linear image of `out`'s size
/// and the pixels of `region` that lie in `out` are encoded (mpr::to_rgb8, the codes a render
/// straight into `out` gives). mpr-view renders its bands so; the pixels of `out` outside `region`
/// are untouched.
template <std::floating_point T>
void render_view(const CameraVariant<T>& camera, const SamplerVariant<T>& sampler, const PixelSamplingVariant& sampling,
                 mpr::ImageView<mpr::Rgb8> out, const mpr::Region& region, const mpr::RenderOptions& options,
                 const ApertureSpec* aperture = nullptr, double aperture_size = 0) {
  mpr::Image<mpr::Color> linear(out.width(), out.height());
  render_view(camera, sampler, sampling, linear.view(), region, options, aperture, aperture_size);
  const int x0 = std::max(region.x, 0), x1 = std::min(region.x + region.width, out.width());
  const int y0 = std::max(region.y, 0), y1 = std::min(region.y + region.height, out.height());
  if (x1 <= x0) return;
  for (int y = y0; y < y1; ++y)
    mpr::PixelTraits<mpr::Rgb8>::from_colors(&linear(x0, y), &out(x0, y), static_cast<std::size_t>(x1 - x0));
}

/// Renders one view through pixel centres (one ray per pixel; benchmarks).
template <std::floating_point T>
void render_view(const CameraVariant<T>& camera, const SamplerVariant<T>& sampler, mpr::ImageView<mpr::Rgb8> out,
                 const mpr::Region& region, const mpr::RenderOptions& options) {
  static const PixelSamplingVariant centre{mpr::PixelCentre{}};
  render_view(camera, sampler, centre, out, region, options);
}

/// `image` encoded as 8-bit sRGB (mpr::to_rgb8 per channel, vectorised).
[[nodiscard]] inline mpr::Image<mpr::Rgb8> encode_rgb8(const mpr::Image<mpr::Color>& image) {
  mpr::Image<mpr::Rgb8> out(image.width(), image.height());
  for (int y = 0; y < image.height(); ++y)
    mpr::PixelTraits<mpr::Rgb8>::from_colors(&image(0, y), &out(0, y), static_cast<std::size_t>(image.width()));
  return out;
}

/// Warns about each view whose focal surface lies partly outside every camera's frame, at the
/// frame where most of it does (`unseen_share`; the views are cheap to set up, the check is 48 x 48
/// projections a camera).
template <std::floating_point T>
void warn_unseen_views(std::ostream& warn, const Job& job, const Loaded<T>& l, int count, int w, int h) {
  for (std::size_t k = 0; k < job.views.size(); ++k) {
    double worst = 0;
    int at = 0;
    bool tilted = false;
    for (int f = 0; f < count; ++f) {
      const FrameParams p = frame_params(job, l.default_focal_depth, frame_time(f, count));
      const double share = unseen_share(make_camera(job, l, p, k, w, h), *l.frames);
      if (share > worst) worst = share, at = f, tilted = p.tilt_x != 0 || p.tilt_y != 0;
    }
    if (worst > 0.01) warn_unseen(warn, job, job.views[k], worst, at, count, tilted);
  }
}

/// --save-depth-maps FOLDER for a run that publishes its files together (`publish`, publish.hpp):
/// the estimated maps are staged with the image, so a run that fails later (a full disk, a
/// --write-depth that cannot be written) leaves no map and no new folder; without `publish`,
/// written at once (save_depth_maps). The line to `info` is printed when they are published.
template <std::floating_point T>
void stage_depth_maps(const Job& job, const Loaded<T>& l, std::ostream* info, Publication* publish) {
  if (publish == nullptr || !job.save_depth_maps || !l.frames) {
    save_depth_maps(job, l, info);
    return;
  }
  const std::filesystem::path folder = *job.save_depth_maps;
  check_output_folder(folder / "x", "--save-depth-maps");
  if (!l.frames->has_depth()) throw mpr::argument_error("--save-depth-maps", "the frame set carries no depth maps");
  for (std::size_t i = 0; i < l.frames->size(); ++i)
    publish->stage(folder / mpr::depth_map_name(l.frames->name(i)), mpr::encode_pfm(l.frames->depth(i).view()));
  publish->note(info, "wrote " + std::to_string(l.frames->size()) + " depth maps to " + folder.string() + "\n");
}

/// Called with each finished frame (index from 0, and the frame count), 8-bit sRGB.
using FrameSink = std::function<void(int index, int count, const mpr::Image<mpr::Rgb8>& image)>;

/// The most bytes of linear pixels (12 a pixel) run_typed holds for a frame that goes out as
/// 8-bit sRGB: each view (tile) of such a frame is rendered in bands of rows of at most this size,
/// each encoded as it is done (16 MiB: a view 4096 pixels wide in bands of 341 rows).
inline constexpr std::size_t kLinearBandBytes = std::size_t{16} << 20;

/// Where run_typed sends each finished frame (index from 0, and the frame count): `linear`, the
/// frame in linear light; or, when only `srgb8` is set, the frame as 8-bit sRGB (mpr::to_rgb8),
/// rendered band by band (kLinearBandBytes) so that no linear image of the whole frame is held.
/// Both give the same 8-bit codes. A callable taking the linear image converts to `linear`.
struct FrameSinks {
  std::function<void(int index, int count, const mpr::Image<mpr::Color>& image)> linear;
  FrameSink srgb8;

  template <class F>
  requires std::is_invocable_v < const F&, int, int, const mpr::Image<mpr::Color>
  & > FrameSinks(F linear_sink) : linear(std::move(linear_sink)) {} // NOLINT(google-explicit-constructor)
  /// The sinks of a frame that goes out as 8-bit sRGB.
  [[nodiscard]] static FrameSinks encoded(FrameSink sink) {
    FrameSinks s;
    s.srgb8 = std::move(sink);
    return s;
  }

private:
  FrameSinks() = default;
};
/// The sink parameter of run_typed (the name its explicit instantiations use).
using LinearFrameSink = FrameSinks;

/// Renders the views of frame parameters `p` into `image` (linear light, or 8-bit sRGB codes
/// through bands of linear pixels: render_view's Rgb8 overload), with their tile labels;
/// --print-camera and the view warnings on the first frame.
template <std::floating_point T, class Pixel>
void render_frame_views(const Job& job, const Loaded<T>& l, const FrameParams& p, int f, int w, int h,
                        const SamplerVariant<T>& sampler, const PixelSamplingVariant& sampling,
                        const mpr::RenderOptions& options, mpr::Image<Pixel>& image, std::ostream* info,
                        std::ostream* warnings) {
  // Rows of one tile per band (render_view's Rgb8 overload holds the band's linear pixels).
  const int band = static_cast<int>(std::clamp<std::size_t>(
      kLinearBandBytes / (sizeof(mpr::Color) * static_cast<std::size_t>(w)), 1, static_cast<std::size_t>(h)));
  const ApertureSpec* aperture = job.aperture ? &*job.aperture : nullptr;
  for (std::size_t k = 0; k < job.views.size(); ++k) {
    const CameraVariant<T> camera = make_camera(job, l, p, k, w, h);
    if (info != nullptr && job.print_camera && f == 0) {
      print_camera(*info, job.views[k], camera, l.footprint);
      if (job.aperture) print_focus(*info, *job.aperture, plane_of(camera));
    }
    if (warnings != nullptr && f == 0) warn_view(*warnings, job, l, job.views[k], camera);
    const int col = static_cast<int>(k) % job.cols, row = static_cast<int>(k) / job.cols;
    const mpr::Region tile(col * w, row * h, w, h);
    if constexpr (std::is_same_v<Pixel, mpr::Color>) {
      render_view(camera, sampler, sampling, image.view(), tile, options, aperture, p.aperture_size);
    } else {
      for (int y0 = tile.y; y0 < tile.y + h; y0 += band) { // the band's rows; the tile's region relative to them
        const int rows = std::min(band, tile.y + h - y0);
        render_view(camera, sampler, sampling, image.view().subview(tile.x, y0, w, rows),
                    mpr::Region(0, tile.y - y0, w, h), options, aperture, p.aperture_size);
      }
    }
    if (job.labels) draw_tile_label(image.view(), tile, tile_label(job.views[k], camera, aperture));
  }
}

/// The focal depth of a --raster sampler (the array's), else that of the frame parameters.
template <class S>
[[nodiscard]] double raster_focal_depth(const S& sampler, const FrameParams& p) {
  if constexpr (requires { sampler.focal_depth(); })
    return static_cast<double>(sampler.focal_depth());
  else
    return p.focal_depth;
}

template <std::floating_point T>
void run_typed(const Job& given, const LinearFrameSink& sink, std::ostream* info, std::ostream* warnings,
               Publication* publish) {
  check_ranges<T>(given);
  const Loaded<T> loaded = load<T>(given);
  if (info != nullptr)
    for (const std::string& note : loaded.notes) *info << note << '\n';
  const Job job = with_focus_at(with_array_defaults(given, loaded), loaded, info); // --focus-at: the focal depth set
  const auto [w, h] = view_size(job, loaded);
  // --prefilter: the frames the views sample, at the output's scale. The depth outputs (--focus-at
  // above, --write-depth below) read the full frames' depth maps.
  const Loaded<T> l = with_prefilter(job, loaded, w, h);
  if (info != nullptr)
    for (std::size_t n = loaded.notes.size(); n < l.notes.size(); ++n) *info << l.notes[n] << '\n';

  preflight(job, l); // every frame checked before the first is rendered
  stage_depth_maps(job, loaded, info, publish);
  if (warnings != nullptr) warn_job(*warnings, job, l);
  const int count = std::max(job.frames, 1);
  if (warnings != nullptr && l.frames != nullptr && job.interpolation != Interpolation::depth && !job.all_in_focus)
    warn_unseen_views(*warnings, job, l, count, w, h);
  const mpr::RenderOptions options{job.threads};
  const PixelSamplingVariant sampling = make_pixel_sampling(job.spp, job.filter);
  bool raster_warned = false;
  for (int f = 0; f < count; ++f) {
    if (job.shard && f % job.shard->second != job.shard->first) continue; // another shard's frame
    const FrameParams p = frame_params(job, l.default_focal_depth, frame_time(f, count));
    const SamplerVariant<T> sampler = make_sampler(job, l, p, w, h);
    if (warnings != nullptr && !raster_warned && job.raster) { // the array's focal depth, once it is rasterized
      warn_raster(*warnings, job, l, std::visit([&](const auto& s) { return raster_focal_depth(s, p); }, sampler));
      raster_warned = true;
    }
    if (sink.linear) {
      mpr::Image<mpr::Color> image(job.cols * w, job.rows * h);
      render_frame_views(job, l, p, f, w, h, sampler, sampling, options, image, info, warnings);
      sink.linear(f, count, image);
    } else {
      mpr::Image<mpr::Rgb8> image(job.cols * w, job.rows * h);
      render_frame_views(job, l, p, f, w, h, sampler, sampling, options, image, info, warnings);
      sink.srgb8(f, count, image);
    }
  }
  write_view_depth(job, loaded, info, publish); // --write-depth (a single image)
}

// Compiled once, in mpr_tools (tools/dispatch/run_float.cpp, run_double.cpp).
extern template void run_typed<float>(const Job&, const LinearFrameSink&, std::ostream*, std::ostream*, Publication*);
extern template void run_typed<double>(const Job&, const LinearFrameSink&, std::ostream*, std::ostream*, Publication*);

/// Runs the job: every frame, in linear light, goes to `sink`; --print-camera text, the depth of
/// --focus-at and the files of --write-depth to `info`, and warnings about the views
/// (light_field_views.hpp) to `warnings` (each when not null). With `publish`, the files of
/// --write-depth are staged there (publish.hpp), else written at the end.
inline void run_linear(const Job& job, const LinearFrameSink& sink, std::ostream* info = nullptr,
                       std::ostream* warnings = nullptr, Publication* publish = nullptr) {
  if (job.use_double)
    run_typed<double>(job, sink, info, warnings, publish);
  else
    run_typed<float>(job, sink, info, warnings, publish);
}

/// run_linear with every frame as 8-bit sRGB for `sink` (FrameSinks::encoded: rendered in bands,
/// the codes encode_rgb8 gives).
inline void run(const Job& job, const FrameSink& sink, std::ostream* info = nullptr, std::ostream* warnings = nullptr,
                Publication* publish = nullptr) {
  run_linear(job, FrameSinks::encoded(sink), info, warnings, publish);
}

/// The sinks for frames written to `path` with `encoding`: `on_frame(index, count, image)` gets
/// 8-bit sRGB codes for an 8-bit PNG or a JPEG (no linear image of the whole frame is held), the
/// linear image for the other formats.
template <class F>
[[nodiscard]] FrameSinks frame_sinks(const std::filesystem::path& path, const OutputEncoding& encoding, F on_frame) {
  const ImageFormat format = image_format(path);
  if (is_linear(format) || (format == ImageFormat::png && encoding.png_bits != 8))
    return FrameSinks(
        [on_frame](int index, int count, const mpr::Image<mpr::Color>& image) { on_frame(index, count, image); });
  return FrameSinks::encoded(
      [on_frame](int index, int count, const mpr::Image<mpr::Rgb8>& image) { on_frame(index, count, image); });
}

/// All frames in memory (tests).
inline std::vector<mpr::Image<mpr::Rgb8>> render_frames(const Job& job, std::ostream* info = nullptr) {
  std::vector<mpr::Image<mpr::Rgb8>> frames;
  run(
      job, [&](int, int, const mpr::Image<mpr::Rgb8>& image) { frames.push_back(image); }, info);
  return frames;
}

/// The numbered path of frame `index` (0-based) of an animation: out.png -> out_0001.png,
/// out.exr -> out_0001.exr (frame_extension).
inline std::filesystem::path frame_path(const std::filesystem::path& output, int index) {
  char number[16];
  std::snprintf(number, sizeof number, "_%04d", index + 1);
  std::filesystem::path p = output;
  p.replace_filename(output.stem().string() + number + frame_extension(output));
  return p;
}

} // namespace mpr_cli
