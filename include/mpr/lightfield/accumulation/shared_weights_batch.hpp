#pragma once
/// \file
/// Many cameras' resampled blocks of one tile that share their bilinear weights, added as one:
/// on a focal plane where every camera's shift is a whole camera pixel (Chess at z = 1000) and
/// the output is at another scale than the cameras' (a magnified 2100x1200 view, a reduced
/// 960x540 one), each camera sees output pixel (i, r) at its own texel offset (jx_c, jy_c) plus
/// the same position (fx + sx i, fy + sy r) as every other camera. Bilinear interpolation is
/// linear in the texels, so
///   sum_c bilerp(I_c, (jx_c, jy_c) + p) = bilerp(sum_c I_c((jx_c, jy_c) + .), p)
/// exactly where every camera's texel pairs lie in its image: the cameras' codes are summed over
/// the block's footprint once (`add_code_rows`, the whole-pixel refocus's kernel: decoded codes
/// summed in registers), and that one grid of sums is resampled once (`resample_tile_any` on
/// float texels) instead of one resampling per camera. A camera's block is the part of the tile
/// where its texel pairs lie inside its image; the batch takes the cameras whose blocks are the
/// first's (the same pixels and rows), and the others, and every camera's pixels outside its
/// block (where the set of cameras seeing a pixel changes), go the per-camera way
/// (frame_tiles.hpp).

#include <mpr/core/simd.hpp>
#include <mpr/lightfield/accumulation/magnified_tile.hpp>
#include <mpr/lightfield/kernels/resample_tile.hpp>
#include <mpr/lightfield/kernels/shift_batch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mpr::detail {

/// The deferred blocks of one tile and their shared geometry, with the working memory to add them
/// (sized when the first block is taken, so that adding them cannot fail). `blocks` has the
/// capacity its owner reserves (one per camera); a block is taken only while there is room.
struct SharedWeightsBatch {
  /// One camera's block: its texel (jx_c, jy_c) (flat 8-bit codes), the same texel's 16-bit
  /// linear values (`CameraFrameSet::linear16`, laid out as the codes) or nullptr, and its
  /// image's row stride (in channels).
  struct Block {
    const std::uint8_t* texels = nullptr;
    const std::uint16_t* linear = nullptr;
    std::ptrdiff_t stride = 0;
  };
  std::vector<Block> blocks;
  std::size_t first = 0, last = 0;          ///< the block's pixels [first, last) of each tile row
  std::size_t r_begin = 0, r_end = 0;       ///< the block's tile rows [r_begin, r_end)
  double fx = 0, fy = 0;                    ///< the block's first pixel from each block's first texel, in [0, 1)
  double sx = 0, sy = 0;                    ///< camera pixels per output pixel along a row, per output row
  std::size_t columns = 0;                  ///< texels per row of the footprint
  std::size_t lines = 0;                    ///< rows of the footprint
  std::vector<float> grid;                  ///< the summed footprint (lines rows of 3 columns channels)
  std::vector<const std::uint8_t*> rows_of; ///< per footprint row: the cameras' codes
  std::vector<const std::uint16_t*> rows16; ///< ... or their 16-bit linear values
  std::vector<int> iy;                      ///< per block row: its upper footprint row
  std::vector<float> ay;                    ///< ... and its vertical fraction
  ResampleTileWork work;                    ///< of `resample_tile_any`
};

/// Positions within this many camera pixels of the batch's (anywhere in the block) share its
/// weights: the tolerance of `shift_add` and of `shift_add_tile`'s grid check. An offset within
/// 1e-4 pixel of a whole texel is taken as on it (as `snap_to_texel` does).
inline constexpr double kSharedWeightsTolerance = 1e-3;

