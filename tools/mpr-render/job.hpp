#pragma once
// mpr-render's job description: what one invocation does, as a `Job`. The command line is parsed
// into it by tools/options/ (the option table shared with mpr-view: make_job, parse_job);
// loading, framing and rendering live in loading.hpp, framing.hpp, samplers.hpp and render_job.hpp.

#include "animation.hpp"
#include "aperture.hpp"
#include "cli_args.hpp"
#include "depth_options.hpp"
#include "output.hpp"
#include "pixel_sampling.hpp"

#include <mpr/core/error.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/depth_proxy.hpp>
#include <mpr/render/policy_names.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mpr_cli {

enum class SamplerKind { scene, obj, par, stanford, lfca, hci, colmap };

/// Whether `kind` is a light field (a calibrated camera array) rather than a scene to ray cast.
[[nodiscard]] constexpr bool is_light_field(SamplerKind kind) noexcept {
  return kind != SamplerKind::scene && kind != SamplerKind::obj;
}
/// --interp: the names are `mpr::interpolation_names`.
using Interpolation = mpr::InterpolationChoice;

/// The names of the interpolations on the command line (--interp) and in the viewer, in the order
/// of `Interpolation`.
inline constexpr std::array<std::string_view, 4> kInterpolationNames{
    mpr::choice_name(mpr::interpolation_names, Interpolation::nearest),
    mpr::choice_name(mpr::interpolation_names, Interpolation::synthetic),
    mpr::choice_name(mpr::interpolation_names, Interpolation::cylinder),
    mpr::choice_name(mpr::interpolation_names, Interpolation::depth)};

/// The command-line name of `interpolation`.
[[nodiscard]] constexpr std::string_view interpolation_name(Interpolation interpolation) noexcept {
  return kInterpolationNames[static_cast<std::size_t>(interpolation)];
}

/// Everything one invocation of mpr-render does. Lengths are world units of the sampler's data
/// (classroom: metres), angles in degrees.
struct Job {
  // Output.
  int width = 480, height = 360; ///< size of ONE view (tile); the image is cols*width x rows*height
  bool size_given = false;       ///< light fields default to the reference camera's size
  int cols = 1, rows = 1;
  std::vector<std::string> views{"default"}; ///< view specs, row-major, one per tile
  std::filesystem::path output = "mpr-render.png";
  OutputEncoding encoding; ///< --bit-depth, --exr-pixel (output.hpp; 8-bit PNG, half-float EXR by default)
  int threads = 0;
  bool use_double = false;
  bool no_budget = false; ///< --no-budget: lift the preflight's memory and time limits (preflight.hpp)
  bool print_camera = false;
  bool labels = false;                      ///< --labels: each tile labelled with its GLC type (and focus)
  bool video = true;                        ///< also write an MP4 of an animation when ffmpeg is on PATH
  std::optional<std::pair<int, int>> shard; ///< --shard K/N: only frames f (from 0) with f % N == K
  int frames = 0;                           ///< 0: a single image; N >= 1: an animation of N frames
  double fps = 12;                          ///< frame rate of the MP4 of an animation
  // Pixel sampling (pixel_sampling.hpp).
  int spp = 1;                          ///< samples per pixel (1: the pixel centre, as before)
  mpr::AnyFilter filter;                ///< reconstruction filter of spp > 1 (default: the box of radius 0.5)
  std::optional<ApertureSpec> aperture; ///< finite aperture (aperture.hpp); needs spp > 1
  // Sampler.
  SamplerKind sampler = SamplerKind::scene;
  std::filesystem::path input; ///< OBJ file, _par.txt file, Stanford / HCI / COLMAP model folder or LFCA positions file
  std::filesystem::path colmap_images; ///< --colmap-images (empty: found beside the model, loading.hpp)
  double obj_scale = 1;
  std::optional<std::pair<int, int>> raster; ///< scene/OBJ: rasterized virtual array of C x R cameras
  int raster_samples = 1;                    ///< --raster: N x N points a camera pixel (odd)
  Interpolation interpolation = Interpolation::synthetic;
  bool interpolation_given = false;                     ///< else: synthetic for refocusing, cylinder for other views
  Track radius{10};                                     ///< cylinder aperture radius (depth proxy: candidate radius)
  bool radius_given = false;                            ///< else: the array's camera spacing (light fields, --raster)
  std::optional<Track> focal_depth;                     ///< light fields: depth of the focal (image) plane
  std::optional<std::filesystem::path> depth_maps;      ///< light fields: folder of one PFM per camera
  std::optional<mpr::PlaneSweepConfig> depth_estimate;  ///< light fields: --depth-maps estimate:, --sweep
  mpr::DepthProxy proxy;                                ///< --proxy: the depth proxy's settings (its radius unused)
  std::string depth_maps_arg;                           ///< --depth-maps as given (the viewer's command line)
  std::string sweep_arg, proxy_arg;                     ///< --sweep and --proxy as given (the same), or ""
  std::optional<std::filesystem::path> save_depth_maps; ///< --save-depth-maps FOLDER: the estimated maps
  bool all_in_focus = false;                            ///< --all-in-focus: the same as --interp depth
  std::optional<std::pair<int, int>> focus_at;          ///< --focus-at X,Y: output pixel whose depth sets the focus
  std::optional<std::filesystem::path> write_depth;     ///< --write-depth FILE.pfm: the depth of the view(s)
  double reference_depth = 1000;                        ///< Stanford / LFCA: depth of the rectified reference plane
  double position_scale = 1;                            ///< Stanford / LFCA: world units per stored position unit
  std::optional<int> camera;                            ///< light fields: the reference camera (index)
  /// Light fields: called after each image is loaded with (loaded, total); not set from the
  /// command line (main.cpp draws a progress line on a terminal with it).
  std::function<void(std::size_t loaded, std::size_t total)> load_progress;
  std::function<void(const mpr::DepthProgress&)> depth_progress; ///< --depth-maps estimate's stages
  double zoom = 1; ///< light fields: the view's focal-plane rectangle scaled by 1 / zoom
  /// Light fields: frames box-filtered to 1/N of their scale before rendering (prefilter.hpp);
  /// nullopt: `auto`, N from the output pixels' footprint on the frames.
  std::optional<int> prefilter;
  // Surface.
  std::optional<mpr::Vec3<double>> plane_centre, look_at;
  std::optional<std::pair<double, double>> plane_size;
  mpr::Vec3<double> up{0, 1, 0};
  Track tilt_x{0}, tilt_y{0};                              ///< degrees, about the plane's width / height direction
  std::optional<std::array<mpr::Vec3<double>, 4>> rectify; ///< scene quad that fills the output
  bool rectify_to_plane = false; ///< `--rectify plane`: the untilted plane's corners fill the output
  // Selector helpers.
  std::optional<mpr::Vec3<double>> scene_centre;
  std::optional<double> scene_scale;
  std::optional<std::string> morph_to;          ///< second view spec of a morph
  Track morph = Track::parse("0:1", "--morph"); ///< morph weight (0: the view, 1: morph_to)

