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
#include <mpr/lightfield/kernels/depth_median_lanes.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

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
  const int w = values.width(), h = values.height();
  Image<float> out(w, h);
  if (c.radius == 0) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) out(x, y) = values(x, y);
    return out;
  }
  // The colour weight exp(-d / 255 / range) as coarse[d / 32] x fine[d % 32].
  std::array<float, 32> coarse, fine;
  for (std::size_t k = 0; k < 32; ++k) {
    coarse[k] = static_cast<float>(std::exp(-static_cast<double>(32 * k) / 255.0 / c.range));
    fine[k] = static_cast<float>(std::exp(-static_cast<double>(k) / 255.0 / c.range));
  }
  // The planes of the row kernel (kernels/depth_median_lanes.hpp), padded by r on every side
  // and on the right to whole chunks: values repeating the nearest pixel's, confidence -1
  // outside the image, the guide as planar channels.
  const int r = c.radius, chunked = (w + detail::kMedianChunk - 1) / detail::kMedianChunk * detail::kMedianChunk;
  const std::ptrdiff_t stride = chunked + 2 * r;
  const std::size_t size = static_cast<std::size_t>(stride) * static_cast<std::size_t>(h + 2 * r);
  const std::ptrdiff_t origin = r * stride + r;
  std::vector<float> planes(2 * size);
  std::vector<std::int32_t> channels(3 * size);
  for (int v = -r; v < h + r; ++v) {
    const int y = std::clamp(v, 0, h - 1);
    const bool row_inside = v == y;
    const std::ptrdiff_t at = origin + v * stride;
    for (int u = -r; u < chunked + r; ++u) {
      const int x = std::clamp(u, 0, w - 1);
      const std::size_t k = static_cast<std::size_t>(at + u);
      const Rgb8 g = guide(x, y);
      planes[k] = values(x, y);
      planes[size + k] = row_inside && u == x ? confidence(x, y) : -1.0f;
      channels[k] = g.r;
      channels[size + k] = g.g;
      channels[2 * size + k] = g.b;
    }
  }
  const detail::MedianRowInputs in{
      planes.data() + origin,
      planes.data() + size + origin,
      {channels.data() + origin, channels.data() + size + origin, channels.data() + 2 * size + origin},
      coarse.data(),
      fine.data(),
      w,
      h,
      r,
      stride,
      static_cast<float>(c.flat),
      static_cast<float>(c.min_confidence)};
  const detail::SimdLevel level = detail::dispatch_level();
  detail::parallel_rows(0, h, detail::resolve_thread_count(threads, h),
                        [&](int y) noexcept { detail::weighted_median_row(in, y, &out(0, y), level); });
  return out;
}

} // namespace mpr
