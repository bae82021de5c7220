#pragma once
/// \file
/// Runs of rays against one camera of a `FrameTable`: the shared row machinery of the light-field
/// interpolations. A run whose points are evenly spaced along a line (a row of a planar image
/// surface) and seen one camera pixel apart is added by shift-and-add of two camera rows
/// (refocusing as in Isaksen et al. 2000; the shift-and-add of synthetic-aperture photography,
/// Vaish et al. 2004), else ray by ray. An interpolation decides which cameras weigh which rays;
/// these functions add them.

#include <mpr/lightfield/accumulation/affine_block.hpp>
#include <mpr/lightfield/accumulation/shift_tile.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/kernels/lerp_row_or_linear.hpp>
#include <mpr/lightfield/kernels/projective_row.hpp>
#include <mpr/lightfield/kernels/projective_tile.hpp>
#include <mpr/lightfield/kernels/resample_row.hpp>
#include <mpr/lightfield/kernels/resample_tile.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>
#include <mpr/lightfield/lerp_row_cache.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

namespace mpr {

/// Points p_i = p_0 + i (p_{n-1} - p_0) / (n - 1) up to rounding (64 ulp of the end points'
/// magnitude, per coordinate). Precondition: n >= 2.
template <std::floating_point T>
[[nodiscard]] bool evenly_spaced(const Vec3<T>* p, std::size_t n) noexcept {
  const Vec3<T> step = (p[n - 1] - p[0]) / static_cast<T>(n - 1);
  const T scale = p[0].cwiseAbs().maxCoeff() + p[n - 1].cwiseAbs().maxCoeff();
  const T tolerance = T(64) * std::numeric_limits<T>::epsilon() * scale;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const Vec3<T> predicted = p[0] + static_cast<T>(i) * step;
    if (!((p[i] - predicted).cwiseAbs().maxCoeff() <= tolerance)) return false;
  }
  return true;
}

/// `evenly_spaced` for points also given as coordinates relative to some fixed point (structure
/// of arrays, vectorised); the tolerance is that of the absolute points `p`.
template <std::floating_point T>
[[nodiscard]] bool evenly_spaced(const Vec3<T>* p, const T* const (&relative)[3], std::size_t n) noexcept {
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max())) return evenly_spaced(p, n);
  const T scale = p[0].cwiseAbs().maxCoeff() + p[n - 1].cwiseAbs().maxCoeff();
  const T tolerance = T(64) * std::numeric_limits<T>::epsilon() * scale;
  return detail::evenly_spaced(relative[0], relative[1], relative[2], static_cast<int>(n), tolerance);
}

/// Where a camera sees a run of points: continuous pixel coordinates of its first (x0, y0),
/// middle (index n / 2: xm, ym) and last (x1, y1) points; and, when known, where the camera
/// asked next (`shift_add`'s `ahead`) sees point i, about (ahead_x + ahead_dx i, ahead_y +
/// ahead_dy i): for its prefetches only (ahead_x NaN: not known, projected instead).
template <std::floating_point T>
struct RunSight {
  T x0, y0, xm, ym, x1, y1;
  T ahead_x = std::numeric_limits<T>::quiet_NaN(), ahead_y = 0, ahead_dx = 0, ahead_dy = 0;
};

namespace detail {
// The shift-and-add kernel over the n pixels of texel rows a and b (flat channel arrays); with
// per-ray weights, those are spread over the three channel slots of each pixel first, a stack
// buffer at a time.
template <class Texel>
void add_texel_rows(const Texel* a, const Texel* b, RowWeights w, const float* ray_weight, float* acc,
                    std::size_t n) noexcept {
  using channel = typename Texel::channel_type;
  // Texels are packed channel triples (static_assert in frame_set.hpp): a row is one flat array
  // of 3 n channels.
  const channel* fa = a->c;
  const channel* fb = b->c;
  if (ray_weight == nullptr) return shift_add_flat(fa, fb, w, nullptr, acc, 3 * n);
  constexpr std::size_t kStep = 256;
  float spread[3 * kStep];
  for (std::size_t s0 = 0; s0 < n; s0 += kStep) {
    const std::size_t m = std::min(kStep, n - s0);
    for (std::size_t i = 0; i < m; ++i) spread[3 * i] = spread[3 * i + 1] = spread[3 * i + 2] = ray_weight[s0 + i];
    shift_add_flat(fa + 3 * s0, fb + 3 * s0, w, spread, acc + 3 * s0, 3 * m);
  }
}
} // namespace detail

