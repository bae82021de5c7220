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
#include <mpr/lightfield/kernels/resample_row.hpp>
#include <mpr/lightfield/kernels/resample_tile.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>

#include <algorithm>
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

#if MPR_HAVE_HWY
/// Pixels of a strip of `resample_tile_planned` (rounded up to whole vectors).
inline constexpr std::size_t kMagnifiedStrip = 128;

/// `resample_tile_stored` for steps up to `kernels::kMagnifiedMaxStep` through the Highway
/// kernels of `level`: where each pixel reads its pair found once for the block
/// (`kernels::MagnifiedPlan`, one period of a 1.5x or 2x view; kept in `work.plan` for the next
/// block at the same positions), the camera rows read in place as 16-bit linear values where the
/// block has them (codes are decoded to them a strip at a time, float channels copied), resampled
/// with one lane permute per value, a strip of `kMagnifiedStrip` pixels at a time down the block
/// (the strip's accumulators and stored rows stay in the first-level cache), each new bottom row
/// blended into its output row as it is resampled; the next block's rows (`t.ahead`) are asked
/// for a part a strip. `no_plan` (nothing added) for a step the plan does not take.
template <class C>
[[nodiscard]] kernels::PlanOutcome resample_tile_planned(const ResampleTile<C>& t, ResampleTileWork& work,
                                                         SimdLevel level) noexcept {
  const std::size_t n = t.n, stride = 3 * t.width;
  const long last_pair = static_cast<long>(t.width) - 2;
  const auto pair_of = [last_pair](double v) noexcept { return std::clamp(static_cast<long>(v), 0L, last_pair); };
  const long j_first = pair_of(t.x), j_last = pair_of(t.x + t.s * static_cast<double>(n - 1));
  const std::size_t count = 3 * static_cast<std::size_t>(j_last + 2 - j_first); // the values the row reads
  if (!work.plan.serves(t.x, t.s, n, t.width, level)) {
    const kernels::PlanOutcome made = kernels::plan_magnified_hwy(work.plan, t.x, t.s, n, t.width, level);
    if (made != kernels::PlanOutcome::made) return made;
  }
  const kernels::MagnifiedPlan& plan = work.plan;
  // Rows read in place: 16-bit values, which the frames follow with 32 more (frame_linear16.hpp).
  const bool in_place = t.linear != nullptr && plan.lanes + 3 <= 32;
  const std::size_t pad = plan.lanes + 3 + 3; // (a period's positions: within a texel of the row's)
  const long y_low = std::min(t.iy[0], t.iy[t.rows - 1]), y_high = std::max(t.iy[0], t.iy[t.rows - 1]) + 1;
  const std::size_t camera_rows = static_cast<std::size_t>(y_high - y_low + 1);
  // Rows not read in place: each strip's part of every camera row of the block taken first (the
  // resampling then reads no value still on its way to the cache), a row every `span` values.
  const std::size_t span = count + pad;
  try {
    if (work.h.size() < 6 * n) work.h.resize(6 * n);
    if constexpr (std::is_same_v<C, float>) {
      if (work.v.size() < span * camera_rows) work.v.assign(span * camera_rows, 0.0f);
    } else {
      if (!in_place && work.v16.size() < span * camera_rows) work.v16.assign(span * camera_rows, 0);
    }
  } catch (...) {
    return kernels::PlanOutcome::out_of_memory;
  }
  const std::size_t strip = (kMagnifiedStrip + plan.lanes - 1) / plan.lanes * plan.lanes;
  const std::size_t row_bytes = count * (in_place ? sizeof(std::uint16_t) : sizeof(C));
  const std::size_t strips = (n + strip - 1) / strip, part = (row_bytes + strips - 1) / strips;
  float* const slot[2] = {work.h.data(), work.h.data() + 3 * n};
  for (std::size_t p0 = 0; p0 < n; p0 += strip) {
    const std::size_t p1 = std::min(n, p0 + strip), c0 = 3 * p0, c1 = 3 * p1, k = p0 / strip;
    if (t.ahead != nullptr)
      for (std::size_t y = 0; y < camera_rows; ++y)
        for (std::size_t b = k * part; b < std::min(row_bytes, (k + 1) * part); b += 64)
          prefetch_l2(static_cast<const char*>(t.ahead) + t.ahead_stride * static_cast<std::ptrdiff_t>(y), b);
    // The values the strip reads (converted, when not read in place).
    const std::size_t v0 = plan.base_of(c0 / plan.lanes);
    const std::size_t v1 = std::min(count, plan.base_of((c1 - 1) / plan.lanes) + plan.lanes + 3);
    if (!in_place)
      for (long y = y_low; y <= y_high; ++y) {
        const std::size_t at = stride * static_cast<std::size_t>(y) + 3 * static_cast<std::size_t>(j_first) + v0;
        const std::size_t to = span * static_cast<std::size_t>(y - y_low) + v0;
        if constexpr (std::is_same_v<C, float>)
          std::copy(t.texels + at, t.texels + at + (v1 - v0), work.v.data() + to);
        else
          decode_row16(t.texels + at, t.lut, work.v16.data() + to, v1 - v0, level);
      }
    long key[2] = {-1, -1};
    // Camera row y resampled into a slot other than `keep` if none holds it (the top row's
    // fetch keeps the slot of y + 1 where it has it: the bottom row needs it next); with `acc`
    // (nullptr: none), acc += w0 (the slot `keep`) + w1 (the new row) in the same pass.
    const auto fetch = [&](long y, int keep, float w0 = 0, float w1 = 0, float* acc = nullptr) noexcept -> int {
      const int s = keep >= 0 ? 1 - keep : (key[0] == y + 1 ? 1 : 0);
      const float* above = keep >= 0 ? slot[keep] : nullptr;
      const std::size_t at = stride * static_cast<std::size_t>(y) + 3 * static_cast<std::size_t>(j_first);
      const std::size_t row = span * static_cast<std::size_t>(y - y_low);
      if constexpr (std::is_same_v<C, float>)
        kernels::resample_planned_hwy(plan, static_cast<const float*>(work.v.data() + row), slot[s], c0, c1, above, w0,
                                      w1, acc);
      else if (in_place)
        kernels::resample_planned_hwy(plan, t.linear + at, slot[s], c0, c1, above, w0, w1, acc);
      else
        kernels::resample_planned_hwy(plan, static_cast<const std::uint16_t*>(work.v16.data() + row), slot[s], c0, c1,
                                      above, w0, w1, acc);
      key[s] = y;
      return s;
    };
    const auto slot_of = [&](long y) noexcept { return key[0] == y ? 0 : key[1] == y ? 1 : -1; };
    for (std::size_t r = 0; r < t.rows; ++r) {
      const long y = t.iy[r];
      const float w0 = (1 - t.ay[r]) * t.scale, w1 = t.ay[r] * t.scale;
      float* acc = t.acc + static_cast<std::ptrdiff_t>(r) * t.acc_stride + static_cast<std::ptrdiff_t>(c0);
      int top = slot_of(y);
      if (top < 0) top = fetch(y, -1);
      if (t.ay[r] == 0.0f) { // the top row alone (`blend_rows` does not read the second)
        blend_rows(slot[top] + c0, slot[top] + c0, w0, 0.0f, nullptr, acc, p1 - p0, level);
        continue;
      }
      const int bottom = slot_of(y + 1);
      if (bottom >= 0)
        blend_rows(slot[top] + c0, slot[bottom] + c0, w0, w1, nullptr, acc, p1 - p0, level);
      else
        (void)fetch(y + 1, top, w0, w1, acc); // resampled and blended in one pass
    }
  }
  return kernels::PlanOutcome::made;
}
#endif

