#pragma once
/// \file
/// A final edge-aware filter for a plane sweep's result: the joint weighted median (Ma, Li, Wang,
/// Yang and Zhang, "Constant time weighted median filtering for stereo matching and beyond",
/// ICCV 2013; as a depth refinement in Hosni et al., "Fast cost-volume filtering", PAMI 2013).
/// Each pixel takes the weighted median of the values in its (2r+1)^2 window, a neighbour q
/// weighing confidence(q) x exp(-|colour(p) - colour(q)| / range): a value (not a blend) that
/// the pixel's own colour region supports, so a step edge stays a step while one- and two-pixel
/// slivers that disagree with their similar-coloured, confident surroundings are replaced.
/// A median of values is the median of any monotone function of them, so plane index, depth and
/// disparity give the same pixel.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace mpr {

/// Settings of `weighted_median`.
struct WeightedMedianConfig {
  /// Window radius in pixels, 0..7 (0: the values unchanged). Default 3 (7 x 7).
  int radius = 3;
  /// Colour distance (sum over channels of |sRGB code difference| / 255) over which a
  /// neighbour's weight falls by a factor e, > 0. Default 0.16 (about 40 codes).
  double range = 0.16;
  /// A pixel whose window's values all lie within this of each other keeps its value (no edge
  /// there; the median would change it by no more than this), >= 0, in the values' unit.
  /// Default 1 (one plane of a sweep's plane coordinate).
  double flat = 1.0;
  /// The smallest weight a confidence gives (a confidence of 0 still counts this much), > 0.
  double min_confidence = 0.02;
};

/// Throws `argument_error` naming the field ("radius", "range", "flat", "min_confidence").
inline void validate(const WeightedMedianConfig& c) {
  if (c.radius < 0 || c.radius > 7) throw argument_error("radius", "must be in 0..7");
  if (!(c.range > 0) || !std::isfinite(c.range)) throw argument_error("range", "must be positive");
  if (!(c.flat >= 0) || !std::isfinite(c.flat)) throw argument_error("flat", "must be finite and >= 0");
  if (!(c.min_confidence > 0) || !(c.min_confidence <= 1)) throw argument_error("min_confidence", "must be in (0, 1]");
}

namespace detail {

/// The weighted median at pixel (x, y) of `values`; see `weighted_median`.
[[nodiscard]] inline float weighted_median_at(ImageView<const float> values, ImageView<const Rgb8> guide,
                                              ImageView<const float> confidence, int x, int y,
                                              const WeightedMedianConfig& c, const float* table) noexcept {
  std::array<std::pair<float, float>, 225> window; // (value, weight)
  int count = 0;
  float lo = values(x, y), hi = lo;
  const int x0 = std::max(0, x - c.radius), x1 = std::min(values.width() - 1, x + c.radius);
  const int y0 = std::max(0, y - c.radius), y1 = std::min(values.height() - 1, y + c.radius);
  for (int v = y0; v <= y1; ++v)
    for (int u = x0; u <= x1; ++u) {
      const float value = values(u, v);
      lo = std::min(lo, value);
      hi = std::max(hi, value);
      window[static_cast<std::size_t>(count++)] = {value, 0.0f};
    }
  if (!(hi - lo > static_cast<float>(c.flat))) return values(x, y);
  const Rgb8 p = guide(x, y);
  const float floor = static_cast<float>(c.min_confidence);
  float total = 0;
  for (int v = y0, k = 0; v <= y1; ++v)
    for (int u = x0; u <= x1; ++u, ++k) {
      const Rgb8 q = guide(u, v);
      const int diff = std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b);
      const float w = table[diff] * std::max(confidence(u, v), floor);
      window[static_cast<std::size_t>(k)].second = w;
      total += w;
    }
  std::sort(window.begin(), window.begin() + count);
  float acc = 0;
  for (int k = 0; k < count; ++k) {
    acc += window[static_cast<std::size_t>(k)].second;
    if (acc >= 0.5f * total) return window[static_cast<std::size_t>(k)].first;
  }
  return window[static_cast<std::size_t>(count - 1)].first;
}

} // namespace detail

/// `values` through the joint weighted median of the file comment, guided by the colours
/// `guide` and weighted by `confidence` (in [0, 1]; all three the same size). Values must be
/// finite. Throws `argument_error` for a bad config or a guide or confidence of another size
/// ("guide", "confidence").
[[nodiscard]] inline Image<float> weighted_median(ImageView<const float> values, ImageView<const Rgb8> guide,
                                                  ImageView<const float> confidence,
                                                  const WeightedMedianConfig& c = {}) {
  validate(c);
  if (guide.width() != values.width() || guide.height() != values.height())
    throw argument_error("guide", "must have the size of the values");
  if (confidence.width() != values.width() || confidence.height() != values.height())
    throw argument_error("confidence", "must have the size of the values");
  Image<float> out(values.width(), values.height());
  std::array<float, 766> table;
  for (std::size_t k = 0; k < table.size(); ++k)
    table[k] = static_cast<float>(std::exp(-static_cast<double>(k) / 255.0 / c.range));
  for (int y = 0; y < values.height(); ++y)
    for (int x = 0; x < values.width(); ++x)
      out(x, y) =
          c.radius == 0 ? values(x, y) : detail::weighted_median_at(values, guide, confidence, x, y, c, table.data());
  return out;
}

} // namespace mpr