namespace detail {
// Where camera `ahead` (nullptr: none) sees X, point i of a run: the channels of its texel at
// the pixel and of the one below it, the pixel clamped to the image so that both exist. The
// position comes from `sight` when it holds the ahead camera's (`RunSight::ahead_x`), else X is
// projected. {nullptr, nullptr} when there is no camera, X is not in front of it, or the position
// is not finite or beyond 1e8 pixels. For prefetches only.
template <std::floating_point T, class Px>
[[nodiscard]] std::array<const typename FrameTable<T, Px>::texel_type::channel_type*, 2>
ahead_rows(const typename FrameTable<T, Px>::Camera* ahead, const Vec3<T>& X, const RunSight<T>* sight = nullptr,
           std::size_t i = 0) noexcept {
  T x, y;
  if (ahead == nullptr || ahead->height < 2) return {};
  if (sight != nullptr && !std::isnan(sight->ahead_x)) {
    x = sight->ahead_x + sight->ahead_dx * static_cast<T>(i);
    y = sight->ahead_y + sight->ahead_dy * static_cast<T>(i);
    if (!(std::abs(x) < T(1e8) && std::abs(y) < T(1e8))) return {}; // keeps the conversions in range
  } else if (!FrameTable<T, Px>::project_any(*ahead, X, x, y)) {
    return {};
  }
  const auto ix = static_cast<std::ptrdiff_t>(std::clamp(std::floor(x), T(0), static_cast<T>(ahead->width - 1)));
  const auto iy = static_cast<std::ptrdiff_t>(std::clamp(std::floor(y), T(0), static_cast<T>(ahead->height - 2)));
  const auto* texel = ahead->texels + iy * ahead->width + ix;
  return {texel->c, texel[ahead->width].c};
}

// Pixels [0, first) and [last, n) of a run that camera c sees at x = x0 + step i (step > 0),
// around the part added by shift-and-add: those whose x lies within 0.01 pixel of the image's
// columns [-0.5, width - 0.5) go ray by ray; those beyond are outside c's image (the run's affine
// model holds within 1e-3 pixel), so c adds nothing to them and they are skipped.
template <std::floating_point T, class Px>
void add_run_edges(const FrameTable<T, Px>& table, const typename FrameTable<T, Px>::Camera& c, const Vec3<T>* points,
                   std::size_t n, std::size_t first, std::size_t last, T x0, T step, float* acc, float* weight,
                   const float* ray_weight) noexcept {
  const T lo = T(-0.51), hi = static_cast<T>(c.width) - T(0.49);
  std::size_t begin = 0, end = n;
  while (begin < first && x0 + step * static_cast<T>(begin) < lo) ++begin;
  while (end > last && x0 + step * static_cast<T>(end - 1) >= hi) --end;
  table.add_per_ray(c, points + begin, first - begin, acc + 3 * begin, weight + begin,
                    ray_weight != nullptr ? ray_weight + begin : nullptr);
  table.add_per_ray(c, points + last, end - last, acc + 3 * last, weight + last,
                    ray_weight != nullptr ? ray_weight + last : nullptr);
}

// The pixels i in [0, n) with 0 <= x0 + step i <= width - 1 (step > 0): [first, last).
template <std::floating_point T>
[[nodiscard]] std::array<std::size_t, 2> resampled_span(T x0, T step, std::size_t n, int width) noexcept {
  const T right = static_cast<T>(width - 1);
  std::size_t first = x0 >= 0 ? 0 : static_cast<std::size_t>(std::min(std::ceil(-x0 / step), static_cast<T>(n)));
  while (first < n && x0 + step * static_cast<T>(first) < 0) ++first;
  while (first > 0 && x0 + step * static_cast<T>(first - 1) >= 0) --first;
  std::size_t last =
      x0 > right ? 0 : static_cast<std::size_t>(std::min(std::floor((right - x0) / step) + 1, static_cast<T>(n)));
  while (last > first && x0 + step * static_cast<T>(last - 1) > right) --last;
  while (last < n && x0 + step * static_cast<T>(last) <= right) ++last;
  return {first, last};
}

// The rest of `shift_add` for a run seen at x0 + step i on camera rows iy, iy1 (iy + 1, or the
// same row in the image's border rows; ay the vertical offset): pixels whose texel pairs lie
// inside the row are blended from two resampled rows (`LerpRowCache::resampled`), the others go
// ray by ray. False when none lies inside.
template <std::floating_point T, class Px>
bool shift_add_resampled(const FrameTable<T, Px>& table, const typename FrameTable<T, Px>::Camera& c,
                         const Vec3<T>* points, std::size_t n, T x0, T step, int iy, int iy1, float ay, float* acc,
                         float* weight, const float* ray_weight, LerpRowCache* cache,
                         const typename FrameTable<T, Px>::Camera* ahead, const RunSight<T>* sight) noexcept {
  using texel_type = typename FrameTable<T, Px>::texel_type;
  const std::array<std::size_t, 2> span = resampled_span(x0, step, n, c.width);
  const std::size_t first = span[0], last = span[1];
  if (first >= last) return false;
  add_run_edges(table, c, points, n, first, last, x0, step, acc, weight, ray_weight);
  thread_local LerpRowCache own;
  LerpRowCache& rows = cache != nullptr ? *cache : own;
  if (cache == nullptr) own.clear();
  const std::size_t m = last - first;
  const double x = static_cast<double>(x0) + static_cast<double>(step) * static_cast<double>(first);
  const auto* row0 = c.texels[static_cast<std::ptrdiff_t>(iy) * c.width].c;
  const auto* row1 = c.texels[static_cast<std::ptrdiff_t>(iy1) * c.width].c;
  const std::uint16_t* lut = texel_decode_table<texel_type>();
  const std::size_t width = static_cast<std::size_t>(c.width);
  const float* rw = ray_weight != nullptr ? ray_weight + first : nullptr;
  const auto add_weights = [&]() noexcept {
    for (std::size_t i = first; i < last; ++i)
      weight[i] += ray_weight == nullptr ? 1.0f : ray_weight[i] > 0 ? ray_weight[i] : 0.0f;
  };
  if (step >= T(1.999)) {
    // Output rows this far apart in the camera (at an isotropic scale) share no camera row, so
    // none is worth keeping: both are resampled and blended in one pass (where the pixels read
    // their texels kept for the next row at the same positions: the camera's next run).
    thread_local ResampleTileWork work;
    if (resample_blend(row0, row1, width, lut, x, static_cast<double>(step), texel_type::scale, ay, rw, acc + 3 * first,
                       m, work)) {
      add_weights();
      return true;
    }
  }
  const auto next = ahead_rows<T, Px>(ahead, points[first], sight, first);
  const float* h0 = rows.resampled(row0, width, lut, m, x, static_cast<double>(step), texel_type::scale, next[0]);
  const float* h1 = h0 != nullptr
                        ? rows.resampled(row1, width, lut, m, x, static_cast<double>(step), texel_type::scale, next[1])
                        : nullptr;
  if (h1 == nullptr) { // out of memory
    table.add_per_ray(c, points + first, m, acc + 3 * first, weight + first, rw);
    return true;
  }
  blend_rows(h0, h1, 1 - ay, ay, rw, acc + 3 * first, m);
  add_weights();
  return true;
}
} // namespace detail

