// --help generated from the option table (help.hpp), and the VIEW grammar after the options.
#include "help.hpp"

namespace mpr_cli {

std::string option_help(Group group, Tools tool, bool examples) {
  std::string text;
  for (const Option& o : option_table()) {
    if (o.group != group || !takes(o.tools, tool) || (tool == Tools::view && !o.in_view_help)) continue;
    text.append("  --").append(o.name);
    if (!o.value.empty()) text.append(" ").append(o.value);
    text.append("\n      ").append(o.help);
    if (!o.default_text.empty()) text.append(" Default: ").append(o.default_text).append(".");
    text.append("\n");
    if (examples) text.append("      e.g. ").append(o.example).append("\n");
  }
  return text;
}

std::string render_help() {
  std::string text = "usage: mpr-render [OPTIONS]\n\nRenders General Linear Camera views of a scene or a light field "
                     "to PNG or JPEG, or the linear render as PFM or OpenEXR.\n";
  for (const Group g : {Group::input, Group::light_field, Group::image, Group::surface, Group::animation, Group::run})
    text.append("\n").append(group_title(g)).append("\n").append(option_help(g, Tools::render, true));
  return text.append("\n").append(view_help());
}

std::string_view view_help() noexcept {
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
