#pragma once
/// \file
/// An object photographed against an empty backdrop (a black cloth, a studio wall), noticed from
/// the images alone: most views' borders show one colour, and a large share of every image is
/// that colour. `detect_backdrop` finds it; `BackdropSilhouette` is the silhouette policy of the
/// visual hull (visual_hull.hpp) that tells the object from it.
///
/// Method: each view's border band (`border` of its shorter side, at least 2 pixels) is binned
/// by colour (16 levels per channel) and its most common bin's mean colour taken; the backdrop
/// colour is the per-channel median of those over the views. A pixel is backdrop when every
/// channel lies within the tolerance of that colour; the tolerance is the least of
/// `min_tolerance`, + 4, ... sRGB codes within which `tolerance_share` of the borders lie (the
/// backdrop's noise and a darker cloth or stand taken in, the object's shading not). Detected
/// when the borders are near-uniform (`min_uniform_share` within `uniform_tolerance` codes),
/// at least `min_views` of the views have `min_border_share` of their border within the
/// tolerance, and the mean share of whole images within it lies in [`min_image_share`,
/// `max_image_share`] (an object fills the rest). Measured on the data here: the Middlebury
/// rings' borders are 83-93 % within 8 codes of black; Stanford Chess and the HCI scenes' 5-47 %.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <type_traits>
#include <vector>