/// Camera c's contribution to a run of n evenly spaced points by shift-and-add: when c sees the
/// run one camera pixel apart along its rows (checked at both ends and the middle against the
/// affine model, within 1e-3 pixel: below one 8-bit level after averaging, since bilinear
/// interpolation is continuous), acc and weight get c's bilinear pixels (times `ray_weight[i]`
/// when given; rays of weight <= 0 are skipped) and true is returned. Pixels near the image's
/// left and right edges go ray by ray. False (nothing added) when the run does not qualify.
/// With a `cache`, the bilinear blend is done in its separable form on cached rows (see
/// `LerpRowCache`). `ahead` (nullptr: none): the camera that will be asked for the same run
/// next (a tile's next camera), whose texels for the run are prefetched while c's rows are
/// interpolated. `sight` (nullptr: projected here): where c sees the run's first, middle (n / 2)
/// and last points, when the caller knows it (`detail::AffineSight`), and where `ahead` does.
/// Preconditions: n >= 2, c undistorted, bilinear filtering.
template <std::floating_point T, class Px>
bool shift_add(const FrameTable<T, Px>& table, const typename FrameTable<T, Px>::Camera& c, const Vec3<T>* points,
               std::size_t n, float* acc, float* weight, const float* ray_weight = nullptr,
               LerpRowCache* cache = nullptr, const typename FrameTable<T, Px>::Camera* ahead = nullptr,
               const RunSight<T>* sight = nullptr) noexcept {
  using Table = FrameTable<T, Px>;
  using texel_type = typename Table::texel_type;
  T x0, y0, x1, y1, xm, ym;
  if (sight != nullptr) {
    x0 = sight->x0, y0 = sight->y0, xm = sight->xm, ym = sight->ym, x1 = sight->x1, y1 = sight->y1;
  } else if (!Table::project_any(c, points[0], x0, y0) || !Table::project_any(c, points[n - 1], x1, y1) ||
             !Table::project_any(c, points[n / 2], xm, ym)) {
    return false;
  }
  const T span = static_cast<T>(n - 1);
  constexpr T kTolerance = T(1e-3);
  // The step along the camera row: one pixel; or, in the separable form (8-bit codes, or a
  // cache), any step up to `detail::kResampleMaxStep` (a resampled row: 2 for output at half the
  // cameras' scale, 1.458 for a 960x540 view of 1400x800 cameras) or a whole 3 to 8 pixels.
  constexpr bool codes = std::is_same_v<typename texel_type::channel_type, std::uint8_t>;
  const bool separable = codes || cache != nullptr;
  if (!(std::abs(y1 - y0) <= kTolerance && std::abs(ym - y0) <= kTolerance)) return false;
  // The nearest whole step (floor: inlined where std::round is a library call; ties cannot pass
  // the tolerance test below).
  const T step = (x1 - x0) / span, steps = std::floor(step + T(0.5));
  // Steps of 2 resample too: computing only the pixels kept beats a whole row then thinned (9%
  // on Chess at 700x400, docs/performance.md).
  const bool whole = (steps == 1 || (separable && steps >= 3 && steps <= 8)) &&
                     std::abs(x1 - x0 - steps * span) <= kTolerance &&
                     std::abs(xm - x0 - steps * static_cast<T>(n / 2)) <= kTolerance;
  const bool resample = !whole && separable && step > 0 && step <= T(detail::kResampleMaxStep) &&
                        std::abs(xm - x0 - step * static_cast<T>(n / 2)) <= kTolerance;
  if (!whole && !resample) return false;
  // Rows wholly above or below the image: nothing to add (every per-ray y is outside too).
  if (y0 < T(-0.5) - kTolerance || y0 >= static_cast<T>(c.height) - T(0.5) + kTolerance) return true;
  if (!(std::abs(x0) < T(1e8) && std::abs(y0) < T(1e8))) return false; // keeps the integer conversions in range
  long lx = 0, ly = 0;
  T ax_t = 0, ay_t = 0;
  if (whole) {
    detail::snap_to_texel(x0, lx, ax_t);
    detail::snap_to_texel(y0, ly, ay_t);
  } else {
    lx = static_cast<long>(std::floor(x0));
    ly = static_cast<long>(std::floor(y0));
    ay_t = y0 - std::floor(y0);
  }
  const int ix = static_cast<int>(lx), iy = static_cast<int>(ly);
  // A row in the image's half-pixel border (y in [-0.5, 0) or [height - 1, height - 0.5)) reads
  // the edge row twice, as the bilinear pixel clamps it; within the tolerance of the border's
  // outer edge, where points may fall either side, it goes ray by ray.
  const bool border = iy < 0 || iy + 1 > c.height - 1;
  if (border && !(y0 >= T(-0.5) + kTolerance && y0 < static_cast<T>(c.height) - T(0.5) - kTolerance)) return false;
  const int row_a = std::clamp(iy, 0, c.height - 1), row_b = std::clamp(iy + 1, 0, c.height - 1);
  if (resample)
    return detail::shift_add_resampled(table, c, points, n, x0, step, row_a, row_b, static_cast<float>(ay_t), acc,
                                       weight, ray_weight, cache, ahead, sight);
  const std::size_t stride = static_cast<std::size_t>(steps);
  // Pixels i whose two texels ix + k i, ix + k i + 1 (k the stride) lie inside the row are shifted
  // and added; the others (near or past the left and right edges) go ray by ray.
  const long k = static_cast<long>(stride);
  // A stride of 1, the common case, without the two divisions.
  const long first = k == 1 ? std::max(0L, -static_cast<long>(ix)) : std::max(0L, (-static_cast<long>(ix) + k - 1) / k);
  const long room = static_cast<long>(c.width) - 2 - ix; // the last texel pair starts at ix + room
  const long last = room < 0 ? 0L : std::min(static_cast<long>(n), (k == 1 ? room : room / k) + 1);
  if (first >= last) return false;
  const std::size_t i_begin = static_cast<std::size_t>(first), i_end = static_cast<std::size_t>(last);
  detail::add_run_edges(table, c, points, n, i_begin, i_end, x0, steps, acc, weight, ray_weight);
  const float ax = static_cast<float>(ax_t), ay = static_cast<float>(ay_t);
  const float sc = texel_type::scale;
  const texel_type* a = c.texels + static_cast<std::ptrdiff_t>(row_a) * c.width + ix;
  const texel_type* b = c.texels + static_cast<std::ptrdiff_t>(row_b) * c.width + ix;
  // The next output row reads row iy + 2 (iy + 1 at a vertical offset of 0) over about the same
  // columns: ask for it now. Short runs (nearest camera, cylinder aperture) are too short for the
  // hardware prefetcher to pick up; on long ones (whole-row refocusing) it does, and extra
  // prefetches cost time.
  const texel_type* below = ay == 0 ? b : b + c.width;
  // The rows' 16-bit linear copy where the frames hold one and the separable form below reads it
  // (`detail::lerp_row_reads_linear`), else nullptr.
  const bool linear_rows = detail::lerp_row_reads_linear(detail::dispatch_level());
  const auto linear_of = [linear_rows](const typename Table::Camera* cam,
                                       const auto* code) noexcept -> const std::uint16_t* {
    return linear_rows && cam != nullptr && cam->linear != nullptr && code != nullptr
               ? cam->linear + (code - cam->texels->c)
               : nullptr;
  };
  if (!border && iy + (ay == 0 ? 1 : 2) < c.height && i_end - i_begin < 1024 && stride == 1) {
    if (const std::uint16_t* lb = linear_of(&c, below->c))
      detail::prefetch_range(lb + 3 * i_begin, lb + 3 * (i_end + 1));
    else
      detail::prefetch_range(below + i_begin, below + i_end + 1);
  }
  const std::size_t m = i_end - i_begin;
  const float* rw = ray_weight != nullptr ? ray_weight + i_begin : nullptr;
  // One camera row (a vertical offset of 0) one pixel apart: decoded, interpolated and added
  // (times the rays' weights, whose sums are added too) in one pass where the level has it.
  const bool one_pass = ay == 0 && stride == 1 &&
                        detail::add_row_one_pass(a[i_begin].c, texel_decode_table<texel_type>(), ax, sc, rw,
                                                 acc + 3 * i_begin, weight + i_begin, 3 * m,
                                                 detail::ahead_rows<T, Px>(ahead, points[i_begin], sight, i_begin)[0]);
  if (one_pass && rw != nullptr) return true; // the weights added too
  if (!one_pass && (codes || cache != nullptr)) {
    // The separable form: always for 8-bit codes, whose decode is then done once per texel.
    thread_local LerpRowCache own;
    LerpRowCache& rows = cache != nullptr ? *cache : own;
    if (cache == nullptr) own.clear();
    const std::uint16_t* lut = texel_decode_table<texel_type>();
    const std::ptrdiff_t start = static_cast<std::ptrdiff_t>(stride * i_begin);
    const auto next = detail::ahead_rows<T, Px>(ahead, points[i_begin], sight, i_begin);
    const float* h0 =
        rows.row(a[start].c, lut, 3 * m, ax, sc, stride, next[0], linear_of(&c, a[start].c), linear_of(ahead, next[0]));
    // At a vertical offset of 0 (snapped) the second row has weight 0 and is not read.
    const float* h1 = h0 == nullptr || ay == 0 ? h0
                                               : rows.row(b[start].c, lut, 3 * m, ax, sc, stride, next[1],
                                                          linear_of(&c, b[start].c), linear_of(ahead, next[1]));
    if (h1 != nullptr) {
      detail::blend_rows(h0, h1, 1 - ay, ay, rw, acc + 3 * i_begin, m);
    } else {
      table.add_per_ray(c, points + i_begin, m, acc + 3 * i_begin, weight + i_begin, rw); // out of memory
      return true;
    }
  } else if (!one_pass) {
    if constexpr (!codes) {
      const detail::RowWeights w{(1 - ax) * (1 - ay) * sc, ax * (1 - ay) * sc, (1 - ax) * ay * sc, ax * ay * sc};
      detail::add_texel_rows(a + i_begin, b + i_begin, w, rw, acc + 3 * i_begin, m);
    }
  }
  if (ray_weight != nullptr) {
    for (std::size_t i = i_begin; i < i_end; ++i) weight[i] += ray_weight[i] > 0 ? ray_weight[i] : 0.0f; // no branch
  } else {
    for (std::size_t i = i_begin; i < i_end; ++i) weight[i] += 1.0f;
  }
  return true;
}

