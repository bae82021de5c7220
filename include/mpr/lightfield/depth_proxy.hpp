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
#include <mpr/core/simd.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/depth_proxy/depth_proxy_lanes.hpp>
#include <mpr/lightfield/depth_proxy/depth_walk.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/interpolation.hpp>
#include <mpr/lightfield/kernels/unit_acos.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <type_traits>

namespace mpr {

/// Answers a ray from the surface point the depth maps give it (see the file comment).
///
/// Surface: only the stretch of the ray inside the box of every point the maps show
/// (`CameraFrameSet::depth_bounds`) is searched. The cameras within `radius` of the ray line are
/// tried nearest first (at most `march_cameras` of them). In camera c the ray projects to a
/// segment of its image, which is walked about one pixel at a time from where the ray enters the
/// box and c's view (and not before its origin unless `whole_line`), but never from nearer than
/// the nearest depth of c's map
/// (`CameraFrameSet::depth_near`: nothing c sees lies nearer); the first step where the ray's
/// depth along c's axis reaches the map's depth brackets the crossing, narrowed to 1/256 of the
/// step and to ray depths within half the `tolerance` by regula falsi (Illinois) and
/// interpolated, or until a point where the ray's and the map's depths agree within 2^-10 of the
/// `tolerance` (`detail::kDepthAgreement`).
/// When the map's depth there differs from the ray's by more than the relative `tolerance`, the
/// ray has only passed behind something c sees in front of it (c is occluded there) and the next
/// camera continues the walk from that point; likewise when the ray leaves c's image. When the
/// ray enters c's view only after that point, c knows nothing of the stretch before, and the
/// next camera searches it too (else a surface seen by the next camera but outside c's image,
/// e.g. a floor near the view's corner, would be skipped), stepping over the stretch c saw free
/// (one such stretch is kept; walks repeat no lookups there). A ray
/// whose walk reaches its vanishing point inside c's image with c's map +inf there runs to
/// infinity unseen (sky), and so does a ray that misses the box or that the walks see free, one
/// camera after another, all the way through it (past an object on an empty backdrop): these get
/// `FrameSamplerConfig::background`. A ray that no tried camera finds a surface for otherwise
/// (an occluded or unseen stretch is left) uses the table's point (`FrameTable::point_of`: the
/// focal depth of `FrameSamplerConfig`).
///
/// Blend: every candidate camera that sees the point X -- projects it inside its image, and its
/// depth map there is not nearer than X's depth by more than `visibility_tolerance` (relative)
/// -- has the penalty p = angle between (X - its centre) and the ray direction; with p_k the
/// (k+1)-th smallest penalty (or twice the largest when fewer cameras see X), the k best get
/// weight (1 - p / p_k) / (p + 1e-6): a camera on the ray line dominates, the weight is
/// continuous as cameras enter and leave the k best. When no candidate sees X, the nearest camera's colour at X
/// (or the background).
///
/// Requirements: the frame set carries depth maps (`validate(table)`, called by
/// `CameraFrameSampler`, throws otherwise); cameras with lens distortion are blended but never
/// walked. Per ray: the candidates (a linear scan up to 64 cameras, else one ball-tree query), a
/// walk from where the ray reaches the nearest depth of the camera's map, about one pixel a step,
/// the crossing narrowed by regula falsi (about 4 lookups), then the visibility of the candidates
/// in order of angle until k + 1 see the point. A batch path (`sample_rays`) takes sixteen rays
/// at a time in SIMD lanes (SSE4, AVX2 or AVX-512).
struct DepthProxy {
  /// Cameras farther than this from the ray line (world units, positive) are neither walked nor
  /// blended. About twice the camera spacing suits planar arrays.
  double radius = 1.0;
  /// Cameras blended per ray (the k of the Unstructured Lumigraph), >= 1.
  int k = 4;
  /// Relative depth tolerance of the surface search, in (0, 1): a crossing whose two sides differ
  /// by more is a depth edge, not the surface (see above).
  double tolerance = 0.01;
  /// Cameras tried in turn for the surface search, >= 1.
  int march_cameras = 4;
  /// Search the ray line in front of the cameras (true), or only the half-line t >= 0 from the
  /// ray's origin (false). A GLC's rays start on its image surface, which may lie inside the
  /// scene (a held-out camera's focal plane): the line finds what lies before it too. A ray
  /// running toward a camera (its depth falling) finds nothing in that camera's view either way.
  bool whole_line = true;
  /// Relative depth tolerance of the blend's visibility test, in (0, 1): a camera sees X unless
  /// its depth map there is nearer than X's depth by more than this. Looser than `tolerance`
  /// because it forgives the maps' own error: a plane sweep's depth is off by up to about a
  /// plane step (1.5% of the depth for Chess at 64 planes), and a camera wrongly found occluded
  /// drops out of the blend (speckles of the remaining cameras' colours); true occluders
  /// usually lie farther in front. Leave-one-out means for 0.01 / 0.03 / 0.05 / 0.08: Chess 39.20 / 39.45 /
  /// 39.63 / 39.76 dB, temple ring 19.89 / 19.96 / 19.85 / 19.48 dB (docs/accuracy.md).
  double visibility_tolerance = 0.03;

