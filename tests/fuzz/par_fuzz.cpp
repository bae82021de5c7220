// libFuzzer target: the `_par.txt` loader (read_par_entries, read_par_file in float and double).
// The input is the calibration file; the folder also holds a.png and b.png (3x2) and c.png
// (4x2), so lines naming them reach image loading and camera validation. Only mpr::error may
// escape the loader; anything else (another exception, a crash, a sanitizer report) is a finding.
#include "fuzz_common.hpp"

#include <mpr/io/par_file.hpp>

namespace {
const std::filesystem::path& folder() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d = mpr_fuzz::scratch("par");
    mpr_fuzz::write_file(d / "a.png", mpr_fuzz::tiny_png(3, 2, 1));
    mpr_fuzz::write_file(d / "b.png", mpr_fuzz::tiny_png(3, 2, 2));
    mpr_fuzz::write_file(d / "c.png", mpr_fuzz::tiny_png(4, 2, 3));
    return d;
  }();
  return dir;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path par = folder() / "x_par.txt";
  mpr_fuzz::write_file(par, mpr_fuzz::as_text(data, size));
  const mpr::LoadLimits limits = mpr_fuzz::fuzz_limits();
  try {
    (void)mpr::read_par_entries<double>(par, limits);
  } catch (const mpr::error&) {
  }
  try {
    (void)mpr::read_par_file<float>(par, limits);
  } catch (const mpr::error&) {
  }
  try {
    (void)mpr::read_par_file<double>(par, limits);
  } catch (const mpr::error&) {
  }
  return 0;
}
