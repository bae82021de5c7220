#pragma once
/// \file
/// `mpr::DepthProxy`: the geometry-aware light-field interpolation. Each ray is intersected with
/// the scene surface that the cameras' depth maps describe (`CameraFrameSet::with_depth`), and the
/// cameras that see that surface point are blended with Unstructured Lumigraph weights (Buehler
/// et al., SIGGRAPH 2001: a penalty for the angle between the camera's ray to the point and the
/// desired ray, the k best cameras, a weight that falls smoothly to zero at the (k+1)-th). This is
/// the "frame-based sampler that uses a geometric proxy" of Yu & McMillan's General Linear Camera
/// system (ECCV 2004), with per-camera depth maps as the proxy.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/interpolation.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>

namespace mpr {

namespace detail {

/// Depth of map `d` (row-major `width * height`) at continuous pixel (x, y) inside the image:
/// bilinear between the four nearest pixel centres when they agree within the relative
/// `tolerance` x 4 (a smooth surface), else the nearest pixel (a depth edge is not blurred).
template <std::floating_point T>
[[nodiscard]] inline T depth_lookup(const float* d, int width, int height, T x, T y, T tolerance) noexcept {
  const T fx = std::floor(x), fy = std::floor(y);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const int xa = std::clamp(x0, 0, width - 1), xb = std::clamp(x0 + 1, 0, width - 1);
  const int ya = std::clamp(y0, 0, height - 1), yb = std::clamp(y0 + 1, 0, height - 1);
  const float* ra = d + static_cast<std::ptrdiff_t>(ya) * width;
  const float* rb = d + static_cast<std::ptrdiff_t>(yb) * width;
  const T d00 = ra[xa], d10 = ra[xb], d01 = rb[xa], d11 = rb[xb];
  const T lo = std::min({d00, d10, d01, d11}), hi = std::max({d00, d10, d01, d11});
  const T ax = x - fx, ay = y - fy;
  if (std::isfinite(hi) && hi <= lo * (1 + 4 * tolerance)) // all finite and close: one smooth surface
    return (d00 * (1 - ax) + d10 * ax) * (1 - ay) + (d01 * (1 - ax) + d11 * ax) * ay;
  if (ay < T(0.5)) return ax < T(0.5) ? d00 : d10;
  return ax < T(0.5) ? d01 : d11;
}

} // namespace detail

/// Answers a ray from the surface point the depth maps give it (see the file comment).
///
/// Surface: the cameras within `radius` of the ray line are tried nearest first (at most
/// `march_cameras` of them). In camera c the ray projects to a segment of its image, which is
/// walked about one pixel at a time from where the ray line enters c's view (`whole_line`) or
/// from the ray's origin, but never from nearer than the nearest depth of c's map
/// (`CameraFrameSet::depth_near`: nothing c sees lies nearer); the first step where the ray's
/// depth along c's axis reaches the map's depth brackets the crossing, narrowed to 1/256 of the
/// step and to ray depths within half the `tolerance` by regula falsi (Illinois) and
/// interpolated.
/// When the map's depth there differs from the ray's by more than the relative `tolerance`, the
/// ray has only passed behind something c sees in front of it (c is occluded there) and the next
/// camera continues the walk from that point; likewise when the ray leaves c's image. When the
/// ray enters c's view only after that point, c knows nothing of the stretch before, and the
/// next camera searches it too (else a surface seen by the next camera but outside c's image,
/// e.g. a floor near the view's corner, would be skipped). A ray
/// whose walk reaches its vanishing point inside c's image with c's map +inf there runs to
/// infinity unseen (sky): it gets `FrameSamplerConfig::background`. A ray that no tried camera
/// finds a surface for otherwise uses the table's point (`FrameTable::point_of`: the focal depth
/// of `FrameSamplerConfig`).
///
/// Blend: every candidate camera that sees the point X -- projects it inside its image, and its
/// depth map there is not nearer than X's depth by more than `tolerance` (relative) -- has the
/// penalty p = angle between (X - its centre) and the ray direction; with p_k the (k+1)-th
/// smallest penalty (or twice the largest when fewer cameras see X), the k best get weight
/// (1 - p / p_k) / (p + 1e-6): a camera on the ray line dominates, the weight is continuous as
/// cameras enter and leave the k best. When no candidate sees X, the nearest camera's colour at X
/// (or the background).
///
/// Requirements: the frame set carries depth maps (`validate(table)`, called by
/// `CameraFrameSampler`, throws otherwise); cameras with lens distortion are blended but never
/// walked. Per ray: the candidates (a linear scan up to 64 cameras, else one ball-tree query), a
/// walk from where the ray reaches the nearest depth of the camera's map, about one pixel a step,
/// the crossing narrowed by regula falsi (about 4 lookups), then the visibility of the candidates
/// in order of angle until k + 1 see the point. No batch or tile path: `sample` per ray.
struct DepthProxy {
  /// Cameras farther than this from the ray line (world units, positive) are neither walked nor
  /// blended. About twice the camera spacing suits planar arrays.
  double radius = 1.0;
  /// Cameras blended per ray (the k of the Unstructured Lumigraph), >= 1.
  int k = 4;
  /// Relative depth tolerance of the surface search and of the visibility test, in (0, 1).
  double tolerance = 0.01;
  /// Cameras tried in turn for the surface search, >= 1.
  int march_cameras = 4;
  /// Search the ray line in front of the cameras (true), or only the half-line t >= 0 from the
  /// ray's origin (false). A GLC's rays start on its image surface, which may lie inside the
  /// scene (a held-out camera's focal plane): the line finds what lies before it too. A ray
  /// running toward a camera (its depth falling) finds nothing in that camera's view either way.
  bool whole_line = true;

