#pragma once
/// \file
/// A resampled block (`detail::ResampleTile`) whose output rows are closer together than the
/// camera's rows (a view that magnifies the cameras' images: each output pixel steps less than
/// one camera pixel, e.g. 2100x1200 from 1400x800 cameras): consecutive output rows read the same
/// camera rows, so each camera row is resampled once into one of two stored rows and every
/// output row blends the two it lies between (`blend_rows`). Resampling both of an output row's
/// camera rows per output row (`detail::resample_tile`) would repeat each camera row's work for
/// every output row that reads it (1.5 to 2 times at 1.5x, twice as often per row).

#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>
#include <mpr/lightfield/kernels/resample_row.hpp>
#include <mpr/lightfield/kernels/resample_tile.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <type_traits>

namespace mpr::detail {

/// Whether the block `t` reads fewer distinct camera rows than it has output rows (its camera
/// row indices move by at most one per output row and stay put at least once): then
/// `resample_tile_stored` resamples fewer rows than `resample_tile`.
template <class C>
[[nodiscard]] bool magnified_rows(const ResampleTile<C>& t) noexcept {
  if (t.rows < 2) return false;
  std::size_t distinct = 1;
  for (std::size_t r = 1; r < t.rows; ++r) {
    const int step = t.iy[r] - t.iy[r - 1];
    if (std::abs(step) > 1) return false;
    distinct += step != 0 ? 1 : 0;
  }
  return distinct < t.rows;
}

/// Adds the block `t` to its accumulators at `level` as `resample_tile` does (same texel pairs,
/// fractions and weights: the portable form's arithmetic), each camera row resampled once
/// (`resample_row`) into one of two stored rows of `work.h`, each output row r the blend
/// (1 - ay[r]) h_{iy[r]} + ay[r] h_{iy[r]+1} of two stored rows. False (nothing added) when
/// working memory cannot grow. Preconditions as `resample_tile`'s.
template <class C>
[[nodiscard]] bool resample_tile_stored(const ResampleTile<C>& t, ResampleTileWork& work,
                                        SimdLevel level = dispatch_level()) noexcept {
  const std::size_t n = t.n, stride = 3 * t.width;
  try {
    if (work.h.size() < 6 * n) work.h.resize(6 * n);
  } catch (...) {
    return false;
  }
  float* const slot[2] = {work.h.data(), work.h.data() + 3 * n};
  long key[2] = {-1, -1}; // the camera row each slot holds (-1: none)
  // The slot holding camera row y, resampled into a slot other than `keep` if none holds it (the
  // top row's fetch keeps the slot of y + 1 where it has it: the bottom row needs it next).
  const auto fetch = [&](long y, int keep) noexcept -> int {
    for (int k = 0; k < 2; ++k)
      if (key[k] == y) return k;
    const int k = keep >= 0 ? 1 - keep : (key[0] == y + 1 ? 1 : 0);
    resample_row(t.texels + stride * static_cast<std::size_t>(y), t.width, t.lut, t.x, t.s, t.scale, slot[k], n,
                 static_cast<const C*>(nullptr), level);
    key[k] = y;
    return k;
  };
  for (std::size_t r = 0; r < t.rows; ++r) {
    const long y = t.iy[r];
    const int top = fetch(y, -1);
    // A vertical fraction of 0 reads the top row alone (`blend_rows` does not read the second).
    const int bottom = t.ay[r] == 0.0f ? top : fetch(y + 1, top);
    blend_rows(slot[top], slot[bottom], 1 - t.ay[r], t.ay[r], nullptr,
               t.acc + static_cast<std::ptrdiff_t>(r) * t.acc_stride, n, level);
  }
  return true;
}

/// `resample_tile_stored` for a block that `magnified_rows` accepts where `resample_tile` would
/// resample rows one by one (any level below AVX-512 with VBMI, or float texels), `resample_tile`
/// otherwise: its fused VBMI pass (both camera rows resampled through groups found once per
/// block, blended in registers) beats a stored row that finds its groups again per camera row
/// (Chess 2100x1200 at z = 820, 1 thread: 98 against 130 ms).
template <class C>
[[nodiscard]] bool resample_tile_any(const ResampleTile<C>& t, ResampleTileWork& work,
                                     SimdLevel level = dispatch_level()) noexcept {
  const bool fused = std::is_same_v<C, std::uint8_t> && level >= SimdLevel::avx512vbmi && t.s <= kResampleMaxStep;
  return !fused && magnified_rows(t) ? resample_tile_stored(t, work, level) : resample_tile(t, work, level);
}

} // namespace mpr::detail