/// Adds the block `t` to its accumulators at `level` as `resample_tile` does, each camera row
/// resampled once into one of two stored rows of `work.h`, each output row r the blend
/// (1 - ay[r]) h_{iy[r]} + ay[r] h_{iy[r]+1} of two stored rows: through a plan
/// (`resample_tile_planned`, positions within `kernels::kMagnifiedPeriodTolerance` pixel over the
/// row) where the step has one, else with `resample_row` (same texel pairs, fractions and weights
/// as the portable form). False (nothing added) when working memory cannot grow. Preconditions as
/// `resample_tile`'s.
template <class C>
[[nodiscard]] bool resample_tile_stored(const ResampleTile<C>& t, ResampleTileWork& work,
                                        SimdLevel level = dispatch_level()) noexcept {
#if MPR_HAVE_HWY
  if (t.s <= kernels::kMagnifiedMaxStep && t.n > 0) {
    const kernels::PlanOutcome done = resample_tile_planned(t, work, level);
    if (done != kernels::PlanOutcome::no_plan) return done == kernels::PlanOutcome::made;
  }
#endif
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

/// `resample_tile_stored` for a block that `magnified_rows` accepts where it takes the block a
/// plan at a time (steps up to `kernels::kMagnifiedMaxStep`, at every level) or where
/// `resample_tile` would resample rows one by one (any level below AVX-512 with VBMI, or float
/// texels); `resample_tile` otherwise: its fused VBMI pass (both camera rows resampled through
/// groups found once per block, blended in registers) beats a stored row that finds its groups
/// again per camera row.
template <class C>
[[nodiscard]] bool resample_tile_any(const ResampleTile<C>& t, ResampleTileWork& work,
                                     SimdLevel level = dispatch_level()) noexcept {
#if MPR_HAVE_HWY
  const bool planned = t.s <= kernels::kMagnifiedMaxStep;
#else
  const bool planned = false;
#endif
  const bool fused = std::is_same_v<C, std::uint8_t> && level >= SimdLevel::avx512vbmi && t.s <= kResampleMaxStep;
  return (planned || !fused) && magnified_rows(t) ? resample_tile_stored(t, work, level)
                                                  : resample_tile(t, work, level);
}

} // namespace mpr::detail