  /// Marks the interpolation as reading depth maps (the rasterized-scene sampler keeps its
  /// z-buffers for it).
  static constexpr bool uses_depth_maps = true;

  /// Throws `argument_error` naming "radius", "k", "tolerance" or "march_cameras" for values
  /// outside the documented ranges.
  void validate() const {
    if (!(radius > 0) || !std::isfinite(radius)) throw argument_error("radius", "must be positive and finite");
    if (k < 1 || k > kMaxCandidates - 1)
      throw argument_error("k", "must be in 1.." + std::to_string(kMaxCandidates - 1));
    if (!(tolerance > 0 && tolerance < 1)) throw argument_error("tolerance", "must lie in (0, 1)");
    if (march_cameras < 1) throw argument_error("march_cameras", "must be at least 1");
  }

  /// Throws `argument_error` ("depth maps") when the table's frames carry no depth maps.
  template <std::floating_point T, class Px>
  void validate(const FrameTable<T, Px>& table) const {
    if (!table.frames().has_depth())
      throw argument_error("depth maps", "the depth-proxy interpolation needs one per camera; camera " +
                                             table.frames().name(0) + " has none");
  }

  template <std::floating_point T, class Px>
  [[nodiscard]] Color sample(const FrameTable<T, Px>& table, const Ray<T>& ray) const noexcept {
    Candidates<T> c;
    collect(table, ray, c);
    bool escaped = false;
    const std::optional<T> t = surface(table, ray, c, escaped);
    if (escaped) return table.config().background;
    const Vec3<T> X = t ? ray.at(*t) : table.point_of(ray);
    return blend(table, ray, X, c);
  }

  /// The ray parameter t of the first surface point along `ray` that the depth maps show (see
  /// the class comment; t >= 0 unless `whole_line`), or nullopt when none is found: the depth of
  /// a light-field view.
  template <std::floating_point T, class Px>
  [[nodiscard]] std::optional<T> surface(const FrameTable<T, Px>& table, const Ray<T>& ray) const noexcept {
    Candidates<T> c;
    collect(table, ray, c);
    bool escaped = false;
    return surface(table, ray, c, escaped);
  }

private:
  static constexpr int kMaxCandidates = 64;
  /// Up to this many cameras a linear scan finds the candidates faster than the ball tree.
  static constexpr std::size_t kScanCameras = 64;
  /// Regula-falsi steps that narrow a one-pixel bracket of the surface crossing to 1/256 of it
  /// (at most), and the most steps when the bracket's ray depths still differ by more than half
  /// the tolerance (near a vanishing point).
  static constexpr int kRefineSteps = 12;
  static constexpr int kRefineLimit = 48;

  template <std::floating_point T>
  struct Candidates {
    int index[kMaxCandidates];
    T distance[kMaxCandidates];
    int count = 0;
  };

  enum class Walk { hit, passed, escaped };

