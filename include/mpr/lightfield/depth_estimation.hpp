#pragma once
/// \file
/// Depth maps estimated from the images of a calibrated camera set by a plane sweep (Collins
/// 1996): for each camera, fronto-parallel planes at depths sampled uniformly in inverse depth
/// are swept through its view; at each plane every pixel's colour is compared with the
/// neighbouring cameras' colours where they see the same point, the per-neighbour costs are
/// combined robustly (the sum of the best few: a neighbour that is occluded there drops out),
/// aggregated over an edge-aware support (the recursive domain-transform filter of Gastal &
/// Oliveira 2011, guided by the camera's own image, so the support stops at colour edges), and
/// the cheapest plane is refined to sub-plane depth by a parabola through its neighbours. Gives
/// a depth map per camera for `CameraFrameSet::with_depth` and `DepthProxy`, with a confidence.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/parallel.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace mpr {

/// Settings of `estimate_depth`. Depths are along the camera's optical axis, world units.
struct PlaneSweepConfig {
  /// Depth range swept, 0 < near < far, finite.
  double near = 1;
  double far = 100;
  /// Planes between near and far, uniform in inverse depth, 2..1024.
  int planes = 64;
  /// Cameras compared with each camera: its nearest by centre distance, 1..32.
  int neighbours = 4;
  /// The cost of a pixel at a plane is the sum of the `best` smallest neighbour costs
  /// (1..neighbours): cameras that are occluded there do not count.
  int best = 2;
  /// A neighbour's cost per pixel is the sum over channels of |difference| of the sRGB codes
  /// / 255, truncated at this value (robust to specularities and occlusion), > 0.
  double truncation = 0.3;
  /// Edge-aware aggregation (domain transform): spatial extent in pixels (>= 0; 0: none) and the
  /// colour difference (sum over channels of sRGB codes / 255) that cuts the support, > 0.
  double spatial = 12;
  double range = 0.2;
  /// Worker threads (the caller included); 0 or less: all hardware threads.
  int threads = 0;
};

/// A camera's estimated depth and, per pixel, a confidence in [0, 1]: 1 - (the best plane's
/// aggregated cost / the mean over planes); near 0 where every plane fits alike (no texture).
struct DepthEstimate {
  Image<float> depth;
  Image<float> confidence;
};

namespace detail {

/// One pass of the recursive domain-transform filter along a line of `n` values `v` (stride
/// `step`) with per-link feedback `a[k]` between elements k-1 and k, forward then backward.
inline void domain_transform_line(float* v, const float* a, int n, std::ptrdiff_t step) noexcept {
  for (int k = 1; k < n; ++k) v[k * step] += a[k * step] * (v[(k - 1) * step] - v[k * step]);
  for (int k = n - 2; k >= 0; --k) v[k * step] += a[(k + 1) * step] * (v[(k + 1) * step] - v[k * step]);
}

} // namespace detail

/// Checks `config`; throws `argument_error` naming the field ("near", "far", "planes",
/// "neighbours", "best", "truncation", "spatial", "range").
inline void validate(const PlaneSweepConfig& c) {
  if (!(c.near > 0) || !std::isfinite(c.near)) throw argument_error("near", "must be positive and finite");
  if (!(c.far > c.near) || !std::isfinite(c.far)) throw argument_error("far", "must be finite and beyond near");
  if (c.planes < 2 || c.planes > 1024) throw argument_error("planes", "must be in 2..1024");
  if (c.neighbours < 1 || c.neighbours > 32) throw argument_error("neighbours", "must be in 1..32");
  if (c.best < 1 || c.best > c.neighbours) throw argument_error("best", "must be in 1..neighbours");
  if (!(c.truncation > 0) || !std::isfinite(c.truncation)) throw argument_error("truncation", "must be positive");
  if (!(c.spatial >= 0) || !std::isfinite(c.spatial)) throw argument_error("spatial", "must be finite and >= 0");
  if (!(c.range > 0) || !std::isfinite(c.range)) throw argument_error("range", "must be positive");
}

