// Many cameras' whole-pixel shifts added together (mpr/lightfield/kernels/shift_batch.hpp), at
// every instruction-set level against a long-double reference: each output row gets the decoded
// texels of exactly the blocks that cover it, for more cameras than one register pass sums and
// rows of every tail length; nothing outside the rows is written. The same with each block's
// 16-bit linear values (`ShiftedBlock::linear`, read instead of the codes below the VBMI level).

#include "lightfield/channel_values.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/kernels/shift_batch.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace {

using LD = long double;

struct Layout {
  const char* name;
  std::size_t cameras, n, rows;
};

} // namespace

TEST_CASE("add_shifted_blocks: every level adds each row the texels of the blocks covering it, nothing else",
          "[shift_batch]") {
  const mpr_test::ChannelValues<std::uint8_t> channels;
  constexpr float kSentinel = -12345.0f;
  constexpr std::size_t kGuard = 21;
  const Layout layouts[] = {
      {"one camera", 1, 50, 3},
      {"49 cameras", 49, 300, 8},
      {"more cameras than one pass sums (300)", 300, 70, 2},
      {"short rows, every tail length", 5, 23, 8},
  };
  std::mt19937_64 rng(1400);
  int failures = 0;
  for (const bool linear : {false, true})
    for (const Layout& l : layouts) {
      INFO(l.name << (linear ? ", with 16-bit linear values" : ""));
      // Each camera: an image of random codes, 3 (n + 64) channels a row (room for its shift) and
      // as many rows as the tile; its block some of the tile's rows and pixels.
      const std::size_t stride = 3 * (l.n + 64);
      std::vector<std::vector<std::uint8_t>> images(l.cameras);
      std::vector<std::vector<std::uint16_t>> values(l.cameras); // each code's table entry
      mpr::detail::ShiftBatch batch;
      for (std::size_t c = 0; c < l.cameras; ++c) {
        std::vector<std::uint8_t>& image = images[c];
        image.resize(stride * l.rows + 64);
        for (std::uint8_t& code : image) {
          code = static_cast<std::uint8_t>(rng() % 256);
          values[c].push_back(channels.lut[code]);
        }
        mpr::detail::ShiftedBlock b;
        b.r_begin = rng() % 3 == 0 ? rng() % l.rows : 0;
        b.r_end = rng() % 3 == 0 ? b.r_begin + rng() % (l.rows - b.r_begin + 1) : l.rows;
        b.stride = static_cast<std::ptrdiff_t>(stride);
        const std::size_t first = 3 * (rng() % 60);
        b.texels = image.data() + first;
        b.linear = linear ? values[c].data() + first : nullptr;
        batch.blocks.push_back(b);
      }
      batch.rows.resize(l.cameras);
      if (linear) batch.rows16.resize(l.cameras);
      const std::size_t acc_stride = 3 * l.n + kGuard;
      std::vector<float> start(acc_stride * l.rows + kGuard);
      for (std::size_t at = 0; at < start.size(); ++at)
        start[at] = at % acc_stride < 3 * l.n && at < acc_stride * l.rows ? static_cast<float>(rng() % 1000) / 999.0f
                                                                          : kSentinel;
      mpr_test::for_each_simd_level([&](mpr_test::SimdLevel level) {
        std::vector<float> acc = start;
        mpr::detail::add_shifted_blocks(batch, l.rows, l.n, channels.lut, channels.scale, acc.data(),
                                        static_cast<std::ptrdiff_t>(acc_stride), level);
        for (std::size_t at = 0; at < acc.size(); ++at) {
          const std::size_t r = at / acc_stride, j = at % acc_stride;
          if (r >= l.rows || j >= 3 * l.n) {
            if (acc[at] != kSentinel && ++failures <= 5) FAIL_CHECK("written outside the rows at " << at);
            continue;
          }
          LD want = start[at], size = std::abs(LD(start[at]));
          int covering = 0;
          for (const mpr::detail::ShiftedBlock& b : batch.blocks) {
            if (r < b.r_begin || r >= b.r_end) continue;
            const LD v = LD(channels.scale) * channels.value(b.texels[(r - b.r_begin) * stride + j]);
            want += v;
            size += v;
            ++covering;
          }
          // Float rounding: of the scaling and addition of each register pass's sum (exact in the
          // kernel), or of each camera's add at the portable level.
          const LD bound = LD(covering + 2) * LD(std::numeric_limits<float>::epsilon()) * size;
          if (!(std::abs(LD(acc[at]) - want) <= bound) && ++failures <= 5)
            FAIL_CHECK("row " << r << " channel " << j << ": " << acc[at] << " vs " << static_cast<double>(want));
        }
      });
    }
  CHECK(failures == 0);
}
