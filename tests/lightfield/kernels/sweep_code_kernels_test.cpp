#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/kernels/sweep_code_kernels.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <random>
#include <vector>

namespace {

using mpr::detail::SimdLevel;

// Planar channels of random codes, `stride` = width + 5 per row, kSweepCodePad codes of noise
// before the first row and after the last (what the kernel may read and must mask).
struct CodeImage {
  int width, height;
  std::ptrdiff_t stride;
  std::vector<std::uint8_t> data;
  CodeImage(int w, int h, unsigned seed)
      : width(w), height(h), stride(w + 5),
        data(static_cast<std::size_t>(3 * (w + 5) * h + 2 * mpr::detail::kSweepCodePad)) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> code(0, 255);
    for (std::uint8_t& v : data) v = static_cast<std::uint8_t>(code(rng));
  }
  [[nodiscard]] const std::uint8_t* channel(int c) const {
    return data.data() + mpr::detail::kSweepCodePad + static_cast<std::ptrdiff_t>(c) * height * stride;
  }
  [[nodiscard]] int at(int c, int x, int y) const { return channel(c)[y * stride + x]; }
};

} // namespace

TEST_CASE("the 16-bit kernel's weights are the bilinear weights in 1/128, summing to 128", "[sweep_code_kernels]") {
  using W = std::array<std::uint16_t, 4>;
  // (1 - fu)(1 - fv), fu (1 - fv), (1 - fu) fv, fu fv times 128, worked by hand.
  CHECK(mpr::detail::sweep_code_weights(0.25f, 0.5f) == W{48, 16, 48, 16}); // 0.375 0.125 0.375 0.125
  // 85.12 36.48 4.48 1.92 round to 85, 36, 4, 2 (127): the largest takes the missing one.
  CHECK(mpr::detail::sweep_code_weights(0.3f, 0.05f) == W{86, 36, 4, 2});
  CHECK(mpr::detail::sweep_code_weights(0.0f, 0.0f) == W{128, 0, 0, 0});
  CHECK(mpr::detail::sweep_code_weights(1.0f, 1.0f) == W{0, 0, 0, 128});
  // 62.72, 26.88, 26.88, 11.52 round to 63, 27, 27, 12 (129): the largest gives up the excess.
  CHECK(mpr::detail::sweep_code_weights(0.3f, 0.3f) == W{62, 27, 27, 12});
  // 127.49, 0.26, 0.26, 0.0005 round to 127, 0, 0, 0: a whole-pixel shift after all.
  CHECK(mpr::detail::sweep_code_weights(0.002f, 0.002f) == W{128, 0, 0, 0});
}

TEST_CASE("a weight of 128 becomes 64 + 64 on one row, which the byte multiply-add takes", "[sweep_code_kernels]") {
  using W = std::array<std::uint16_t, 4>;
  const std::uint8_t top[3] = {1, 2, 3}, bottom[3] = {4, 5, 6};
  const auto set = [&](const W& w) {
    mpr::detail::SweepCodeRow r{};
    for (int c = 0; c < 3; ++c) {
      r.top[c] = top + c;
      r.bottom[c] = bottom + c;
    }
    mpr::detail::sweep_code_set_weights(r, w);
    return r;
  };
  const auto weights = [](const mpr::detail::SweepCodeRow& r) { return W{r.w[0], r.w[1], r.w[2], r.w[3]}; };
  mpr::detail::SweepCodeRow r = set({48, 16, 48, 16}); // below 128: as given
  CHECK(weights(r) == W{48, 16, 48, 16});
  CHECK((r.top[1] == top + 1 && r.bottom[1] == bottom + 1));
  r = set({128, 0, 0, 0}); // the top row's left tap: twice the top row
  CHECK(weights(r) == W{64, 0, 64, 0});
  CHECK((r.top[2] == top + 2 && r.bottom[2] == top + 2));
  r = set({0, 128, 0, 0});
  CHECK(weights(r) == W{0, 64, 0, 64});
  CHECK((r.top[0] == top && r.bottom[0] == top));
  r = set({0, 0, 128, 0}); // the bottom row's: twice the bottom row
  CHECK(weights(r) == W{64, 0, 64, 0});
  CHECK((r.top[1] == bottom + 1 && r.bottom[1] == bottom + 1));
  r = set({0, 0, 0, 128});
  CHECK(weights(r) == W{0, 64, 0, 64});
  CHECK((r.top[0] == bottom && r.bottom[0] == bottom));
}

