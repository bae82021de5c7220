#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/plane_sweep/sweep_row.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace {

using mpr::detail::SimdLevel;
using mpr::detail::SweepNeighbourRow;

mpr::Image<mpr::Rgb8> random_image(int width, int height, std::mt19937& rng) {
  std::uniform_int_distribution<int> code(0, 255);
  mpr::Image<mpr::Rgb8> image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(code(rng)), static_cast<std::uint8_t>(code(rng)),
                              static_cast<std::uint8_t>(code(rng))};
  return image;
}

// Row y's cost neighbour by neighbour over the whole row, as the sweep did before the fused
// kernel: keep rows at tau, each neighbour's translated or projective row inserted, the mean.
std::vector<float> per_neighbour(const mpr::detail::SweepRowInputs& in, int y, float d) {
  const int width = in.reference->width;
  const std::size_t w = static_cast<std::size_t>(width);
  std::vector<float> keep(static_cast<std::size_t>(in.best) * w, in.tau), value(w), out(w);
  float* k[32];
  for (int i = 0; i < in.best; ++i) k[i] = keep.data() + static_cast<std::size_t>(i) * w;
  const float* ref[3];
  for (int c = 0; c < 3; ++c) ref[c] = in.reference->channel(c) + static_cast<std::ptrdiff_t>(y) * in.reference->stride;
  for (int j = 0; j < in.m; ++j) {
    const SweepNeighbourRow p = mpr::detail::sweep_neighbour_row(in, j, width, y, d);
    if (p.kind == SweepNeighbourRow::projective) {
      mpr::detail::sweep_projective_cost(ref, in.neighbours[j].view(), p.row, 0, in.tau, value.data(), w, in.level);
      mpr::detail::sweep_keep_best(k, in.best, value.data(), w, in.level);
    } else if (p.kind == SweepNeighbourRow::shift) {
      const mpr::detail::SweepShiftRow row = p.shifted(in.neighbours[j], p.xb);
      const float* seg[3] = {ref[0] + p.xb, ref[1] + p.xb, ref[2] + p.xb};
      const std::size_t count = static_cast<std::size_t>(p.xe - p.xb);
      if (in.best <= mpr::detail::kSweepShiftKeepBest) {
        mpr::detail::sweep_shift_keep(seg, row, in.tau, k[0] + p.xb, static_cast<std::ptrdiff_t>(w), in.best, count,
                                      in.level);
      } else {
        mpr::detail::sweep_shift_cost(seg, row, in.tau, value.data() + p.xb, count, in.level);
        float* kk[32];
        for (int i = 0; i < in.best; ++i) kk[i] = k[i] + p.xb;
        mpr::detail::sweep_keep_best(kk, in.best, value.data() + p.xb, count, in.level);
      }
    }
  }
  mpr::detail::sweep_mean_best(k, in.best, out.data(), w, in.level);
  return out;
}

} // namespace

