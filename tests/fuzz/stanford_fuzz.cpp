// libFuzzer target: Stanford archive names and folders. Every input line (at most 6, at most 80
// bytes, no '/' or NUL) is parsed with parse_stanford_view_name and becomes a file in a fresh
// folder: a 3x2 PNG (a 4x2 one when the line length is odd), or, for a line starting with '@',
// a symbolic link to itself (a link loop) named by the rest. Then read_stanford_light_field loads
// the folder in float and double; an input starting with '!' uses a position scale of 1e300.
// Only mpr::error may escape.
#include "fuzz_common.hpp"

#include <mpr/io/stanford_light_field.hpp>

#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path base = mpr_fuzz::scratch("stanford");
  static const std::string png_a = mpr_fuzz::tiny_png(3, 2, 1), png_b = mpr_fuzz::tiny_png(4, 2, 2);
  const std::filesystem::path dir = base / "set";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::string_view text = mpr_fuzz::as_text(data, size);
  mpr::PlanarArrayOptions options;
  if (!text.empty() && text[0] == '!') {
    options.scale = 1e300;
    text.remove_prefix(1);
  }
  for (int n = 0; n < 6 && !text.empty(); ++n) {
    const auto [line, rest] = mpr_fuzz::split_once(text, "\n");
    text = rest;
    (void)mpr::parse_stanford_view_name(std::string(line));
    std::string name(line.substr(0, 80));
    const bool link = !name.empty() && name[0] == '@';
    if (link) name.erase(0, 1);
    if (name.empty() || name == "." || name == ".." || name.find_first_of(std::string("/\0", 2)) != std::string::npos)
      continue;
    std::error_code ec;
    if (link)
      std::filesystem::create_symlink(dir / name, dir / name, ec);
    else
      mpr_fuzz::write_file(dir / name, line.size() % 2 ? png_b : png_a);
  }
  const mpr::LoadLimits limits = mpr_fuzz::fuzz_limits();
  try {
    (void)mpr::read_stanford_light_field<float>(dir, options, limits);
  } catch (const mpr::error&) {
  }
  try {
    (void)mpr::read_stanford_light_field<double>(dir, options, limits);
  } catch (const mpr::error&) {
  }
  return 0;
}
