// libFuzzer target: PFM depth maps (read_pfm), the header parsed before the data is read. The
// input is the file. Only mpr::error may escape; a map that reads must round-trip bit-exactly
// through encode_pfm (NaN payloads included).
#include "fuzz_common.hpp"

#include <mpr/io/pfm.hpp>

#include <cstdlib>
#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path path = mpr_fuzz::scratch("pfm") / "x.pfm";
  mpr_fuzz::write_file(path, mpr_fuzz::as_text(data, size));
  try {
    const mpr::Image<float> map = mpr::read_pfm(path, mpr_fuzz::fuzz_limits());
    const std::vector<unsigned char> bytes = mpr::encode_pfm(map.view());
    mpr_fuzz::write_file(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
    const mpr::Image<float> back = mpr::read_pfm(path, mpr_fuzz::fuzz_limits());
    if (back.width() != map.width() || back.height() != map.height()) std::abort();
    for (int y = 0; y < map.height(); ++y)
      if (std::memcmp(back.view().row(y), map.view().row(y), sizeof(float) * static_cast<std::size_t>(map.width())) !=
          0)
        std::abort();
  } catch (const mpr::error&) {
  }
  return 0;
}
