// libFuzzer target: the LFCA loader (read_lfca in float and double). The input is the positions
// file, optionally followed by "\n--\n" and the homography of camera `a`; cameras `b` and `c`
// have identity homographies. a.png and b.png are 3x2, c.png is 4x2. Only mpr::error may escape.
#include "fuzz_common.hpp"

#include <mpr/io/lfca_calibration.hpp>

namespace {
const std::filesystem::path& folder() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d = mpr_fuzz::scratch("lfca");
    mpr_fuzz::write_file(d / "a.png", mpr_fuzz::tiny_png(3, 2, 1));
    mpr_fuzz::write_file(d / "b.png", mpr_fuzz::tiny_png(3, 2, 2));
    mpr_fuzz::write_file(d / "c.png", mpr_fuzz::tiny_png(4, 2, 3));
    mpr_fuzz::write_file(d / "b.homography.txt", "1 0 0\n0 1 0\n0 0 1\n");
    mpr_fuzz::write_file(d / "c.homography.txt", "1 0 0 0 1 0 0 0 1");
    return d;
  }();
  return dir;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto [positions, homography] = mpr_fuzz::split_once(mpr_fuzz::as_text(data, size), "\n--\n");
  mpr_fuzz::write_file(folder() / "p.txt", positions);
  mpr_fuzz::write_file(folder() / "a.homography.txt", homography);
  const mpr::LoadLimits limits = mpr_fuzz::fuzz_limits();
  try {
    (void)mpr::read_lfca<double>(folder() / "p.txt", {}, limits);
  } catch (const mpr::error&) {
  }
  try {
    (void)mpr::read_lfca<float>(folder() / "p.txt", {}, limits);
  } catch (const mpr::error&) {
  }
  return 0;
}