namespace detail {
// Camera c's homography of the run of n evenly spaced points (from its end points, in double),
// as the projective-row kernel takes it; checked at the middle point against `project_any`
// within 1e-3 pixel, as `shift_add` checks its own. False when the run does not qualify.
template <std::floating_point T, class Px>
bool projective_row_of(const typename FrameTable<T, Px>::Camera& c, const Vec3<T>* points, std::size_t n,
                       ProjectiveRow<T, typename FrameTable<T, Px>::texel_type::channel_type>& row) noexcept {
  using Table = FrameTable<T, Px>;
  const Vec3<double> p0 = points[0].template cast<double>();
  const Vec3<double> step = (points[n - 1].template cast<double>() - p0) / static_cast<double>(n - 1);
  double h0[3], hs[3];
  for (int r = 0; r < 3; ++r) {
    const T* P = c.P + 4 * r;
    h0[r] = P[0] * p0.x() + P[1] * p0.y() + P[2] * p0.z() + P[3];
    hs[r] = P[0] * step.x() + P[1] * step.y() + P[2] * step.z();
  }
  const std::size_t mid = n / 2;
  const double wm = h0[2] + static_cast<double>(mid) * hs[2];
  T xm, ym;
  if (!(wm > 0) || !Table::project_any(c, points[mid], xm, ym)) {
    // The middle point behind the camera: when the model agrees (w <= 0 there too), the kernel
    // skips it like `project` would; a disagreement goes ray by ray.
    if (wm > 0 || Table::project_any(c, points[mid], xm, ym)) return false;
  } else {
    constexpr double kTolerance = 1e-3;
    const double mx = (h0[0] + static_cast<double>(mid) * hs[0]) / wm;
    const double my = (h0[1] + static_cast<double>(mid) * hs[1]) / wm;
    if (!(std::abs(mx - static_cast<double>(xm)) <= kTolerance && std::abs(my - static_cast<double>(ym)) <= kTolerance))
      return false;
  }
  if (!gather_indexable(c.width, c.height)) return false;
  row = {{static_cast<T>(h0[0]), static_cast<T>(h0[1]), static_cast<T>(h0[2])},
         {static_cast<T>(hs[0]), static_cast<T>(hs[1]), static_cast<T>(hs[2])},
         c.width,
         c.height,
         c.texels->c,
         Table::texel_type::scale,
         texel_decode_table<typename Table::texel_type>(),
         c.linear};
  return true;
}
} // namespace detail

