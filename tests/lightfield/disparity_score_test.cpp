#include <mpr/lightfield/disparity_score.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace {

// Truth 0 everywhere; the estimate's errors, hand-scored below.
mpr::Image<float> errors_4x2() {
  mpr::Image<float> e(4, 2);
  const float v[8] = {0.0f, 0.005f, 0.02f, 0.05f, 0.1f, -0.2f, 0.003f, 0.04f};
  for (int i = 0; i < 8; ++i) e(i % 4, i / 4) = v[i];
  return e;
}

} // namespace

TEST_CASE("disparity scores: hand-worked BadPix, MSE x100 and Q25", "[disparity_score]") {
  const mpr::Image<float> truth(4, 2), estimate = errors_4x2();
  const mpr::DisparityScore s = mpr::score_disparity(estimate.view(), truth.view(), {0, {}});
  CHECK(s.pixels == 8);
  CHECK(s.badpix_001 == Approx(62.5)); // 0.02 0.05 0.1 0.2 0.04
  CHECK(s.badpix_003 == Approx(50.0)); // 0.05 0.1 0.2 0.04
  CHECK(s.badpix_007 == Approx(25.0)); // 0.1 0.2
  // (0 + 25e-6 + 4e-4 + 2.5e-3 + 1e-2 + 4e-2 + 9e-6 + 1.6e-3) / 8 x 100
  CHECK(s.mse_x100 == Approx(0.681675).epsilon(1e-5));
  CHECK(s.q25_x100 == Approx(0.3).epsilon(1e-5)); // 2nd smallest of 8: 0.003
}

TEST_CASE("disparity scores: the mask and the border leave pixels out", "[disparity_score]") {
  const mpr::Image<float> truth(4, 2), estimate = errors_4x2();
  mpr::Image<std::uint8_t> mask(4, 2, 1);
  mask(1, 1) = 0; // the -0.2
  const mpr::DisparityScore s = mpr::score_disparity(estimate.view(), truth.view(), {0, mask.view()});
  CHECK(s.pixels == 7);
  CHECK(s.badpix_007 == Approx(100.0 / 7)); // 0.1 only
  // The published 15-pixel border: of 32x32 only the central 2x2 pixels count.
  const mpr::Image<float> zero(32, 32);
  mpr::Image<float> e(32, 32);
  e(14, 20) = 1; // in the border
  e(15, 15) = 1; // inside
  const mpr::DisparityScore b = mpr::score_disparity(e.view(), zero.view());
  CHECK(b.pixels == 4);
  CHECK(b.badpix_007 == Approx(25));
  CHECK(b.mse_x100 == Approx(25));
}

TEST_CASE("disparity scores: non-finite estimates are bad, unknown truth is left out", "[disparity_score]") {
  mpr::Image<float> truth(2, 1), estimate(2, 1);
  estimate(0, 0) = std::numeric_limits<float>::quiet_NaN();
  const mpr::DisparityScore s = mpr::score_disparity(estimate.view(), truth.view(), {0, {}});
  CHECK(s.badpix_007 == Approx(50));
  CHECK(std::isinf(s.mse_x100));
  truth(0, 0) = std::numeric_limits<float>::infinity();
  const mpr::DisparityScore t = mpr::score_disparity(estimate.view(), truth.view(), {0, {}});
  CHECK(t.pixels == 1);
  CHECK(t.badpix_007 == 0);
}

TEST_CASE("disparity scores: the most confident share", "[disparity_score]") {
  const mpr::Image<float> truth(4, 1);
  mpr::Image<float> estimate(4, 1), confidence(4, 1);
  const float err[4] = {0.1f, 0.0f, 0.2f, 0.0f}, conf[4] = {0.1f, 0.9f, 0.2f, 0.8f};
  for (int x = 0; x < 4; ++x) {
    estimate(x, 0) = err[x];
    confidence(x, 0) = conf[x];
  }
  const mpr::DisparityScoreRegion all{0, {}};
  CHECK(mpr::score_most_confident(estimate.view(), truth.view(), confidence.view(), 0.5, all).badpix_007 == 0);
  CHECK(mpr::score_most_confident(estimate.view(), truth.view(), confidence.view(), 0.5, all).pixels == 2);
  CHECK(mpr::score_most_confident(estimate.view(), truth.view(), confidence.view(), 0.75, all).badpix_007 ==
        Approx(100.0 / 3)); // adds the 0.2 (confidence 0.2)
  CHECK(mpr::score_most_confident(estimate.view(), truth.view(), confidence.view(), 1.0, all).badpix_007 == 50);
}

TEST_CASE("disparity scores: bad arguments name the parameter", "[disparity_score]") {
  const mpr::Image<float> a(4, 2), b(4, 3);
  CHECK_THROWS_WITH(mpr::score_disparity(a.view(), b.view()), Catch::Contains("invalid estimate: is 4x2"));
  CHECK_THROWS_WITH(mpr::score_disparity(a.view(), a.view(), {-1, {}}), Catch::Contains("invalid border"));
  const mpr::Image<std::uint8_t> mask(3, 2);
  CHECK_THROWS_WITH(mpr::score_disparity(a.view(), a.view(), {0, mask.view()}), Catch::Contains("invalid mask"));
  CHECK_THROWS_WITH(mpr::score_most_confident(a.view(), a.view(), a.view(), 0.0), Catch::Contains("invalid fraction"));
  CHECK_THROWS_WITH(mpr::score_most_confident(a.view(), a.view(), b.view(), 0.5),
                    Catch::Contains("invalid confidence"));
}
