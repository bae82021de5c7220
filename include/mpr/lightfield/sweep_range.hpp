#pragma once
/// \file
/// The depth range a plane sweep searches, found from the calibration and the images when the
/// user gives none (`PlaneSweepConfig` near = far = 0). Two things bound it:
///
/// - The common frustum: a point the sweep can match lies in front of a camera and of its
///   partner camera, inside both images. Along the ray of a reference pixel p at depth z (inverse
///   depth w = 1 / z) the partner sees the homogeneous pixel A w + M p (`detail::depth_homography`
///   divided by z), linear in w, so each image edge bounds w on one side: the visible stretch is
///   an interval of w, found exactly. Over the pixels of a 17 x 17 grid spanning each reference
///   image it gives `frustum_near` .. `frustum_far` (+inf for parallel cameras, which see
///   together out to infinity).
/// - Sparse matches: on images reduced by a power of two to at most `coarse_width` pixels wide,
///   the most textured pixel of each 8 x 8 cell of a reference camera is compared with its
///   partner along the epipolar segment of the common frustum (zero-mean normalised
///   cross-correlation of 7 x 7 grey patches, about two steps per reduced pixel); a match whose
///   best score reaches `min_score` and stands out from every position more than 3 steps away
///   (1 - best <= 0.5 (1 - second)) with both partners, whose depths agree within two search
///   steps and 2% in inverse depth, gives a depth (the longer baseline's; with fewer than 64
///   such, the nearest partner's matches alone give them). The range spans the `quantile` and 1 -
///   `quantile` depths, widened in inverse depth by `margin` of its span plus 2% of the nearest
///   depth's on each side (never beyond twice the farthest depth), inside the common frustum.
///
/// References: up to `reference_cameras` cameras spread over the set; partners: each one's
/// nearest camera and the one nearest to three times that distance (a longer baseline, finer
/// depth; cameras within 1% of the median distance, at the same place, are skipped). With fewer than `min_matches`
/// matches (no texture) the range is the common frustum's, its far end at most 100 times its near end.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/plane_sweep/depth_homography.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