/// Camera c's contribution to a run of n evenly spaced points seen at any spacing and angle: the
/// camera's homography of the run's line (`detail::projective_row_of`) drives the projective-row
/// kernel, which gathers each point's bilinear pixel (`detail::projective_row`). False (nothing
/// added) when the run does not qualify.
/// Preconditions: n >= 2, c undistorted, bilinear filtering, `evenly_spaced(points, n)`.
template <std::floating_point T, class Px>
bool add_projective(const FrameTable<T, Px>& /*table*/, const typename FrameTable<T, Px>::Camera& c,
                    const Vec3<T>* points, std::size_t n, float* acc, float* weight,
                    const float* ray_weight = nullptr) noexcept {
  detail::ProjectiveRow<T, typename FrameTable<T, Px>::texel_type::channel_type> row;
  if (!detail::projective_row_of<T, Px>(c, points, n, row)) return false;
  detail::projective_row(row, n, ray_weight, acc, weight);
  return true;
}

/// The most runs `add_projective_tile` takes at once.
inline constexpr std::size_t kMaxTileRuns = 64;

/// Camera c's contribution to runs of n evenly spaced points each (run r at points[r], adding to
/// out[r]: acc, weight and ray weights as in `add_projective`), each run as in `add_projective`,
/// all at once (`detail::projective_tile`: on AVX-512 with VBMI the texels the runs share are
/// decoded once). False (nothing added) when any run does not qualify, or more than `kMaxTileRuns`.
/// Preconditions: n >= 2, c undistorted, bilinear filtering, every run `evenly_spaced`,
/// out.size() == points.size().
template <std::floating_point T, class Px>
bool add_projective_tile(const FrameTable<T, Px>& /*table*/, const typename FrameTable<T, Px>::Camera& c,
                         std::span<const Vec3<T>* const> points, std::span<const detail::TileRowOut> out,
                         std::size_t n) noexcept {
  using Row = detail::ProjectiveRow<T, typename FrameTable<T, Px>::texel_type::channel_type>;
  Row row[kMaxTileRuns];
  if (points.size() > kMaxTileRuns) return false;
  for (std::size_t r = 0; r < points.size(); ++r)
    if (!detail::projective_row_of<T, Px>(c, points[r], n, row[r])) return false;
  detail::projective_tile(std::span<const Row>(row, points.size()), out, n);
  return true;
}

