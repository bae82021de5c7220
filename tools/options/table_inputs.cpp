// The option table's INPUT and LIGHT FIELDS sections (table_sections.hpp).
#include "table_sections.hpp"

#include <array>
#include <string_view>

namespace mpr_cli::table {

namespace {

/// The input of the job when its sampler is `kind`.
template <SamplerKind kind>
Saved input_of(const SaveContext& c) {
  return c.job.sampler == kind ? Saved(c.job.input.string()) : kOmit;
}

constexpr std::array<std::string_view, 1> kScenes{"classroom"};

// mpr-render's defaults are those of Job (job.hpp); the save command writes the options in
// this order.
constexpr std::array kOptions = {
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

};

} // namespace

std::span<const Option> input_options() noexcept { return kOptions; }

} // namespace mpr_cli::table
