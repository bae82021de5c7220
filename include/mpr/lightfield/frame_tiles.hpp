#pragma once
/// \file
/// A tile of runs against one camera of a `FrameTable` at once: when the camera sees the tile as
/// a regular grid of its image (a focal plane parallel to the camera plane), the whole tile is
/// one 2-D shift-and-add at the cameras' pixel scale (`detail::shift_tile`: each camera row
/// interpolated once for the two output rows that read it), or one resampled block at any other
/// (`detail::resample_tile`), instead of a shift-and-add per run (`shift_add`, frame_runs.hpp).

#include <mpr/core/simd.hpp>
#include <mpr/lightfield/accumulation/magnified_tile.hpp>
#include <mpr/lightfield/accumulation/shared_weights_batch.hpp>
#include <mpr/lightfield/accumulation/shift_tile.hpp>
#include <mpr/lightfield/frame_runs.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/kernels/resample_tile.hpp>
#include <mpr/lightfield/kernels/running_sums.hpp>
#include <mpr/lightfield/kernels/shift_batch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace mpr {

/// Working memory of `shift_add_tile`, one per thread (it grows to the longest rows seen).
struct TileWork {
  std::vector<float> h;              // of `detail::shift_tile`
  std::vector<int> iy;               // per row of a resampled block: its upper camera row
  std::vector<float> ay;             // ... and its vertical fraction
  detail::ResampleTileWork resample; // of `detail::resample_tile`
};

/// weight[r n + i] += steps[r (n + 1)] + ... + steps[r (n + 1) + i] for the `rows` runs of n
/// pixels of a tile: the per-pixel counts that `shift_add_tile` leaves as steps (a difference
/// array, two entries per run and camera instead of one per pixel), folded in. The steps are
/// whole numbers (camera counts), so the sums are exact in any order: 16 at a time on AVX-512.
inline void add_weight_steps(const float* steps, std::size_t rows, std::size_t n, float* weight,
                             detail::SimdLevel level = detail::dispatch_level()) noexcept {
  for (std::size_t r = 0; r < rows; ++r) {
#if defined(MPR_SIMD_X86)
    if (level >= detail::SimdLevel::avx512) {
      detail::add_running_sums_avx512(steps + r * (n + 1), n, weight + r * n);
      continue;
    }
#endif
    (void)level;
    detail::add_running_sums_portable(steps + r * (n + 1), n, weight + r * n);
  }
}

namespace detail {
// The block of rows [r_begin, r_end) and pixels [first, last) of a tile that camera c sees at
// (x0 + sx i, y0 + sy r), whose texel pairs lie inside the image (see `shift_add_tile`).
struct TileBlock {
  long r_begin = 0, r_end = 0, first = 0, last = 0;
  [[nodiscard]] bool empty() const noexcept { return r_begin >= r_end || first >= last; }
};

// Rows r with 0 <= floor(y0 + sy r) <= height - 2 (contiguous: y is monotonic in r), and pixels
// i with 0 <= x0 + sx i <= width - 1 (sx > 0).
template <std::floating_point T>
TileBlock tile_block(T x0, T y0, T sx, T sy, std::size_t rows, std::size_t n, int width, int height) noexcept {
  TileBlock b;
  const auto inside = [&](long r) noexcept {
    const T y = std::floor(y0 + sy * static_cast<T>(r));
    return y >= 0 && y <= static_cast<T>(height - 2);
  };
  while (b.r_begin < static_cast<long>(rows) && !inside(b.r_begin)) ++b.r_begin;
  b.r_end = b.r_begin;
  while (b.r_end < static_cast<long>(rows) && inside(b.r_end)) ++b.r_end;
  const auto [first, last] = resampled_span(x0, sx, n, width);
  b.first = static_cast<long>(first);
  b.last = static_cast<long>(last);
  return b;
}
} // namespace detail