/// The fewest points `add_run` adds as a run (shift-and-add or projective row); shorter runs go
/// ray by ray.
inline constexpr std::size_t kShortestRun = 8;

/// Camera c's (weighted) contribution to a run of n points: shift-and-add when the run
/// qualifies (`even`: its points are evenly spaced, see `evenly_spaced`; bilinear filtering
/// assumed by the caller), else the projective row (`add_projective`), else ray by ray.
/// `ray_weight` as in `FrameTable::add_per_ray`; `cache`, `ahead` and `sight` as in `shift_add`.
template <std::floating_point T, class Px>
void add_run(const FrameTable<T, Px>& table, const typename FrameTable<T, Px>::Camera& c, const Vec3<T>* points,
             std::size_t n, bool even, float* acc, float* weight, const float* ray_weight = nullptr,
             LerpRowCache* cache = nullptr, const typename FrameTable<T, Px>::Camera* ahead = nullptr,
             const RunSight<T>* sight = nullptr) noexcept {
  if (even && !c.distorted && n >= kShortestRun &&
      (shift_add(table, c, points, n, acc, weight, ray_weight, cache, ahead, sight) ||
       add_projective(table, c, points, n, acc, weight, ray_weight)))
    return;
  table.add_per_ray(c, points, n, acc, weight, ray_weight);
}

} // namespace mpr