TEST_CASE("a row's cost is the same with the fused kernel as neighbour by neighbour", "[sweep_row]") {
  // Random neighbours: translated rows (reference pixel x at x + tx / d, y + ty / d) into images
  // of other widths and heights, so that the pixels each one sees differ, overlap partly or not
  // at all, or are none; projective rows; 1-6 or 1-20 neighbours (beyond 4 translated ones: the chunked
  // kernel, rows of up to 60 pixels: whole chunks of 16, partly seen ones and a remainder), every
  // best. Every row of the reference, at every SIMD level.
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int fused_partial = 0, chunked = 0, cases = 0, codes = 0;
  for (int trial = 0; trial < 320; ++trial) {
    const int width = 1 + static_cast<int>(unit(rng) * 60), height = 2 + static_cast<int>(unit(rng) * 5);
    mpr::detail::SweepPlanes reference;
    mpr::detail::sweep_planes(random_image(width, height, rng), true, reference);
    const int m = 1 + static_cast<int>(unit(rng) * (trial % 2 == 0 ? 6.0f : 20.0f));
    std::vector<mpr::detail::SweepPlanes> neighbours(static_cast<std::size_t>(m));
    std::vector<mpr::Mat3<float>> M(static_cast<std::size_t>(m));
    std::vector<mpr::Vec3<float>> A(static_cast<std::size_t>(m));
    const float d = 0.5f + 3 * unit(rng);
    bool all_shift = m <= mpr::detail::kSweepShiftMeanNeighbours;
    for (int j = 0; j < m; ++j) {
      const int nw = 1 + static_cast<int>(unit(rng) * 80), nh = 2 + static_cast<int>(unit(rng) * 6);
      mpr::detail::sweep_planes(random_image(nw, nh, rng), false, neighbours[static_cast<std::size_t>(j)]);
      M[static_cast<std::size_t>(j)].setIdentity();
      if (unit(rng) < 0.15f) { // a projective row: w changes along the row
        M[static_cast<std::size_t>(j)](2, 0) = 0.01f;
        all_shift = false;
      }
      // Offsets of up to +-40 pixels, a third of them whole.
      float tx = (unit(rng) - 0.5f) * 80, ty = (unit(rng) - 0.5f) * 4;
      if (unit(rng) < 0.33f) tx = static_cast<float>(static_cast<int>(tx));
      A[static_cast<std::size_t>(j)] = mpr::Vec3<float>(tx * d, ty * d, 0);
    }
    const int best = 1 + static_cast<int>(unit(rng) * static_cast<float>(m));
    const float tau = 0.2f + unit(rng);
    mpr_test::for_each_simd_level([&](SimdLevel level) {
      mpr::detail::SweepRowInputs in{&reference, neighbours.data(), M.data(), A.data(), m, best, tau, level};
      for (int y = 0; y < height; ++y) {
        in.codes = false;
        const std::vector<float> expected = per_neighbour(in, y, d);
        std::vector<float> keep(static_cast<std::size_t>(best * width), -7.0f), value(static_cast<std::size_t>(width));
        std::vector<float> out(static_cast<std::size_t>(width) + 1, -1.0f), coded(out);
        float* k[32];
        for (int i = 0; i < best; ++i) k[i] = keep.data() + static_cast<std::size_t>(i * width);
        mpr::detail::sweep_cost_row(in, y, d, out.data(), k, value.data());
        INFO("trial " << trial << " width " << width << " m " << m << " best " << best << " y " << y);
        // Bit for bit, but where the chunked kernel drops the worst m - best (< best) costs from
        // the sum instead of summing the best: the same value up to the sums' rounding.
        float worst = 0, worst_coded = 0;
        for (std::size_t x = 0; x < expected.size(); ++x) worst = std::max(worst, std::abs(out[x] - expected[x]));
        CHECK(worst <= 1e-5f);
        CHECK(out.back() == -1.0f); // nothing past the row
        // On 16-bit codes where the chunked kernel takes the row: within the weights' rounding to
        // 1/128 (kernels/sweep_code_kernels_test.cpp) of the float values.
        in.codes = true;
        mpr::detail::sweep_cost_row(in, y, d, coded.data(), k, value.data());
        for (std::size_t x = 0; x < expected.size(); ++x)
          worst_coded = std::max(worst_coded, std::abs(coded[x] - expected[x]));
        CHECK(worst_coded <= 3 * 2.0f / 128 + 3.0f / 8160);
        CHECK(coded.back() == -1.0f);
        codes += worst_coded > 1e-5f;
        ++cases;
        if (level == SimdLevel::portable && m > mpr::detail::kSweepShiftMeanNeighbours &&
            best <= mpr::detail::kSweepSeenBest) {
          bool projective = false;
          for (int j = 0; j < m; ++j)
            projective = projective ||
                         mpr::detail::sweep_neighbour_row(in, j, width, y, d).kind == SweepNeighbourRow::projective;
          chunked += !projective;
        }
        if (level == SimdLevel::portable && all_shift) {
          // Count rows where the fused kernel ran beside edge segments.
          int cb = 0, ce = width;
          bool seen = true;
          for (int j = 0; j < m; ++j) {
            const SweepNeighbourRow p = mpr::detail::sweep_neighbour_row(in, j, width, y, d);
            seen = seen && p.kind == SweepNeighbourRow::shift;
            cb = std::max(cb, p.xb);
            ce = std::min(ce, p.xe);
          }
          fused_partial += seen && cb < ce && (cb > 0 || ce < width);
        }
      }
    });
  }
  CHECK(cases > 500);
  CHECK(fused_partial > 20); // the split into edge segments and fused core was exercised
  CHECK(chunked > 50);       // the chunked kernel of many translated rows was exercised
  CHECK(codes > 50);         // and its 16-bit twin
}

TEST_CASE("a neighbour row at extreme depths and offsets reads inside both images", "[sweep_row]") {
  // Neighbour pixel (x + tx / d, y + ty / d): offsets and depths from ordinary to overflowing,
  // infinite and NaN. A translated row must cover reference pixels [xb, xe) within the row and
  // read neighbour columns x + s and rows v0, v1 inside the neighbour; every float converted to
  // an int on the way stays in range (checked by the clang float-cast-overflow builds).
  std::mt19937 rng(5);
  mpr::detail::SweepPlanes reference, neighbour;
  mpr::detail::sweep_planes(random_image(9, 4, rng), true, reference);
  mpr::detail::sweep_planes(random_image(6, 3, rng), false, neighbour);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  const float big = std::numeric_limits<float>::max(), tiny = std::numeric_limits<float>::denorm_min();
  const float offsets[] = {0.0f,  2.5f,   -3.0f, 8.75f, -8.9f, 1e9f, -1e9f, 3e9f,
                           1e30f, -1e30f, big,   -big,  inf,   -inf, nan};
  const float depths[] = {1.0f, 0.25f, 1e-20f, tiny, 1e20f, big, inf, nan, 0.0f, -1.0f};
  mpr::Mat3<float> M = mpr::Mat3<float>::Identity();
  int shifted = 0;
  for (const float tx : offsets)
    for (const float ty : {0.0f, 0.5f, 1.75f, 1e30f, nan})
      for (const float d : depths) {
        const mpr::Vec3<float> A(tx * d, ty * d, 0);
        const mpr::detail::SweepRowInputs in{&reference, &neighbour, &M, &A, 1, 1, 0.3f, SimdLevel::portable};
        for (int y = 0; y < reference.height; ++y) {
          const SweepNeighbourRow p = mpr::detail::sweep_neighbour_row(in, 0, reference.width, y, d);
          if (p.kind != SweepNeighbourRow::shift) continue;
          INFO("tx " << tx << " ty " << ty << " d " << d << " y " << y);
          ++shifted;
          CHECK(0 <= p.xb);
          CHECK(p.xb < p.xe);
          CHECK(p.xe <= reference.width);
          CHECK(p.xb + p.s >= 0);
          CHECK(p.xe - 1 + p.s <= neighbour.width - 1);
          CHECK(0 <= p.v0);
          CHECK(p.v0 <= p.v1);
          CHECK(p.v1 <= neighbour.height - 1);
          CHECK(p.fu >= 0.0f);
          CHECK(p.fu <= 1.0f);
        }
      }
  CHECK(shifted > 50);
}
