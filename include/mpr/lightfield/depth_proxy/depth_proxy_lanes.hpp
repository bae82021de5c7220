#pragma once
/// \file
/// `DepthProxy`'s batch path (lightfield/depth_proxy.hpp): sixteen rays at a time, one per lane
/// of the kernels of kernels/depth_lanes_hwy.hpp (SSE4, AVX2 or AVX-512). The scan of the camera
/// centres gives each ray its candidates and its nearest camera; the rays that share a nearest
/// camera walk its depth map together, and the rays that camera does not settle walk their next
/// candidates in turn, again together where they share one; the blend's visibility tests, angles
/// and choice of the k + 1 best cameras run across the lanes, and so does the weighing of 8-bit
/// frames. Everything here but the kernels is per ray, compiled as the per-ray path is, so that
/// both round alike. Templated on the proxy (`DepthProxy`, whose friend it is), so that this
/// header needs only the proxy's declaration.

#include <mpr/core/color.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/depth_proxy/depth_walk.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/kernels/depth_lane_data.hpp>
#include <mpr/lightfield/kernels/depth_lanes_hwy.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <type_traits>

namespace mpr::detail {

/// The sixteen-lane steps of `DepthProxy` (defined where the lanes exist: x86 with Highway;
/// elsewhere declared only, and `DepthProxy` answers per ray).
template <class Proxy, class Px>
struct DepthProxyLanes;

#if MPR_HAVE_HWY && defined(MPR_SIMD_X86)

/// Whether the lanes run at `level` (0: the per-ray path), and at which Highway target.
[[nodiscard]] inline std::int64_t depth_lanes_target(SimdLevel level) noexcept {
  return kernels::depth_lanes_target(level);
}

/// The sixteen-lane steps of `Proxy::sample_rays` (`DepthProxy`) for tables of texel type `Px`
/// (a friend of `Proxy`).
template <class Proxy, class Px>
struct DepthProxyLanes {
  /// Whether the sixteen-lane path answers for `p` over `table` (see `DepthProxy::sample_rays`).
  [[nodiscard]] static bool applies(const Proxy& p, const FrameTable<float, Px>& table) noexcept {
    if (table.size() > Proxy::kScanCameras || p.k + 1 > kDepthLaneSlots) return false;
    for (const auto& cam : table.cameras())
      if (cam.distorted || static_cast<long long>(cam.width) * cam.height >= (1ll << 31)) return false;
    return true;
  }

  /// What the lane kernels read of a table, prepared once per batch (`target`: the Highway
  /// target they run at): each camera's projection, centre, size and depth map; for the
  /// weighing, each camera's texels, with `lanes` when it applies (8-bit frames, bilinear
  /// filter), else the weighing stays per ray.
  struct Blend {
    LaneCamera lane[Proxy::kScanCameras];
    WeighCamera cameras[Proxy::kScanCameras];
    std::int64_t target = 0;
    bool lanes = false;

    Blend(const FrameTable<float, Px>& table, std::int64_t target_) noexcept : target(target_) {
      for (std::size_t i = 0; i < table.size(); ++i) {
        const auto& c = table.camera(i);
        lane[i] = LaneCamera{c.P,
                             c.centre.x(),
                             c.centre.y(),
                             c.centre.z(),
                             c.width,
                             c.height,
                             table.frames().depth(i).data(),
                             table.frames().depth_near(i)};
      }
      if constexpr (std::is_same_v<typename FrameTable<float, Px>::texel_type, Srgb8Texel>) {
        lanes = table.config().filter == PixelFilter::bilinear;
        for (std::size_t i = 0; i < table.size(); ++i) {
          const auto& c = table.camera(i);
          cameras[i] = WeighCamera{&c.texels->c[0], c.width, c.height};
        }
      }
    }
  };

  /// Up to sixteen rays in lanes: the scan's results, and each ray's surface (`t`, or none;
  /// `escaped`: it ran to infinity unseen), as `DepthProxy::surface` finds it.
  struct Group {
    RayLanes r;
    alignas(64) float distance[Proxy::kScanCameras][16];
    std::uint16_t near[Proxy::kScanCameras];
    alignas(64) int first[16];
    std::optional<float> t[16];
    bool escaped[16] = {};
  };