  // The cameras within the radius of the ray line, nearest first (the nearest kMaxCandidates);
  // the single nearest camera when none is that close.
  template <std::floating_point T, class Px>
  void collect(const FrameTable<T, Px>& table, const Ray<T>& ray, Candidates<T>& c) const noexcept {
    const auto add = [&](int i, T d) noexcept {
      int at = c.count;
      if (c.count == kMaxCandidates) {
        if (!(d < c.distance[kMaxCandidates - 1])) return;
        at = kMaxCandidates - 1;
      } else {
        ++c.count;
      }
      while (at > 0 && (d < c.distance[at - 1] || (d == c.distance[at - 1] && i < c.index[at - 1]))) {
        c.index[at] = c.index[at - 1];
        c.distance[at] = c.distance[at - 1];
        --at;
      }
      c.index[at] = i;
      c.distance[at] = d;
    };
    if (table.size() <= kScanCameras) {
      const T dd = ray.direction.squaredNorm();
      if (dd > 0 && std::isfinite(dd)) {
        const T inv = T(1) / dd, r2 = static_cast<T>(radius) * static_cast<T>(radius);
        for (std::size_t i = 0; i < table.size(); ++i) {
          const T d2 = line_distance2(table.camera(i).centre, ray.origin, ray.direction, inv);
          if (d2 < r2) add(static_cast<int>(i), std::sqrt(d2));
        }
      }
    } else {
      table.index().within(ray.origin, ray.direction, static_cast<T>(radius), add);
    }
    if (c.count == 0) {
      const int nearest = table.index().nearest(ray.origin, ray.direction);
      if (nearest >= 0) {
        c.index[0] = nearest;
        c.distance[0] = 0;
        c.count = 1;
      }
    }
  }

  // The surface point (see the public `surface`); `escaped` is set when a walk follows the ray to
  // its vanishing point inside a camera's image and that camera sees nothing there.
  template <std::floating_point T, class Px>
  [[nodiscard]] std::optional<T> surface(const FrameTable<T, Px>& table, const Ray<T>& ray, const Candidates<T>& c,
                                         bool& escaped) const noexcept {
    T t = whole_line ? -std::numeric_limits<T>::infinity() : T(0);
    int walked = 0;
    for (int j = 0; j < c.count && walked < march_cameras; ++j) {
      const std::size_t i = static_cast<std::size_t>(c.index[j]);
      if (table.camera(i).distorted) continue;
      ++walked;
      const Walk w = walk<T, Px>(table.camera(i), table.frames().depth(i).data(), table.frames().depth_near(i), ray, t);
      if (w == Walk::hit) return t;
      if (w == Walk::escaped) {
        escaped = true;
        return std::nullopt;
      }
    }
    return std::nullopt;
  }