/// Takes a camera's block of a tile into `batch` when it shares the batch's weights: the tile's
/// pixel (i, r) at camera pixel (x0 + sx i, y0 + sy r) of an image of `width` x `height` texels
/// (flat 8-bit codes at `texels`; their 16-bit linear values at `linear`, or nullptr), the block its pixels [first,
/// last) of rows [r_begin, r_end), every one of whose texel pairs lies inside the image. The first block taken sets the
/// geometry; later ones must cover the same pixels and rows, with the same steps and fractional
/// offsets (within `kSharedWeightsTolerance` over the block) and the same footprint. False
/// (nothing taken) otherwise, or when the batch is full or its working memory cannot grow.
/// Preconditions: first < last, r_begin < r_end, |x0|, |y0| < 1e8.
[[nodiscard]] inline bool defer_shared_weights(SharedWeightsBatch& batch, const std::uint8_t* texels,
                                               const std::uint16_t* linear, std::size_t width, std::size_t height,
                                               double x0, double y0, double sx, double sy, std::size_t first,
                                               std::size_t last, std::size_t r_begin, std::size_t r_end) noexcept {
  if (batch.blocks.size() >= batch.blocks.capacity() || !(sx > 0 && sy > 0)) return false;
  // The block's first texel and fractional offsets, snapped to a whole texel within 1e-4.
  const auto split = [](double v, long& j, double& f) noexcept {
    j = static_cast<long>(std::floor(v));
    f = v - static_cast<double>(j);
    if (f > 1 - 1e-4) ++j, f = 0;
    if (f < 1e-4) f = 0;
  };
  long jx = 0, jy = 0;
  double fx = 0, fy = 0;
  split(x0 + sx * static_cast<double>(first), jx, fx);
  split(y0 + sy * static_cast<double>(r_begin), jy, fy);
  const double far_x = static_cast<double>(last - first - 1), far_y = static_cast<double>(r_end - r_begin - 1);
  const std::size_t columns = static_cast<std::size_t>(fx + sx * far_x) + 2;
  const std::size_t lines = static_cast<std::size_t>(fy + sy * far_y) + 2;
  if (jx < 0 || jy < 0 || static_cast<std::size_t>(jx) + columns > width ||
      static_cast<std::size_t>(jy) + lines > height)
    return false;
  if (batch.blocks.empty()) {
    const std::size_t n = last - first, rows = r_end - r_begin;
    try {
      if (batch.grid.size() < 3 * columns * lines) batch.grid.resize(3 * columns * lines);
      if (batch.rows_of.size() < batch.blocks.capacity()) batch.rows_of.resize(batch.blocks.capacity());
      if (batch.rows16.size() < batch.blocks.capacity()) batch.rows16.resize(batch.blocks.capacity());
      if (batch.iy.size() < rows) {
        batch.iy.resize(rows);
        batch.ay.resize(rows);
      }
      if (batch.work.h.size() < 6 * n) batch.work.h.resize(6 * n);
    } catch (...) {
      return false;
    }
    batch.first = first, batch.last = last, batch.r_begin = r_begin, batch.r_end = r_end;
    batch.fx = fx, batch.fy = fy, batch.sx = sx, batch.sy = sy;
    batch.columns = columns, batch.lines = lines;
  } else {
    const bool same = first == batch.first && last == batch.last && r_begin == batch.r_begin && r_end == batch.r_end &&
                      columns == batch.columns && lines == batch.lines &&
                      std::abs(fx - batch.fx) + std::abs(sx - batch.sx) * far_x <= kSharedWeightsTolerance &&
                      std::abs(fy - batch.fy) + std::abs(sy - batch.sy) * far_y <= kSharedWeightsTolerance;
    if (!same) return false;
  }
  const std::ptrdiff_t stride = 3 * static_cast<std::ptrdiff_t>(width);
  const std::ptrdiff_t at = stride * jy + 3 * jx;
  batch.blocks.push_back({texels + at, linear != nullptr ? linear + at : nullptr, stride});
  return true;
}

/// Adds the blocks of `batch` to the tile's accumulators (tile row r's at acc + r `acc_stride`,
/// pixel i's channels at 3 i), `scale` and `lut` those of the texel type, and empties it: the
/// cameras' decoded codes summed over the footprint (`add_code_rows`; below the VBMI level, when
/// every block has its 16-bit linear values, those summed by `kernels::sum_linear_rows_hwy`: the
/// same sums without a decode), the sums resampled at
/// (fx + sx i, fy + sy r) over the block and blended into its rows (`resample_tile_any`).
inline void add_shared_weights(SharedWeightsBatch& batch, const std::uint16_t* lut, float scale, float* acc,
                               std::ptrdiff_t acc_stride, SimdLevel level = dispatch_level()) noexcept {
  const std::size_t k = batch.blocks.size();
  if (k == 0) return;
  const std::size_t m = 3 * batch.columns, rows = batch.r_end - batch.r_begin;
  float* grid = batch.grid.data();
  std::fill(grid, grid + m * batch.lines, 0.0f);
#if MPR_HAVE_HWY
  const bool linear =
      level < SimdLevel::avx512vbmi && std::all_of(batch.blocks.begin(), batch.blocks.end(),
                                                   [](const SharedWeightsBatch::Block& b) { return b.linear; });
#endif
  for (std::size_t g = 0; g < batch.lines; ++g) {
    const std::ptrdiff_t down = static_cast<std::ptrdiff_t>(g);
#if MPR_HAVE_HWY
    if (linear) {
      for (std::size_t c = 0; c < k; ++c) batch.rows16[c] = batch.blocks[c].linear + down * batch.blocks[c].stride;
      kernels::sum_linear_rows_hwy(batch.rows16.data(), k, scale, grid + g * m, m, level);
      continue;
    }
#endif
    for (std::size_t c = 0; c < k; ++c) batch.rows_of[c] = batch.blocks[c].texels + down * batch.blocks[c].stride;
    add_code_rows(batch.rows_of.data(), k, lut, scale, grid + g * m, m, level);
  }
  for (std::size_t r = 0; r < rows; ++r) {
    const double y = batch.fy + batch.sy * static_cast<double>(r), fr = std::floor(y);
    batch.iy[r] = static_cast<int>(fr);
    batch.ay[r] = static_cast<float>(y - fr);
  }
  ResampleTile<float> t;
  t.texels = grid;
  t.width = batch.columns;
  t.x = batch.fx;
  t.s = batch.sx;
  t.n = batch.last - batch.first;
  t.rows = rows;
  t.iy = batch.iy.data();
  t.ay = batch.ay.data();
  t.scale = 1;
  t.acc = acc + static_cast<std::ptrdiff_t>(batch.r_begin) * acc_stride + 3 * static_cast<std::ptrdiff_t>(batch.first);
  t.acc_stride = acc_stride;
  // Cannot fail: its working memory (two rows of n pixels) was sized with the first block.
  (void)resample_tile_any(t, batch.work, level);
  batch.blocks.clear();
}

} // namespace mpr::detail