/// Camera c's contribution to `rows` runs of n evenly spaced points each (run r at points + n r,
/// adding to acc + 3 n r and weight + n r; the weights of the pixels added in two dimensions go
/// to `weight_steps`, rows (n + 1) entries, see `add_weight_steps`) when c sees them as a
/// regular grid of its image: point i of run r at camera pixel (x0 + sx i, y0 + sy r), checked at
/// each run's ends and middle within 1e-3 pixel (the contract of `shift_add`), with 0 < sx <=
/// `detail::kResampleMaxStep`. A grid one pixel apart both ways is a 2-D shift
/// (`detail::shift_tile`; an offset within `detail::texel_snap` of a texel is taken as on it, so
/// integer shifts add texels uninterpolated), any other is resampled (`detail::resample_tile`). Pixels whose texel
/// pairs lie inside the image are added so, those near the left and right edges ray by ray
/// (`detail::add_run_edges`), runs on the image's top and bottom rows or beyond through
/// `shift_add` one by one (or ray by ray). False (nothing added) when the tile is no such grid
/// for c, or working memory cannot grow: then add its runs one by one. `ahead` as in
/// `shift_add`. With a `batch` (nullptr: none) and 8-bit codes, a whole-pixel shift whose block
/// spans the runs' whole length is not added but appended to it, while it has room (its
/// capacity), to be added with the other cameras' (`detail::add_shifted_blocks`); its edges and
/// weights are added now. (Blocks over part of the runs are added at once: summed row by row with
/// the others, their pieces scatter the reads, docs/performance.md.) Likewise with `shared`
/// (nullptr: none) and 8-bit codes, a resampled block that shares the bilinear weights and the
/// extent of the blocks taken before it (a whole-pixel focal plane at another scale) is taken
/// by it (`detail::defer_shared_weights`), to be added with the others'
/// (`detail::add_shared_weights`).
/// Preconditions: every run evenly spaced (`evenly_spaced`), bilinear filtering.
template <std::floating_point T, class Px>
bool shift_add_tile(const FrameTable<T, Px>& table, const typename FrameTable<T, Px>::Camera& c, const Vec3<T>* points,
                    std::size_t rows, std::size_t n, float* acc, float* weight, float* weight_steps, TileWork& work,
                    const typename FrameTable<T, Px>::Camera* ahead = nullptr, detail::ShiftBatch* batch = nullptr,
                    detail::SharedWeightsBatch* shared = nullptr) noexcept {
  using Table = FrameTable<T, Px>;
  using texel_type = typename Table::texel_type;
  if (rows < 2 || n < 8 || c.distorted || c.width < 2 || c.height < 2) return false;
  constexpr T kTolerance = T(1e-3);
  T x0, y0, x1, y1, xr, yr;
  if (!Table::project_any(c, points[0], x0, y0) || !Table::project_any(c, points[n - 1], x1, y1) ||
      !Table::project_any(c, points[(rows - 1) * n], xr, yr))
    return false;
  T sx = (x1 - x0) / static_cast<T>(n - 1), sy = (yr - y0) / static_cast<T>(rows - 1);
  const bool shift = std::abs(sx - 1) * static_cast<T>(n - 1) <= kTolerance &&
                     std::abs(sy - 1) * static_cast<T>(rows - 1) <= kTolerance;
  if (shift) sx = sy = 1;
  if (!(sx > 0 && sx <= T(detail::kResampleMaxStep) && std::abs(sy) < T(1e6))) return false;
  for (std::size_t r = 0; r < rows; ++r)
    for (const std::size_t i : {std::size_t(0), n / 2, n - 1}) {
      T x, y;
      if (!Table::project_any(c, points[r * n + i], x, y) ||
          !(std::abs(x - (x0 + sx * static_cast<T>(i))) <= kTolerance &&
            std::abs(y - (y0 + sy * static_cast<T>(r))) <= kTolerance))
        return false;
    }
  if (!(std::abs(x0) < T(1e8) && std::abs(y0) < T(1e8))) return false; // keeps the conversions in range
  // The 2-D shift's texel and offsets, snapped to a texel within `texel_snap`, so that integer
  // shifts add decoded texels with no interpolation (`detail::shift_tile`).
  long ix = 0, iy = 0;
  T ax = 0, ay = 0;
  detail::snap_to_texel(x0, ix, ax);
  detail::snap_to_texel(y0, iy, ay);
  detail::TileBlock b;
  if (shift) { // rows reading camera rows iy + r and iy + r + 1; pixels reading texels ix + i, ix + i + 1
    // With ay = 0 a row reads one camera row; with ax = ay = 0 a pixel reads one texel (the
    // image's last row and column then need no second one).
    const long below = ay == 0 ? 0 : 1, right = ax == 0 && ay == 0 ? 0 : 1;
    b.r_begin = std::clamp(-iy, 0L, static_cast<long>(rows));
    b.r_end = std::clamp(static_cast<long>(c.height) - below - iy, b.r_begin, static_cast<long>(rows));
    b.first = std::max(0L, -ix);
    b.last = std::min(static_cast<long>(n), static_cast<long>(c.width) - right - ix);
  } else {
    b = detail::tile_block(x0, y0, sx, sy, rows, n, c.width, c.height);
  }
  const std::size_t m = b.empty() ? 0 : 3 * static_cast<std::size_t>(b.last - b.first);
  try {
    if (shift && work.h.size() < detail::shift_tile_work(m)) work.h.resize(detail::shift_tile_work(m));
    if (!shift && work.iy.size() < rows) {
      work.iy.resize(rows);
      work.ay.resize(rows);
    }
  } catch (...) {
    return false;
  }
  for (long r = 0; r < static_cast<long>(rows); ++r) {
    const std::size_t o = static_cast<std::size_t>(r) * n;
    if (b.empty() || r < b.r_begin || r >= b.r_end) {
      if (!shift_add(table, c, points + o, n, acc + 3 * o, weight + o)) // the image's edge rows, or beyond
        table.add_per_ray(c, points + o, n, acc + 3 * o, weight + o);
      continue;
    }
    detail::add_run_edges(table, c, points + o, n, static_cast<std::size_t>(b.first), static_cast<std::size_t>(b.last),
                          x0, sx, acc + 3 * o, weight + o, nullptr);
    weight_steps[static_cast<std::size_t>(r) * (n + 1) + static_cast<std::size_t>(b.first)] += 1.0f;
    weight_steps[static_cast<std::size_t>(r) * (n + 1) + static_cast<std::size_t>(b.last)] -= 1.0f;
  }
  if (b.empty()) return true;
  float* block_acc = acc + 3 * (static_cast<std::size_t>(b.r_begin) * n + static_cast<std::size_t>(b.first));
  if (!shift) {
    if constexpr (std::is_same_v<typename texel_type::channel_type, std::uint8_t>) {
      if (shared != nullptr &&
          detail::defer_shared_weights(*shared, c.texels->c, c.linear, static_cast<std::size_t>(c.width),
                                       static_cast<std::size_t>(c.height), static_cast<double>(x0),
                                       static_cast<double>(y0), static_cast<double>(sx), static_cast<double>(sy),
                                       static_cast<std::size_t>(b.first), static_cast<std::size_t>(b.last),
                                       static_cast<std::size_t>(b.r_begin), static_cast<std::size_t>(b.r_end)))
        return true;
    }
    for (long r = b.r_begin; r < b.r_end; ++r) {
      const T y = y0 + sy * static_cast<T>(r), fr = std::floor(y);
      work.iy[static_cast<std::size_t>(r - b.r_begin)] = static_cast<int>(fr);
      work.ay[static_cast<std::size_t>(r - b.r_begin)] = static_cast<float>(y - fr);
    }
    detail::ResampleTile<typename texel_type::channel_type> tile;
    tile.texels = c.texels->c;
    tile.width = static_cast<std::size_t>(c.width);
    tile.x = static_cast<double>(x0) + static_cast<double>(sx) * static_cast<double>(b.first);
    tile.s = static_cast<double>(sx);
    tile.n = static_cast<std::size_t>(b.last - b.first);
    tile.rows = static_cast<std::size_t>(b.r_end - b.r_begin);
    tile.iy = work.iy.data();
    tile.ay = work.ay.data();
    tile.scale = texel_type::scale;
    tile.lut = texel_decode_table<texel_type>();
    tile.linear = c.linear;
    // The next camera's rows of the block from its first pixel (its block's, nearly), asked for
    // while this one's are read.
    if (ahead != nullptr && ahead->width == c.width && ahead->height == c.height) {
      const auto next = detail::ahead_rows<T, Px>(
          ahead, points[static_cast<std::size_t>(b.r_begin) * n + static_cast<std::size_t>(b.first)]);
      if (next[0] != nullptr) {
        const std::ptrdiff_t first = next[0] - ahead->texels->c, stride = next[1] - next[0]; // channels
        const bool linear = c.linear != nullptr && ahead->linear != nullptr;
        tile.ahead = linear ? static_cast<const void*>(ahead->linear + first) : static_cast<const void*>(next[0]);
        tile.ahead_stride = stride * static_cast<std::ptrdiff_t>(linear ? sizeof(std::uint16_t) : sizeof(*next[0]));
      }
    }
    tile.acc = block_acc;
    tile.acc_stride = 3 * static_cast<std::ptrdiff_t>(n);
    if (!detail::resample_tile_any(tile, work.resample)) // out of memory: ray by ray
      for (long r = b.r_begin; r < b.r_end; ++r) {
        const std::size_t o = static_cast<std::size_t>(r) * n + static_cast<std::size_t>(b.first);
        table.add_per_ray(c, points + o, tile.n, acc + 3 * o, weight + o);
        weight_steps[static_cast<std::size_t>(r) * (n + 1) + static_cast<std::size_t>(b.first)] -= 1.0f;
        weight_steps[static_cast<std::size_t>(r) * (n + 1) + static_cast<std::size_t>(b.last)] += 1.0f;
      }
    return true;
  }
  const std::ptrdiff_t first_texel = (iy + b.r_begin) * c.width + ix + b.first;
  const auto* texels = c.texels[first_texel].c;
  // The same channels in the frames' 16-bit linear copy, when they hold one.
  const std::uint16_t* linear = c.linear != nullptr ? c.linear + 3 * first_texel : nullptr;
  if constexpr (std::is_same_v<typename texel_type::channel_type, std::uint8_t>) {
    if (batch != nullptr && ax == 0 && ay == 0 && b.first == 0 && b.last == static_cast<long>(n) &&
        batch->blocks.size() < batch->blocks.capacity()) {
      batch->blocks.push_back({texels, 3 * static_cast<std::ptrdiff_t>(c.width), static_cast<std::size_t>(b.r_begin),
                               static_cast<std::size_t>(b.r_end), linear});
      return true;
    }
  }
  detail::ShiftTile<typename texel_type::channel_type> tile;
  tile.texels = texels;
  tile.stride = 3 * static_cast<std::ptrdiff_t>(c.width);
  tile.rows = static_cast<std::size_t>(b.r_end - b.r_begin);
  tile.m = m;
  tile.ax = static_cast<float>(ax);
  tile.ay = static_cast<float>(ay);
  tile.scale = texel_type::scale;
  tile.lut = texel_decode_table<texel_type>();
  tile.acc = block_acc;
  tile.acc_stride = 3 * static_cast<std::ptrdiff_t>(n);
  tile.linear = linear;
  const auto next = detail::ahead_rows<T, Px>(
      ahead, points[static_cast<std::size_t>(b.r_begin) * n + static_cast<std::size_t>(b.first)]);
  const std::uint16_t* next_linear = nullptr; // the ahead camera's rows in its 16-bit copy
  if constexpr (std::is_same_v<typename texel_type::channel_type, std::uint8_t>)
    if (next[0] != nullptr && ahead->linear != nullptr) next_linear = ahead->linear + (next[0] - ahead->texels->c);
  detail::shift_tile(tile, work.h.data(), next[0], next[1] - next[0], next_linear);
  return true;
}

} // namespace mpr
