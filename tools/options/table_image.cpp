// The option table's IMAGE and IMAGE PLANE sections (table_sections.hpp).
#include "table_sections.hpp"

#include "mpr-render/aperture.hpp"
#include "mpr-render/pixel_sampling.hpp"

#include <mpr/render/policy_names.hpp>

#include <array>
#include <string>
#include <type_traits>
#include <variant>

namespace mpr_cli::table {

namespace {

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

// mpr-render's defaults are those of Job (job.hpp); the save command writes the options in
// this order.
constexpr std::array kOptions = {
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
                 for (const double d : c.job.aperture->focus) focus.append(focus.empty() ? "" : ",").append(num(d));
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

};

} // namespace

std::span<const Option> image_options() noexcept { return kOptions; }

} // namespace mpr_cli::table