  /// Marks the interpolation as reading depth maps (the rasterized-scene sampler keeps its
  /// z-buffers for it).
  static constexpr bool uses_depth_maps = true;

  /// Throws `argument_error` naming "radius", "k", "tolerance", "march_cameras" or
  /// "visibility_tolerance" for values outside the documented ranges.
  void validate() const {
    if (!(radius > 0) || !std::isfinite(radius)) throw argument_error("radius", "must be positive and finite");
    if (k < 1 || k > kMaxCandidates - 1)
      throw argument_error("k", "must be in 1.." + std::to_string(kMaxCandidates - 1));
    if (!(tolerance > 0 && tolerance < 1)) throw argument_error("tolerance", "must lie in (0, 1)");
    if (march_cameras < 1) throw argument_error("march_cameras", "must be at least 1");
    if (!(visibility_tolerance > 0 && visibility_tolerance < 1))
      throw argument_error("visibility_tolerance", "must lie in (0, 1)");
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

  /// `out[i] = sample(table, rays[i])` for every i (precondition: equal lengths). On x86 with
  /// Highway (`MPR_HAVE_HWY`), at every `level` from SSE4.2 up (the kernels of
  /// kernels/depth_lanes_hwy.hpp: SSE4 at `portable`, AVX2, AVX-512), for float tables of at
  /// most 64 undistorted cameras and k < 8: sixteen rays at a time ((depth_proxy/depth_proxy_lanes.hpp)),
  /// one lane per ray, for the scan of the camera centres, the walks through each ray's cameras,
  /// the blend's choice of cameras and the weighing of 8-bit frames. Bit for bit the per-ray
  /// answer where the per-ray code is built without fused multiply-adds (no -march or -mfma);
  /// with them, a decision at a threshold that the rounding of a fused product moves may go the
  /// other way (Chess: 8 of 1.12 million pixels; the classroom's exact z-buffers: 0.24%).
  /// Elsewhere, `sample` per ray. `level` (default: `detail::dispatch_level()`) must be one the
  /// CPU runs.
  template <std::floating_point T, class Px>
  void sample_rays(const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, std::span<Color> out,
                   detail::SimdLevel level = detail::dispatch_level()) const noexcept {
    const bool lanes = by_sixteen(table, rays, level, [&](auto group, std::size_t at, const auto& blend) {
      detail::DepthProxyLanes<DepthProxy, Px>::sample16(*this, table, group, blend, out.data() + at);
    });
    if (!lanes)
      for (std::size_t i = 0; i < rays.size(); ++i) out[i] = sample(table, rays[i]);
  }

  /// `out[i] = surface(table, rays[i])` for every i (precondition: equal lengths), with the
  /// sixteen-lane walks of `sample_rays` where it has them.
  template <std::floating_point T, class Px>
  void surface_rays(const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, std::span<std::optional<T>> out,
                    detail::SimdLevel level = detail::dispatch_level()) const noexcept {
    const bool lanes = by_sixteen(table, rays, level, [&](auto group, std::size_t at, const auto& blend) {
      detail::DepthProxyLanes<DepthProxy, Px>::surface16(*this, table, group, blend, out.data() + at);
    });
    if (!lanes)
      for (std::size_t i = 0; i < rays.size(); ++i) out[i] = surface(table, rays[i]);
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
  template <class, class>
  friend struct detail::DepthProxyLanes;

  static constexpr int kMaxCandidates = 64;
  /// Up to this many cameras a linear scan finds the candidates faster than the ball tree.
  static constexpr std::size_t kScanCameras = 64;

  // When the sixteen-lane path answers for `table` at `level` (see `sample_rays`): `lanes(group,
  // at, blend)` for the groups of at most sixteen rays starting at rays[at] (`blend`: what the
  // lane kernels read of the table, prepared once), and true; else false.
  template <std::floating_point T, class Px, class Lanes>
  bool by_sixteen(const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, detail::SimdLevel level,
                  const Lanes& lanes) const noexcept {
#if MPR_HAVE_HWY && defined(MPR_SIMD_X86)
    if constexpr (std::is_same_v<T, float>) {
      using Batch = detail::DepthProxyLanes<DepthProxy, Px>;
      const std::int64_t target = detail::depth_lanes_target(level);
      if (target != 0 && Batch::applies(*this, table)) {
        const typename Batch::Blend blend(table, target);
        for (std::size_t at = 0; at < rays.size(); at += 16)
          lanes(rays.subspan(at, std::min<std::size_t>(16, rays.size() - at)), at, blend);
        return true;
      }
    }
#endif
    (void)table, (void)rays, (void)level, (void)lanes;
    return false;
  }

  template <std::floating_point T>
  struct Candidates {
    int index[kMaxCandidates];
    T distance[kMaxCandidates];
    int count = 0;
  };

  // Adds camera i at distance d to `c`, kept nearest first (the lower index first among equal
  // distances), the nearest kMaxCandidates only.
  template <std::floating_point T>
  static void insert(Candidates<T>& c, int i, T d) noexcept {
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
  }

  // The cameras within the radius of the ray line, nearest first (the nearest kMaxCandidates);
  // the single nearest camera when none is that close.
  template <std::floating_point T, class Px>
  void collect(const FrameTable<T, Px>& table, const Ray<T>& ray, Candidates<T>& c) const noexcept {
    const auto add = [&](int i, T d) noexcept { insert(c, i, d); };
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

  // The surface point (see the public `surface`); `escaped` is set when the ray holds no surface
  // the maps show: it misses their box, the walks saw it free through the box, or a walk followed
  // it to its vanishing point inside a camera's image and that camera sees nothing there.
  template <std::floating_point T, class Px>
  [[nodiscard]] std::optional<T> surface(const FrameTable<T, Px>& table, const Ray<T>& ray, const Candidates<T>& c,
                                         bool& escaped) const noexcept {
    const T inf = std::numeric_limits<T>::infinity();
    // Outside the box of everything the maps show, the ray holds no surface: the search starts
    // where the ray enters it and ends where the ray leaves it.
    const std::array<T, 2> stretch = detail::box_stretch(ray, table.frames().depth_bounds(), whole_line ? -inf : T(0));
    if (!(stretch[0] < stretch[1])) {
      escaped = true;
      return std::nullopt;
    }
    detail::DepthSearch<T> search{stretch[0], inf, inf};
    int walked = 0;
    for (int j = 0; j < c.count && walked < march_cameras; ++j) {
      const std::size_t i = static_cast<std::size_t>(c.index[j]);
      if (table.camera(i).distorted) continue;
      ++walked;
      const detail::DepthWalk w = detail::depth_walk<T, Px>(table.camera(i), table.frames().depth(i).data(),
                                                            table.frames().depth_near(i), ray, tolerance, search);
      if (w == detail::DepthWalk::hit) return search.t;
      if (w == detail::DepthWalk::escaped || search.t >= stretch[1]) {
        escaped = true;
        return std::nullopt;
      }
    }
    return std::nullopt;
  }

  template <std::floating_point T>
  struct Seen {
    int camera;
    T x, y;
  };

  // The Unstructured-Lumigraph average of the `n` cameras that see the point, by increasing
  // `penalty`; `at(j)` gives the j-th camera and its pixel.
  template <std::floating_point T, class Px, class At>
  [[nodiscard]] Color weigh(const FrameTable<T, Px>& table, const T* penalty, int n, const At& at) const noexcept {
    // The (k+1)-th smallest penalty of the cameras that see X, or twice the largest when at most
    // k do.
    const T threshold = n > k ? std::max(penalty[k], T(1e-6)) : 2 * penalty[n - 1] + T(1e-6);
    float acc[3] = {0, 0, 0};
    float weight = 0;
    for (int j = 0; j < n; ++j) {
      if (!(penalty[j] < threshold)) continue;
      const float w = static_cast<float>((1 - penalty[j] / threshold) / (penalty[j] + T(1e-6)));
      const Seen<T> s = at(j);
      table.fetch_add(table.camera(static_cast<std::size_t>(s.camera)), s.x, s.y, w, acc);
      weight += w;
    }
    return table.finish(acc, weight);
  }

  template <std::floating_point T, class Px>
  [[nodiscard]] Color blend(const FrameTable<T, Px>& table, const Ray<T>& ray, const Vec3<T>& X,
                            const Candidates<T>& c) const noexcept {
    const T tol = static_cast<T>(visibility_tolerance);
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
      penalty[n] = detail::unit_acos(cosine[j]);
      px[n] = x;
      py[n] = y;
      ++n;
    }
    if (n == 0) {
      const int nearest = c.count > 0 ? c.index[0] : -1;
      return table.camera_color(nearest, X);
    }
    return weigh(table, penalty, n, [&](int j) { return Seen<T>{seen[j], px[j], py[j]}; });
  }
};

} // namespace mpr
