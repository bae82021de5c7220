// libFuzzer target: image loading (read_image_info, read_rgb8, read_linear) with stb_image
// compiled in and instrumented. The input is the image file (PNG, JPEG, BMP, GIF, ... whatever
// stb_image recognises). Only mpr::error may escape; a decoded image must have the size its
// header promised.
#include "fuzz_common.hpp"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = mpr_fuzz::scratch("png");
  const std::filesystem::path path = dir / "x.png";
  mpr_fuzz::write_file(path, mpr_fuzz::as_text(data, size));
  const mpr::LoadLimits limits = mpr_fuzz::fuzz_limits();
  mpr::ImageInfo info;
  bool header = false;
  try {
    info = mpr::read_image_info(path, limits);
    header = true;
  } catch (const mpr::error&) {
  }
  try {
    const mpr::Image<mpr::Rgb8> image = mpr::read_rgb8(path, limits);
    if (!header || image.width() != info.width || image.height() != info.height) std::abort();
    (void)mpr::read_linear(path, limits);
  } catch (const mpr::error&) {
  }
  return 0;
}
