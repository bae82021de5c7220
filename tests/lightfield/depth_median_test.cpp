#include <mpr/lightfield/depth_median.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <utility>
#include <vector>

namespace {

// A 9x7 image split at x = 4.5: black with value 0 on the left, white with value 10 on the right.
struct Step {
  mpr::Image<float> values{9, 7};
  mpr::Image<mpr::Rgb8> guide{9, 7};
  mpr::Image<float> confidence{9, 7, 1.0f};
  Step() {
    for (int y = 0; y < 7; ++y)
      for (int x = 0; x < 9; ++x) {
        const bool right = x >= 5;
        values(x, y) = right ? 10.0f : 0.0f;
        guide(x, y) = right ? mpr::Rgb8{255, 255, 255} : mpr::Rgb8{0, 0, 0};
      }
  }
};

} // namespace

TEST_CASE("weighted median: a step stays a step and a wrong sliver beside it takes its colour side's value",
          "[depth_median]") {
  Step s;
  for (int y = 0; y < 7; ++y) s.values(4, y) = 10.0f; // the left side's last column took the right's value
  const mpr::Image<float> out = mpr::weighted_median(s.values.view(), s.guide.view(), s.confidence.view(), {2, 0.16});
  for (int y = 0; y < 7; ++y) {
    CHECK(out(4, y) == 0.0f); // black: the white pixels weigh exp(-3 / 0.16), nothing
    CHECK(out(3, y) == 0.0f);
    CHECK(out(5, y) == 10.0f);
    CHECK(out(8, y) == 10.0f);
  }
}

TEST_CASE("weighted median: confidence weighs the votes (hand-worked 3x3)", "[depth_median]") {
  // One colour; the 3x3 window around (1, 1): five values 1 of confidence 0.1 (weight 0.5 in all)
  // and four values 5 of confidence 1 (weight 4): half of 4.5 is reached within the 5s. A plain
  // median would give 1.
  mpr::Image<float> values(3, 3, 1.0f), confidence(3, 3, 0.1f);
  const mpr::Image<mpr::Rgb8> guide(3, 3, mpr::Rgb8{90, 90, 90});
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{2, 0}, std::pair{0, 2}, std::pair{2, 2}}) {
    values(x, y) = 5.0f;
    confidence(x, y) = 1.0f;
  }
  const mpr::Image<float> out = mpr::weighted_median(values.view(), guide.view(), confidence.view(), {1, 0.16});
  CHECK(out(1, 1) == 5.0f);
  // Corner (0, 0): window (0..1)^2 holds 5 (weight 1) and three 1s (0.3): 5.
  CHECK(out(0, 0) == 5.0f);
  // Edge (1, 0): window x 0..2, y 0..1: two 5s (2) and four 1s (0.4): 5.
  CHECK(out(1, 0) == 5.0f);
}

TEST_CASE("weighted median: radius 0 and windows within `flat` leave the values unchanged", "[depth_median]") {
  Step s;
  s.values(2, 3) = 0.75f; // within flat = 1 of its neighbours
  const mpr::Image<float> none = mpr::weighted_median(s.values.view(), s.guide.view(), s.confidence.view(), {0});
  CHECK(none(2, 3) == 0.75f);
  CHECK(none(4, 3) == 0.0f);
  const mpr::Image<float> flat = mpr::weighted_median(s.values.view(), s.guide.view(), s.confidence.view(), {1});
  CHECK(flat(2, 3) == 0.75f);
  mpr::WeightedMedianConfig strict{1};
  strict.flat = 0.5; // now the window's spread 0.75 counts as an edge: the median of the 0s
  const mpr::Image<float> filtered = mpr::weighted_median(s.values.view(), s.guide.view(), s.confidence.view(), strict);
  CHECK(filtered(2, 3) == 0.0f);
}