  /// Fills `g` for `rays` (at most sixteen; `blend` prepared for `table`). The steps across
  /// the lanes are the kernels of kernels/depth_lanes_hwy.hpp; the rest stays per ray here.
  static void surfaces16(const Proxy& p, const FrameTable<float, Px>& table, std::span<const Ray<float>> rays,
                         const Blend& blend, Group& g) noexcept {
    using T = float;
    const int n = static_cast<int>(rays.size());
    RayLanes& r = g.r;
    unsigned valid = 0;
    for (int l = 0; l < 16; ++l) {
      const Ray<T>& ray = rays[static_cast<std::size_t>(std::min(l, n - 1))];
      const T dd = ray.direction.squaredNorm();
      if (l < n && dd > 0 && std::isfinite(dd)) valid |= 1u << l;
      r.ox[l] = ray.origin.x();
      r.oy[l] = ray.origin.y();
      r.oz[l] = ray.origin.z();
      r.vx[l] = ray.direction.x();
      r.vy[l] = ray.direction.y();
      r.vz[l] = ray.direction.z();
      r.inverse_length2[l] = T(1) / dd;
      r.length[l] = ray.direction.norm();
    }
    // The candidates: every camera against the sixteen ray lines at once. Each lane's nearest
    // is its first walk; its whole list, sorted as `collect` sorts it, is only needed when that
    // walk does not find the surface.
    auto& distance = g.distance;
    auto& near = g.near;
    auto& first = g.first;
    const std::size_t cameras = table.size();
    kernels::scan_cameras(blend.target, blend.lane, table.size(), r,
                          static_cast<T>(p.radius) * static_cast<T>(p.radius), valid, near, distance, first);
    unsigned alone = 0, walking = 0; // lanes with no camera within the radius, lanes that walk
    for (int l = 0; l < n; ++l) {
      if (first[l] < 0) {
        const Ray<T>& ray = rays[static_cast<std::size_t>(l)];
        first[l] = table.index().nearest(ray.origin, ray.direction);
        alone |= 1u << l;
        if (first[l] < 0) continue;
        const std::size_t i = static_cast<std::size_t>(first[l]);
        if (near[i] == 0) std::fill(distance[i], distance[i] + 16, std::numeric_limits<T>::infinity()); // unwritten
        near[i] = static_cast<std::uint16_t>(near[i] | 1u << l); // blended as well
        distance[i][l] = 0;
      }
      walking |= 1u << l;
    }
    const auto candidates = [&](int l, typename Proxy::template Candidates<T>& cl) {
      if (alone >> l & 1u) {
        cl.count = first[l] < 0 ? 0 : 1;
        cl.index[0] = first[l];
        cl.distance[0] = 0;
        return;
      }
      cl.count = 0;
      for (std::size_t i = 0; i < cameras; ++i)
        if (near[i] >> l & 1u) Proxy::insert(cl, static_cast<int>(i), distance[i][l]);
    };
    // The surface of each ray: the rays that share their nearest camera walk its map together;
    // where that camera does not settle it, the search goes on through each ray's next
    // candidates in turn, the rays whose next camera is the same again together.
    // Each ray's search runs through the box of everything the maps show (`DepthProxy::surface`);
    // a ray that misses it holds no surface.
    const T inf = std::numeric_limits<T>::infinity();
    WalkLanesResult search;
    alignas(64) T leave[16];
    for (int l = 0; l < 16; ++l) {
      search.t[l] = p.whole_line ? -inf : T(0);
      leave[l] = inf;
      if (l >= n) continue;
      const std::array<T, 2> stretch =
          box_stretch(rays[static_cast<std::size_t>(l)], table.frames().depth_bounds(), search.t[l]);
      if (stretch[0] < stretch[1]) {
        search.t[l] = stretch[0];
        leave[l] = stretch[1];
      } else {
        g.escaped[l] = true;
        walking &= ~(1u << l);
      }
    }
    std::fill(search.skip_begin, search.skip_begin + 16, inf);
    std::fill(search.skip_end, search.skip_end + 16, inf);
    unsigned hit = 0;
    const auto walk_round = [&](unsigned lanes, const auto& camera_of) {
      unsigned passed = 0;
      while (lanes != 0) {
        const int camera = camera_of(__builtin_ctz(lanes));
        unsigned group = 0;
        for (unsigned m = lanes; m != 0; m &= m - 1)
          if (camera_of(__builtin_ctz(m)) == camera) group |= 1u << __builtin_ctz(m);
        lanes &= ~group;
        const std::size_t i = static_cast<std::size_t>(camera);
        WalkLanesResult w;
        kernels::walk_lanes(blend.target, blend.lane[i], r, group, search, static_cast<T>(p.tolerance), w);
        for (unsigned m = group; m != 0; m &= m - 1) {
          const int l = __builtin_ctz(m);
          search.t[l] = w.t[l];
          search.skip_begin[l] = w.skip_begin[l];
          search.skip_end[l] = w.skip_end[l];
          g.escaped[l] = (w.escaped >> l & 1u) != 0 || ((w.passed >> l & 1u) != 0 && w.t[l] >= leave[l]);
          if (g.escaped[l]) w.passed &= ~(1u << l);
        }
        hit |= w.hit;
        passed |= w.passed;
      }
      return passed;
    };
    unsigned going = walk_round(walking, [&](int l) { return first[l]; });
    if (going != 0 && p.march_cameras > 1) {
      typename Proxy::template Candidates<T> c[16];
      for (unsigned m = going; m != 0; m &= m - 1) candidates(__builtin_ctz(m), c[__builtin_ctz(m)]);
      for (int j = 1; going != 0 && j < p.march_cameras; ++j) {
        for (unsigned m = going; m != 0; m &= m - 1)
          if (j >= c[__builtin_ctz(m)].count) going &= ~(1u << __builtin_ctz(m));
        going = walk_round(going, [&](int l) { return c[l].index[j]; });
      }
    }
    for (int l = 0; l < n; ++l) {
      g.t[l].reset();
      if (hit >> l & 1u) g.t[l] = search.t[l];
    }
  }