TEST_CASE("the 16-bit kernel takes the rows whose sums fit in 16 bits", "[sweep_code_kernels]") {
  CHECK(mpr::detail::sweep_code_tau(0.3f) == 2448); // 0.3 x 255 x 32
  CHECK(mpr::detail::sweep_code_tau(5.0f) == 3 * 8160);
  CHECK(mpr::detail::sweep_code_fits(12, 8, 0.3f));
  CHECK(mpr::detail::sweep_code_fits(26, 8, 0.3f));        // 26 x 2448 = 63648
  CHECK_FALSE(mpr::detail::sweep_code_fits(27, 8, 0.3f));  // 66096
  CHECK_FALSE(mpr::detail::sweep_code_fits(12, 8, 1.0f));  // 12 x 8160
  CHECK(mpr::detail::sweep_code_fits(8, 8, 1.0f));         // 65280
  CHECK_FALSE(mpr::detail::sweep_code_fits(12, 17, 0.1f)); // more kept than the kernel takes
}

TEST_CASE("the 16-bit kernel's cost of one pixel, worked by hand", "[sweep_code_kernels]") {
  // Weights {86, 36, 4, 2} (fu 0.3, fv 0.05); per channel the codes of the top row's two taps,
  // the bottom row's, and the reference's code:
  //   channel 0: 11 20 / 30 40, ref 14: 86 11 + 36 20 + 4 30 + 2 40 = 1866, |1866 - 1792| = 74,
  //              / 4 = 18 (the remainder dropped)
  //   channel 1: 0 255 / 255 0, ref 0: 40 x 255 = 10200, / 4 = 2550
  //   channel 2: 7 7 / 7 7, ref 7: 896 - 896 = 0
  // 2568 units, 2448 at truncation 0.3 (2448 units), 2568 at 0.45 (3672).
  constexpr std::ptrdiff_t pad = mpr::detail::kSweepCodePad;
  const int codes[3][5] = {{11, 20, 30, 40, 14}, {0, 255, 255, 0, 0}, {7, 7, 7, 7, 7}};
  std::vector<std::uint8_t> top[3], bottom[3], ref_codes[3];
  const std::uint8_t* ref[3];
  mpr::detail::SweepCodeRow r{};
  for (int c = 0; c < 3; ++c) {
    const auto row = [&](std::vector<std::uint8_t>& v, std::initializer_list<int> values) {
      v.assign(static_cast<std::size_t>(2 * pad + 2), 0);
      std::size_t i = static_cast<std::size_t>(pad);
      for (const int code : values) v[i++] = static_cast<std::uint8_t>(code);
    };
    row(top[c], {codes[c][0], codes[c][1]});
    row(bottom[c], {codes[c][2], codes[c][3]});
    row(ref_codes[c], {codes[c][4]});
    r.top[c] = top[c].data() + pad;
    r.bottom[c] = bottom[c].data() + pad;
    ref[c] = ref_codes[c].data() + pad;
  }
  mpr::detail::sweep_code_set_weights(r, mpr::detail::sweep_code_weights(0.3f, 0.05f));
  r.xb = 0;
  r.xe = 1;
  CHECK(mpr::detail::sweep_code_cost_at(ref, r, 3672, 0) == 2568);
  CHECK(mpr::detail::sweep_code_cost_at(ref, r, 2448, 0) == 2448);
  mpr_test::for_each_simd_level([&](SimdLevel level) {
    float out[2] = {-1.0f, -1.0f};
    mpr::detail::sweep_code_mean_seen(ref, &r, 1, 1, 0.45f, out, 1, level);
    CHECK(out[0] == 2568.0f / 8160.0f);
    CHECK(out[1] == -1.0f);
    mpr::detail::sweep_code_mean_seen(ref, &r, 1, 1, 0.3f, out, 1, level);
    CHECK(out[0] == 2448.0f / 8160.0f);
  });
}