TEST_CASE("weighted median: bad settings and sizes are refused by name", "[depth_median]") {
  Step s;
  const mpr::Image<float> small(3, 3);
  CHECK_THROWS_WITH(mpr::weighted_median(s.values.view(), s.guide.view(), small.view()), Catch::Contains("confidence"));
  CHECK_THROWS_WITH(mpr::weighted_median(s.values.view(), mpr::Image<mpr::Rgb8>(2, 2).view(), s.confidence.view()),
                    Catch::Contains("guide"));
  CHECK_THROWS_WITH(mpr::weighted_median(s.values.view(), s.guide.view(), s.confidence.view(), {8}),
                    Catch::Contains("radius"));
  CHECK_THROWS_WITH(mpr::weighted_median(s.values.view(), s.guide.view(), s.confidence.view(), {1, 0.0}),
                    Catch::Contains("range"));
}

TEST_CASE("weighted median: close values, ranked within one another (hand-worked 3x3)", "[depth_median]") {
  // One colour; the window of (1, 1) holds 0 and 100 (confidence 1) and seven values between 10
  // and 10.6 (confidence 0.1, but 10.4 and 10.5: 1). Ascending cumulative weight: 0: 1, 10.0..10.3:
  // 1.1..1.4, 10.4: 2.4, which first reaches half of 4.5: 10.4 (a plain median gives 10.3).
  const float v[9] = {10.2f, 100.0f, 10.0f, 10.5f, 10.3f, 0.0f, 10.6f, 10.4f, 10.1f};
  const float c[9] = {0.1f, 1.0f, 0.1f, 1.0f, 0.1f, 1.0f, 0.1f, 1.0f, 0.1f};
  mpr::Image<float> values(3, 3), confidence(3, 3);
  for (int k = 0; k < 9; ++k) {
    values(k % 3, k / 3) = v[k];
    confidence(k % 3, k / 3) = c[k];
  }
  const mpr::Image<mpr::Rgb8> guide(3, 3, mpr::Rgb8{40, 50, 60});
  const mpr::Image<float> out = mpr::weighted_median(values.view(), guide.view(), confidence.view(), {1, 0.16});
  CHECK(out(1, 1) == 10.4f);
}

namespace {

// The weighted median of the file comment worked out the plain way, in double: the clipped
// window's values sorted with their weights, summed in ascending order up to half the total.
// `margin`: how far (relative to the total) the sum just below the answer and the sum at it lie
// from half; a float computation may pick the neighbouring value only where that is tiny.
struct Oracle {
  float value;
  double margin;
};
Oracle oracle_median(const mpr::Image<float>& values, const mpr::Image<mpr::Rgb8>& guide,
                     const mpr::Image<float>& confidence, int x, int y, int r, double range, double floor) {
  std::vector<std::pair<float, double>> window;
  const mpr::Rgb8 p = guide(x, y);
  for (int v = std::max(0, y - r); v <= std::min(values.height() - 1, y + r); ++v)
    for (int u = std::max(0, x - r); u <= std::min(values.width() - 1, x + r); ++u) {
      const mpr::Rgb8 q = guide(u, v);
      const int d = std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b);
      const double w = static_cast<float>(std::exp(-d / 255.0 / range)) * std::max<double>(confidence(u, v), floor);
      window.emplace_back(values(u, v), w);
    }
  std::sort(window.begin(), window.end());
  double total = 0;
  for (const auto& e : window) total += e.second;
  double below = 0;
  for (std::size_t i = 0; i < window.size();) {
    const float v = window[i].first;
    const double before = below;
    for (; i < window.size() && window[i].first == v; ++i) below += window[i].second;
    if (below >= 0.5 * total) return {v, std::min(0.5 * total - before, below - 0.5 * total) / total};
  }
  return {window.back().first, 0};
}

} // namespace