  // Walks `ray` from parameter `t` through camera c's depth map `d`. Returns hit with t at the
  // surface, escaped when the ray reaches its vanishing point inside c's image in front of
  // everything c sees and c's map is +inf there (the ray runs to infinity: background), or passed
  // with t where the walk stopped (c occluded there, or the ray left c's image or field of
  // view): the next camera continues from there. When c sees the ray only from beyond t (it
  // enters c's view later), what lies before that is unknown to c: a walk that passes then
  // leaves t as it was, so the next camera searches that stretch too.
  template <std::floating_point T, class Px>
  [[nodiscard]] Walk walk(const typename FrameTable<T, Px>::Camera& c, const float* d, float near, const Ray<T>& ray,
                          T& t) const noexcept {
    const T* P = c.P;
    const Vec3<T>& o = ray.origin;
    const Vec3<T>& v = ray.direction;
    // Homogeneous pixel h(t) = a + t b; the third coordinate is the depth along c's axis.
    T a[3], b[3];
    for (int r = 0; r < 3; ++r) {
      a[r] = P[4 * r] * o.x() + P[4 * r + 1] * o.y() + P[4 * r + 2] * o.z() + P[4 * r + 3];
      b[r] = P[4 * r] * v.x() + P[4 * r + 1] * v.y() + P[4 * r + 2] * v.z();
    }
    // The interval where h projects inside the image (shrunk by 1e-3 pixel) in front of c.
    T lo = t, hi = std::numeric_limits<T>::infinity();
    bool empty = false;
    const auto clip = [&](T u, T w) { // keep u + t w >= 0
      if (w > 0)
        lo = std::max(lo, -u / w);
      else if (w < 0)
        hi = std::min(hi, -u / w);
      else if (u < 0)
        empty = true;
    };
    const T e = T(0.499), W = static_cast<T>(c.width) - T(0.5) - T(1e-3),
            H = static_cast<T>(c.height) - T(0.5) - T(1e-3);
    // In front of c, by a margin that keeps the first pixel step (z^2 / m in t) positive.
    clip(a[2] - T(1e-6) * (std::abs(a[2]) + std::abs(b[2])), b[2]);
    clip(a[0] + e * a[2], b[0] + e * b[2]);
    clip(W * a[2] - a[0], W * b[2] - b[0]);
    clip(a[1] + e * a[2], b[1] + e * b[2]);
    clip(H * a[2] - a[1], H * b[2] - b[1]);
    // Nearer than the nearest depth in c's map the ray is in front of everything c sees (the
    // map's depth and its interpolation are >= near): the walk starts where z reaches near.
    if (empty || !(lo < hi) || !std::isfinite(lo)) return Walk::passed;
    const T tol = static_cast<T>(tolerance);
    const T leave = hi; // where the ray leaves c's view
    // The walk passes on from `at`, or from where it began when c does not see the ray at t.
    const bool gap = lo > t;
    const T from = t;
    const auto pass = [&](T at) {
      t = gap ? from : at;
      return Walk::passed;
    };
    if (std::isfinite(near)) {
      clip(a[2] - static_cast<T>(near) * (1 - tol), b[2]);
      if (empty || !(lo < hi) || !std::isfinite(lo)) // in front of all c sees wherever c sees the ray
        return pass(std::isfinite(leave) ? leave : t);
    }
    // f(s) = ray depth - map depth at the ray's pixel (< 0: the ray is in front of the surface).
    const auto f = [&](T s, T& z) {
      z = a[2] + s * b[2];
      if (!(z > 0)) return -std::numeric_limits<T>::infinity();
      const T inv = T(1) / z;
      return z - detail::depth_lookup(d, c.width, c.height, (a[0] + s * b[0]) * inv, (a[1] + s * b[1]) * inv, tol);
    };
    // Pixels moved per unit t: m / z^2.
    const T mx = b[0] * a[2] - a[0] * b[2], my = b[1] * a[2] - a[1] * b[2];
    const T m = std::sqrt(mx * mx + my * my);
    T z = 0;
    T s = lo;
    T fs = f(s, z);
    if (!(fs < 0)) { // the walk starts at or behind the surface c sees
      if (fs <= tol * z) {
        t = s;
        return Walk::hit;
      }
      return pass(s);
    }
    for (int step = 0; step < 1 << 16; ++step) {
      if (s >= hi) break;
      const T zs = a[2] + s * b[2];
      T next;
      if (!std::isfinite(hi)) {
        // Toward the vanishing point (b[2] > 0): within half a pixel of it, the rest of the ray
        // stays on one pixel; the surface there (if any) is hit where the depths agree.
        if (!(m > 0) || m < T(0.5) * b[2] * zs) {
          T zv = 0;
          const T fv = f(s, zv);
          const T dv = zv - fv;
          if (std::isfinite(dv) && dv > zs && b[2] > 0) {
            t = (dv - a[2]) / b[2];
            return Walk::hit;
          }
          if (zv > 0 && std::isinf(dv)) return Walk::escaped;
          break;
        }
        next = s + zs * zs / m;
      } else {
        next = m > 0 ? std::min(hi, s + zs * zs / m) : hi;
      }
      T zn = 0;
      const T fn = f(next, zn);
      if (fn >= 0) {
        // Bracketed in [s, next], at most one pixel of c: narrowed by the Illinois variant of
        // regula falsi (a crossing of the maps' bilinear surface is found in a few lookups; at
        // a step between pixels, a depth edge, the halved end weights still shrink the
        // bracket) to 1/256 of the step and to ray depths within half the tolerance (near the
        // vanishing point a pixel spans a long stretch of the ray), then f interpolated
        // linearly.
        T s0 = s, s1 = next, f0 = fs, f1 = fn, z0 = zs, z1 = zn;
        T g0 = f0, g1 = f1; // the end values regula falsi weighs (halved when an end is kept)
        const T resolution = (next - s) * T(1.0 / 256);
        int kept = 0; // +1: the last step moved s0, -1: it moved s1
        for (int it = 0; it < kRefineLimit && (it < kRefineSteps || z1 - z0 > T(0.5) * tol * z1) &&
                         (s1 - s0 > resolution || z1 - z0 > T(0.5) * tol * z1);
             ++it) {
          T mid = g1 - g0 > 0 ? s0 + (s1 - s0) * (-g0 / (g1 - g0)) : T(0.5) * (s0 + s1);
          if (!(mid > s0 && mid < s1)) mid = T(0.5) * (s0 + s1);
          T zm = 0;
          const T fm = f(mid, zm);
          if (fm < 0) {
            s0 = mid;
            z0 = zm;
            f0 = g0 = fm;
            if (kept == 1) g1 *= T(0.5);
            kept = 1;
          } else {
            s1 = mid;
            f1 = g1 = fm;
            z1 = zm;
            if (kept == -1) g0 *= T(0.5);
            kept = -1;
          }
        }
        if (f1 <= tol * z1 && -f0 <= tol * z1) {
          const T denom = f1 - f0;
          t = denom > 0 ? s0 + (s1 - s0) * (-f0 / denom) : s1;
          return Walk::hit;
        }
        return pass(s0); // c is occluded from here on
      }
      s = next;
      fs = fn;
    }
    return pass(std::isfinite(hi) ? leave : s);
  }