namespace mpr {

/// Settings of `sweep_range` (see the file comment).
struct SweepRangeConfig {
  /// Cameras whose pixels are matched, spread over the set, >= 1.
  int reference_cameras = 6;
  /// The reduced images are at most this wide (pixels), >= 16.
  int coarse_width = 256;
  /// Least zero-mean normalised cross-correlation of a match, in (0, 1].
  double min_score = 0.8;
  /// Share of the matched depths left out at each end, in [0, 0.5).
  double quantile = 0.02;
  /// Widening on each side, as a share of the range's span in inverse depth, >= 0.
  double margin = 0.15;
  /// Fewer matches than this: the common frustum's range, >= 1.
  int min_matches = 16;
};

/// Where a sweep range came from.
enum class SweepRangeSource {
  given,   ///< the user's near and far
  matches, ///< sparse matches inside the common frustum
  frustum, ///< the common frustum alone (too few matches)
};

/// A depth range along the cameras' optical axes (world units), how it was found, and the
/// common frustum it lies in.
struct SweepRange {
  double near = 0;
  double far = 0;
  SweepRangeSource source = SweepRangeSource::given;
  /// Matches behind the range (`SweepRangeSource::matches`).
  int matches = 0;
  /// The common frustum's depth range; `frustum_far` is +inf for cameras that see together out
  /// to infinity.
  double frustum_near = 0;
  double frustum_far = 0;
};

/// Throws `argument_error` naming the field of `SweepRangeConfig` out of its range.
inline void validate(const SweepRangeConfig& c) {
  if (c.reference_cameras < 1) throw argument_error("reference_cameras", "must be at least 1");
  if (c.coarse_width < 16) throw argument_error("coarse_width", "must be at least 16");
  if (!(c.min_score > 0 && c.min_score <= 1)) throw argument_error("min_score", "must lie in (0, 1]");
  if (!(c.quantile >= 0 && c.quantile < 0.5)) throw argument_error("quantile", "must lie in [0, 0.5)");
  if (!(c.margin >= 0) || !std::isfinite(c.margin)) throw argument_error("margin", "must be finite and >= 0");
  if (c.min_matches < 1) throw argument_error("min_matches", "must be at least 1");
}

namespace detail {

/// The interval [lo, hi] of inverse depth w (initially as given) over which the partner of
/// homography `h` sees reference pixel `p` inside its image shrunk by `inset` pixels on every
/// side (`lo > hi`: nowhere). Each edge is one linear inequality a w + b >= 0 in w.
inline void visible_inverse_depths(const DepthHomography& h, const Vec3<double>& p, int width, int height, double inset,
                                   double& lo, double& hi) {
  const Vec3<double> m = h.M * p;
  const auto keep = [&](double a, double b) { // a w + b >= 0
    if (a > 0)
      lo = std::max(lo, -b / a);
    else if (a < 0)
      hi = std::min(hi, -b / a);
    else if (b < 0)
      hi = -std::numeric_limits<double>::infinity();
  };
  const double x0 = inset - 0.5, x1 = width - 0.5 - inset, y0 = inset - 0.5, y1 = height - 0.5 - inset;
  keep(h.A.z(), m.z() - 1e-12);                     // in front
  keep(h.A.x() - x0 * h.A.z(), m.x() - x0 * m.z()); // x >= x0
  keep(x1 * h.A.z() - h.A.x(), x1 * m.z() - m.x()); // x <= x1
  keep(h.A.y() - y0 * h.A.z(), m.y() - y0 * m.z()); // y >= y0
  keep(y1 * h.A.z() - h.A.y(), y1 * m.z() - m.y()); // y <= y1
}

/// A grey image reduced by `scale` (box mean of scale x scale pixels; 0..255).
template <class Px>
[[nodiscard]] Image<float> reduced_grey(const Image<Px>& image, int scale) {
  const int w = std::max(1, image.width() / scale), h = std::max(1, image.height() / scale);
  Image<float> out(w, h, 0.0f);
  const float norm = 1.0f / static_cast<float>(scale * scale);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float s = 0;
      for (int j = 0; j < scale; ++j)
        for (int i = 0; i < scale; ++i) {
          Rgb8 c;
          if constexpr (std::is_same_v<Px, Rgb8>)
            c = image(x * scale + i, y * scale + j);
          else
            c = to_rgb8(image(x * scale + i, y * scale + j));
          s += 0.299f * c.r + 0.587f * c.g + 0.114f * c.b;
        }
      out(x, y) = s * norm;
    }
  return out;
}

/// Bilinear sample of `g` at (x, y), clamped to the image.
[[nodiscard]] inline float grey_at(const Image<float>& g, double x, double y) noexcept {
  x = x >= 0 ? std::min(x, g.width() - 1.0) : 0.0;  // NaN reads the first column, as -inf does
  y = y >= 0 ? std::min(y, g.height() - 1.0) : 0.0;
  const int x0 = std::min(static_cast<int>(x), g.width() - 2 < 0 ? 0 : g.width() - 2);
  const int y0 = std::min(static_cast<int>(y), g.height() - 2 < 0 ? 0 : g.height() - 2);
  const int x1 = std::min(x0 + 1, g.width() - 1), y1 = std::min(y0 + 1, g.height() - 1);
  const double fx = x - x0, fy = y - y0;
  return static_cast<float>((1 - fy) * ((1 - fx) * g(x0, y0) + fx * g(x1, y0)) +
                            fy * ((1 - fx) * g(x0, y1) + fx * g(x1, y1)));
}

/// Zero-mean normalised cross-correlation of the 7 x 7 patch `a` (mean-free, `norm_a` its norm)
/// with the patch of `g` centred at (x, y); -1 where `g`'s patch is flat.
[[nodiscard]] inline double patch_zncc(const float* a, double norm_a, const Image<float>& g, double x,
                                       double y) noexcept {
  float b[49];
  double mean = 0;
  for (int j = 0, k = 0; j < 7; ++j)
    for (int i = 0; i < 7; ++i, ++k) mean += b[k] = grey_at(g, x + i - 3, y + j - 3);
  mean /= 49;
  double dot = 0, nb = 0;
  for (int k = 0; k < 49; ++k) {
    const double v = b[k] - mean;
    dot += a[k] * v;
    nb += v * v;
  }
  return nb > 1e-9 ? dot / std::sqrt(norm_a * nb) : -1.0;
}

/// The partners of reference camera `r` (see the file comment) and the distance to the nearest;
/// empty when every other camera stands at (nearly) the same place.
template <std::floating_point T, class Px>
[[nodiscard]] std::vector<std::size_t> range_partners(const CameraFrameSet<T, Px>& frames, std::size_t r,
                                                      double& nearest) {
  const PinholeCamera<T>& ref = frames.camera(r);
  std::vector<std::pair<double, std::size_t>> by_distance;
  for (std::size_t j = 0; j < frames.size(); ++j)
    if (j != r) by_distance.emplace_back(static_cast<double>((frames.camera(j).centre() - ref.centre()).norm()), j);
  std::sort(by_distance.begin(), by_distance.end());
  // A camera at (nearly) the same place has no baseline: skip those within 1% of the median.
  const double tiny = 0.01 * by_distance[by_distance.size() / 2].first;
  const auto first =
      std::find_if(by_distance.begin(), by_distance.end(), [&](const auto& e) { return e.first > tiny; });
  if (first == by_distance.end()) return {};
  std::vector<std::size_t> partners{first->second};
  nearest = first->first;
  std::size_t far_one = first->second;
  double gap = std::numeric_limits<double>::infinity();
  for (const auto& [d, j] : by_distance)
    if (d >= 2 * nearest && std::abs(d - 3 * nearest) < gap) {
      gap = std::abs(d - 3 * nearest);
      far_one = j;
    }
  if (far_one != partners.front()) partners.push_back(far_one);
  return partners;
}

/// Widens `out.frustum_near` .. `out.frustum_far` by the common frustum of reference camera `r`
/// and each of `partners` over a 17 x 17 grid of pixels spanning the reference image, inverse
/// depths at most `w_max`.
template <std::floating_point T, class Px>
void widen_common_frustum(const CameraFrameSet<T, Px>& frames, std::size_t r, const std::vector<std::size_t>& partners,
                          double w_max, SweepRange& out) {
  const PinholeCamera<T>& ref = frames.camera(r);
  for (const std::size_t j : partners) {
    const DepthHomography h = depth_homography(ref, frames.camera(j));
    for (int gy = 0; gy <= 16; ++gy)
      for (int gx = 0; gx <= 16; ++gx) {
        const Vec3<double> p((ref.width() - 1) * gx / 16.0, (ref.height() - 1) * gy / 16.0, 1);
        double lo = 0, hi = w_max;
        visible_inverse_depths(h, p, frames.camera(j).width(), frames.camera(j).height(), 0, lo, hi);
        if (!(lo <= hi) || !(hi > 0)) continue;
        out.frustum_near = std::min(out.frustum_near, 1 / hi);
        out.frustum_far = std::max(out.frustum_far, lo > 0 ? 1 / lo : std::numeric_limits<double>::infinity());
      }
  }
}

/// A partner's reduced grey image and the homography from the reference camera to it.
struct RangePartner {
  Image<float> grey;
  DepthHomography h;
  int width, height;
};

/// The match of the mean-free 7 x 7 patch `a` (norm `norm_a`) of full-resolution reference pixel
/// `p` along its epipolar segment in partner `o` (images reduced by `scale`), inverse depths in
/// (0, `w_max`]: false when none stands out (see the file comment); else its inverse depth `w`
/// and the inverse depth of one search step `step`.
inline bool match_along_segment(const RangePartner& o, const float* a, double norm_a, const Vec3<double>& p, int scale,
                                double w_max, double min_score, double& w, double& step) {
  double lo = 0, hi = w_max;
  visible_inverse_depths(o.h, p, o.width, o.height, 4.0 * scale, lo, hi);
  if (!(lo < hi)) return false;
  const auto seen = [&](double v) {
    const Vec3<double> q = o.h.A * v + o.h.M * p;
    return Vec2<double>((q.x() / q.z() - 0.5 * (scale - 1)) / scale, (q.y() / q.z() - 0.5 * (scale - 1)) / scale);
  };
  const double length = (seen(hi) - seen(lo)).norm();
  const double steps = 2 * length;  // clamped before the conversion: NaN or inf take the limits
  const int count = steps > 2 ? static_cast<int>(std::ceil(std::min(steps, 768.0))) : 2;
  std::vector<double> score(static_cast<std::size_t>(count) + 1);
  int best = 0;
  for (int k = 0; k <= count; ++k) {
    const Vec2<double> q = seen(lo + (hi - lo) * k / count);
    score[static_cast<std::size_t>(k)] = patch_zncc(a, norm_a, o.grey, q.x(), q.y());
    if (score[static_cast<std::size_t>(k)] > score[static_cast<std::size_t>(best)]) best = k;
  }
  double second = -1;
  for (int k = 0; k <= count; ++k)
    if (std::abs(k - best) > 3) second = std::max(second, score[static_cast<std::size_t>(k)]);
  const double top = score[static_cast<std::size_t>(best)];
  w = lo + (hi - lo) * best / count;
  step = (hi - lo) / count;
  return top >= min_score && 1 - top <= 0.5 * (1 - second) && w > 0;
}

/// The sparse matches of reference camera `r` with `partners` (see the file comment): the depths
/// both partners agree on appended to `depths`, the nearest partner's to `loose`.
template <std::floating_point T, class Px>
void sparse_matches(const CameraFrameSet<T, Px>& frames, std::size_t r, const std::vector<std::size_t>& partners,
                    double w_max, const SweepRangeConfig& config, std::vector<double>& depths,
                    std::vector<double>& loose) {
  const PinholeCamera<T>& ref = frames.camera(r);
  int scale = 1;
  while (ref.width() / scale > config.coarse_width) scale *= 2;
  const Image<float> g = reduced_grey(frames.image(r), scale);
  const auto full = [&](double c) { return scale * c + 0.5 * (scale - 1); }; // reduced -> full pixel
  std::vector<RangePartner> with;
  for (const std::size_t j : partners) {
    const PinholeCamera<T>& other = frames.camera(j);
    if (other.width() / scale < 16 || other.height() / scale < 16) continue;
    with.push_back({reduced_grey(frames.image(j), scale), depth_homography(ref, other), other.width(), other.height()});
  }
  for (int cy = 4; cy + 8 <= g.height() - 4; cy += 8)
    for (int cx = 4; cx + 8 <= g.width() - 4; cx += 8) {
      // The cell's most textured pixel.
      int bx = cx, by = cy;
      float strongest = -1;
      for (int y = cy; y < cy + 8; ++y)
        for (int x = cx; x < cx + 8; ++x) {
          const float s = std::abs(g(x + 1, y) - g(x - 1, y)) + std::abs(g(x, y + 1) - g(x, y - 1));
          if (s > strongest) {
            strongest = s;
            bx = x;
            by = y;
          }
        }
      float a[49];
      double mean = 0, norm_a = 0;
      for (int k = 0, y = by - 3; y <= by + 3; ++y)
        for (int x = bx - 3; x <= bx + 3; ++x, ++k) mean += a[k] = g(x, y);
      mean /= 49;
      for (float& v : a) {
        v = static_cast<float>(v - mean);
        norm_a += static_cast<double>(v) * v;
      }
      if (norm_a < 49 * 4.0 * 4.0) continue; // flat: less than 4 grey levels of contrast
      const Vec3<double> p(full(bx), full(by), 1);
      // Each partner's match: its inverse depth and the inverse depth of one search step.
      std::vector<std::pair<double, double>> found;
      for (const RangePartner& o : with) {
        double w = 0, step = 0;
        if (!match_along_segment(o, a, norm_a, p, scale, w_max, config.min_score, w, step)) break;
        found.emplace_back(w, step);
      }
      if (found.empty()) continue;
      loose.push_back(1 / found.front().first);
      if (found.size() != with.size()) continue;
      // Two partners must agree within two steps of the coarser search and 2%.
      if (found.size() == 2 && std::abs(found[0].first - found[1].first) >
                                   2 * std::max(found[0].second, found[1].second) + 0.02 * found[1].first)
        continue;
      depths.push_back(1 / found.back().first); // the longer baseline's, the finer
    }
}

} // namespace detail

