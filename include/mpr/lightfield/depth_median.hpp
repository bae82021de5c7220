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

/// Value bins of `weighted_median_at`.
inline constexpr int kWeightedMedianBins = 32;

/// The weighted median at pixel (x, y) of `values`; see `weighted_median`: the smallest value of
/// the window whose cumulative weight in ascending order (equal values together) reaches half the
/// total. The values go into kWeightedMedianBins bins evenly over the window's [min, max] (a
/// monotone map, so a bin's values all lie below the next bin's) with their weights summed per
/// bin; the bin where the running sum reaches half the total holds the median, found among that
/// bin's few values in order. No sorting of the window, no data-dependent swaps. lo < hi: the
/// window's smallest and largest value (`window_range`).
[[nodiscard]] inline float weighted_median_at(ImageView<const float> values, ImageView<const Rgb8> guide,
                                              ImageView<const float> confidence, int x, int y, float lo, float hi,
                                              const WeightedMedianConfig& c, const float* table) noexcept {
  constexpr int N = 225, B = kWeightedMedianBins;
  float value[N], weight[N], mass[B] = {};
  unsigned char bin[N];
  int count = 0;
  float total = 0;
  const int x0 = std::max(0, x - c.radius), x1 = std::min(values.width() - 1, x + c.radius);
  const int y0 = std::max(0, y - c.radius), y1 = std::min(values.height() - 1, y + c.radius);
  const Rgb8 p = guide(x, y);
  const float floor = static_cast<float>(c.min_confidence);
  // Bin k holds the values with floor((v - lo) * scale) = k, the top one in bin B - 1 (a scale
  // kept finite: a tiny spread puts every value but hi in bin 0, still in order).
  const float scale = static_cast<float>(std::min(B / (static_cast<double>(hi) - static_cast<double>(lo)), 1e30));
  for (int v = y0; v <= y1; ++v) {
    const float* vr = values.row(v);
    const float* cr = confidence.row(v);
    const Rgb8* gr = guide.row(v);
    for (int u = x0; u <= x1; ++u, ++count) {
      const Rgb8 q = gr[u];
      const int diff = std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b);
      const float w = table[diff] * std::max(cr[u], floor);
      const int k = static_cast<int>(std::min((vr[u] - lo) * scale, static_cast<float>(B - 1)));
      value[count] = vr[u];
      weight[count] = w;
      bin[count] = static_cast<unsigned char>(k);
      mass[k] += w;
      total += w;
    }
  }
  const float target = 0.5f * total;
  float below = 0;
  int median_bin = 0;
  while (median_bin < B - 1 && below + mass[median_bin] < target) below += mass[median_bin++];
  // That bin's values in ascending order (insertion: a handful), then the running sum.
  float in_value[N], in_weight[N];
  int in = 0;
  for (int k = 0; k < count; ++k) {
    if (bin[k] != median_bin) continue;
    int i = in++;
    for (; i > 0 && in_value[i - 1] > value[k]; --i) {
      in_value[i] = in_value[i - 1];
      in_weight[i] = in_weight[i - 1];
    }
    in_value[i] = value[k];
    in_weight[i] = weight[k];
  }
  for (int i = 0; i < in;) {
    const float v = in_value[i];
    for (; i < in && in_value[i] == v; ++i) below += in_weight[i];
    if (below >= target) return v;
  }
  // Only where rounding left the sums short of the target: the bin's largest value.
  return in > 0 ? in_value[in - 1] : hi;
}

/// The smallest and largest of `values` over each pixel's (2r+1)^2 window, clipped at the image:
/// a running min and max along the rows, then along the columns.
struct WindowRange {
  Image<float> lo, hi;
};
[[nodiscard]] inline WindowRange window_range(ImageView<const float> values, int r) {
  const int w = values.width(), h = values.height();
  Image<float> lo(w, h), hi(w, h);
  WindowRange out{Image<float>(w, h), Image<float>(w, h)};
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
      out.lo(x, y) = a;
      out.hi(x, y) = b;
    }
  return out;
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
  const detail::WindowRange range = detail::window_range(values, c.radius);
  const float flat = static_cast<float>(c.flat);
  detail::parallel_rows(0, values.height(), detail::resolve_thread_count(threads, values.height()),
                        [&](int y) noexcept {
                          for (int x = 0; x < values.width(); ++x)
                            if (range.hi(x, y) - range.lo(x, y) > flat)
                              out(x, y) = detail::weighted_median_at(values, guide, confidence, x, y, range.lo(x, y),
                                                                     range.hi(x, y), c, table.data());
                        });
  return out;
}

} // namespace mpr