  /// `out[l] = p.surface(table, rays[l])` for up to sixteen rays (`blend` prepared for `table`).
  static void surface16(const Proxy& p, const FrameTable<float, Px>& table, std::span<const Ray<float>> rays,
                        const Blend& blend, std::optional<float>* out) noexcept {
    Group g;
    surfaces16(p, table, rays, blend, g);
    for (std::size_t l = 0; l < rays.size(); ++l) out[l] = g.escaped[l] ? std::nullopt : g.t[l];
  }

  /// `out[l] = p.sample(table, rays[l])` for up to sixteen rays (`blend` prepared for `table`).
  static void sample16(const Proxy& p, const FrameTable<float, Px>& table, std::span<const Ray<float>> rays,
                       const Blend& blend, Color* out) noexcept {
    using T = float;
    const int n = static_cast<int>(rays.size());
    Group g;
    surfaces16(p, table, rays, blend, g);
    const auto& first = g.first;
    const auto& escaped = g.escaped;
    alignas(64) T point[3][16] = {};
    unsigned blended = 0;
    for (int l = 0; l < n; ++l) {
      const Ray<T>& ray = rays[static_cast<std::size_t>(l)];
      const Vec3<T> X = g.t[l] ? ray.at(*g.t[l]) : table.point_of(ray);
      for (int j = 0; j < 3; ++j) point[j][l] = X[j];
      if (!escaped[l]) blended |= 1u << l;
    }
    // The blend: the k + 1 cameras that see each point with the smallest angles, chosen across
    // the lanes, then weighed per ray.
    const int slots = p.k + 1;
    LaneChoice best;
    kernels::choose_cameras(blend.target, blend.lane, table.size(), g.r, point, g.distance, g.near, blended, slots,
                            static_cast<T>(p.visibility_tolerance), best);
    prefetch_next(table, best, slots, n);
    // 8-bit frames, bilinear: every lane's weighing at once.
    unsigned weighed = 0;
    alignas(64) float acc[3][16], weight[16];
    if (blend.lanes) {
      for (int l = 0; l < n; ++l)
        if (!escaped[l] && best.camera[0][l] >= 0) weighed |= 1u << l;
      kernels::weigh_lanes(blend.target, blend.cameras, best, slots, p.k, weighed, Srgb8Texel::linear16(),
                           Srgb8Texel::scale, acc, weight);
    }
    for (int l = 0; l < n; ++l) {
      if (escaped[l]) {
        out[l] = table.config().background;
        continue;
      }
      if (weighed >> l & 1u) {
        const float sum[3] = {acc[0][l], acc[1][l], acc[2][l]};
        out[l] = table.finish(sum, weight[l]);
        continue;
      }
      T penalty[kDepthLaneSlots];
      int count = 0;
      for (; count < slots && best.camera[count][l] >= 0; ++count) penalty[count] = best.penalty[count][l];
      if (count == 0) {
        out[l] = table.camera_color(first[l], Vec3<T>(point[0][l], point[1][l], point[2][l]));
        continue;
      }
      out[l] = p.weigh(table, penalty, count, [&](int j) {
        return typename Proxy::template Seen<T>{best.camera[j][l], best.x[j][l], best.y[j][l]};
      });
    }
  }

  // Asks for the texels that the next sixteen rays of the row will likely read from the cameras
  // these chose: those of the last lane, 16 to 32 pixels further along both rows of each of its
  // bilinear taps (a row of rays moves about a camera pixel a ray). Row after row, each camera
  // gives a new texel row, and there are more of these streams than the hardware follows.
  static void prefetch_next(const FrameTable<float, Px>& table, const LaneChoice& best, int slots, int n) noexcept {
    const int l = n - 1;
    for (int j = 0; j < slots; ++j) {
      const int i = best.camera[j][l];
      if (i < 0) break;
      const auto& cam = table.camera(static_cast<std::size_t>(i));
      const int x = std::min(static_cast<int>(best.x[j][l]) + 16, cam.width - 1);
      const int y = std::clamp(static_cast<int>(best.y[j][l]), 0, cam.height - 1);
      const auto* row = cam.texels + static_cast<std::ptrdiff_t>(y) * cam.width + x;
      const int ahead = std::min(16, cam.width - 1 - x);
      __builtin_prefetch(row);
      __builtin_prefetch(row + ahead);
      if (y + 1 < cam.height) {
        __builtin_prefetch(row + cam.width);
        __builtin_prefetch(row + cam.width + ahead);
      }
    }
  }
};

#endif

} // namespace mpr::detail
