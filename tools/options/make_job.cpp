// The parsed command line -> Job (make_job.hpp), one function per part of the job.
#include "make_job.hpp"

#include "parse.hpp"

#include <mpr/core/error.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <system_error>
#include <tuple>
#include <vector>

namespace mpr_cli {

std::pair<int, int> parse_shard(const std::string& text, int frames) {
  if (frames == 0) throw mpr::argument_error("--shard", "splits an animation: needs --frames N");
  const std::vector<std::string> parts = split(text, '/');
  if (parts.size() != 2) throw mpr::argument_error("--shard", "'" + text + "' is not K/N");
  const int n = parse_int(parts[1], "--shard", 1, frames);
  return {parse_int(parts[0], "--shard", 0, n - 1), n};
}

namespace {

/// --bit-depth 8|16 (PNG only) and --exr-pixel half|float (OpenEXR only) for the job's output.
void read_output_encoding(Job& job, const OptionValues& args) {
  const ImageFormat format = image_format(job.output);
  if (const auto k = args.choice("bit-depth")) {
    job.encoding.png_bits = *k == 0 ? 8 : 16;
    if (format == ImageFormat::jpeg && job.encoding.png_bits == 16)
      throw mpr::argument_error("--bit-depth", "JPEG is 8-bit; write .png for 16 bits, .pfm or .exr for linear floats");
    if (is_linear(format))
      throw mpr::argument_error("--bit-depth", "applies to .png; '" + job.output.string() + "' stores linear floats");
  }
  if (const auto k = args.choice("exr-pixel")) {
    if (format != ImageFormat::exr)
      throw mpr::argument_error("--exr-pixel", "applies to .exr output, not '" + job.output.string() + "'");
    job.encoding.exr_pixel = *k == 1 ? ExrPixel::full : ExrPixel::half;
  }
}

/// The output file, the image's size and views, and the run's settings.
void read_output(Job& job, const OptionValues& args) {
  if (const auto v = args.get("output")) {
    if (v->empty()) throw mpr::argument_error("--output", "empty file name");
    job.output = *v;
  }
  (void)image_format(job.output); // .png, .jpg, .jpeg, .pfm, .exr or none; anything else is refused
  read_output_encoding(job, args);
  if (const auto v = args.size("size")) {
    std::tie(job.width, job.height) = *v;
    job.size_given = true;
  }
  if (const auto v = args.size("layout")) {
    std::tie(job.cols, job.rows) = *v;
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
  if (const auto v = args.integer("threads")) job.threads = *v;
  job.use_double = args.has("double");
  job.no_budget = args.has("no-budget");
  job.print_camera = args.has("print-camera");
  job.video = !args.has("no-video");
  if (const auto v = args.integer("frames")) job.frames = *v;
  if (const auto v = args.get("shard")) job.shard = parse_shard(*v, job.frames);
}

/// Samples per pixel, their filter, the finite aperture, labels and the video's frame rate.
void read_pixel_sampling(Job& job, const OptionValues& args) {
  if (const auto v = args.integer("spp")) job.spp = *v;
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
  if (args.has("fps")) {
    if (job.frames == 0) throw mpr::argument_error("--fps", "applies to animations (--frames N)");
    job.fps = *args.number("fps");
  }
}

/// `--NAME` given for a job that is not a light field.
void light_field_only(const OptionValues& args, const Job& job, std::string_view name) {
  if (args.has(name) && !is_light_field(job.sampler))
    throw mpr::argument_error("--" + std::string(name),
                              "applies to light fields (--par, --stanford, --lfca, --hci, --colmap) only");
}

/// The sampler (one of the input options) and its input file or folder.
void read_sampler(Job& job, const OptionValues& args) {
  int samplers = 0;
  if (args.has("scene")) {
    (void)args.choice("scene");
    ++samplers;
  }
  constexpr std::array<std::pair<std::string_view, SamplerKind>, 6> inputs{{{"obj", SamplerKind::obj},
                                                                            {"par", SamplerKind::par},
                                                                            {"stanford", SamplerKind::stanford},
                                                                            {"lfca", SamplerKind::lfca},
                                                                            {"hci", SamplerKind::hci},
                                                                            {"colmap", SamplerKind::colmap}}};
  for (const auto& [name, kind] : inputs) {
    const auto v = args.get(name);
    if (!v) continue;
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
  if (samplers > 1)
    throw mpr::argument_error("--scene/--obj/--par/--stanford/--lfca/--hci/--colmap", "choose one sampler");
  if (const auto v = args.get("colmap-images")) {
    if (job.sampler != SamplerKind::colmap) throw mpr::argument_error("--colmap-images", "applies to --colmap only");
    job.colmap_images = *v;
    std::error_code ec;
    if (!std::filesystem::is_directory(job.colmap_images, ec))
      throw mpr::io_error(job.colmap_images.string(), "no such folder");
  }
  if (args.has("raster")) {
    if (is_light_field(job.sampler)) throw mpr::argument_error("--raster", "applies to --scene and --obj only");
    job.raster = args.size("raster");
  }
  if (args.has("raster-samples")) {
    if (!job.raster) throw mpr::argument_error("--raster-samples", "applies to --raster only");
    job.raster_samples = *args.integer("raster-samples");
    if (job.raster_samples % 2 == 0)
      throw mpr::argument_error("--raster-samples", "must be odd (the middle point lies on the pixel centre)");
  }
  for (const char* name : {"reference-depth", "position-scale", "camera", "zoom", "depth-maps", "prefilter"})
    light_field_only(args, job, name);
  if (const auto v = args.get("prefilter"); v && *v != "auto") job.prefilter = args.integer("prefilter");
  if (!job.raster)
    for (const char* name : {"interp", "radius", "focal-depth"}) light_field_only(args, job, name);
  if (args.has("obj-scale")) {
    if (job.sampler != SamplerKind::obj) throw mpr::argument_error("--obj-scale", "applies to --obj only");
    job.obj_scale = *args.number("obj-scale");
  }
}

/// --interp and --all-in-focus (the depth interpolation).
void read_interpolation(Job& job, const OptionValues& args) {
  if (const auto k = args.choice("interp")) {
    job.interpolation_given = true;
    job.interpolation = static_cast<Interpolation>(*k);
  }
  if (args.has("all-in-focus")) {
    if (job.interpolation_given && job.interpolation != Interpolation::depth)
      throw mpr::argument_error("--all-in-focus", "is the depth interpolation; drop --interp " + *args.get("interp"));
    if (!is_light_field(job.sampler) && !job.raster)
      throw mpr::argument_error("--all-in-focus",
                                "applies to light fields and --raster (a ray-cast scene is sharp at every depth)");
    job.all_in_focus = true;
    job.interpolation = Interpolation::depth;
    job.interpolation_given = true;
  }
}

/// --depth-maps (a folder or estimate:), --sweep and --save-depth-maps.
void read_depth_maps(Job& job, const OptionValues& args) {
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
                                           "estimate[:NEAR:FAR]");
    parse_sweep(*v, *job.depth_estimate);
    job.sweep_arg = *v;
  }
  if (const auto v = args.get("save-depth-maps")) {
    if (!job.depth_estimate)
      throw mpr::argument_error("--save-depth-maps", "saves estimated maps: needs --depth-maps estimate[:NEAR:FAR]");
    job.save_depth_maps = *v;
    // The Stanford reader refuses a folder holding out_*.pfm files beside the images.
    std::error_code ec;
    if (job.sampler == SamplerKind::stanford && std::filesystem::equivalent(*job.save_depth_maps, job.input, ec))
      throw mpr::argument_error("--save-depth-maps", "'" + *v +
                                                         "' is the --stanford folder, which the depth maps would make "
                                                         "unreadable; save them in a folder of their own");
  }
}

/// --focus-at and --write-depth, the readers of depth, and --proxy.
void read_depth_outputs(Job& job, const OptionValues& args, const JobContext& context) {
  const bool light_field = is_light_field(job.sampler);
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
          "--focus-at", "needs --depth-maps FOLDER or estimate[:NEAR:FAR] (the depth under the pixel comes from the "
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
          "--write-depth",
          "needs --depth-maps FOLDER or estimate[:NEAR:FAR] for a light field (its depth comes from the "
          "cameras' depth maps)");
    if (depth_preview_path(*job.write_depth) == job.output)
      throw mpr::argument_error("--write-depth", "its preview " + depth_preview_path(*job.write_depth).string() +
                                                     " would overwrite --output");
  }
  const bool reads_depth = job.interpolation == Interpolation::depth || job.focus_at || job.write_depth;
  if (job.has_depth_maps() && !context.reads_depth_maps && !reads_depth)
    throw mpr::argument_error(
        "--depth-maps", "is read by --interp depth, --all-in-focus, --focus-at and --write-depth; give one of them");
  if (const auto v = args.get("proxy")) {
    if (!reads_depth && !context.reads_depth_maps)
      throw mpr::argument_error("--proxy", "sets the depth proxy of --interp depth, --all-in-focus, --focus-at and "
                                           "--write-depth; give one of them");
    parse_proxy(*v, job.proxy);
    job.proxy_arg = *v;
  }
  if (job.interpolation == Interpolation::depth && light_field && !job.has_depth_maps())
    throw mpr::argument_error(
        job.all_in_focus ? "--all-in-focus" : "--interp depth",
        "needs --depth-maps FOLDER (one PFM per camera) or estimate[:NEAR:FAR] for a light field");
}

