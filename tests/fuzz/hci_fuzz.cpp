// libFuzzer target: scenes of the HCI 4D light-field benchmark (io/hci_light_field.hpp,
// io/hci_parameters.hpp). The input is up to three parts separated by "\n--\n":
//   1. the text of parameters.cfg (no such file when the input starts with '~');
//   2. the views, one line each (at most 12, at most 40 bytes, no '/' or NUL): the line L gives
//      the file input_Cam<L>.png, a 3x3 PNG (4x3 when L ends in '+', which is dropped from the
//      name); a line starting with '@' gives a symbolic link to itself (a link loop) instead;
//   3. gt_disp_lowres.pfm (no such file without this part).
// parse_hci_parameters reads part 1 and parse_hci_view_name every line; read_hci_light_field
// loads the folder in float and double. Only mpr::error may escape; a scene that loads must
// hold a frame per view, its centre among them, and the grid of its parameters.
#include "fuzz_common.hpp"

#include <mpr/io/hci_light_field.hpp>
#include <mpr/io/hci_parameters.hpp>

#include <cstdlib>
#include <string>

namespace {

template <typename T>
void load(const std::filesystem::path& dir) {
  try {
    const mpr::HciLightField<T> lf = mpr::read_hci_light_field<T>(dir, {}, mpr_fuzz::fuzz_limits());
    if (lf.frames.size() != lf.views.size() || lf.centre >= lf.views.size() || lf.frames.size() == 0) std::abort();
    if (lf.views[lf.centre] != (lf.cams_y / 2) * lf.cams_x + lf.cams_x / 2) std::abort();
    for (std::size_t i = 0; i < lf.views.size(); ++i)
      if (lf.row(i) < 0 || lf.row(i) >= lf.cams_y || lf.column(i) < 0 || lf.column(i) >= lf.cams_x) std::abort();
    if (lf.ground_truth && (lf.ground_truth->width() != lf.frames.image(0).width() ||
                            lf.ground_truth->height() != lf.frames.image(0).height()))
      std::abort();
    (void)lf.near_depth();
    (void)lf.far_depth();
  } catch (const mpr::error&) {
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path base = mpr_fuzz::scratch("hci");
  static const std::string png_a = mpr_fuzz::tiny_png(3, 3, 1), png_b = mpr_fuzz::tiny_png(4, 3, 2);
  const std::filesystem::path dir = base / "scene";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::string_view text = mpr_fuzz::as_text(data, size);
  const bool no_cfg = !text.empty() && text[0] == '~';
  constexpr std::string_view sep = "\n--\n";
  const auto [cfg, rest] = mpr_fuzz::split_once(text, sep);
  auto [views, gt] = mpr_fuzz::split_once(rest, sep);
  const bool has_gt = text.find(sep) != std::string_view::npos && rest.find(sep) != std::string_view::npos;
  if (!no_cfg) {
    try {
      (void)mpr::parse_hci_parameters(std::string(cfg), "parameters.cfg");
    } catch (const mpr::error&) {
    }
    mpr_fuzz::write_file(dir / "parameters.cfg", cfg);
  }
  for (int n = 0; n < 12 && !views.empty(); ++n) {
    const auto [line, after] = mpr_fuzz::split_once(views, "\n");
    views = after;
    std::string name(line.substr(0, 40));
    const bool link = !name.empty() && name[0] == '@';
    if (link) name.erase(0, 1);
    const bool wide = !name.empty() && name.back() == '+';
    if (wide) name.pop_back();
    name = "input_Cam" + name + ".png";
    (void)mpr::parse_hci_view_name(name);
    if (name.find_first_of(std::string("/\0", 2)) != std::string::npos) continue;
    std::error_code ec;
    if (link)
      std::filesystem::create_symlink(dir / name, dir / name, ec);
    else
      mpr_fuzz::write_file(dir / name, wide ? png_b : png_a);
  }
  if (has_gt) mpr_fuzz::write_file(dir / "gt_disp_lowres.pfm", gt);
  load<float>(dir);
  load<double>(dir);
  return 0;
}
