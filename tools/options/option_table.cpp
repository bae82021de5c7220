// The option table of mpr-render and mpr-view (option_table.hpp): every option once.
#include "option_table.hpp"

#include "mpr-render/aperture.hpp"
#include "mpr-render/pixel_sampling.hpp"

#include <mpr/policy_names.hpp>

#include <array>
#include <charconv>
#include <string>
#include <type_traits>
#include <variant>

namespace mpr_cli {

namespace {

// --- How the save command writes values back (shortest text that reads back the same double).

std::string num(double v) {
  char text[32];
  const std::to_chars_result r = std::to_chars(text, text + sizeof text, v);
  return std::string(text, r.ptr);
}
std::string vec3(const mpr::Vec3<double>& v) { return num(v.x()) + "," + num(v.y()) + "," + num(v.z()); }
std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

/// --filter NAME:RADIUS of `filter` (parse_filter reads it back); names from mpr::filter_names.
std::string filter_text(const mpr::AnyFilter& filter) {
  const auto name = std::visit(
      [](const auto& f) -> mpr::FilterChoice {
        using F = std::remove_cvref_t<decltype(f)>;
        if constexpr (std::is_same_v<F, mpr::BoxFilter>) return mpr::FilterChoice::box;
        if constexpr (std::is_same_v<F, mpr::TentFilter>) return mpr::FilterChoice::tent;
        if constexpr (std::is_same_v<F, mpr::GaussianFilter>) return mpr::FilterChoice::gaussian;
        if constexpr (std::is_same_v<F, mpr::MitchellFilter>) return mpr::FilterChoice::mitchell;
        return mpr::FilterChoice::lanczos;
      },
      filter.variant());
  return std::string(mpr::choice_name(mpr::filter_names, name)) + ":" + num(filter.radius());
}

/// --aperture SHAPE:SIZE of `spec` at animation time `time` (parse_aperture reads it back).
std::string aperture_text(const ApertureSpec& spec, double time) {
  const std::string shape = std::visit(
      [](const auto& a) -> std::string {
        using A = std::remove_cvref_t<decltype(a)>;
        if constexpr (std::is_same_v<A, mpr::glc::SquareAperture>) return "square";
        if constexpr (std::is_same_v<A, mpr::glc::GaussianAperture>) return "gaussian";
        if constexpr (std::is_same_v<A, mpr::glc::PolygonAperture>) return "polygon" + std::to_string(a.blades());
        return "disc";
      },
      spec.shape.variant());
  return shape + ":" + num(spec.size.at(time));
}

using Saved = std::optional<std::string>;
constexpr Saved kOmit = std::nullopt;

/// The input of the job when its sampler is `kind`.
template <SamplerKind kind>
Saved input_of(const SaveContext& c) {
  return c.job.sampler == kind ? Saved(c.job.input.string()) : kOmit;
}
/// Light fields and --raster: the interpolation's options apply.
bool interpolated(const Job& j) { return is_light_field(j.sampler) || j.raster.has_value(); }
/// The depth interpolation's own options (depth maps, proxy) shape the picture.
bool depth_interpolated(const Job& j) { return interpolated(j) && j.interpolation == Interpolation::depth; }
/// One view (no --layout).
bool single_view(const Job& j) { return j.cols * j.rows == 1; }

constexpr std::array<std::string_view, 1> kScenes{"classroom"};
constexpr std::array<std::string_view, 2> kBitDepths{"8", "16"};
constexpr std::array<std::string_view, 2> kExrPixels{"half", "float"};

constexpr Group input = Group::input, lf = Group::light_field, image = Group::image, surface = Group::surface,
                anim = Group::animation, run = Group::run, viewer = Group::viewer;
constexpr ValueKind flag = ValueKind::flag, integer = ValueKind::integer, number = ValueKind::number,
                    size = ValueKind::size, vec = ValueKind::vec3, track = ValueKind::track, choice = ValueKind::choice;
constexpr std::string_view kPositive = "must be positive";

// The table. The save command writes the options in this order; mpr-render's defaults are
// those of Job (job.hpp).
const std::array kOptions = {
    // Input: the sampler.
    Option{.name = "scene",
           .value = "classroom",
           .help = "Sampler: the built-in classroom demo scene, ray cast through a BVH.",
           .default_text = "classroom",
           .example = "--scene classroom",
           .kind = choice,
           .group = input,
           .bound_text = "is not a built-in scene (classroom)",
           .choices = kScenes},
    Option{.name = "obj",
           .value = "FILE.obj",
           .help = "Sampler: a Wavefront OBJ mesh (with MTL/texture), ray cast.",
           .example = "--obj examples/boxes.obj",
           .group = input,
           .save = input_of<SamplerKind::obj>},
    Option{.name = "obj-scale",
           .value = "S",
           .help = "Uniform scale of the OBJ positions.",
           .default_text = "1",
           .example = "--obj examples/boxes.obj --obj-scale 0.01",
           .kind = number,
           .group = input,
           .lo = 0,
           .lo_open = true,
           .bound_text = kPositive,
           .save =
               [](const SaveContext& c) {
                 return c.job.sampler == SamplerKind::obj && c.job.obj_scale != 1 ? Saved(num(c.job.obj_scale)) : kOmit;
               }},
    Option{.name = "par",
           .value = "FILE_par.txt",
           .help = "Sampler: a light field from a Middlebury-style _par.txt calibration.",
           .example = "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt",
           .group = input,
           .save = input_of<SamplerKind::par>},
    Option{.name = "stanford",
           .value = "FOLDER",
           .help = "Sampler: a Stanford light-field archive folder of out_RR_CC_Y_X.png images.",
           .example = "--stanford $MPR_DATA_DIR/stanford/chess --focal-depth 820",
           .group = input,
           .save = input_of<SamplerKind::stanford>},
    Option{.name = "lfca",
           .value = "POSITIONS.txt",
           .help = "Sampler: LFCA camera positions ('id X Y' lines) with {id}.png and {id}.homography.txt.",
           .example = "--lfca $MPR_DATA_DIR/lfca/positions.txt",
           .group = input,
           .save = input_of<SamplerKind::lfca>},
    Option{.name = "hci",
           .value = "FOLDER",
           .help = "Sampler: a scene of the HCI 4D light-field benchmark (input_CamNNN.png views of a 9x9 grid or any "
                   "subset holding the centre; parameters.cfg for the metric array, else an array in disparity units: "
                   "docs/depth.md). Default view: the centre camera, focused on the zero-disparity plane.",
           .example = "--hci $MPR_DATA_DIR/hci/backgammon --size 256x256",
           .group = input,
           .save = input_of<SamplerKind::hci>},
    Option{.name = "colmap",
           .value = "MODEL_FOLDER",
           .help = "Sampler: a COLMAP sparse model in text form (cameras.txt: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, "
                   "RADIAL, OPENCV without tangential terms; images.txt) with its images (--colmap-images, else "
                   "images/ found beside the model, as in PROJECT/sparse/0 and PROJECT/images).",
           .example = "--colmap $MPR_DATA_DIR/colmap/sparse/0",
           .group = input,
           .save = input_of<SamplerKind::colmap>},
    Option{.name = "colmap-images",
           .value = "FOLDER",
           .help = "--colmap: the folder of the model's images.",
           .example = "--colmap $MPR_DATA_DIR/colmap/sparse/0 --colmap-images $MPR_DATA_DIR/colmap/images",
           .group = input,
           .save =
               [](const SaveContext& c) {
                 return c.job.sampler == SamplerKind::colmap && !c.job.colmap_images.empty()
                            ? Saved(c.job.colmap_images.string())
                            : kOmit;
               }},

    // Light fields and --raster.
    Option{.name = "raster",
           .value = "CxR",
           .help = "Scene/OBJ: sample a rasterized virtual camera array of C x R cameras (160x120 pixels each, on the "
                   "image plane) instead of ray casting; --interp, --radius and --focal-depth (in front of the plane) "
                   "apply. Arrays estimated above 1 GiB (about 6,000 cameras) are refused before rendering.",
           .example = "--raster 16x12 --interp cylinder --radius 0.5",
           .kind = size,
           .group = lf,
           .save =
               [](const SaveContext& c) {
                 return c.job.raster ? Saved(size_text(c.job.raster->first, c.job.raster->second)) : kOmit;
               }},
    Option{.name = "raster-samples",
           .value = "N",
           .help = "--raster: each camera pixel the mean, in linear light, of N x N rasterized points over its area "
                   "(anti-aliased frames: no staircases or moire; the middle point gives the depth). N odd, 1..15 "
                   "(1: the pixel centre). Rasterizing takes up to N^2 times as long.",
           .default_text = "1",
           .example = "--raster 8x6 --raster-samples 3 --interp depth --view B",
           .kind = integer,
           .group = lf,
           .lo = 1,
           .hi = 15,
           .save =
               [](const SaveContext& c) {
                 return c.job.raster && c.job.raster_samples > 1 ? Saved(std::to_string(c.job.raster_samples)) : kOmit;
               }},
    Option{.name = "interp",
           .value = "nearest|synthetic|cylinder|depth",
           .help = "Light-field interpolation: nearest camera, full synthetic aperture, cylinder aperture of --radius, "
                   "or depth proxy (the surface from per-camera depth maps, the cameras that see it blended by angle; "
                   "--raster keeps the rasterizer's depth, light fields need --depth-maps; --radius: the cameras "
                   "considered, default twice the spacing).",
           .default_text = "synthetic for a planar array's reference view, cylinder for its other views, nearest for "
                           "every view of a ring or unstructured set",
           .example = "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --interp cylinder --radius 0.3",
           .kind = choice,
           .group = lf,
           .choices = kInterpolationNames,
           .save =
               [](const SaveContext& c) {
                 return interpolated(c.job) ? Saved(std::string(interpolation_name(c.job.interpolation))) : kOmit;
               }},
    Option{.name = "radius",
           .value = "R|A:B|T=V,...",
           .help = "Cylinder aperture radius, world units; animatable.",
           .default_text = "the array's camera spacing (a light field's median nearest-neighbour distance, the "
                           "--raster grid's cell width; twice that for --interp depth)",
           .example = "--raster 8x6 --interp cylinder --radius 0.5:3 --frames 9",
           .kind = track,
           .group = lf,
           .lo = 0,
           .lo_open = true,
           .bound_text = kPositive,
           .save =
               [](const SaveContext& c) {
                 return interpolated(c.job) && (c.job.interpolation == Interpolation::cylinder ||
                                                c.job.interpolation == Interpolation::depth)
                            ? Saved(num(c.job.radius.at(c.time)))
                            : kOmit;
               }},
    Option{.name = "depth-maps",
           .value = "FOLDER|estimate[:NEAR:FAR[:PLANES]]",
           .help = "Light fields: one PFM depth map per camera (depth along its optical axis, +inf where nothing was "
                   "seen), named after its image (cam.png -> cam.pfm), or estimated from the images by a plane sweep "
                   "over depths NEAR to FAR along the cameras' axes (PLANES planes, default 64; without NEAR:FAR the "
                   "range the calibration and the images give, and an object on an empty backdrop kept inside its "
                   "visual hull; mpr::estimate_scene_depth, docs/depth.md); read by --interp depth, --all-in-focus, "
                   "--focus-at and --write-depth.",
           .example = "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --all-in-focus --depth-maps "
                      "estimate:0.44:0.72",
           .group = lf,
           // Under another interpolation the viewer keeps depth maps for click-to-focus only, and
           // mpr-render refuses depth maps that nothing reads.
           .save =
               [](const SaveContext& c) {
                 return depth_interpolated(c.job) && c.job.has_depth_maps() ? Saved(c.job.depth_maps_arg) : kOmit;
               }},
    Option{.name = "sweep",
           .value = "KEY=VALUE,...",
           .help = "With --depth-maps estimate: the plane sweep's other settings (mpr::PlaneSweepConfig): selection "
                   "(axes: the cameras along the camera's image row and column, the default; nearest: the nearest by "
                   "distance), neighbours (cameras compared, 16), best (the smallest costs averaged, 8: occluded "
                   "neighbours drop out), truncation (0.3), spatial (aggregation extent in pixels, 12), range (colour "
                   "difference that cuts it, 0.2). Clean synthetic arrays: best=4 and spatial scaled to the frames "
                   "(docs/lightfield.md).",
           .example = "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --all-in-focus --depth-maps "
                      "estimate:0.44:0.72 --sweep best=3,spatial=6",
           .group = lf,
           .save =
               [](const SaveContext& c) {
                 return depth_interpolated(c.job) && c.job.has_depth_maps() && !c.job.sweep_arg.empty()
                            ? Saved(c.job.sweep_arg)
                            : kOmit;
               }},
    Option{.name = "proxy",
           .value = "KEY=VALUE,...",
           .help = "With --interp depth, --all-in-focus, --focus-at or --write-depth: the depth proxy's settings but "
                   "its radius (mpr::DepthProxy; --radius sets that): k (cameras blended, 4), tolerance (relative "
                   "depth tolerance of the surface search, 0.01), visibility_tolerance (of the blend's depth test, "
                   "0.03: forgives estimated maps' error), march_cameras (cameras tried in turn for the surface, 4), "
                   "whole_line (1: search the whole ray line, 0: only in front of the view's image surface).",
           .example = "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --all-in-focus --depth-maps "
                      "estimate:0.44:0.72 --proxy k=6,visibility_tolerance=0.05",
           .group = lf,
           .save =
               [](const SaveContext& c) {
                 return depth_interpolated(c.job) && !c.job.proxy_arg.empty() ? Saved(c.job.proxy_arg) : kOmit;
               }},
    Option{.name = "save-depth-maps",
           .value = "FOLDER",
           .help = "With --depth-maps estimate: write the estimated maps there as PFMs (read them back with "
                   "--depth-maps FOLDER).",
           .example = "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --all-in-focus --depth-maps "
                      "estimate:0.44:0.72:32 --save-depth-maps temple-depth",
           .group = lf},
    Option{.name = "all-in-focus",
           .help = "Light fields and --raster: every ray focused at its own depth, the first "
                   "surface the depth maps show along it (the same as --interp depth: the "
                   "cameras within --radius that see that point, the 4 best by angle "
                   "blended); --focal-depth only serves rays no depth map explains. Light "
                   "fields need --depth-maps.",
           .example = "--raster 8x6 --all-in-focus --view G",
           .kind = flag,
           .group = lf},
    Option{.name = "focus-at",
           .value = "X,Y",
           .help = "Autofocus: focus on what output pixel (X, Y) shows (from the top-left corner), and print the depth "
                   "chosen. Light fields (needs --depth-maps) and --raster: sets --focal-depth (light fields: the "
                   "depth along the reference camera's axis, the focal plane moved until that pixel's ray meets the "
                   "surface on it); a ray-cast scene with --aperture: sets --focus. The depth is taken with the first "
                   "frame's other settings.",
           .example = "--raster 8x6 --size 320x240 --focus-at 160,80",
           .group = lf},
    Option{.name = "write-depth",
           .value = "FILE.pfm",
           .help = "Also write the depth seen by each output pixel (one ray through its centre) as a PFM, +inf where "
                   "nothing is seen, and FILE_preview.png colour-mapped with a legend. Light fields (needs "
                   "--depth-maps): the depth of the surface the depth maps show, along the reference camera's axis "
                   "(the units of --focal-depth); scenes, also --raster: the ray cast's depth in front of the image "
                   "plane. Any view, tilt or layout; not with --frames.",
           .example = "--layout 2x1 --views A,G --write-depth depth_AG.pfm",
           .group = lf},
    Option{.name = "focal-depth",
           .value = "D|A:B|T=V,...",
           .help = "Light fields: depth of the focal (image) plane in front of the reference camera; animatable.",
           .default_text = "the reference plane",
           .example = "--stanford $MPR_DATA_DIR/stanford/chess --focal-depth 700:950 --frames 9",
           .kind = track,
           .group = lf,
           .lo = 0,
           .lo_open = true,
           .bound_text = "must be positive (in front of the camera)",
           .save =
               [](const SaveContext& c) {
                 return interpolated(c.job) && c.job.focal_depth ? Saved(num(c.job.focal_depth->at(c.time))) : kOmit;
               }},
    Option{.name = "reference-depth",
           .value = "D",
           .help = "Stanford/LFCA: depth of the rectified reference plane.",
           .default_text = "1000",
           .example = "--stanford $MPR_DATA_DIR/stanford/chess --reference-depth 1000 --position-scale 1",
           .kind = number,
           .group = lf,
           .lo = 0,
           .lo_open = true,
           .bound_text = kPositive,
           .save =
               [](const SaveContext& c) {
                 return is_light_field(c.job.sampler) && c.job.reference_depth != 1000
                            ? Saved(num(c.job.reference_depth))
                            : kOmit;
               }},
    Option{.name = "position-scale",
           .value = "S",
           .help = "Stanford/LFCA: world units per stored camera-position unit.",
           .default_text = "1",
           .example = "--stanford $MPR_DATA_DIR/stanford/chess --reference-depth 1000 --position-scale 1",
           .kind = number,
           .group = lf,
           .lo = 0,
           .lo_open = true,
           .bound_text = kPositive,
           .save =
               [](const SaveContext& c) {
                 return is_light_field(c.job.sampler) && c.job.position_scale != 1 ? Saved(num(c.job.position_scale))
                                                                                   : kOmit;
               }},
    Option{.name = "camera",
           .value = "K",
           .help = "Light fields: index of the reference camera.",
           .default_text = "the array centre for Stanford/LFCA, the middle camera for _par.txt",
           .example = "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --camera 3",
           .kind = integer,
           .group = lf,
           .lo = 0,
           .hi = 1000000,
           .save =
               [](const SaveContext& c) {
                 return is_light_field(c.job.sampler) && c.job.camera ? Saved(std::to_string(*c.job.camera)) : kOmit;
               }},
    Option{.name = "zoom",
           .value = "F",
           .help = "Light fields: magnification of the view about its centre (1: the reference camera's view, cropped "
                   "to the aspect ratio of --size; 2 shows the middle half).",
           .default_text = "1",
           .example = "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --zoom 2",
           .kind = number,
           .group = lf,
           .lo = 0,
           .hi = 1e6,
           .lo_open = true,
           .bound_text = "must lie in (0, 1e6]"},
    Option{.name = "prefilter",
           .value = "auto|N",
           .help = "Light fields: sample the frames box-filtered in linear light to 1/N of their scale (N = 1..8; "
                   "mpr::downsampled), so a smaller output averages each pixel's footprint instead of point-sampling "
                   "it and reads a quarter of the texels at N = 2. auto: N = the camera pixels an output pixel spans "
                   "on the focal surface, rounded down, over every frame (700x400 from 1400x800 Chess: 2; mpr-view's "
                   "960x540: 1), except under --interp depth and --spp N > 1; 1: the full frames.",
           .default_text = "auto",
           .example = "--stanford $MPR_DATA_DIR/stanford/chess --size 700x400 --prefilter 1",
           .kind = integer,
           .group = lf,
           .lo = 1,
           .hi = 8,
           .save =
               [](const SaveContext& c) { // auto is not written: the viewer's default too
                 return is_light_field(c.job.sampler) && c.job.prefilter ? Saved(std::to_string(*c.job.prefilter))
                                                                         : kOmit;
               }},

    // The image: size, views, pixel sampling, aperture.
    Option{.name = "size",
           .value = "WxH",
           .help = "Size of one view in pixels (light fields: the reference camera's size by default, and another "
                   "aspect ratio crops the camera's view instead of stretching it).",
           .default_text = "480x360",
           .example = "--size 640x480",
           .kind = size,
           .group = image,
           .save = [](const SaveContext& c) { return Saved(size_text(c.view_width, c.view_height)); }},
    Option{
        .name = "layout",
        .value = "CxR",
        .help = "Tile C x R views side by side in one image; list them with --views.",
        .default_text = "1x1",
        .example = "--layout 3x3 --views A,B,C,D,E,F,G,H,I",
        .kind = size,
        .group = image,
        .save =
            [](const SaveContext& c) { return single_view(c.job) ? kOmit : Saved(size_text(c.job.cols, c.job.rows)); }},
    Option{.name = "view",
           .value = "VIEW",
           .help = "The camera (selector) of a single view; see VIEW below.",
           .default_text = "'default'",
           .example = "--view G",
           .group = image,
           .save =
               [](const SaveContext& c) {
                 return single_view(c.job) && c.job.views[0] != "default" ? Saved(c.job.views[0]) : kOmit;
               }},
    Option{.name = "views",
           .value = "V1,V2,...",
           .help = "One VIEW per tile of --layout, row-major (',' separates views; use ';' inside, and quote the list "
                   "for the shell).",
           .example = "--layout 3x1 --views 'A,G,pinhole:0;1.6;10'",
           .group = image,
           .save =
               [](const SaveContext& c) {
                 if (single_view(c.job)) return kOmit;
                 std::string views;
                 for (std::size_t k = 0; k < c.job.views.size(); ++k) {
                   std::string v = c.job.views[k];
                   for (char& ch : v)
                     if (ch == ',') ch = ';';
                   views.append(k == 0 ? "" : ",").append(v);
                 }
                 return Saved(views);
               }},
    Option{.name = "spp",
           .value = "N",
           .help = "Samples per pixel, 1 to 4096 (1: one ray through each pixel centre). N > 1 anti-aliases: N "
                   "scrambled Sobol points per pixel (mpr::OwenSobol), combined by --filter.",
           .default_text = "1",
           .example = "--layout 3x1 --views A,D,G --size 320x240 --spp 16",
           .kind = integer,
           .group = image,
           .lo = 1,
           .hi = kMaxSpp,
           .save = [](const SaveContext& c) { return c.job.spp > 1 ? Saved(std::to_string(c.job.spp)) : kOmit; }},
    Option{.name = "filter",
           .value = "NAME[:RADIUS]",
           .help = "Reconstruction filter of --spp N > 1: box, tent, gaussian, mitchell or lanczos, radius in pixels "
                   "(defaults as in pbrt-v4: box 0.5, tent 2, gaussian 1.5, mitchell 2, lanczos 4).",
           .default_text = "box",
           .example = "--size 320x240 --spp 16 --filter mitchell:2",
           .group = image,
           .save = [](const SaveContext& c) { return c.job.spp > 1 ? Saved(filter_text(c.job.filter)) : kOmit; }},
    Option{.name = "aperture",
           .value = "SHAPE:SIZE|SHAPE:A:B|SHAPE:T=V,...",
           .help = "Finite aperture (Adams & Levoy 2007): disc, square, gaussian or polygonN (N blades), SIZE its "
                   "radius (half side, sigma) in world units, >= 0 (0: the pinhole); animatable (SHAPE:0:0.5 opens it "
                   "over --frames N). Needs --spp N > 1; focused on the image plane unless --focus.",
           .example = "--view A --spp 32 --aperture disc:0.3 --focus 9",
           .group = image,
           .save =
               [](const SaveContext& c) {
                 return c.job.aperture ? Saved(aperture_text(*c.job.aperture, c.time)) : kOmit;
               }},
    Option{.name = "lens-distance",
           .value = "D",
           .help = "With --aperture: the lens plane's distance behind the image plane, world units.",
           .default_text = "the image plane's width",
           .example = "--view A --spp 32 --aperture disc:0.3 --lens-distance 4 --focus 9",
           .group = image,
           .save =
               [](const SaveContext& c) {
                 return c.job.aperture && c.job.aperture->distance ? Saved(num(*c.job.aperture->distance)) : kOmit;
               }},
    Option{.name = "focus",
           .value = "D|DU,DV",
           .help = "With --aperture: focus at distance D in front of the image plane (a refocused thin lens), or two "
                   "focal lines (astigmatic: the horizontal direction sharp at DU, the vertical at DV); --print-camera "
                   "names the focus.",
           .example = "--view G --spp 32 --aperture polygon6:0.4 --focus 4,12 --print-camera",
           .group = image,
           .save =
               [](const SaveContext& c) {
                 if (!c.job.aperture || c.job.aperture->focus.empty()) return kOmit;
                 std::string focus;
                 for (const double d : c.job.aperture->focus) focus += (focus.empty() ? "" : ",") + num(d);
                 return Saved(focus);
               }},
    Option{.name = "labels",
           .help = "Label each tile with its view, GLC type (mpr::glc::classify) and, with --aperture, its focus "
                   "(mpr::glc::classify_focus).",
           .example = "--layout 3x1 --views A,D,G --size 320x240 --spp 8 --aperture disc:0.3 --focus 9 --labels",
           .kind = flag,
           .group = image},
    Option{.name = "print-camera",
           .help = "Print each view's GLC type, slits and centre (mpr::glc::classify) to stdout.",
           .example = "--view G --print-camera",
           .kind = flag,
           .group = image,
           .in_view_help = false},

    // The image plane.
    Option{.name = "plane-centre",
           .value = "X,Y,Z",
           .help = "Centre of the image plane.",
           .default_text = "depends on the sampler",
           .example = "--plane-centre 0,3.1,3 --look-at 0,1.6,-8 --plane-size 8,6",
           .kind = vec,
           .group = surface,
           .save = [](const SaveContext& c) { return c.job.plane_centre ? Saved(vec3(*c.job.plane_centre)) : kOmit; }},
    Option{.name = "look-at",
           .value = "X,Y,Z",
           .help = "The image plane faces this point (its normal points at it).",
           .example = "--plane-centre 0,1.6,3 --look-at 0,1.6,-8 --plane-size 8,6",
           .kind = vec,
           .group = surface,
           .save =
               [](const SaveContext& c) {
                 return c.job.plane_centre && c.job.look_at ? Saved(vec3(*c.job.look_at)) : kOmit;
               }},
    Option{.name = "plane-size",
           .value = "W,H",
           .help = "Extent of the image plane in world units.",
           .example = "--plane-centre 0,3.1,3 --look-at 0,1.6,-8 --plane-size 12,9",
           .group = surface,
           .save =
               [](const SaveContext& c) {
                 return c.job.plane_centre && c.job.plane_size
                            ? Saved(num(c.job.plane_size->first) + "," + num(c.job.plane_size->second))
                            : kOmit;
               }},
    Option{.name = "up",
           .value = "X,Y,Z",
           .help = "Up direction of the image plane.",
           .default_text = "0,1,0",
           .example = "--up 0,1,0",
           .kind = vec,
           .group = surface,
           .save =
               [](const SaveContext& c) {
                 return c.job.up != mpr::Vec3<double>(0, 1, 0) ? Saved(vec3(c.job.up)) : kOmit;
               }},
    Option{.name = "tilt-x",
           .value = "DEG|A:B|T=V,...",
           .help = "Tilt the image plane about its horizontal axis, degrees, within (-89, 89); animatable.",
           .default_text = "0",
           .example = "--view G --tilt-x 0:30 --rectify plane --frames 24",
           .kind = track,
           .group = surface,
           .lo = -89,
           .hi = 89,
           .lo_open = true,
           .hi_open = true,
           .bound_text = "must lie within (-89, 89) degrees",
           .save =
               [](const SaveContext& c) {
                 const double v = c.job.tilt_x.at(c.time);
                 return v != 0 ? Saved(num(v)) : kOmit;
               }},
    Option{.name = "tilt-y",
           .value = "DEG|A:B|T=V,...",
           .help = "Tilt the image plane about its vertical axis, degrees, within (-89, 89); animatable.",
           .default_text = "0",
           .example = "--tilt-y -20:20 --rectify plane --frames 24",
           .kind = track,
           .group = surface,
           .lo = -89,
           .hi = 89,
           .lo_open = true,
           .hi_open = true,
           .bound_text = "must lie within (-89, 89) degrees",
           .save =
               [](const SaveContext& c) {
                 const double v = c.job.tilt_y.at(c.time);
                 return v != 0 ? Saved(num(v)) : kOmit;
               }},
    Option{.name = "rectify",
           .value = "P1;P2;P3;P4",
           .help = "Rectifying homography: the world quadrilateral (top-left, top-right, bottom-right, bottom-left; "
                   "each X,Y,Z; quote it for the shell) that fills each view (mpr::glc::rectify). 'plane': the "
                   "untilted image plane's corners, so a tilted focal plane keeps the untilted framing.",
           .example = "--view C --rectify '-4.4,5.4,-14;4.4,5.4,-14;4.4,-1.2,-14;-4.4,-1.2,-14'",
           .group = surface,
           .save =
               [](const SaveContext& c) {
                 if (c.job.rectify_to_plane) return Saved("plane");
                 if (!c.job.rectify) return kOmit;
                 std::string quad;
                 for (std::size_t i = 0; i < 4; ++i) quad.append(i == 0 ? "" : ";").append(vec3((*c.job.rectify)[i]));
                 return Saved(quad);
               }},
    Option{.name = "scene-centre",
           .value = "X,Y,Z",
           .help = "Where the gallery views aim.",
           .default_text = "the middle of the scene",
           .example = "--scene-centre 0,1.6,-8",
           .kind = vec,
           .group = surface,
           .save = [](const SaveContext& c) { return c.job.scene_centre ? Saved(vec3(*c.job.scene_centre)) : kOmit; }},
    Option{.name = "scene-scale",
           .value = "S",
           .help = "Size of the scene the gallery views frame, world units.",
           .default_text = "the scene's",
           .example = "--scene-scale 14",
           .kind = number,
           .group = surface,
           .lo = 0,
           .lo_open = true,
           .bound_text = kPositive,
           .save = [](const SaveContext& c) { return c.job.scene_scale ? Saved(num(*c.job.scene_scale)) : kOmit; }},

    // Animation (one frame, the one on screen, in the save command).
    Option{.name = "frames",
           .value = "N",
           .help = "Render an animation of N frames (numbered PNGs; an MP4 too when ffmpeg is on PATH). mpr-view: the "
                   "frames ',' and '.' step through.",
           .example = "--frames 24 --tilt-x 0:30",
           .kind = integer,
           .group = anim,
           .lo = 1,
           .hi = 100000},
    Option{.name = "morph-to",
           .value = "VIEW",
           .help = "Animation: morph from the view to this VIEW by interpolating corner directions.",
           .example = "--view A --morph-to G --frames 24",
           .group = anim,
           .save =
               [](const SaveContext& c) {
                 return c.job.morph_to && c.job.morph.at(c.time) != 0 ? Saved(*c.job.morph_to) : kOmit;
               }},
    Option{.name = "morph",
           .value = "A:B|T=V,...",
           .help = "Morph weight over the animation.",
           .default_text = "0:1",
           .example = "--view A --morph-to G --morph 0=0,0.5=1,1=0 --frames 24",
           .kind = track,
           .group = anim,
           .save =
               [](const SaveContext& c) {
                 return c.job.morph_to && c.job.morph.at(c.time) != 0 ? Saved(num(c.job.morph.at(c.time))) : kOmit;
               }},
    Option{.name = "fps",
           .value = "F",
           .help = "Animation: frame rate of the MP4 in frames per second.",
           .default_text = "12",
           .example = "--tilt-x 0:30 --frames 3 --fps 24",
           .kind = number,
           .group = anim,
           .lo = 0,
           .hi = 1000,
           .lo_open = true,
           .bound_text = "must lie in (0, 1000] frames per second"},
    Option{.name = "shard",
           .value = "K/N",
           .help = "Render only the frames f (counted from 0) with f % N == K of an animation; they keep their global "
                   "numbers, so N processes (a Slurm job array: --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT) "
                   "write the frames of one run between them. No MP4 and no stale-frame removal (no shard sees every "
                   "frame).",
           .example = "--tilt-y -20:20 --frames 6 --shard 0/3 --no-video",
           .group = anim,
           .in_view_help = false},
    Option{.name = "no-video",
           .help = "Do not write an MP4 even when ffmpeg is available.",
           .example = "--tilt-y -20:20 --frames 24 --no-video",
           .kind = flag,
           .group = anim,
           .in_view_help = false},

    // Output and run.
    Option{
        .name = "threads",
        .value = "N",
        .help = "Worker threads, 0 = all. Images are identical for any N.",
        .default_text = "0",
        .example = "--threads 2",
        .kind = integer,
        .group = run,
        .lo = 0,
        .hi = 1024,
        .save = [](const SaveContext& c) { return c.job.threads != 0 ? Saved(std::to_string(c.job.threads)) : kOmit; }},
    Option{.name = "double",
           .help = "Render in double precision.",
           .default_text = "float",
           .example = "--double",
           .kind = flag,
           .group = run,
           .save = [](const SaveContext& c) { return c.job.use_double ? Saved("") : kOmit; }},
    Option{.name = "no-budget",
           .help = "Lift the documented limits that refuse a job before it starts (an image over 2^28 pixels, over "
                   "2^34 rays in all, a --raster array over 1 GiB or 30 minutes): for a machine that can afford it.",
           .example = "--size 320x240 --spp 64 --no-budget",
           .kind = flag,
           .group = run,
           .save = [](const SaveContext& c) { return c.job.no_budget ? Saved("") : kOmit; }},
    Option{.name = "bit-depth",
           .value = "8|16",
           .help = "Bits per channel of a .png output: 16 writes 16-bit sRGB-encoded PNG (libpng).",
           .default_text = "8",
           .example = "--bit-depth 16 --output view16.png",
           .kind = choice,
           .group = run,
           .choices = kBitDepths,
           .in_view_help = false},
    Option{.name = "exr-pixel",
           .value = "half|float",
           .help = "Sample type of an .exr output: half (16-bit floats) or float (the render's 32-bit values "
                   "exactly).",
           .default_text = "half",
           .example = "--exr-pixel float --output linear.exr",
           .kind = choice,
           .group = run,
           .choices = kExrPixels,
           .in_view_help = false},
    Option{.name = "output",
           .value = "FILE.png|FILE.jpg|FILE.pfm|FILE.exr",
           .help = "Output image by the extension: .png (8-bit sRGB; 16-bit with --bit-depth 16), .jpg or .jpeg "
                   "(JPEG, quality 95), or the linear render as floats: .pfm (RGB PFM, 32-bit) or .exr (OpenEXR, half "
                   "floats; --exr-pixel float). With --frames N: FILE_0001.png ... FILE_NNNN.png (stale frames "
                   "FILE_NNNN.png beyond N of an earlier run are removed; the MP4 only from .png or .jpg frames). "
                   "mpr-view: the base name of the PNGs that S saves (default mpr-view.png).",
           .default_text = "mpr-render.png",
           .example = "--output out/cross.png",
           .group = run,
           .save = [](const SaveContext& c) { return Saved(c.output.string()); }},
    Option{.name = "help",
           .help = "Print this help and exit.",
           .example = "mpr-render --help",
           .kind = flag,
           .group = run,
           .in_view_help = false},

    // mpr-view only.
    Option{.name = "script",
           .value = "FILE",
           .help = "Drive the window from a script of timed events (wait MS, key NAME, drag X0,Y0 X1,Y1 [BUTTON], "
                   "wheel N, click X,Y, screenshot PATH) and exit when it ends; errors are reported before the window "
                   "opens.",
           .example = "--script tests/view.txt",
           .group = viewer,
           .tools = Tools::view},
    Option{.name = "benchmark",
           .help = "Open no window: render the view repeatedly through the viewer's render thread and print "
                   "frames/s and the time from an input event to the first quarter-resolution frame.",
           .example = "--benchmark --size 960x540 --threads 2",
           .kind = flag,
           .group = viewer,
           .tools = Tools::view},
    Option{.name = "benchmark-frames",
           .value = "N",
           .help = "Frames per benchmark measurement.",
           .default_text = "30",
           .example = "--benchmark-frames 10",
           .kind = integer,
           .group = viewer,
           .tools = Tools::view,
           .lo = 1,
           .hi = 10000},
};

} // namespace

std::span<const Option> option_table() noexcept { return kOptions; }

const Option* find_option(std::string_view name, Tools tool) noexcept {
  for (const Option& o : kOptions)
    if (o.name == name && takes(o.tools, tool)) return &o;
  return nullptr;
}

std::string_view group_title(Group group) noexcept {
  switch (group) {
  case Group::input:
    return "INPUT (the sampler; default: the classroom scene)";
  case Group::light_field:
    return "LIGHT FIELDS AND --raster";
  case Group::image:
    return "IMAGE";
  case Group::surface:
    return "IMAGE PLANE";
  case Group::animation:
    return "ANIMATION";
  case Group::run:
    return "OUTPUT AND RUN";
  case Group::viewer:
    return "VIEWER";
  }
  return "";
}

} // namespace mpr_cli