/// The interpolation's radius, the focal plane and the light field's geometry.
void read_focus(Job& job, const OptionValues& args) {
  if (args.has("radius")) {
    if (job.interpolation_given && job.interpolation != Interpolation::cylinder &&
        job.interpolation != Interpolation::depth)
      throw mpr::argument_error("--radius", "needs --interp cylinder or depth");
    if (job.interpolation != Interpolation::depth) job.interpolation = Interpolation::cylinder;
    job.radius_given = true;
    job.radius = *args.track("radius");
  }
  if (const auto v = args.track("focal-depth")) job.focal_depth = *v;
  if (const auto v = args.number("reference-depth")) job.reference_depth = *v;
  if (const auto v = args.number("position-scale")) job.position_scale = *v;
  if (const auto v = args.integer("camera")) job.camera = *v;
  if (const auto v = args.number("zoom")) job.zoom = *v;
}

/// The image plane, its tilt and rectification, the gallery's framing and the morph.
void read_surface(Job& job, const OptionValues& args) {
  const bool light_field = is_light_field(job.sampler);
  job.plane_centre = args.vec3("plane-centre");
  job.look_at = args.vec3("look-at");
  if (const auto v = args.vec3("up")) job.up = *v;
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
  if (const auto v = args.track("tilt-x")) job.tilt_x = *v;
  if (const auto v = args.track("tilt-y")) job.tilt_y = *v;
  if (const auto v = args.get("rectify"); v && *v == "plane") {
    job.rectify_to_plane = true;
  } else if (v) {
    const std::vector<std::string> corners = split(*v, ';');
    if (corners.size() != 4) throw mpr::argument_error("--rectify", "needs four X,Y,Z corners separated by ';'");
    std::array<mpr::Vec3<double>, 4> quad;
    for (std::size_t k = 0; k < 4; ++k) quad[k] = parse_vec3(corners[k], "--rectify");
    job.rectify = quad;
  }
  job.scene_centre = args.vec3("scene-centre");
  job.scene_scale = args.number("scene-scale");
  if (const auto v = args.get("morph-to")) job.morph_to = *v;
  if (args.has("morph")) {
    if (!job.morph_to) throw mpr::argument_error("--morph", "needs --morph-to");
    job.morph = *args.track("morph");
  }
}

} // namespace

Job make_job(const OptionValues& args, const JobContext& context) {
  Job job;
  read_output(job, args);
  read_pixel_sampling(job, args);
  read_sampler(job, args);
  read_interpolation(job, args);
  read_depth_maps(job, args);
  read_depth_outputs(job, args, context);
  read_focus(job, args);
  read_surface(job, args);
  if (job.focus_at && job.focal_depth && animated(*job.focal_depth))
    throw mpr::argument_error("--focus-at", "sets the focal depth; --focal-depth may only give the plane it starts "
                                            "from, one number");
  check_animation(job);
  return job;
}

Job parse_job(int argc, const char* const* argv) { return make_job(parse_options(argc, argv, Tools::render)); }

} // namespace mpr_cli
