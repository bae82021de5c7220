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
#include <mpr/core/parallel.hpp>

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
  float total = 0;
  const int x0 = std::max(0, x - c.radius), x1 = std::min(values.width() - 1, x + c.radius);
  const int y0 = std::max(0, y - c.radius), y1 = std::min(values.height() - 1, y + c.radius);
  const Rgb8 p = guide(x, y);
  const float floor = static_cast<float>(c.min_confidence);
  for (int v = y0; v <= y1; ++v)
    for (int u = x0; u <= x1; ++u) {
      const Rgb8 q = guide(u, v);
      const int diff = std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b);
      const float w = table[diff] * std::max(confidence(u, v), floor);
      window[static_cast<std::size_t>(count++)] = {values(u, v), w};
      total += w;
    }
  // Weighted selection (a three-way quickselect): the smallest value whose cumulative weight in
  // ascending order reaches half the total, in expected linear time.
  float target = 0.5f * total;
  int lo = 0, hi = count;
  while (hi - lo > 1) {
    const float pivot = window[static_cast<std::size_t>(lo + (hi - lo) / 2)].first;
    int lt = lo, gt = hi, i = lo;
    float below = 0, equal = 0;
    while (i < gt) { // [lo, lt) < pivot, [lt, i) == pivot, [gt, hi) > pivot
      const auto e = window[static_cast<std::size_t>(i)];
      if (e.first < pivot) {
        below += e.second;
        std::swap(window[static_cast<std::size_t>(lt++)], window[static_cast<std::size_t>(i++)]);
      } else if (e.first > pivot) {
        std::swap(window[static_cast<std::size_t>(--gt)], window[static_cast<std::size_t>(i)]);
      } else {
        equal += e.second;
        ++i;
      }
    }
    if (below >= target && lt > lo) {
      hi = lt;
    } else if (below + equal >= target || gt == hi) {
      return pivot;
    } else {
      target -= below + equal;
      lo = gt;
    }
  }
  return window[static_cast<std::size_t>(lo)].first;
}

/// The spread (max - min) of `values` over each pixel's (2r+1)^2 window, clipped at the image:
/// a running min and max along the rows, then along the columns.
[[nodiscard]] inline Image<float> window_spread(ImageView<const float> values, int r) {
  const int w = values.width(), h = values.height();
  Image<float> lo(w, h), hi(w, h), spread(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float a = values(x, y), b = a;
      for (int u = std::max(0, x - r); u <= std::min(w - 1, x + r); ++u) {
        a = std::min(a, values(u, y));
        b = std::max(b, values(u, y));
      }
      lo(x, y) = a;
      hi(x, y) = b;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float a = lo(x, y), b = hi(x, y);
      for (int v = std::max(0, y - r); v <= std::min(h - 1, y + r); ++v) {
        a = std::min(a, lo(x, v));
        b = std::max(b, hi(x, v));
      }
      spread(x, y) = b - a;
    }
  return spread;
}

} // namespace detail

/// `values` through the joint weighted median of the file comment, guided by the colours
/// `guide` and weighted by `confidence` (in [0, 1]; all three the same size), on `threads`
/// workers (0 or less: all hardware threads). Values must be finite. Throws `argument_error` for
/// a bad config or a guide or confidence of another size ("guide", "confidence").
[[nodiscard]] inline Image<float> weighted_median(ImageView<const float> values, ImageView<const Rgb8> guide,
                                                  ImageView<const float> confidence, const WeightedMedianConfig& c = {},
                                                  int threads = 1) {
  validate(c);
  if (guide.width() != values.width() || guide.height() != values.height())
    throw argument_error("guide", "must have the size of the values");
  if (confidence.width() != values.width() || confidence.height() != values.height())
    throw argument_error("confidence", "must have the size of the values");
  Image<float> out(values.width(), values.height());
  for (int y = 0; y < values.height(); ++y)
    for (int x = 0; x < values.width(); ++x) out(x, y) = values(x, y);
  if (c.radius == 0) return out;
  std::array<float, 766> table;
  for (std::size_t k = 0; k < table.size(); ++k)
    table[k] = static_cast<float>(std::exp(-static_cast<double>(k) / 255.0 / c.range));
  const Image<float> spread = detail::window_spread(values, c.radius);
  const float flat = static_cast<float>(c.flat);
  detail::parallel_rows(0, values.height(), detail::resolve_thread_count(threads, values.height()),
                        [&](int y) noexcept {
                          for (int x = 0; x < values.width(); ++x)
                            if (spread(x, y) > flat)
                              out(x, y) = detail::weighted_median_at(values, guide, confidence, x, y, c, table.data());
                        });
  return out;
}

} // namespace mpr