/// The depth map of camera `camera` of `frames` by the plane sweep of the file comment, compared
/// with its `config.neighbours` nearest cameras. Throws `argument_error` for a bad config, a
/// camera index out of range ("camera"), a set of fewer than two cameras or a camera with lens
/// distortion ("frames", naming it).
template <std::floating_point T, class Px>
[[nodiscard]] DepthEstimate estimate_depth(const CameraFrameSet<T, Px>& frames, std::size_t camera,
                                           const PlaneSweepConfig& config) {
  validate(config);
  if (camera >= frames.size()) throw argument_error("camera", "index out of range");
  if (frames.size() < 2) throw argument_error("frames", "a plane sweep needs at least two cameras");
  // The nearest cameras by centre distance.
  const PinholeCamera<T>& ref = frames.camera(camera);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (i != camera) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const T da = (frames.camera(a).centre() - ref.centre()).squaredNorm();
    const T db = (frames.camera(b).centre() - ref.centre()).squaredNorm();
    return da < db || (da == db && a < b);
  });
  order.resize(std::min<std::size_t>(order.size(), static_cast<std::size_t>(config.neighbours)));
  for (const std::size_t i : order)
    if (frames.camera(i).has_distortion() || ref.has_distortion())
      throw argument_error("frames", frames.name(i) + ": lens distortion is not supported by the plane sweep");
  const int width = ref.width(), height = ref.height();
  const int m = static_cast<int>(order.size());
  const int best = std::min(config.best, m);
  // Colours are compared as sRGB codes / 255 (perceptually even: dark texture counts as much as
  // bright), three floats per pixel, for the camera and its neighbours.
  const auto codes = [&](std::size_t i) {
    const Image<Px>& image = frames.image(i);
    std::vector<float> v(3 * static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.height()));
    std::size_t k = 0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) {
        Rgb8 p;
        if constexpr (std::is_same_v<Px, Rgb8>)
          p = image(x, y);
        else
          p = to_rgb8(image(x, y));
        v[k++] = p.r / 255.0f;
        v[k++] = p.g / 255.0f;
        v[k++] = p.b / 255.0f;
      }
    return v;
  };
  const std::vector<float> rt = codes(camera);
  std::vector<std::vector<float>> nt;
  for (const std::size_t i : order) nt.push_back(codes(i));

  // Pixel p of the reference at depth d is X = C + d R^T K^-1 p; neighbour j sees it at
  // h = A_j + d M_j p (homogeneous), A_j = K_j (R_j C + t_j), M_j = K_j R_j R^T K^-1.
  const Mat3<double> back = ref.R().template cast<double>().transpose() * ref.K().template cast<double>().inverse();
  const Vec3<double> centre = ref.centre().template cast<double>();
  std::vector<Mat3<float>> M(static_cast<std::size_t>(m));
  std::vector<Vec3<float>> A(static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) {
    const PinholeCamera<T>& c = frames.camera(order[static_cast<std::size_t>(j)]);
    const Mat3<double> K = c.K().template cast<double>(), R = c.R().template cast<double>();
    M[static_cast<std::size_t>(j)] = (K * R * back).template cast<float>();
    A[static_cast<std::size_t>(j)] = (K * (R * centre + c.t().template cast<double>())).template cast<float>();
  }

  // Domain-transform feedback per link, from the reference image's colour differences.
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<float> ax(n, 0.0f), ay(n, 0.0f);
  const double sigma = std::max(config.spatial, 1e-6);
  const double base = std::exp(-std::sqrt(2.0) / sigma);
  const auto diff = [&](std::size_t a, std::size_t b) {
    float s = 0;
    for (std::size_t k = 0; k < 3; ++k) s += std::abs(rt[3 * a + k] - rt[3 * b + k]);
    return s;
  };
  const double ratio = sigma / config.range;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t k = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      if (x > 0) ax[k] = static_cast<float>(std::pow(base, 1 + ratio * diff(k, k - 1)));
      if (y > 0) ay[k] = static_cast<float>(std::pow(base, 1 + ratio * diff(k, k - static_cast<std::size_t>(width))));
    }

  std::vector<float> cost(n), best_cost(n, std::numeric_limits<float>::infinity()), sum(n, 0.0f), left(n, 0.0f),
      right(n, 0.0f), previous(n, 0.0f);
  std::vector<int> best_plane(n, 0);
  const double inv_near = 1 / config.near, inv_far = 1 / config.far;
  const auto depth_of = [&](double index) {
    return 1 / (inv_near + (inv_far - inv_near) * index / static_cast<double>(config.planes - 1));
  };
  const float tau = static_cast<float>(config.truncation);
  for (int plane = 0; plane < config.planes; ++plane) {
    const float d = static_cast<float>(depth_of(plane));
    detail::parallel_rows(0, height, config.threads, [&](int y) noexcept {
      float costs[32];
      for (int x = 0; x < width; ++x) {
        const std::size_t k =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        const Vec3<float> p(static_cast<float>(x), static_cast<float>(y), 1.0f);
        int seen = 0;
        for (int j = 0; j < m; ++j) {
          const Vec3<float> h = A[static_cast<std::size_t>(j)] + d * (M[static_cast<std::size_t>(j)] * p);
          const PinholeCamera<T>& c = frames.camera(order[static_cast<std::size_t>(j)]);
          if (!(h.z() > 0)) continue;
          const float u = h.x() / h.z(), v = h.y() / h.z();
          if (!(u >= 0 && v >= 0 && u <= static_cast<float>(c.width() - 1) && v <= static_cast<float>(c.height() - 1)))
            continue;
          const int u0 = std::min(static_cast<int>(u), c.width() - 2 < 0 ? 0 : c.width() - 2);
          const int v0 = std::min(static_cast<int>(v), c.height() - 2 < 0 ? 0 : c.height() - 2);
          const int u1 = std::min(u0 + 1, c.width() - 1), v1 = std::min(v0 + 1, c.height() - 1);
          const float fu = u - static_cast<float>(u0), fv = v - static_cast<float>(v0);
          const float* t = nt[static_cast<std::size_t>(j)].data();
          const std::ptrdiff_t w = c.width();
          const float* t00 = t + 3 * (v0 * w + u0);
          const float* t10 = t + 3 * (v0 * w + u1);
          const float* t01 = t + 3 * (v1 * w + u0);
          const float* t11 = t + 3 * (v1 * w + u1);
          float s = 0;
          for (std::size_t ch = 0; ch < 3; ++ch) {
            const float a = t00[ch] * (1 - fu) + t10[ch] * fu, b = t01[ch] * (1 - fu) + t11[ch] * fu;
            s += std::abs((a * (1 - fv) + b * fv) - rt[3 * k + ch]);
          }
          costs[seen++] = std::min(s, tau);
        }
        // A neighbour that does not see the point counts as the truncation (the worst cost),
        // so a plane is not preferred because few neighbours see it; the best few are averaged.
        for (int j = seen; j < m; ++j) costs[j] = tau;
        std::partial_sort(costs, costs + best, costs + m);
        float c = 0;
        for (int j = 0; j < best; ++j) c += costs[j];
        cost[k] = c / static_cast<float>(best);
      }
    });
    if (config.spatial > 0) {
      detail::parallel_rows(0, height, config.threads, [&](int y) noexcept {
        detail::domain_transform_line(cost.data() + static_cast<std::ptrdiff_t>(y) * width,
                                      ax.data() + static_cast<std::ptrdiff_t>(y) * width, width, 1);
      });
      detail::parallel_rows(0, width, config.threads, [&](int x) noexcept {
        detail::domain_transform_line(cost.data() + x, ay.data() + x, height, width);
      });
    }
    for (std::size_t k = 0; k < n; ++k) {
      const float c = cost[k];
      sum[k] += c;
      if (best_plane[k] == plane - 1) right[k] = c;
      if (c < best_cost[k]) {
        best_cost[k] = c;
        best_plane[k] = plane;
        left[k] = plane > 0 ? previous[k] : c;
        right[k] = c;
      }
      previous[k] = c;
    }
  }
  DepthEstimate out{Image<float>(width, height), Image<float>(width, height)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t k = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      const int b = best_plane[k];
      double offset = 0;
      if (b > 0 && b < config.planes - 1) {
        const double curvature = left[k] - 2.0 * best_cost[k] + right[k];
        if (curvature > 0) offset = std::clamp(0.5 * (left[k] - right[k]) / curvature, -0.5, 0.5);
      }
      out.depth(x, y) = static_cast<float>(depth_of(b + offset));
      const float mean = sum[k] / static_cast<float>(config.planes);
      out.confidence(x, y) = mean > 0 ? std::clamp(1.0f - best_cost[k] / mean, 0.0f, 1.0f) : 0.0f;
    }
  return out;
}

/// The estimated depth maps of every camera of `frames` (see `estimate_depth`), in camera order,
/// for `CameraFrameSet::with_depth`.
template <std::floating_point T, class Px>
[[nodiscard]] std::vector<Image<float>> estimate_depth_maps(const CameraFrameSet<T, Px>& frames,
                                                            const PlaneSweepConfig& config) {
  std::vector<Image<float>> maps;
  maps.reserve(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) maps.push_back(estimate_depth(frames, i, config).depth);
  return maps;
}

} // namespace mpr
