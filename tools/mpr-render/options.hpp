#pragma once
// mpr-render's option table: every option with its value placeholder, help text and an example
// (printed by --help and parsed by parse_args), and the VIEW grammar printed after them.

#include "cli_args.hpp"

#include <vector>

namespace mpr_cli {

/// Every option of mpr-render, with help text and an example.
inline const std::vector<OptionSpec>& options() {
  static const std::vector<OptionSpec> specs = {
      {"help", "", "Print this help and exit.", "mpr-render --help"},
      {"output", "FILE.png|FILE.jpg|FILE.pfm|FILE.exr",
       "Output image by the extension (default mpr-render.png): .png (8-bit sRGB; 16-bit with --bit-depth 16), "
       ".jpg or .jpeg (JPEG, quality 95), or the linear render as floats: .pfm (RGB PFM, 32-bit) or .exr "
       "(OpenEXR, half floats; --exr-pixel float). With --frames N: FILE_0001.png ... FILE_NNNN.png (stale frames "
       "FILE_NNNN.png beyond N of an earlier run are removed; the MP4 only from .png or .jpg frames).",
       "--output out/cross.png"},
      {"bit-depth", "8|16",
       "Bits per channel of a .png output (default 8): 16 writes 16-bit sRGB-encoded PNG (libpng).",
       "--bit-depth 16 --output view16.png"},
      {"exr-pixel", "half|float",
       "Sample type of an .exr output (default half: 16-bit floats; float: the render's 32-bit values exactly).",
       "--exr-pixel float --output linear.exr"},
      {"size", "WxH",
       "Size of one view in pixels (default 480x360; light fields: the reference camera's size, and another "
       "aspect ratio crops the camera's view instead of stretching it).",
       "--size 640x480"},
      {"layout", "CxR", "Tile C x R views side by side in one image (default 1x1); list them with --views.",
       "--layout 3x3 --views A,B,C,D,E,F,G,H,I"},
      {"view", "VIEW", "The camera (selector) of a single view; see VIEW below (default: 'default').", "--view G"},
      {"views", "V1,V2,...",
       "One VIEW per tile of --layout, row-major (',' separates views; use ';' inside, and quote the list for "
       "the shell).",
       "--layout 3x1 --views 'A,G,pinhole:0;1.6;10'"},
      {"threads", "N", "Worker threads, 0 = all (default 0). Images are identical for any N.", "--threads 2"},
      {"double", "", "Render in double precision (default float).", "--double"},
      {"spp", "N",
       "Samples per pixel, 1 to 4096 (default 1: one ray through each pixel centre). N > 1 anti-aliases: N "
       "scrambled Sobol points per pixel (mpr::OwenSobol), combined by --filter.",
       "--layout 3x1 --views A,D,G --size 320x240 --spp 16"},
      {"filter", "NAME[:RADIUS]",
       "Reconstruction filter of --spp N > 1: box, tent, gaussian, mitchell or lanczos, radius in pixels "
       "(defaults as in pbrt-v4: box 0.5, tent 2, gaussian 1.5, mitchell 2, lanczos 4).",
       "--size 320x240 --spp 16 --filter mitchell:2"},
      {"aperture", "SHAPE:SIZE|SHAPE:A:B|SHAPE:T=V,...",
       "Finite aperture (Adams & Levoy 2007): disc, square, gaussian or polygonN (N blades), SIZE its radius "
       "(half side, sigma) in world units, >= 0 (0: the pinhole); animatable (SHAPE:0:0.5 opens it over --frames N). "
       "Needs --spp N > 1; focused on the image plane unless --focus.",
       "--view A --spp 32 --aperture disc:0.3 --focus 9"},
      {"lens-distance", "D",
       "With --aperture: the lens plane's distance behind the image plane, world units (default: the image plane's "
       "width).",
       "--view A --spp 32 --aperture disc:0.3 --lens-distance 4 --focus 9"},
      {"focus", "D|DU,DV",
       "With --aperture: focus at distance D in front of the image plane (a refocused thin lens), or two focal lines "
       "(astigmatic: the horizontal direction sharp at DU, the vertical at DV); --print-camera names the focus.",
       "--view G --spp 32 --aperture polygon6:0.4 --focus 4,12 --print-camera"},
      {"labels", "",
       "Label each tile with its view, GLC type (mpr::glc::classify) and, with --aperture, its focus "
       "(mpr::glc::classify_focus).",
       "--layout 3x1 --views A,D,G --size 320x240 --spp 8 --aperture disc:0.3 --focus 9 --labels"},
      {"print-camera", "", "Print each view's GLC type, slits and centre (mpr::glc::classify) to stdout.",
       "--view G --print-camera"},
      {"scene", "classroom", "Sampler: the built-in classroom demo scene, ray cast through a BVH (default).",
       "--scene classroom"},
      {"obj", "FILE.obj", "Sampler: a Wavefront OBJ mesh (with MTL/texture), ray cast.", "--obj examples/boxes.obj"},
      {"raster", "CxR",
       "Scene/OBJ: sample a rasterized virtual camera array of C x R cameras (160x120 pixels each, on the image "
       "plane) instead of ray casting; --interp, --radius and --focal-depth (in front of the plane) apply. "
       "Arrays estimated above 1 GiB (about 6,000 cameras) are refused before rendering.",
       "--raster 16x12 --interp cylinder --radius 0.5"},
      {"raster-samples", "N",
       "--raster: each camera pixel the mean, in linear light, of N x N rasterized points over its area (anti-aliased "
       "frames: no staircases or moire; the middle point gives the depth). N odd, 1..15; default 1 (the pixel "
       "centre). Rasterizing takes up to N^2 times as long.",
       "--raster 8x6 --raster-samples 3 --interp depth --view B"},
      {"obj-scale", "S", "Uniform scale of the OBJ positions (default 1).",
       "--obj examples/boxes.obj --obj-scale 0.01"},
      {"par", "FILE_par.txt", "Sampler: a light field from a Middlebury-style _par.txt calibration.",
       "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt"},
      {"stanford", "FOLDER", "Sampler: a Stanford light-field archive folder of out_RR_CC_Y_X.png images.",
       "--stanford $MPR_DATA_DIR/stanford/chess --focal-depth 820"},
      {"lfca", "POSITIONS.txt",
       "Sampler: LFCA camera positions ('id X Y' lines) with {id}.png and {id}.homography.txt.",
       "--lfca $MPR_DATA_DIR/lfca/positions.txt"},
      {"hci", "FOLDER",
       "Sampler: a scene of the HCI 4D light-field benchmark (input_CamNNN.png views of a 9x9 grid or any subset "
       "holding the centre; parameters.cfg for the metric array, else an array in disparity units: "
       "docs/depth.md). Default view: the centre camera, focused on the zero-disparity plane.",
       "--hci $MPR_DATA_DIR/hci/backgammon --size 256x256"},
      {"colmap", "MODEL_FOLDER",
       "Sampler: a COLMAP sparse model in text form (cameras.txt: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, "
       "OPENCV without tangential terms; images.txt) with its images (--colmap-images, else images/ found beside the "
       "model, as in PROJECT/sparse/0 and PROJECT/images).",
       "--colmap $MPR_DATA_DIR/colmap/sparse/0"},
      {"colmap-images", "FOLDER", "--colmap: the folder of the model's images.",
       "--colmap $MPR_DATA_DIR/colmap/sparse/0 --colmap-images $MPR_DATA_DIR/colmap/images"},
      {"interp", "nearest|synthetic|cylinder|depth",
       "Light-field interpolation: nearest camera, full synthetic aperture, cylinder aperture of --radius, or depth "
       "proxy (the surface from per-camera depth maps, the cameras that see it blended by angle; --raster keeps the "
       "rasterizer's depth, light fields need --depth-maps; --radius: the cameras considered, default twice the "
       "spacing) (default synthetic).",
       "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --interp cylinder --radius 0.3"},
      {"depth-maps", "FOLDER|estimate:NEAR:FAR[:PLANES]",
       "Light fields: one PFM depth map per camera (depth along its optical axis, +inf where nothing was seen), named "
       "after its image (cam.png -> cam.pfm), or estimated from the images by a plane sweep over depths NEAR to FAR "
       "along the cameras' axes (PLANES planes, default 64; mpr::estimate_depth_maps, docs/lightfield.md); read by "
       "--interp depth, --all-in-focus, --focus-at and --write-depth.",
       "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --all-in-focus --depth-maps "
       "estimate:0.44:0.72"},
      {"sweep", "KEY=VALUE,...",
       "With --depth-maps estimate: the plane sweep's other settings (mpr::PlaneSweepConfig): selection (axes: the "
       "cameras along the camera's image row and column, the default; nearest: the nearest by distance), neighbours "
       "(cameras compared, 16), best (the smallest costs averaged, 8: occluded neighbours drop out), truncation "
       "(0.3), spatial (aggregation extent in pixels, 12), range (colour difference that cuts it, 0.2). Clean "
       "synthetic arrays: best=4 and spatial scaled to the frames "
       "(docs/lightfield.md).",
       "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --all-in-focus --depth-maps "
       "estimate:0.44:0.72 --sweep best=3,spatial=6"},
      {"proxy", "KEY=VALUE,...",
       "With --interp depth, --all-in-focus, --focus-at or --write-depth: the depth proxy's settings but its radius "
       "(mpr::DepthProxy; --radius sets that): k (cameras blended, 4), tolerance (relative depth tolerance of the "
       "surface search, 0.01), visibility_tolerance (of the blend's depth test, 0.03: forgives estimated maps' "
       "error), march_cameras (cameras tried in turn for the surface, 4), whole_line (1: search the whole ray line, "
       "0: only in front of the view's image surface).",
       "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --all-in-focus --depth-maps "
       "estimate:0.44:0.72 --proxy k=6,visibility_tolerance=0.05"},
      {"save-depth-maps", "FOLDER",
       "With --depth-maps estimate: write the estimated maps there as PFMs (read them back with --depth-maps FOLDER).",
       "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --all-in-focus --depth-maps "
       "estimate:0.44:0.72:32 --save-depth-maps temple-depth"},
      {"all-in-focus", "",
       "Light fields and --raster: every ray focused at its own depth, the first surface the depth maps show along it "
       "(the same as --interp depth: the cameras within --radius that see that point, the 4 best by angle blended); "
       "--focal-depth only serves rays no depth map explains. Light fields need --depth-maps.",
       "--raster 8x6 --all-in-focus --view G"},
      {"focus-at", "X,Y",
       "Autofocus: focus on what output pixel (X, Y) shows (from the top-left corner), and print the depth chosen. "
       "Light fields (needs --depth-maps) and --raster: sets --focal-depth (light fields: the depth along the "
       "reference camera's axis, the focal plane moved until that pixel's ray meets the surface on it); a ray-cast "
       "scene with --aperture: sets --focus. The depth is taken with the first frame's other settings.",
       "--raster 8x6 --size 320x240 --focus-at 160,80"},
      {"write-depth", "FILE.pfm",
       "Also write the depth seen by each output pixel (one ray through its centre) as a PFM, +inf where nothing is "
       "seen, and FILE_preview.png colour-mapped with a legend. Light fields (needs --depth-maps): the depth of the "
       "surface the depth maps show, along the reference camera's axis (the units of --focal-depth); scenes, also "
       "--raster: the ray cast's depth in front of the image plane. Any view, tilt or layout; not with --frames.",
       "--layout 2x1 --views A,G --write-depth depth_AG.pfm"},
      {"radius", "R|A:B|T=V,...",
       "Cylinder aperture radius, world units; animatable. Default: the array's camera spacing (a light field's "
       "median nearest-neighbour distance, the --raster grid's cell width; twice that for --interp depth).",
       "--raster 8x6 --interp cylinder --radius 0.5:3 --frames 9"},
      {"focal-depth", "D|A:B|T=V,...",
       "Light fields: depth of the focal (image) plane in front of the reference camera (default: the reference "
       "plane); animatable.",
       "--stanford $MPR_DATA_DIR/stanford/chess --focal-depth 700:950 --frames 9"},
      {"reference-depth", "D", "Stanford/LFCA: depth of the rectified reference plane (default 1000).",
       "--stanford $MPR_DATA_DIR/stanford/chess --reference-depth 1000 --position-scale 1"},
      {"position-scale", "S", "Stanford/LFCA: world units per stored camera-position unit (default 1).",
       "--stanford $MPR_DATA_DIR/stanford/chess --reference-depth 1000 --position-scale 1"},
      {"camera", "K",
       "Light fields: index of the reference camera (default: the array centre for Stanford/LFCA, "
       "the middle camera for _par.txt).",
       "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --camera 3"},
      {"zoom", "F",
       "Light fields: magnification of the view about its centre (default 1: the reference camera's view, "
       "cropped to the aspect ratio of --size; 2 shows the middle half).",
       "--par $MPR_DATA_DIR/middlebury/templeSparseRing/templeSR_par.txt --zoom 2"},
      {"prefilter", "auto|N",
       "Light fields: sample the frames box-filtered in linear light to 1/N of their scale (N = 1..8; "
       "mpr::downsampled), so a smaller output averages each pixel's footprint instead of point-sampling it and reads "
       "a quarter of the texels at N = 2. auto (default): N = the camera pixels an output pixel spans on the focal "
       "surface, rounded down, over every frame (700x400 from 1400x800 Chess: 2; mpr-view's 960x540: 1), except under "
       "--interp depth and --spp N > 1; 1: the full frames.",
       "--stanford $MPR_DATA_DIR/stanford/chess --size 700x400 --prefilter 1"},
      {"plane-centre", "X,Y,Z", "Centre of the image plane (default: depends on the sampler).",
       "--plane-centre 0,3.1,3 --look-at 0,1.6,-8 --plane-size 8,6"},
      {"look-at", "X,Y,Z", "The image plane faces this point (its normal points at it).",
       "--plane-centre 0,1.6,3 --look-at 0,1.6,-8 --plane-size 8,6"},
      {"plane-size", "W,H", "Extent of the image plane in world units.",
       "--plane-centre 0,3.1,3 --look-at 0,1.6,-8 --plane-size 12,9"},
      {"up", "X,Y,Z", "Up direction of the image plane (default 0,1,0).", "--up 0,1,0"},
      {"tilt-x", "DEG|A:B|T=V,...", "Tilt the image plane about its horizontal axis, degrees; animatable.",
       "--view G --tilt-x 0:30 --rectify plane --frames 24"},
      {"tilt-y", "DEG|A:B|T=V,...", "Tilt the image plane about its vertical axis, degrees; animatable.",
       "--tilt-y -20:20 --rectify plane --frames 24"},
      {"rectify", "P1;P2;P3;P4",
       "Rectifying homography: the world quadrilateral (top-left, top-right, bottom-right, bottom-left; each "
       "X,Y,Z; quote it for the shell) that fills each view (mpr::glc::rectify). 'plane': the untilted image plane's "
       "corners, so a "
       "tilted focal plane keeps the untilted framing.",
       "--view C --rectify '-4.4,5.4,-14;4.4,5.4,-14;4.4,-1.2,-14;-4.4,-1.2,-14'"},
      {"scene-centre", "X,Y,Z", "Where the gallery views aim (default: the middle of the scene).",
       "--scene-centre 0,1.6,-8"},
      {"scene-scale", "S", "Size of the scene the gallery views frame, world units (default: the scene's).",
       "--scene-scale 14"},
      {"frames", "N", "Render an animation of N frames (numbered PNGs; an MP4 too when ffmpeg is on PATH).",
       "--frames 24 --tilt-x 0:30"},
      {"morph-to", "VIEW", "Animation: morph from the view to this VIEW by interpolating corner directions.",
       "--view A --morph-to G --frames 24"},
      {"morph", "A:B|T=V,...", "Morph weight over the animation (default 0:1).",
       "--view A --morph-to G --morph 0=0,0.5=1,1=0 --frames 24"},
      {"fps", "F", "Animation: frame rate of the MP4 in frames per second (default 12).",
       "--tilt-x 0:30 --frames 3 --fps 24"},
      {"no-budget", "",
       "Lift the documented limits that refuse a job before it starts (an image over 2^28 pixels, over 2^34 rays "
       "in all, a --raster array over 1 GiB or 30 minutes): for a machine that can afford it.",
       "--size 320x240 --spp 64 --no-budget"},
      {"shard", "K/N",
       "Render only the frames f (counted from 0) with f % N == K of an animation; they keep their global "
       "numbers, so N processes (a Slurm job array: --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT) write "
       "the frames of one run between them. No MP4 and no stale-frame removal (no shard sees every frame).",
       "--tilt-y -20:20 --frames 6 --shard 0/3 --no-video"},
      {"no-video", "", "Do not write an MP4 even when ffmpeg is available.", "--tilt-y -20:20 --frames 24 --no-video"},
  };
  return specs;
}

/// The text after the options in --help. Every "e.g." above and below, and every command under
/// "Examples:", runs in ctest (tools/mpr-render/run_examples.cmake).
inline const char* view_help() {
  return R"(VIEW (a camera, i.e. a GLC ray selector on the image plane):
  default            scene: gallery view A; light field: the reference camera's pinhole
  A..I or a name     gallery view (mpr::glc::gallery_view): A perspective, B orthographic, C oblique,
                     D pushbroom, E twisted, F twisted_down, G cross_slit, H pencil, I bilinear
  pinhole:C          pinhole with centre C                          e.g. pinhole:0,1.6,10
  orthographic:D     parallel rays along D                          e.g. orthographic:0,-0.1,-1
  oblique:AU,AV      rays tilted AU, AV degrees from the normal     e.g. oblique:30,10
  pushbroom:P:D      slit through P along D                         e.g. pushbroom:0,1.6,10:1,0,0
  cross_slit:P1:D1:P2:D2  two slits                                 e.g. cross_slit:0,1.6,10:0,11,-1.5:0,1.6,20:1,0,0
  pencil:P:D:K       slit through P along D, twist K (1/length)     e.g. pencil:0,1.6,10:1,0,0:0.05
  twisted:D:W:K      twisted orthographic: direction D, in-plane tilt direction W (a vector), twist K
                                                                    e.g. twisted:0,-0.1,-1:1,0,0:0.05
  bilinear:D:C:K     bilinear: direction D, convergence C, twist K  e.g. bilinear:0,0,-1:-0.05:0.05
  corners:D00:D10:D01  explicit ray directions at the top-left, top-right and bottom-left corners
                                                                    e.g. corners:-0.3,-0.1,-1:0.3,-0.1,-1:-0.3,-0.5,-1
Slits (D, D1, D2) must be parallel to the image plane: the default scene plane faces 0,-1.5,-11 (from
0,3.1,3 towards 0,1.6,-8), so its horizontal is 1,0,0 and its vertical 0,11,-1.5.
In --views, separate the numbers of a vector with ';' instead of ',' (e.g. pinhole:0;1.6;10) and
quote the list, since ';' ends a shell command.
ANIMATABLE values are a number, FROM:TO (linear over the frames) or keyframes T=V,T=V,... with
times from 0 to 1; an animated value needs --frames N, and --frames needs an animated value.
$MPR_DATA_DIR below is the folder of the real data sets (../shared/data in the repository).

Examples:
  mpr-render --view G --print-camera --output cross_slit.png
  mpr-render --layout 3x3 --views A,B,C,D,E,F,G,H,I --size 320x240 --output gallery.png
  mpr-render --obj examples/boxes.obj --output boxes.jpg
  mpr-render --stanford $MPR_DATA_DIR/stanford/chess --interp cylinder --radius 10 --focal-depth 820 --output chess.png
  mpr-render --stanford $MPR_DATA_DIR/stanford/chess --focal-depth 820 --tilt-x 0:-28 --rectify plane --frames 24 --output tilt.png
  mpr-render --stanford $MPR_DATA_DIR/stanford/chess --depth-maps estimate:600:1400 --save-depth-maps chess-depth --all-in-focus --output chess_all_in_focus.png
  mpr-render --stanford $MPR_DATA_DIR/stanford/chess --depth-maps chess-depth --focus-at 1010,540 --write-depth chess_depth.pfm --output chess_autofocus.png
  mpr-render --stanford $MPR_DATA_DIR/stanford/chess --depth-maps chess-depth --all-in-focus --view G --output chess_all_in_focus_G.png
)";
}

} // namespace mpr_cli
