#pragma once
/// \file
/// Mixed pixels at depth edges, decided by their colour. A pixel on a depth edge sees both
/// surfaces: its colour is (in linear light) the blend c = a f + (1 - a) b of the two sides'
/// colours f and b, a being the share of the pixel that the f side covers. Its centre, where a
/// depth map is defined, lies on the f side when a > 1/2 (a straight edge through the pixel).
/// A plane sweep cannot tell (the pixel's colour matches neither side's in the other views, and
/// the aggregation leans towards the more textured side), so it gives the edge's pixels to either
/// side about at random; here, where the depth jumps across a pixel (its two neighbours along
/// the axis of the larger jump differ by more than `jump`), the pixel takes the value of the
/// neighbour whose side its colour is nearer to: a, the projection of c - b onto f - b, against
/// 1/2, with f and b the two neighbours' colours. Matting (Levin et al. 2008) states the same
/// compositing model.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace mpr {

/// Settings of `snap_mixed_pixels`.
struct EdgeSnapConfig {
  /// The jump across a pixel (between its two neighbours along an image axis) at which it counts
  /// as a mixed pixel of a depth edge, in the values' unit, > 0; infinity: none. Default 8 (planes
  /// of a sweep's plane coordinate: an eighth of the default 64 planes' range).
  double jump = 8;
};

/// Throws `argument_error` ("jump") unless jump > 0.
inline void validate(const EdgeSnapConfig& c) {
  if (!(c.jump > 0)) throw argument_error("jump", "must be positive");
}

namespace detail {

/// sRGB code to linear light (IEC 61966-2-1).
[[nodiscard]] inline std::array<float, 256> linear_light_table() {
  std::array<float, 256> t{};
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double c = static_cast<double>(k) / 255.0;
    t[k] = static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
  }
  return t;
}

} // namespace detail

/// `values` with the mixed pixels of its depth edges decided by colour (file comment), guided by
/// `guide` (sRGB, the same size). The outermost rows and columns are kept. Throws
/// `argument_error` for a bad config or a guide of another size ("guide").
[[nodiscard]] inline Image<float> snap_mixed_pixels(ImageView<const float> values, ImageView<const Rgb8> guide,
                                                    const EdgeSnapConfig& c = {}) {
  validate(c);
  if (guide.width() != values.width() || guide.height() != values.height())
    throw argument_error("guide", "must have the size of the values");
  const std::array<float, 256> lin = detail::linear_light_table();
  Image<float> out(values.width(), values.height());
  for (int y = 0; y < values.height(); ++y)
    for (int x = 0; x < values.width(); ++x) out(x, y) = values(x, y);
  const float jump = static_cast<float>(std::min(c.jump, 1e30));
  for (int y = 1; y + 1 < values.height(); ++y)
    for (int x = 1; x + 1 < values.width(); ++x) {
      const float jv = std::abs(values(x, y + 1) - values(x, y - 1));
      const float jh = std::abs(values(x + 1, y) - values(x - 1, y));
      if (!(std::max(jv, jh) > jump)) continue;
      const bool vertical = jv >= jh;
      const int bx = vertical ? x : x - 1, by = vertical ? y - 1 : y; // side b
      const int fx = vertical ? x : x + 1, fy = vertical ? y + 1 : y; // side f
      const Rgb8 b = guide(bx, by), f = guide(fx, fy), p = guide(x, y);
      const float d[3] = {lin[f.r] - lin[b.r], lin[f.g] - lin[b.g], lin[f.b] - lin[b.b]};
      const float e[3] = {lin[p.r] - lin[b.r], lin[p.g] - lin[b.g], lin[p.b] - lin[b.b]};
      const float norm = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (!(norm > 1e-12f)) continue; // the sides look alike: colour cannot tell
      const float a = (e[0] * d[0] + e[1] * d[1] + e[2] * d[2]) / norm;
      out(x, y) = a > 0.5f ? values(fx, fy) : values(bx, by);
    }
  return out;
}

} // namespace mpr