  template <std::floating_point T, class Px>
  [[nodiscard]] Color blend(const FrameTable<T, Px>& table, const Ray<T>& ray, const Vec3<T>& X,
                            const Candidates<T>& c) const noexcept {
    const T tol = static_cast<T>(tolerance);
    const T length = ray.direction.norm();
    // The candidates in front of the ray by decreasing cosine (increasing penalty); only the
    // first k + 1 that see X matter, so visibility is tested in that order until they are found.
    int order[kMaxCandidates];
    T cosine[kMaxCandidates];
    int m = 0;
    for (int j = 0; j < c.count; ++j) {
      const Vec3<T> to = X - table.camera(static_cast<std::size_t>(c.index[j])).centre;
      const T cs = to.dot(ray.direction) / (to.norm() * length);
      if (!(cs > 0)) continue;
      int at = m++;
      for (; at > 0 && cosine[at - 1] < cs; --at) {
        cosine[at] = cosine[at - 1];
        order[at] = order[at - 1];
      }
      cosine[at] = std::min(cs, T(1));
      order[at] = c.index[j];
    }
    int seen[kMaxCandidates];
    T penalty[kMaxCandidates], px[kMaxCandidates], py[kMaxCandidates];
    int n = 0;
    for (int j = 0; j < m && n <= k; ++j) {
      const std::size_t i = static_cast<std::size_t>(order[j]);
      const auto& cam = table.camera(i);
      T x, y;
      if (!FrameTable<T, Px>::project(cam, X, x, y)) continue;
      const T* P = cam.P;
      const T z = P[8] * X.x() + P[9] * X.y() + P[10] * X.z() + P[11];
      const T depth = detail::depth_lookup(table.frames().depth(i).data(), cam.width, cam.height, x, y, tol);
      if (depth < z * (1 - tol)) continue; // something nearer hides X from this camera
      seen[n] = static_cast<int>(i);
      penalty[n] = std::acos(cosine[j]);
      px[n] = x;
      py[n] = y;
      ++n;
    }
    if (n == 0) {
      const int nearest = c.count > 0 ? c.index[0] : -1;
      return table.camera_color(nearest, X);
    }
    // The (k+1)-th smallest penalty of the cameras that see X, or twice the largest when at most
    // k do.
    const T threshold = n > k ? std::max(penalty[k], T(1e-6)) : 2 * penalty[n - 1] + T(1e-6);
    float acc[3] = {0, 0, 0};
    float weight = 0;
    for (int j = 0; j < n; ++j) {
      if (!(penalty[j] < threshold)) continue;
      const float w = static_cast<float>((1 - penalty[j] / threshold) / (penalty[j] + T(1e-6)));
      table.fetch_add(table.camera(static_cast<std::size_t>(seen[j])), px[j], py[j], w, acc);
      weight += w;
    }
    return table.finish(acc, weight);
  }
};

} // namespace mpr