namespace mpr {

/// Settings of `detect_backdrop` (see the file comment).
struct BackdropConfig {
  /// Width of the border band, as a share of the image's shorter side, in (0, 0.5).
  double border = 0.03;
  /// A near-uniform backdrop: at least `min_uniform_share` (in (0, 1]) of the borders lie
  /// within `uniform_tolerance` codes (0..255) of its colour.
  int uniform_tolerance = 8;
  double min_uniform_share = 0.7;
  /// The tolerance: the first of `min_tolerance`, + 4, ... below 64 codes (else 64) within which
  /// `tolerance_share` (in (0, 1]) of the borders lie.
  int min_tolerance = 12;
  double tolerance_share = 0.9;
  /// Share of a view's border within the tolerance for the view to show the backdrop, (0, 1].
  double min_border_share = 0.6;
  /// Share of the views that must show the backdrop, (0, 1].
  double min_views = 0.75;
  /// Bounds on the mean share of whole images within the tolerance, 0 <= min < max <= 1.
  double min_image_share = 0.2;
  double max_image_share = 0.98;
};

/// A backdrop `detect_backdrop` found.
struct Backdrop {
  Rgb8 colour{};
  /// Largest |channel difference| (sRGB codes) of a backdrop pixel from `colour`.
  int tolerance = 0;
  /// Views whose border shows the backdrop, and all views.
  std::size_t views = 0;
  std::size_t total = 0;
  /// Mean share of the views' borders within `BackdropConfig::uniform_tolerance`.
  double uniform_share = 0;
  /// Mean share of the views' borders and of whole images within the tolerance.
  double border_share = 0;
  double image_share = 0;
};

/// The object is every pixel farther than `tolerance` from `colour` in some channel.
struct BackdropSilhouette {
  Rgb8 colour{};
  int tolerance = 20;
  [[nodiscard]] bool foreground(Rgb8 p) const noexcept {
    return std::abs(p.r - colour.r) > tolerance || std::abs(p.g - colour.g) > tolerance ||
           std::abs(p.b - colour.b) > tolerance;
  }
};

/// Throws `argument_error` naming the field of `BackdropConfig` out of its range.
inline void validate(const BackdropConfig& c) {
  if (!(c.border > 0 && c.border < 0.5)) throw argument_error("border", "must lie in (0, 0.5)");
  if (c.uniform_tolerance < 0 || c.uniform_tolerance > 255)
    throw argument_error("uniform_tolerance", "must be in 0..255");
  if (!(c.min_uniform_share > 0 && c.min_uniform_share <= 1))
    throw argument_error("min_uniform_share", "must lie in (0, 1]");
  if (c.min_tolerance < 0 || c.min_tolerance > 64) throw argument_error("min_tolerance", "must be in 0..64");
  if (!(c.tolerance_share > 0 && c.tolerance_share <= 1)) throw argument_error("tolerance_share", "must lie in (0, 1]");
  if (!(c.min_border_share > 0 && c.min_border_share <= 1))
    throw argument_error("min_border_share", "must lie in (0, 1]");
  if (!(c.min_views > 0 && c.min_views <= 1)) throw argument_error("min_views", "must lie in (0, 1]");
  if (!(c.min_image_share >= 0 && c.min_image_share < c.max_image_share && c.max_image_share <= 1))
    throw argument_error("min_image_share", "needs 0 <= min_image_share < max_image_share <= 1");
}

namespace detail {

template <class Px>
[[nodiscard]] Rgb8 backdrop_rgb8(const Px& p) noexcept {
  if constexpr (std::is_same_v<Px, Rgb8>)
    return p;
  else
    return to_rgb8(p);
}

/// Calls f(pixel) for each pixel of the border band of `image`, `band` pixels wide.
template <class Px, class F>
void for_each_border_pixel(const Image<Px>& image, int band, F&& f) {
  const int w = image.width(), h = image.height();
  for (int y = 0; y < h; ++y) {
    const bool edge_row = y < band || y >= h - band;
    for (int x = 0; x < w; ++x)
      if (edge_row || x < band || x >= w - band) f(backdrop_rgb8(image(x, y)));
  }
}

[[nodiscard]] inline int channel_distance(Rgb8 a, Rgb8 b) noexcept {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

} // namespace detail

/// The candidate backdrop of `frames` and its measures, whether or not `detect_backdrop` accepts
/// it (a tool can say why none was found). Throws `argument_error` ("frames") for an empty set,
/// and as `validate(config)`.
template <std::floating_point T, class Px>
[[nodiscard]] Backdrop measure_backdrop(const CameraFrameSet<T, Px>& frames, const BackdropConfig& config = {}) {
  validate(config);
  if (frames.empty()) throw argument_error("frames", "no cameras");
  const std::size_t n = frames.size();
  const auto band_of = [&](const Image<Px>& image) {
    return std::max(2, static_cast<int>(std::lround(config.border * std::min(image.width(), image.height()))));
  };
  // Each view's most common border colour.
  std::vector<int> reds, greens, blues;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::uint32_t> count(4096, 0);
    std::vector<std::array<std::uint64_t, 3>> sum(4096, {0, 0, 0});
    detail::for_each_border_pixel(frames.image(i), band_of(frames.image(i)), [&](Rgb8 p) {
      const int bin = (p.r >> 4) << 8 | (p.g >> 4) << 4 | (p.b >> 4);
      ++count[static_cast<std::size_t>(bin)];
      sum[static_cast<std::size_t>(bin)][0] += p.r;
      sum[static_cast<std::size_t>(bin)][1] += p.g;
      sum[static_cast<std::size_t>(bin)][2] += p.b;
    });
    const std::size_t mode = static_cast<std::size_t>(std::max_element(count.begin(), count.end()) - count.begin());
    const double c = std::max<double>(count[mode], 1);
    reds.push_back(static_cast<int>(std::lround(static_cast<double>(sum[mode][0]) / c)));
    greens.push_back(static_cast<int>(std::lround(static_cast<double>(sum[mode][1]) / c)));
    blues.push_back(static_cast<int>(std::lround(static_cast<double>(sum[mode][2]) / c)));
  }
  const auto median = [](std::vector<int> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return static_cast<std::uint8_t>(v[v.size() / 2]);
  };
  Backdrop b;
  b.colour = Rgb8{median(reds), median(greens), median(blues)};
  b.total = n;
  // Border pixels per distance from the colour (0..255), over all views, and per view.
  std::vector<std::array<std::uint32_t, 256>> border(n);
  std::vector<std::size_t> border_size(n, 0);
  std::array<double, 256> all{};
  for (std::size_t i = 0; i < n; ++i) {
    border[i].fill(0);
    detail::for_each_border_pixel(frames.image(i), band_of(frames.image(i)), [&](Rgb8 p) {
      ++border[i][static_cast<std::size_t>(detail::channel_distance(p, b.colour))];
      ++border_size[i];
    });
    for (std::size_t d = 0; d < 256; ++d)
      all[d] += static_cast<double>(border[i][d]) / static_cast<double>(border_size[i]) / static_cast<double>(n);
  }
  const auto share_within = [&](int t) {
    double s = 0;
    for (int d = 0; d <= t; ++d) s += all[static_cast<std::size_t>(d)];
    return s;
  };
  b.uniform_share = share_within(config.uniform_tolerance);
  b.tolerance = 64;
  for (int t = config.min_tolerance; t < 64; t += 4)
    if (share_within(t) >= config.tolerance_share) {
      b.tolerance = t;
      break;
    }
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t within = 0;
    for (int d = 0; d <= b.tolerance; ++d) within += border[i][static_cast<std::size_t>(d)];
    const double share = static_cast<double>(within) / static_cast<double>(border_size[i]);
    b.border_share += share / static_cast<double>(n);
    if (share >= config.min_border_share) ++b.views;
    const Image<Px>& image = frames.image(i);
    std::size_t inside = 0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x)
        inside += detail::channel_distance(detail::backdrop_rgb8(image(x, y)), b.colour) <= b.tolerance;
    b.image_share +=
        static_cast<double>(inside) / (static_cast<double>(image.width()) * image.height()) / static_cast<double>(n);
  }
  return b;
}

/// Whether `b` (from `measure_backdrop`) passes the tests of `config`.
[[nodiscard]] inline bool accepted(const Backdrop& b, const BackdropConfig& config) noexcept {
  return b.uniform_share >= config.min_uniform_share &&
         static_cast<double>(b.views) >= config.min_views * static_cast<double>(b.total) &&
         b.image_share >= config.min_image_share && b.image_share <= config.max_image_share;
}

/// The backdrop of `frames`, or nullopt when the views show none (see the file comment).
/// Throws as `measure_backdrop`.
template <std::floating_point T, class Px>
[[nodiscard]] std::optional<Backdrop> detect_backdrop(const CameraFrameSet<T, Px>& frames,
                                                      const BackdropConfig& config = {}) {
  const Backdrop b = measure_backdrop(frames, config);
  if (!accepted(b, config)) return std::nullopt;
  return b;
}

} // namespace mpr
