#pragma once
// mpr-render's job description: the parsed command line as a `Job` (make_job / parse_job).
// The options are listed in options.hpp; loading, framing and rendering live in loading.hpp,
// framing.hpp, samplers.hpp and render_job.hpp.

#include "animation.hpp"
#include "aperture.hpp"
#include "cli_args.hpp"
#include "depth_options.hpp"
#include "options.hpp"
#include "output.hpp"
#include "pixel_sampling.hpp"

#include <mpr/core/error.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/depth_proxy.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace mpr_cli {

enum class SamplerKind { scene, obj, par, stanford, lfca, hci, colmap };

/// Whether `kind` is a light field (a calibrated camera array) rather than a scene to ray cast.
[[nodiscard]] constexpr bool is_light_field(SamplerKind kind) noexcept {
  return kind != SamplerKind::scene && kind != SamplerKind::obj;
}
enum class Interpolation { nearest, synthetic, cylinder, depth };

/// Everything one invocation of mpr-render does. Lengths are world units of the sampler's data
/// (classroom: metres), angles in degrees.
struct Job {
  // Output.
  int width = 480, height = 360; ///< size of ONE view (tile); the image is cols*width x rows*height
  bool size_given = false;       ///< light fields default to the reference camera's size
  int cols = 1, rows = 1;
  std::vector<std::string> views{"default"}; ///< view specs, row-major, one per tile
  std::filesystem::path output = "mpr-render.png";
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

/// --shard K/N of an animation of `frames` frames: N in [1, frames], K in [0, N - 1] (0-based, as
/// Slurm's $SLURM_ARRAY_TASK_ID of --array=0-(N-1)).
inline std::pair<int, int> parse_shard(const std::string& text, int frames) {
  if (frames == 0) throw mpr::argument_error("--shard", "splits an animation: needs --frames N");
  const std::vector<std::string> parts = split(text, '/');
  if (parts.size() != 2) throw mpr::argument_error("--shard", "'" + text + "' is not K/N");
  const int n = parse_int(parts[1], "--shard", 1, frames);
  return {parse_int(parts[0], "--shard", 0, n - 1), n};
}

/// What the program calling `make_job` does with the options beyond mpr-render's use of them.
struct JobContext {
  /// The program reads --depth-maps itself (mpr-view: click-to-focus), so they need no other
  /// reader on the command line. Default false (mpr-render).
  bool reads_depth_maps = false;
};

/// Builds the Job from a parsed command line; throws argument_error naming the option.
inline Job make_job(const ParsedArgs& args, const JobContext& context = {}) {
  Job job;
  if (const auto v = args.get("output")) {
    if (v->empty()) throw mpr::argument_error("--output", "empty file name");
    job.output = *v;
  }
  (void)image_format(job.output); // .png, .jpg, .jpeg or none; anything else is refused
  if (const auto v = args.get("size")) {
    std::tie(job.width, job.height) = parse_size(*v, "--size");
    job.size_given = true;
  }
  if (const auto v = args.get("layout")) {
    std::tie(job.cols, job.rows) = parse_size(*v, "--layout");
    if (job.cols * job.rows > 64) throw mpr::argument_error("--layout", "at most 64 views");
  }
  if (args.has("view") && args.has("views")) throw mpr::argument_error("--view", "give --view or --views, not both");
  if (const auto v = args.get("view")) job.views = {*v};
  if (const auto v = args.get("views")) {
    job.views = split(*v, ',');
    for (std::string& s : job.views)
      for (char& c : s)
        if (c == ';') c = ',';
  }
  if (static_cast<int>(job.views.size()) == 1 && job.cols * job.rows > 1)
    job.views.assign(static_cast<std::size_t>(job.cols * job.rows), job.views[0]);
  if (static_cast<int>(job.views.size()) != job.cols * job.rows)
    throw mpr::argument_error("--views", std::to_string(job.views.size()) + " views for a " + std::to_string(job.cols) +
                                             "x" + std::to_string(job.rows) + " layout");
  if (const auto v = args.get("threads")) job.threads = parse_int(*v, "--threads", 0, 1024);
  job.use_double = args.has("double");
  job.no_budget = args.has("no-budget");
  job.print_camera = args.has("print-camera");
  job.video = !args.has("no-video");
  if (const auto v = args.get("frames")) job.frames = parse_int(*v, "--frames", 1, 100000);
  if (const auto v = args.get("shard")) job.shard = parse_shard(*v, job.frames);
  if (const auto v = args.get("spp")) job.spp = parse_spp(*v);
  if (const auto v = args.get("filter")) {
    job.filter = parse_filter(*v);
    if (job.spp == 1) throw mpr::argument_error("--filter", "needs --spp N with N > 1 (one sample is not filtered)");
  }
  if (const auto v = args.get("aperture")) {
    job.aperture = parse_aperture(*v);
    if (job.spp == 1) throw mpr::argument_error("--aperture", "needs --spp N with N > 1 (samples over the aperture)");
  }
  if (const auto v = args.get("lens-distance")) {
    if (!job.aperture) throw mpr::argument_error("--lens-distance", "needs --aperture SHAPE:SIZE");
    job.aperture->distance = parse_lens_distance(*v);
  }
  if (const auto v = args.get("focus")) {
    if (!job.aperture) throw mpr::argument_error("--focus", "needs --aperture SHAPE:SIZE");
    job.aperture->focus = parse_focus(*v);
  }
  job.labels = args.has("labels");
  if (const auto v = args.get("fps")) {
    if (job.frames == 0) throw mpr::argument_error("--fps", "applies to animations (--frames N)");
    job.fps = parse_number(*v, "--fps");
    if (!(job.fps > 0 && job.fps <= 1000))
      throw mpr::argument_error("--fps", "must lie in (0, 1000] frames per second");
  }

  int samplers = 0;
  if (const auto v = args.get("scene")) {
    if (*v != "classroom") throw mpr::argument_error("--scene", "'" + *v + "' is not a built-in scene (classroom)");
    ++samplers;
  }
  const auto input = [&](const char* name, SamplerKind kind) {
    if (const auto v = args.get(name)) {
      job.sampler = kind;
      job.input = *v;
      ++samplers;
      std::error_code ec;
      if (!std::filesystem::exists(job.input, ec))
        throw mpr::io_error(job.input.string(),
                            kind == SamplerKind::stanford || kind == SamplerKind::hci || kind == SamplerKind::colmap
                                ? "no such folder"
                                : "no such file");
    }
  };
  input("obj", SamplerKind::obj);
  input("par", SamplerKind::par);
  input("stanford", SamplerKind::stanford);
  input("lfca", SamplerKind::lfca);
  input("hci", SamplerKind::hci);
  input("colmap", SamplerKind::colmap);
  if (samplers > 1)
    throw mpr::argument_error("--scene/--obj/--par/--stanford/--lfca/--hci/--colmap", "choose one sampler");
  const bool light_field = is_light_field(job.sampler);
  const auto lf_only = [&](const char* name) {
    if (args.has(name) && !light_field)
      throw mpr::argument_error(std::string("--") + name,
                                "applies to light fields (--par, --stanford, --lfca, --hci, --colmap) only");
  };
  if (const auto v = args.get("colmap-images")) {
    if (job.sampler != SamplerKind::colmap) throw mpr::argument_error("--colmap-images", "applies to --colmap only");
    job.colmap_images = *v;
    std::error_code ec;
    if (!std::filesystem::is_directory(job.colmap_images, ec))
      throw mpr::io_error(job.colmap_images.string(), "no such folder");
  }
  if (const auto v = args.get("raster")) {
    if (light_field) throw mpr::argument_error("--raster", "applies to --scene and --obj only");
    job.raster = parse_size(*v, "--raster");
  }
  if (const auto v = args.get("raster-samples")) {
    if (!job.raster) throw mpr::argument_error("--raster-samples", "applies to --raster only");
    job.raster_samples = parse_int(*v, "--raster-samples", 1, 15);
    if (job.raster_samples % 2 == 0)
      throw mpr::argument_error("--raster-samples", "must be odd (the middle point lies on the pixel centre)");
  }
  for (const char* name : {"reference-depth", "position-scale", "camera", "zoom", "depth-maps", "prefilter"})
    lf_only(name);
  if (const auto v = args.get("prefilter"); v && *v != "auto") job.prefilter = parse_int(*v, "--prefilter", 1, 8);
  if (!job.raster)
    for (const char* name : {"interp", "radius", "focal-depth"}) lf_only(name);
  if (args.has("obj-scale") && job.sampler != SamplerKind::obj)
    throw mpr::argument_error("--obj-scale", "applies to --obj only");
  if (const auto v = args.get("obj-scale")) {
    job.obj_scale = parse_number(*v, "--obj-scale");
    if (!(job.obj_scale > 0)) throw mpr::argument_error("--obj-scale", "must be positive");
  }
  if (const auto v = args.get("interp")) {
    job.interpolation_given = true;
    if (*v == "nearest")
      job.interpolation = Interpolation::nearest;
    else if (*v == "synthetic")
      job.interpolation = Interpolation::synthetic;
    else if (*v == "cylinder")
      job.interpolation = Interpolation::cylinder;
    else if (*v == "depth")
      job.interpolation = Interpolation::depth;
    else
      throw mpr::argument_error("--interp", "'" + *v + "' is not nearest, synthetic, cylinder or depth");
  }
  if (args.has("all-in-focus")) {
    if (job.interpolation_given && job.interpolation != Interpolation::depth)
      throw mpr::argument_error("--all-in-focus", "is the depth interpolation; drop --interp " + *args.get("interp"));
    if (!light_field && !job.raster)
      throw mpr::argument_error("--all-in-focus",
                                "applies to light fields and --raster (a ray-cast scene is sharp at every depth)");
    job.all_in_focus = true;
    job.interpolation = Interpolation::depth;
    job.interpolation_given = true;
  }
  if (const auto v = args.get("depth-maps")) {
    job.depth_maps_arg = *v;
    if (*v == "estimate" || v->starts_with("estimate:")) {
      job.depth_estimate = parse_depth_estimate(*v);
    } else {
      job.depth_maps = *v;
      std::error_code ec;
      if (!std::filesystem::is_directory(job.depth_maps.value(), ec)) throw mpr::io_error(*v, "no such folder");
    }
  }
  if (const auto v = args.get("sweep")) {
    if (!job.depth_estimate)
      throw mpr::argument_error("--sweep", "sets the plane sweep of estimated depth maps: needs --depth-maps "
                                           "estimate:NEAR:FAR");
    parse_sweep(*v, *job.depth_estimate);
    job.sweep_arg = *v;
  }
  if (const auto v = args.get("save-depth-maps")) {
    if (!job.depth_estimate)
      throw mpr::argument_error("--save-depth-maps", "saves estimated maps: needs --depth-maps estimate:NEAR:FAR");
    job.save_depth_maps = *v;
    // The Stanford reader refuses a folder holding out_*.pfm files beside the images.
    std::error_code ec;
    if (job.sampler == SamplerKind::stanford && std::filesystem::equivalent(*job.save_depth_maps, job.input, ec))
      throw mpr::argument_error("--save-depth-maps", "'" + *v +
                                                         "' is the --stanford folder, which the depth maps would make "
                                                         "unreadable; save them in a folder of their own");
  }
  if (const auto v = args.get("focus-at")) {
    const std::vector<std::string> xy = split(*v, ',');
    if (xy.size() != 2) throw mpr::argument_error("--focus-at", "'" + *v + "' is not X,Y (output pixel coordinates)");
    job.focus_at = std::pair{parse_int(xy[0], "--focus-at", 0, 1 << 20), parse_int(xy[1], "--focus-at", 0, 1 << 20)};
    if (job.all_in_focus)
      throw mpr::argument_error("--focus-at", "--all-in-focus has no focal depth (each ray is focused at its own)");
    if (job.aperture && !job.aperture->focus.empty())
      throw mpr::argument_error("--focus-at", "sets the focus itself; drop --focus");
    if (!light_field && !job.raster && !job.aperture)
      throw mpr::argument_error("--focus-at", "applies to light fields, --raster and --aperture (a pinhole view of a "
                                              "ray-cast scene is sharp at every depth)");
    if (light_field && !job.has_depth_maps())
      throw mpr::argument_error(
          "--focus-at", "needs --depth-maps FOLDER or estimate:NEAR:FAR (the depth under the pixel comes from the "
                        "cameras' depth maps)");
  }
  if (const auto v = args.get("write-depth")) {
    job.write_depth = *v;
    if (detail::lower(job.write_depth->extension().string()) != ".pfm")
      throw mpr::argument_error("--write-depth", "'" + *v + "': writes a .pfm file (and a PNG preview beside it)");
    if (job.frames > 0)
      throw mpr::argument_error("--write-depth", "writes the depth of one image, not of an animation (--frames)");
    if (light_field && !job.has_depth_maps())
      throw mpr::argument_error(
          "--write-depth", "needs --depth-maps FOLDER or estimate:NEAR:FAR for a light field (its depth comes from the "
                           "cameras' depth maps)");
    if (depth_preview_path(*job.write_depth) == job.output)
      throw mpr::argument_error("--write-depth", "its preview " + depth_preview_path(*job.write_depth).string() +
                                                     " would overwrite --output");
  }
  if (job.has_depth_maps() && !context.reads_depth_maps && job.interpolation != Interpolation::depth && !job.focus_at &&
      !job.write_depth)
    throw mpr::argument_error(
        "--depth-maps", "is read by --interp depth, --all-in-focus, --focus-at and --write-depth; give one of them");
  if (const auto v = args.get("proxy")) {
    if (job.interpolation != Interpolation::depth && !job.focus_at && !job.write_depth && !context.reads_depth_maps)
      throw mpr::argument_error("--proxy", "sets the depth proxy of --interp depth, --all-in-focus, --focus-at and "
                                           "--write-depth; give one of them");
    parse_proxy(*v, job.proxy);
    job.proxy_arg = *v;
  }
  if (job.interpolation == Interpolation::depth && light_field && !job.has_depth_maps())
    throw mpr::argument_error(job.all_in_focus ? "--all-in-focus" : "--interp depth",
                              "needs --depth-maps FOLDER (one PFM per camera) or estimate:NEAR:FAR for a light field");
  if (const auto v = args.get("radius")) {
    if (job.interpolation_given && job.interpolation != Interpolation::cylinder &&
        job.interpolation != Interpolation::depth)
      throw mpr::argument_error("--radius", "needs --interp cylinder or depth");
    if (job.interpolation != Interpolation::depth) job.interpolation = Interpolation::cylinder;
    job.radius_given = true;
    job.radius = parse_track(*v, "--radius");
    for (const Track::Key& k : job.radius.keys())
      if (!(k.value > 0)) throw mpr::argument_error("--radius", "must be positive");
  }
  if (const auto v = args.get("focal-depth")) {
    job.focal_depth = parse_track(*v, "--focal-depth");
    for (const Track::Key& k : job.focal_depth->keys())
      if (!(k.value > 0)) throw mpr::argument_error("--focal-depth", "must be positive (in front of the camera)");
  }
  if (const auto v = args.get("reference-depth")) {
    job.reference_depth = parse_number(*v, "--reference-depth");
    if (!(job.reference_depth > 0)) throw mpr::argument_error("--reference-depth", "must be positive");
  }
  if (const auto v = args.get("position-scale")) {
    job.position_scale = parse_number(*v, "--position-scale");
    if (!(job.position_scale > 0)) throw mpr::argument_error("--position-scale", "must be positive");
  }
  if (const auto v = args.get("camera")) job.camera = parse_int(*v, "--camera", 0, 1000000);
  if (const auto v = args.get("zoom")) {
    job.zoom = parse_number(*v, "--zoom");
    if (!(job.zoom > 0 && job.zoom <= 1e6)) throw mpr::argument_error("--zoom", "must lie in (0, 1e6]");
  }

  if (const auto v = args.get("plane-centre")) job.plane_centre = parse_vec3(*v, "--plane-centre");
  if (const auto v = args.get("look-at")) job.look_at = parse_vec3(*v, "--look-at");
  if (const auto v = args.get("up")) job.up = parse_vec3(*v, "--up");
  if (const auto v = args.get("plane-size")) {
    const std::vector<std::string> wh = split(*v, ',');
    if (wh.size() != 2) throw mpr::argument_error("--plane-size", "'" + *v + "' is not W,H");
    job.plane_size = {parse_number(wh[0], "--plane-size"), parse_number(wh[1], "--plane-size")};
    if (!(job.plane_size->first > 0) || !(job.plane_size->second > 0))
      throw mpr::argument_error("--plane-size", "must be positive");
  }
  if ((job.plane_centre || job.look_at || job.plane_size) && !(job.plane_centre && job.look_at && job.plane_size))
    throw mpr::argument_error("--plane-centre", "give --plane-centre, --look-at and --plane-size together");
  if (light_field && job.plane_centre)
    throw mpr::argument_error("--plane-centre", "light fields use --focal-depth and --camera");
  if (const auto v = args.get("tilt-x")) job.tilt_x = parse_track(*v, "--tilt-x");
  if (const auto v = args.get("tilt-y")) job.tilt_y = parse_track(*v, "--tilt-y");
  for (const Track* t : {&job.tilt_x, &job.tilt_y})
    for (const Track::Key& k : t->keys())
      if (!(std::abs(k.value) < 89))
        throw mpr::argument_error(t == &job.tilt_x ? "--tilt-x" : "--tilt-y", "must lie within (-89, 89) degrees");
  if (const auto v = args.get("rectify"); v && *v == "plane") {
    job.rectify_to_plane = true;
  } else if (v) {
    const std::vector<std::string> corners = split(*v, ';');
    if (corners.size() != 4) throw mpr::argument_error("--rectify", "needs four X,Y,Z corners separated by ';'");
    std::array<mpr::Vec3<double>, 4> quad;
    for (std::size_t k = 0; k < 4; ++k) quad[k] = parse_vec3(corners[k], "--rectify");
    job.rectify = quad;
  }
  if (const auto v = args.get("scene-centre")) job.scene_centre = parse_vec3(*v, "--scene-centre");
  if (const auto v = args.get("scene-scale")) {
    job.scene_scale = parse_number(*v, "--scene-scale");
    if (!(*job.scene_scale > 0)) throw mpr::argument_error("--scene-scale", "must be positive");
  }
  if (const auto v = args.get("morph-to")) job.morph_to = *v;
  if (const auto v = args.get("morph")) {
    if (!job.morph_to) throw mpr::argument_error("--morph", "needs --morph-to");
    job.morph = parse_track(*v, "--morph");
  }
  if (job.focus_at && job.focal_depth && animated(*job.focal_depth))
    throw mpr::argument_error("--focus-at", "sets the focal depth; --focal-depth may only give the plane it starts "
                                            "from, one number");
  check_animation(job);
  return job;
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

/// Parses a command line (argv[0] is skipped) into a Job.
inline Job parse_job(int argc, const char* const* argv) { return make_job(parse_args(argc, argv, options())); }

} // namespace mpr_cli
