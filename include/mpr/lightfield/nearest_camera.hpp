#pragma once
/// \file
/// `mpr::NearestCamera`: the light-field interpolation that answers a ray from the one camera
/// whose centre is nearest to the ray line (light field rendering, Levoy & Hanrahan 1996, with
/// the nearest-neighbour reconstruction used for General Linear Cameras by Yu & McMillan 2004).

#include <mpr/core/concepts.hpp>
#include <mpr/core/ray_grid.hpp>
#include <mpr/lightfield/frame_runs.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/interpolation.hpp>
#include <mpr/lightfield/plane_rows.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

namespace mpr {

/// The camera whose centre is nearest to the ray *line* (not only the half-line), and the pixel
/// where that camera sees the ray's point. Ties (equal distance) go to the lowest camera index.
/// When that camera does not see the point (behind it or outside its image), the background.
///
/// Batch: each ray first tries the previous ray's camera with a proof (below). Tile, on a planar
/// array: a row at a time, the choice proved for blocks of 32 rays by a vectorised test, and
/// each run of pixels with one camera added by one shift-and-add; from a `RayGrid` (rays affine in
/// the pixel) the same without a ray per pixel. Equal to `sample` up to the shift-and-add's 1e-3
/// pixel.
struct NearestCamera {
  template <std::floating_point T, class Px>
  [[nodiscard]] Color sample(const FrameTable<T, Px>& table, const Ray<T>& ray) const noexcept {
    const Vec3<T> X = table.point_of(ray);
    return table.camera_color(table.index().nearest(ray.origin, ray.direction), X);
  }

  template <std::floating_point T, class Px>
  void sample_rays(const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, std::span<Color> out) const noexcept {
    int hint = -1;
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const int k = nearest_with_hint(table, rays[i], hint);
      out[i] = table.camera_color(k, table.point_of(rays[i]));
      hint = k;
    }
  }

  template <std::floating_point T, class Px>
  void sample_tile(const FrameTable<T, Px>& table, std::span<const Ray<T>> rays, int width,
                   std::span<Color> out) const noexcept {
    const std::size_t w = tile_width(rays.size(), width);
    if (w > 0 && table.plane() &&
        row_path(table, *table.plane(), rays.size() / w, w, out,
                 TileRows<T, Px>{table, *table.plane(), rays.data(), w}))
      return;
    for_each_row(rays, w, out, [&](std::span<const Ray<T>> r, std::span<Color> o) { sample_rays(table, r, o); });
  }

  /// The tile path for a tile whose rays are affine in the pixel (`GridRaySampler`): the same
  /// row path, its crossings computed from the grid instead of from one ray per pixel. False on
  /// a non-planar array.
  template <std::floating_point T, class Px, class ExactRay>
  [[nodiscard]] bool sample_grid(const FrameTable<T, Px>& table, const RayGrid<T, ExactRay>& grid,
                                 std::span<Color> out) const noexcept {
    if (!table.plane() || grid.width <= 0 || grid.rows <= 0) return false;
    return row_path(table, *table.plane(), static_cast<std::size_t>(grid.rows), static_cast<std::size_t>(grid.width),
                    out, GridRows<T, Px, ExactRay>{table, *table.plane(), grid});
  }

  /// The nearest camera to the ray line, trying `hint` first. On a planar array, camera k is
  /// provably the unique nearest when (a) every listed neighbour j is strictly farther from the
  /// line, and (b) every other camera is too: such a c_j has distance >= cos(theta) |c_j - x|
  /// >= cos(theta) (separation_k - |c_k - x|), where x is where the line meets the camera plane
  /// and theta its angle to the plane normal; (b) requires that bound to exceed d_k. When a
  /// neighbour is nearer, the proof is retried from it (a short walk); otherwise, or on a
  /// non-planar array, the ball tree decides.
  template <std::floating_point T, class Px>
  [[nodiscard]] static int nearest_with_hint(const FrameTable<T, Px>& table, const Ray<T>& ray, int hint) noexcept {
    if (table.plane() && hint >= 0) {
      const ArrayPlane<T>& plane = *table.plane();
      Vec3<T> x = Vec3<T>::Zero();
      T cosine = 0;
      const T dd = ray.direction.squaredNorm();
      if (dd > 0 && std::isfinite(dd) && plane.hit(ray, x, cosine)) {
        const T inv = T(1) / dd;
        const T margin = T(1e-4) * plane.extent;
        int k = hint;
        for (int step = 0; step < 4; ++step) {
          const std::size_t ks = static_cast<std::size_t>(k);
          const Vec3<T>& centre = table.camera(ks).centre;
          const T dk2 = line_distance2(centre, ray.origin, ray.direction, inv);
          int nearer = -1;
          T best = dk2;
          bool proved = true;
          for (int m = plane.neighbours_begin[ks]; m < plane.neighbours_end[ks]; ++m) {
            const int j = plane.neighbours[static_cast<std::size_t>(m)];
            const T dj2 =
                line_distance2(table.camera(static_cast<std::size_t>(j)).centre, ray.origin, ray.direction, inv);
            if (dj2 < best) {
              best = dj2;
              nearer = j;
            }
            if (!(dj2 > dk2 * T(1.0001) + margin * margin)) proved = false;
          }
          if (nearer >= 0) {
            k = nearer;
            continue;
          }
          if (proved && cosine * (plane.separation[ks] - (centre - x).norm()) > std::sqrt(dk2) * T(1.001) + margin)
            return k;
          break;
        }
      }
    }
    return table.index().nearest(ray.origin, ray.direction);
  }

private:
  static constexpr std::size_t kProofBlock = 32;

