#pragma once
/// \file
/// The surface search of `DepthProxy` (lightfield/depth_proxy.hpp) in one camera: a ray walked
/// through the camera's depth map about one pixel a step until it reaches the surface the map
/// shows, the crossing narrowed by regula falsi; and where the search along a ray stands
/// between the cameras it tries in turn.

#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/frame_table.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mpr::detail {

/// Depth of map `d` (row-major `width * height`) at continuous pixel (x, y) inside the image:
/// bilinear between the four nearest pixel centres when they agree within the relative
/// `tolerance` x 4 (a smooth surface), else the nearest pixel (a depth edge is not blurred).
/// A point outside the image (infinite coordinates included) reads the nearest edge pixels; a
/// NaN coordinate reads column or row 0. The float-to-int conversion is always in range.
template <std::floating_point T>
[[nodiscard]] inline T depth_lookup(const float* d, int width, int height, T x, T y, T tolerance) noexcept {
  // Clamped before floor and the conversion (a ray through a map of huge depths projects to
  // huge or infinite coordinates): outside [0, size - 1] both taps are the edge pixel anyway.
  x = x >= T(-1) ? std::min(x, static_cast<T>(width)) : T(-1);
  y = y >= T(-1) ? std::min(y, static_cast<T>(height)) : T(-1);
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

/// How a walk through one camera's depth map ended (`depth_walk`).
enum class DepthWalk { hit, passed, escaped };

/// Where the surface search along a ray stands: the ray before `t` holds no surface (or is not
/// searched), nor does [skip_begin, skip_end), a stretch beyond t that a camera saw free (none
/// when skip_begin is +inf).
template <std::floating_point T>
struct DepthSearch {
  T t, skip_begin, skip_end;
};

/// The stretch [t0, t1] of `ray` (parameter t, from `from` on) inside the axis-aligned box
/// `bounds` (lower and upper corner; `CameraFrameSet::depth_bounds`): no surface the depth maps
/// show lies on the ray outside it. Empty (t0 >= t1) when the ray misses the box, the box is
/// empty, or the ray or `from` holds a NaN.
template <std::floating_point T>
[[nodiscard]] inline std::array<T, 2> box_stretch(const Ray<T>& ray, const std::array<Vec3<T>, 2>& bounds,
                                                  T from) noexcept {
  T t0 = from, t1 = std::numeric_limits<T>::infinity();
  for (int a = 0; a < 3; ++a) {
    const T lo = bounds[0][a], hi = bounds[1][a], o = ray.origin[a], d = ray.direction[a];
    if (!(lo <= hi)) return {T(1), T(0)};
    if (d == 0) {
      if (!(o >= lo && o <= hi)) return {T(1), T(0)};
      continue;
    }
    const T u = (lo - o) / d, v = (hi - o) / d;
    if (std::isnan(u) || std::isnan(v)) return {T(1), T(0)};
    t0 = std::max(t0, std::min(u, v));
    t1 = std::min(t1, std::max(u, v));
  }
  if (std::isnan(t0)) return {T(1), T(0)};
  return {t0, t1};
}

/// Regula-falsi steps that narrow a one-pixel bracket of the surface crossing to 1/256 of it (at
/// most), and the most steps when the bracket's ray depths still differ by more than half the
/// tolerance (near a vanishing point).
inline constexpr int kDepthRefineSteps = 12;
inline constexpr int kDepthRefineLimit = 48;
/// The narrowing also ends, on the surface, at a point where the ray's depth and the map's agree
/// within this fraction of the tolerance (relative to the ray's depth): 2^-10, 1e-5 of the depth
/// at the default tolerance, far below what the maps resolve. Without it the bracket's far end
/// took a few more lookups to pull in (Chess: 6.3 refining steps a walk of sixteen lanes, 3.4
/// with it).
inline constexpr float kDepthAgreement = 1.0f / 1024;

/// Walks `ray` from parameter `search.t` through camera c's depth map `d` (row-major, c's size;
/// `near` its nearest depth, `CameraFrameSet::depth_near`), `tolerance` the relative depth
/// tolerance (`DepthProxy::tolerance`). Returns hit with `search.t` at the surface; escaped when
/// the ray reaches its vanishing point inside c's image in front of everything c sees and c's
/// map is +inf there (the ray runs to infinity: background); or passed with `search.t` where the
/// walk stopped (c occluded there, or the ray left c's image or field of view): the next camera
/// continues from there. When c sees the ray only from beyond t (it enters c's view later), what
/// lies before is unknown to c: a walk that passes then leaves t as it was and records the
/// stretch it saw free as the search's skip, so the next camera searches the rest and steps over
/// that stretch.
template <std::floating_point T, class Px>
[[nodiscard]] DepthWalk depth_walk(const typename FrameTable<T, Px>::Camera& c, const float* d, float near,
                                   const Ray<T>& ray, double tolerance, DepthSearch<T>& search) noexcept {
  T& t = search.t;
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
  const T e = T(0.499), W = static_cast<T>(c.width) - T(0.5) - T(1e-3), H = static_cast<T>(c.height) - T(0.5) - T(1e-3);
  // In front of c, by a margin that keeps the first pixel step (z^2 / m in t) positive.
  clip(a[2] - T(1e-6) * (std::abs(a[2]) + std::abs(b[2])), b[2]);
  clip(a[0] + e * a[2], b[0] + e * b[2]);
  clip(W * a[2] - a[0], W * b[2] - b[0]);
  clip(a[1] + e * a[2], b[1] + e * b[2]);
  clip(H * a[2] - a[1], H * b[2] - b[1]);
  // Nearer than the nearest depth in c's map the ray is in front of everything c sees (the
  // map's depth and its interpolation are >= near): the walk starts where z reaches near.
  if (empty || !(lo < hi) || !std::isfinite(lo)) return DepthWalk::passed;
  const T tol = static_cast<T>(tolerance);
  const T leave = hi; // where the ray leaves c's view
  // The walk passes on from `at`; when c does not see the ray at t, [view, at) (when not empty)
  // becomes the skip (merged with the one there when they overlap) and t stays.
  const bool gap = lo > t;
  const T view = lo;
  T& sb = search.skip_begin;
  T& se = search.skip_end;
  const auto pass = [&](T at) {
    if (!gap) {
      t = at >= sb ? std::max(at, se) : at;
      if (t >= sb) sb = se = std::numeric_limits<T>::infinity();
    } else if (view < at && (!(sb < se) || (view <= se && at >= sb))) {
      const bool none = !(sb < se);
      sb = none ? view : std::min(sb, view);
      se = none ? at : std::max(se, at);
    }
    return DepthWalk::passed;
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
    return z - depth_lookup(d, c.width, c.height, (a[0] + s * b[0]) * inv, (a[1] + s * b[1]) * inv, tol);
  };
  // Pixels moved per unit t: m / z^2.
  const T mx = b[0] * a[2] - a[0] * b[2], my = b[1] * a[2] - a[1] * b[2];
  const T m = std::sqrt(mx * mx + my * my);
  if (lo >= sb && lo < se) { // the walk would start inside the stretch seen free
    if (!(se < hi)) return pass(std::isfinite(leave) ? leave : se);
    lo = se;
  }
  // Where a walk starts (or resumes after the stretch seen free) at or behind the surface c
  // sees (fs >= 0): the surface itself within the tolerance, else c is occluded from there.
  const auto start_behind = [&](T at, T fat, T zat) {
    if (fat <= tol * zat) {
      t = at;
      return DepthWalk::hit;
    }
    return pass(at);
  };
  T z = 0;
  T s = lo;
  T fs = f(s, z);
  if (!(fs < 0)) return start_behind(s, fs, z);
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
          return DepthWalk::hit;
        }
        if (zv > 0 && std::isinf(dv)) return DepthWalk::escaped;
        break;
      }
      next = s + zs * zs / m;
    } else {
      next = m > 0 ? std::min(hi, s + zs * zs / m) : hi;
    }
    if (s < sb && next > sb) next = sb; // up to the stretch seen free, then over it
    T zn = 0;
    const T fn = f(next, zn);
    if (fn >= 0) {
      // Bracketed in [s, next], at most one pixel of c: narrowed by the Illinois variant of
      // regula falsi (a crossing of the maps' bilinear surface is found in a few lookups; at
      // a step between pixels, a depth edge, the halved end weights still shrink the
      // bracket) to 1/256 of the step and to ray depths within half the tolerance (near the
      // vanishing point a pixel spans a long stretch of the ray), then f interpolated
      // linearly; or until a point where the depths agree (`kDepthAgreement`), the surface.
      T s0 = s, s1 = next, f0 = fs, f1 = fn, z0 = zs, z1 = zn;
      T g0 = f0, g1 = f1; // the end values regula falsi weighs (halved when an end is kept)
      const T resolution = (next - s) * T(1.0 / 256);
      const T agree = tol * T(kDepthAgreement);
      int kept = 0; // +1: the last step moved s0, -1: it moved s1
      for (int it = 0; it < kDepthRefineLimit && (it < kDepthRefineSteps || z1 - z0 > T(0.5) * tol * z1) &&
                       (s1 - s0 > resolution || z1 - z0 > T(0.5) * tol * z1);
           ++it) {
        T mid = g1 - g0 > 0 ? s0 + (s1 - s0) * (-g0 / (g1 - g0)) : T(0.5) * (s0 + s1);
        if (!(mid > s0 && mid < s1)) mid = T(0.5) * (s0 + s1);
        T zm = 0;
        const T fm = f(mid, zm);
        if (std::abs(fm) <= agree * zm) {
          t = mid;
          return DepthWalk::hit;
        }
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
        return DepthWalk::hit;
      }
      return pass(s0); // c is occluded from here on
    }
    s = next;
    fs = fn;
    if (s >= sb && s < se) {
      if (!(se < hi)) break;
      s = se;
      fs = f(s, z);
      if (!(fs < 0)) return start_behind(s, fs, z);
    }
  }
  return pass(std::isfinite(hi) ? leave : s);
}

} // namespace mpr::detail