/// The depth range to sweep for `frames` (see the file comment). Throws `argument_error`
/// ("frames") for fewer than two cameras or when no two cameras see anything together, and as
/// `validate(config)`.
template <std::floating_point T, class Px>
[[nodiscard]] SweepRange sweep_range(const CameraFrameSet<T, Px>& frames, const SweepRangeConfig& config = {}) {
  validate(config);
  const std::size_t n = frames.size();
  if (n < 2) throw argument_error("frames", "a sweep range needs at least two cameras");
  SweepRange out;
  out.frustum_near = std::numeric_limits<double>::infinity();
  out.frustum_far = 0;
  std::vector<std::size_t> refs;
  const std::size_t want = std::min<std::size_t>(n, static_cast<std::size_t>(config.reference_cameras));
  for (std::size_t i = 0; i < want; ++i) {
    const std::size_t r = want == 1 ? n / 2 : (i * (n - 1) + (want - 1) / 2) / (want - 1);
    if (refs.empty() || refs.back() != r) refs.push_back(r);
  }
  std::vector<double> depths, loose; // matches both partners agree on; the nearest partner's
  for (const std::size_t r : refs) {
    double nearest = 0;
    const std::vector<std::size_t> partners = detail::range_partners(frames, r, nearest);
    if (partners.empty()) continue;
    const double w_max = nearest > 0 ? 2 / nearest : 1e30; // nothing nearer than half the baseline
    detail::widen_common_frustum(frames, r, partners, w_max, out);
    detail::sparse_matches(frames, r, partners, w_max, config, depths, loose);
  }
  if (!(out.frustum_near < out.frustum_far))
    throw argument_error("frames", "no two cameras see anything together: give the depth range");
  // Too few agreed matches (a ring, whose farther partner sees the object from far aside): the
  // nearest partner's alone.
  if (static_cast<int>(depths.size()) < std::max(config.min_matches, 64)) depths.swap(loose);
  if (static_cast<int>(depths.size()) >= config.min_matches) {
    std::sort(depths.begin(), depths.end());
    const std::size_t m = depths.size();
    const auto at = [&](double q) {
      return depths[std::min(m - 1, static_cast<std::size_t>(std::floor(q * static_cast<double>(m - 1) + 0.5)))];
    };
    const double w_far = 1 / at(1 - config.quantile), w_near = 1 / at(config.quantile);
    const double widen = config.margin * (w_near - w_far) + 0.02 * w_near;
    out.near = std::max(out.frustum_near, 1 / (w_near + widen));
    out.far = std::min(out.frustum_far, 1 / std::max(w_far - widen, 0.5 * w_far));
    out.matches = static_cast<int>(m);
    out.source = SweepRangeSource::matches;
  } else {
    out.near = out.frustum_near;
    out.far = std::min(out.frustum_far, 100 * out.frustum_near);
    out.source = SweepRangeSource::frustum;
  }
  if (!(out.far > out.near)) out.far = out.near * 1.01;
  return out;
}

} // namespace mpr