  // A row at a time on a planar array. Once camera k is chosen for a pixel, the following
  // pixels are proved to keep k a block at a time (`detail::prove_nearest`, vectorised); the
  // first pixel the proof does not cover gets `nearest_with_hint`, which is exact. The block
  // proof uses the two facts of `nearest_with_hint`: (a) every listed neighbour j is farther than
  // k by a margin; (b) an unlisted camera j has distance >= cos(theta) (sep_k - r) with
  // r = |c_k - x| the in-plane distance to the crossing x, while d_k <= r; so d_j > d_k when
  // r < rho = (cos_min sep_k - margin) / (cos_min + 1.001), cos_min the least cosine of the row.
  // Each run of pixels with one camera is a shift-and-add of one camera row when the run's
  // points are evenly spaced and lie along the camera's rows, a projective row when they are
  // evenly spaced otherwise (a tilted plane), else per ray.
  // `source` gives the rows (`TileRows` or `GridRows`).
  template <std::floating_point T, class Px, class Rows>
  static bool row_path(const FrameTable<T, Px>& table, const ArrayPlane<T>& plane, std::size_t rows, std::size_t w,
                       std::span<Color> out, const Rows& source) noexcept {
    using Flag = typename PlaneRowScratch<T>::Flag;
    thread_local PlaneRowScratch<T> scratch;
    if (!scratch.reserve(w)) return false;
    const T margin = T(1e-4) * plane.extent;
    Flag pass[kProofBlock];
    T threshold[kProofBlock];
    for (std::size_t r = 0; r < rows; ++r) {
      bool all_cross = true, even = false;
      T slack = 0;
      const T cos_min = source.prepare(r, scratch, all_cross, even, slack);
      const Vec3<T>* points = scratch.points.data();
      Color* o = out.data() + r * w;
      // Pixels [s0, e) of camera kk: one shift-and-add when the points are evenly spaced.
      const auto emit = [&](std::size_t s0, std::size_t e, int kk) noexcept {
        bool copied = false;
        if (even && kk >= 0 && e - s0 >= 8 && !table.camera(static_cast<std::size_t>(kk)).distorted) {
          // Added straight into the output (packed channel triples, as `PixelTraits<Rgb8>` reads them).
          static_assert(sizeof(Color) == 3 * sizeof(float));
          float* acc = o[s0].data();
          float* weight = scratch.weight.data() + s0;
          const std::size_t n = e - s0;
          std::fill(acc, acc + 3 * n, 0.0f);
          std::fill(weight, weight + n, 0.0f);
          const auto& c = table.camera(static_cast<std::size_t>(kk));
          copied =
              shift_add(table, c, points + s0, n, acc, weight) || add_projective(table, c, points + s0, n, acc, weight);
          // One camera: weight is exactly 1 where it added its pixel, 0 where it sees nothing.
          if (copied) {
            unsigned unseen = 0;
            for (std::size_t i = 0; i < n; ++i) unseen += weight[i] > 0 ? 0u : 1u;
            if (unseen > 0)
              for (std::size_t i = 0; i < n; ++i)
                if (!(weight[i] > 0)) o[s0 + i] = table.config().background;
          }
        }
        if (!copied)
          for (std::size_t i = s0; i < e; ++i) o[i] = table.camera_color(kk, points[i]);
      };
      int k = -1, prepared = -1, block_k = -1;
      std::size_t run = 0;                   // the first pixel of camera k's run
      std::size_t block = 0, block_size = 0; // the pixels whose proof flags `pass` holds, for block_k
      detail::NearestCandidate<T> candidate{};
      for (std::size_t i = 0; i < w;) {
        if (k >= 0) {
          if (prepared != k) {
            // With crossings up to `slack` from the exact rays' (a grid row), rho shrinks by
            // slack and the neighbours must be farther by 2 slack: (d_k + 2 slack)^2 <= d_k^2 +
            // 4 slack (rho + slack), since d_k <= r < rho.
            const std::size_t ks = static_cast<std::size_t>(k);
            const T reach = cos_min * plane.separation[ks] - margin - slack * (cos_min + T(1.001));
            const T rho = reach > 0 ? reach / (cos_min + T(1.001)) : T(0);
            candidate = {plane.centre_u[ks],
                         plane.centre_v[ks],
                         rho * rho,
                         margin * margin + 4 * slack * (rho + slack),
                         plane.neighbour_u.data() + plane.neighbours_begin[ks],
                         plane.neighbour_v.data() + plane.neighbours_begin[ks],
                         plane.neighbours_end[ks] - plane.neighbours_begin[ks]};
            prepared = k;
          }
          // A block's flags stay valid for its camera: after a fallback that kept k, the scan
          // goes on in the same block.
          if (block_k != k || i >= block + block_size) {
            block = i;
            block_size = std::min(kProofBlock, w - i);
            block_k = k;
            detail::prove_nearest(scratch.plane_rays(i), block_size, candidate, pass, threshold);
          }
          std::size_t p = i - block;
          while (p < block_size && pass[p] != 0) ++p;
          i = block + p;
          if (p == block_size) continue;
        }
        const int next = nearest_with_hint(table, source.ray(r, i), k);
        if (next != k) {
          if (i > run) emit(run, i, k);
          run = i;
          k = next;
        }
        ++i;
      }
      emit(run, w, k);
    }
    return true;
  }
};

} // namespace mpr