  /// Light fields: depth maps come from a folder or from estimation (--depth-maps).
  [[nodiscard]] bool has_depth_maps() const noexcept { return depth_maps.has_value() || depth_estimate.has_value(); }
  /// The depth proxy of --interp depth and of the depth outputs: `proxy` (--proxy) with `radius`.
  [[nodiscard]] mpr::DepthProxy depth_proxy(double radius) const noexcept {
    mpr::DepthProxy d = proxy;
    d.radius = radius;
    return d;
  }
};

/// True when the track takes more than one value over the animation.
[[nodiscard]] inline bool animated(const Track& track) noexcept {
  for (const Track::Key& k : track.keys())
    if (k.value != track.keys().front().value) return true;
  return false;
}

/// The first option of `job` whose value changes over an animation ("--tilt-x", "--morph-to",
/// ...), or "" when nothing is animated.
[[nodiscard]] inline std::string animated_option(const Job& job) {
  if (job.morph_to && animated(job.morph)) return "--morph-to";
  if (animated(job.tilt_x)) return "--tilt-x";
  if (animated(job.tilt_y)) return "--tilt-y";
  if (animated(job.radius)) return "--radius";
  if (job.focal_depth && animated(*job.focal_depth)) return "--focal-depth";
  if (job.aperture && animated(job.aperture->size)) return "--aperture";
  return "";
}

/// An animated value needs --frames (without it only the start would be rendered), and
/// --frames needs an animated value (otherwise every frame would be the same image).
inline void check_animation(const Job& job) {
  const std::string option = animated_option(job);
  if (!option.empty() && job.frames == 0)
    throw mpr::argument_error(option, "is animated (it changes over time): give --frames N to render N frames");
  if (option.empty() && job.frames > 0)
    throw mpr::argument_error("--frames", "nothing is animated (give a FROM:TO or keyframe value to --tilt-x, "
                                          "--tilt-y, --radius, --focal-depth, --aperture's size or --morph, or "
                                          "--morph-to VIEW)");
}

/// The colour-mapped preview written beside the depth of --write-depth: FILE.pfm -> FILE_preview.png.
[[nodiscard]] inline std::filesystem::path depth_preview_path(const std::filesystem::path& pfm) {
  std::filesystem::path p = pfm;
  p.replace_filename(pfm.stem().string() + "_preview.png");
  return p;
}

/// The parameters of one frame.
struct FrameParams {
  double tilt_x = 0, tilt_y = 0, radius = 10, focal_depth = 1, morph = 0;
  double aperture_size = 0; ///< --aperture: the finite aperture's size in this frame
};

inline FrameParams frame_params(const Job& job, double default_focal_depth, double t) {
  FrameParams p;
  p.tilt_x = job.tilt_x.at(t);
  p.tilt_y = job.tilt_y.at(t);
  p.radius = job.radius.at(t);
  p.focal_depth = job.focal_depth ? job.focal_depth->at(t) : default_focal_depth;
  p.morph = job.morph.at(t);
  if (job.aperture) p.aperture_size = job.aperture->size.at(t);
  return p;
}

} // namespace mpr_cli
