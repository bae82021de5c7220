#pragma once
/// \file
/// Scores of an estimated disparity map against the true one, as the 4D Light Field Benchmark
/// publishes them (Honauer et al., ACCV 2016): BadPix(t), the percentage of pixels whose
/// absolute disparity error exceeds t (0.01, 0.03, 0.07 pixel), MSE x100 (100 x the mean squared
/// error) and Q25 (100 x the 25th percentile of the absolute error), over the pixels of a mask
/// with a border left out (15 pixels on each side in the published evaluations). Also the same
/// scores over the most confident share of those pixels, to judge a confidence map.

#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace mpr {

/// Which pixels count: those at least `border` pixels from every image edge where the mask (if
/// any, same size as the maps) is non-zero.
struct DisparityScoreRegion {
  int border = 15;
  std::optional<ImageView<const std::uint8_t>> mask;
};

/// Scores of `score_disparity`; percentages and x100 figures as the benchmark prints them.
struct DisparityScore {
  std::size_t pixels = 0; ///< pixels scored
  double badpix_001 = 0;  ///< % with |error| > 0.01
  double badpix_003 = 0;  ///< % with |error| > 0.03
  double badpix_007 = 0;  ///< % with |error| > 0.07
  double mse_x100 = 0;    ///< 100 x mean squared error (infinite if an estimate is not finite)
  double q25_x100 = 0;    ///< 100 x the 25th percentile of |error| (nearest rank)
};

/// The scores of the absolute errors `errors` (any order; reordered). NaN counts as infinite.
[[nodiscard]] inline DisparityScore score_errors(std::vector<double>& errors) noexcept {
  DisparityScore s;
  s.pixels = errors.size();
  if (errors.empty()) return s;
  std::size_t b1 = 0, b3 = 0, b7 = 0;
  double sum = 0;
  for (double& e : errors) {
    if (!(e == e)) e = std::numeric_limits<double>::infinity();
    b1 += e > 0.01;
    b3 += e > 0.03;
    b7 += e > 0.07;
    sum += e * e;
  }
  const double n = static_cast<double>(errors.size());
  s.badpix_001 = 100.0 * static_cast<double>(b1) / n;
  s.badpix_003 = 100.0 * static_cast<double>(b3) / n;
  s.badpix_007 = 100.0 * static_cast<double>(b7) / n;
  s.mse_x100 = 100.0 * sum / n;
  // Nearest rank: the smallest error with at least 25 % of the errors at or below it.
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.25 * n)) - 1;
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(rank), errors.end());
  s.q25_x100 = 100.0 * errors[rank];
  return s;
}

namespace detail {

/// Throws `argument_error` naming `what` unless `a` has the size of `truth`.
template <class A>
void check_score_size(const A& a, ImageView<const float> truth, const char* what) {
  if (a.width() != truth.width() || a.height() != truth.height())
    throw argument_error(what, "is " + std::to_string(a.width()) + "x" + std::to_string(a.height()) +
                                   ", the ground truth " + std::to_string(truth.width()) + "x" +
                                   std::to_string(truth.height()));
}

/// Calls `fn(x, y)` for each pixel of `region`; checks sizes and the border.
template <class Fn>
void for_scored_pixels(ImageView<const float> truth, const DisparityScoreRegion& region, Fn&& fn) {
  if (region.border < 0) throw argument_error("border", "must be >= 0");
  if (region.mask) check_score_size(*region.mask, truth, "mask");
  for (int y = region.border; y < truth.height() - region.border; ++y)
    for (int x = region.border; x < truth.width() - region.border; ++x)
      if (!region.mask || (*region.mask)(x, y) != 0) fn(x, y);
}

} // namespace detail

/// The benchmark's scores of `estimate` against `truth` (disparities, same size) over `region`.
/// Throws `argument_error` ("estimate", "mask", "border") for maps of different sizes or a
/// negative border. Pixels where the truth is not finite are left out.
[[nodiscard]] inline DisparityScore score_disparity(ImageView<const float> estimate, ImageView<const float> truth,
                                                    const DisparityScoreRegion& region = {}) {
  detail::check_score_size(estimate, truth, "estimate");
  std::vector<double> errors;
  detail::for_scored_pixels(truth, region, [&](int x, int y) {
    if (std::isfinite(truth(x, y))) errors.push_back(std::abs(static_cast<double>(estimate(x, y)) - truth(x, y)));
  });
  return score_errors(errors);
}

/// The scores over the `fraction` (0..1] of the pixels of `region` with the highest
/// `confidence` (ties by raster order): a confidence map that is low where the error is high
/// gives far smaller errors here than over all pixels. Throws as `score_disparity`, and
/// `argument_error` ("confidence", "fraction") for a confidence map of another size or a
/// fraction outside (0, 1].
[[nodiscard]] inline DisparityScore score_most_confident(ImageView<const float> estimate, ImageView<const float> truth,
                                                         ImageView<const float> confidence, double fraction,
                                                         const DisparityScoreRegion& region = {}) {
  detail::check_score_size(estimate, truth, "estimate");
  detail::check_score_size(confidence, truth, "confidence");
  if (!(fraction > 0 && fraction <= 1)) throw argument_error("fraction", "must lie in (0, 1]");
  std::vector<std::pair<float, double>> ranked; // (-confidence, error): sorted most confident first
  detail::for_scored_pixels(truth, region, [&](int x, int y) {
    if (std::isfinite(truth(x, y)))
      ranked.emplace_back(-confidence(x, y), std::abs(static_cast<double>(estimate(x, y)) - truth(x, y)));
  });
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const auto keep = static_cast<std::size_t>(std::llround(fraction * static_cast<double>(ranked.size())));
  std::vector<double> errors;
  for (std::size_t i = 0; i < keep; ++i) errors.push_back(ranked[i].second);
  return score_errors(errors);
}

} // namespace mpr