TEST_CASE("weighted median: random windows against the sorted-window oracle, every radius and the image edges",
          "[depth_median]") {
  // 37 x 23: chunks of pixels that end past the right edge, windows clipped on every side, and
  // values on a coarse grid (many equal values) or continuous.
  std::mt19937 rng(46);
  for (const int r : {1, 2, 3, 5, 7})
    for (const bool coarse : {true, false}) {
      const int w = 37, h = 23;
      mpr::Image<float> values(w, h), confidence(w, h);
      mpr::Image<mpr::Rgb8> guide(w, h);
      std::uniform_real_distribution<float> value(0.0f, 20.0f), conf(0.0f, 1.0f);
      std::uniform_int_distribution<int> code(0, 2); // three colours, far apart and alike
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          values(x, y) = coarse ? std::floor(value(rng) / 4) : value(rng);
          confidence(x, y) = conf(rng) < 0.1f ? 0.0f : conf(rng);
          const auto c = static_cast<std::uint8_t>(40 + 60 * code(rng));
          guide(x, y) = {c, static_cast<std::uint8_t>(c / 2), static_cast<std::uint8_t>(255 - c)};
        }
      mpr::WeightedMedianConfig c{r, 0.16};
      c.flat = 0.5;
      const mpr::Image<float> out = mpr::weighted_median(values.view(), guide.view(), confidence.view(), c);
      int checked = 0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          float lo = values(x, y), hi = lo;
          for (int v = std::max(0, y - r); v <= std::min(h - 1, y + r); ++v)
            for (int u = std::max(0, x - r); u <= std::min(w - 1, x + r); ++u) {
              lo = std::min(lo, values(u, v));
              hi = std::max(hi, values(u, v));
            }
          if (hi - lo <= 0.5f) {
            CHECK(out(x, y) == values(x, y));
            continue;
          }
          const Oracle o = oracle_median(values, guide, confidence, x, y, r, 0.16, 0.02);
          if (o.margin < 1e-5) continue; // a tie within float rounding: either neighbour will do
          INFO("r " << r << " coarse " << coarse << " at " << x << ", " << y);
          CHECK(out(x, y) == o.value);
          ++checked;
        }
      CHECK(checked > w * h / 2);
    }
}

TEST_CASE("weighted median: views with padded rows give what packed images give", "[depth_median]") {
  // The values and confidence as the 9 x 7 corner of wider images (rows 13 apart).
  Step s;
  for (int y = 0; y < 7; ++y) s.values(4, y) = 10.0f;
  s.confidence(6, 2) = 0.3f;
  mpr::Image<float> wide_values(13, 7, -1.0f), wide_confidence(13, 7, 0.5f);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x) {
      wide_values(x + 4, y) = s.values(x, y);
      wide_confidence(x + 4, y) = s.confidence(x, y);
    }
  const mpr::ImageView<const float> values = wide_values.view().subview(4, 0, 9, 7);
  const mpr::ImageView<const float> confidence = wide_confidence.view().subview(4, 0, 9, 7);
  const mpr::Image<float> packed = mpr::weighted_median(s.values.view(), s.guide.view(), s.confidence.view(), {2});
  const mpr::Image<float> padded = mpr::weighted_median(values, s.guide.view(), confidence, {2});
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 9; ++x) CHECK(padded(x, y) == packed(x, y));
  CHECK(padded(4, 3) == 0.0f);
}

TEST_CASE("weighted median: a chunk is one register of the level", "[depth_median]") {
  using mpr::detail::median_lanes;
  using mpr::detail::SimdLevel;
#if defined(__GNUC__)
  // A vector type wider than the level's registers is lowered to scalar code.
  STATIC_REQUIRE(sizeof(mpr::detail::MedianVectors<median_lanes(SimdLevel::portable)>::Lanes) == 16);
  STATIC_REQUIRE(sizeof(mpr::detail::MedianVectors<median_lanes(SimdLevel::avx2)>::Lanes) == 32);
  STATIC_REQUIRE(sizeof(mpr::detail::MedianVectors<median_lanes(SimdLevel::avx512)>::Lanes) == 64);
#endif
  // The padding unit holds a whole number of chunks at every level.
  for (const SimdLevel level : mpr::detail::kSimdLevels) CHECK(mpr::detail::kMedianChunk % median_lanes(level) == 0);
}