TEST_CASE("the 16-bit kernel averages the best integer costs of the neighbours that see each pixel",
          "[sweep_code_kernels]") {
  // Twelve neighbours' rows over a row of 77 pixels (whole chunks of 64, 32 or 16 pixels by level
  // and a remainder of 13, each as even and odd pixels), each seen over its own span: whole, from
  // or up to inside a chunk, one even pixel, one odd pixel, none; four of them
  // whole-pixel shifts (a weight of 128 on each of the four taps in turn). The expected value
  // per pixel, from the documented integer costs: per channel |sum of weight x code - 128 x
  // reference code| / 4 (remainder dropped), summed, at most tau; tau for a neighbour that does
  // not see it; sorted, the best summed, over best x 8160. Also within the weights' rounding of
  // the float cost of the same blend (code / 255).
  const CodeImage image(120, 12, 31), ref_image(77, 1, 37);
  const int width = 77, m = 12;
  const std::uint8_t* ref[3] = {ref_image.channel(0), ref_image.channel(1), ref_image.channel(2)};
  const float tau = 0.45f;
  const unsigned tau_units = 3672; // 0.45 x 8160
  const int shifts[m] = {0, 3, 17, 9, 20, 1, 5, 12, 7, 2, 14, 11}, rows[m] = {0, 4, 7, 2, 9, 1, 3, 5, 8, 6, 10, 0};
  const int xbs[m] = {0, 5, 32, 0, 21, 31, 0, 70, 76, 10, 3, 0},
            xes[m] = {77, 77, 64, 33, 22, 50, 64, 77, 77, 10, 40, 77};
  const float fus[m] = {0.25f, 0.0f, 0.8f, 1.0f, 0.5f, 0.1f, 0.9f, 1.0f, 0.6f, 0.2f, 0.75f, 0.0f};
  const float fvs[m] = {0.4f, 1.0f, 0.0f, 1.0f, 0.3f, 0.7f, 0.15f, 0.0f, 0.95f, 0.2f, 0.45f, 0.0f};
  mpr::detail::SweepCodeRow coded[m];
  std::array<std::uint16_t, 4> weights[m];
  for (int j = 0; j < m; ++j) {
    weights[j] = mpr::detail::sweep_code_weights(fus[j], fvs[j]);
    for (int c = 0; c < 3; ++c) {
      coded[j].top[c] = image.channel(c) + rows[j] * image.stride + shifts[j] + xbs[j];
      coded[j].bottom[c] = image.channel(c) + (rows[j] + 1) * image.stride + shifts[j] + xbs[j];
    }
    mpr::detail::sweep_code_set_weights(coded[j], weights[j]);
    coded[j].xb = xbs[j];
    coded[j].xe = xes[j];
  }
  double worst_float = 0;
  for (int used : {m, 5}) {
    for (int best = 1; best <= used; ++best) {
      std::vector<float> expected(static_cast<std::size_t>(width)), near(static_cast<std::size_t>(width));
      for (int x = 0; x < width; ++x) {
        std::vector<unsigned> c;
        std::vector<float> f;
        for (int j = 0; j < used; ++j) {
          if (x < xbs[j] || x >= xes[j]) {
            c.push_back(tau_units);
            f.push_back(tau);
            continue;
          }
          const int u = x + shifts[j], v = rows[j];
          const std::array<std::uint16_t, 4>& w = weights[j];
          unsigned s = 0;
          float fs = 0;
          for (int ch = 0; ch < 3; ++ch) {
            const int blend = w[0] * image.at(ch, u, v) + w[1] * image.at(ch, u + 1, v) +
                              w[2] * image.at(ch, u, v + 1) + w[3] * image.at(ch, u + 1, v + 1);
            s += static_cast<unsigned>(std::abs(blend - 128 * ref[ch][x])) / 4;
            const float a = (1 - fus[j]) * image.at(ch, u, v) + fus[j] * image.at(ch, u + 1, v);
            const float b = (1 - fus[j]) * image.at(ch, u, v + 1) + fus[j] * image.at(ch, u + 1, v + 1);
            fs += std::abs((1 - fvs[j]) * a + fvs[j] * b - static_cast<float>(ref[ch][x])) / 255.0f;
          }
          c.push_back(std::min(s, tau_units));
          f.push_back(std::min(fs, tau));
        }
        std::sort(c.begin(), c.end());
        std::sort(f.begin(), f.end());
        unsigned sum = 0;
        float fsum = 0;
        for (int i = 0; i < best; ++i) {
          sum += c[static_cast<std::size_t>(i)];
          fsum += f[static_cast<std::size_t>(i)];
        }
        expected[static_cast<std::size_t>(x)] = static_cast<float>(sum) / static_cast<float>(best * 8160);
        near[static_cast<std::size_t>(x)] = fsum / static_cast<float>(best);
      }
      mpr_test::for_each_simd_level([&](SimdLevel level) {
        std::vector<float> out(static_cast<std::size_t>(width) + 1, -1.0f);
        mpr::detail::sweep_code_mean_seen(ref, coded, used, best, tau, out.data(), width, level);
        for (int x = 0; x < width; ++x) {
          INFO("m " << used << " best " << best << " x " << x);
          CHECK(out[static_cast<std::size_t>(x)] == expected[static_cast<std::size_t>(x)]);
          worst_float = std::max(worst_float, static_cast<double>(std::abs(out[static_cast<std::size_t>(x)] -
                                                                           near[static_cast<std::size_t>(x)])));
        }
        CHECK(out[static_cast<std::size_t>(width)] == -1.0f); // nothing written past the row
      });
    }
  }
  // Each weight is within 2.5/128 of the exact one and they sum to 1, so a blend of values in [0,
  // 1] moves by at most 4/128 / 2; three channels, plus the dropped quarters (3/8160).
  INFO("worst difference from the float cost " << worst_float);
  CHECK(worst_float <= 3 * 2.0 / 128 + 3.0 / 8160);
  CHECK(worst_float > 0);
}
