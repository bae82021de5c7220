#pragma once
/// \file
/// Where each channel of a magnified camera row reads its texel pair (`MagnifiedPlan`: a step of
/// at most one camera pixel per output pixel, a view at 1.5x or 2x the cameras' scale), built
/// once for a block of rows by the Highway kernel of a level (`plan_magnified_row`,
/// kernels/resample_row_hwy.inl), and a row resampled through it (`resample_planned_hwy`): one
/// lane permute per value. `detail::resample_tile_planned` (accumulation/magnified_tile.hpp) uses
/// them. Only available when Highway's headers are (`MPR_HAVE_HWY`, core/config.hpp).

#include <mpr/core/config.hpp>
#if MPR_HAVE_HWY
#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/lerp_row_hwy.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mpr::kernels {

/// The largest step (camera pixels per output pixel) of `MagnifiedPlan`: output at the cameras'
/// scale or magnified, each pixel's pair at most one texel on from the last.
inline constexpr double kMagnifiedMaxStep = 1.0;

/// How far (pixels, over a row) `MagnifiedPlan` may move positions to a step of a ratio p / q:
/// the tolerance of the grid a tile's cameras see (`shift_add_tile` checks its points within
/// 1e-3 pixel). The float projections of a Chess view at 1.5x give steps within 2.1e-4 pixel over
/// a 2100-pixel row of 2 / 3.
inline constexpr double kMagnifiedPeriodTolerance = 1e-3;

/// Where each channel of a row of n pixels at x + s i (s <= `kMagnifiedMaxStep`) on camera rows
/// of `texels` texels reads its texel pair and fraction, in the vector layout of one level's
/// Highway target (`plan_magnified_row`, kernels/resample_row_hwy.inl): built once for a block of
/// rows at the same positions (`resample_tile_stored`), read for each of its camera rows
/// (`resample_planned_hwy`). A step within `kMagnifiedPeriodTolerance` pixel over the row of a
/// ratio p / q (q <= 16: 1.5x, 2x, 1.25x ... magnification) repeats its pattern every q pixels,
/// p texels on: then the plan holds one period of vectors (`period`, the smallest whole number of
/// vectors that is a whole number of such patterns) and how many values the next one starts on
/// (`advance`), and the positions are taken at x + (p / q) i.
struct MagnifiedPlan {
  double x = 0, s = 0;
  std::size_t n = 0, texels = 0, lanes = 0;
  std::size_t period = 0, advance = 0; ///< vectors of a period, values from one to the next
  detail::SimdLevel level = detail::SimdLevel::portable;
  std::vector<std::int32_t> base;  ///< per vector: where its values start (`plan_magnified_row`)
  std::vector<std::int32_t> entry; ///< per vector: its lanes' value indices, then their fractions' bits

  /// Whether the plan is the one of these positions at `level1` (positions within 1e-6 pixel).
  [[nodiscard]] bool serves(double x1, double s1, std::size_t n1, std::size_t texels1,
                            detail::SimdLevel level1) const noexcept {
    return lanes != 0 && n1 == n && texels1 == texels && level1 == level && std::abs(x1 - x) <= 1e-6 &&
           std::abs(s1 - s) * static_cast<double>(n) <= 1e-6;
  }
  /// The first value vector q reads.
  [[nodiscard]] std::size_t base_of(std::size_t q) const noexcept {
    return static_cast<std::size_t>(base[q % period]) + q / period * advance;
  }
};

/// What `plan_magnified_hwy` did.
enum class PlanOutcome {
  made,         ///< the plan is the one asked for
  no_plan,      ///< the step has none: within 1e-3 of 1 but no ratio within the period tolerance
  out_of_memory ///< memory could not grow
};

/// Makes `plan` the one of pixels at x + s i, i < n, on rows of `texels` texels for `level`'s
/// Highway target (`hwy_visit`), where the step has one; `plan` is left empty otherwise.
/// Preconditions: texels >= 2, x >= 0, 0 < s <= `kMagnifiedMaxStep`.
[[nodiscard]] inline PlanOutcome plan_magnified_hwy(MagnifiedPlan& plan, double x, double s, std::size_t n,
                                                    std::size_t texels,
                                                    detail::SimdLevel level = detail::dispatch_level()) noexcept {
  std::size_t lanes = 0;
  hwy_visit(level, false, [&](auto t) { lanes = magnified_lanes(t); });
  std::size_t vectors = (3 * n + lanes - 1) / lanes, pixels = n, advance = 0;
  double step = s;
  // A ratio p / q within `kMagnifiedPeriodTolerance` pixel over the row, whose last pixel is on
  // the row (its pair is then not clamped: at most that far past the last texel, the next value
  // weighted by at most as much).
  for (std::size_t q = 1; q <= 16; ++q) {
    const double p = std::round(s * static_cast<double>(q));
    if (p < 1 || std::abs(s - p / static_cast<double>(q)) * static_cast<double>(n) > kMagnifiedPeriodTolerance)
      continue;
    const double end = x + p / static_cast<double>(q) * static_cast<double>(n - 1);
    if (!(end <= static_cast<double>(texels) - 1 + kMagnifiedPeriodTolerance)) break;
    std::size_t channels = 3 * q; // a period: the least common multiple of 3 q channels and N lanes
    while (channels % lanes != 0) channels += 3 * q;
    vectors = channels / lanes;
    pixels = channels / 3;
    advance = 3 * static_cast<std::size_t>(p) * (pixels / q);
    step = p / static_cast<double>(q);
    break;
  }
  plan.lanes = 0;
  if (advance == 0 && !(s <= 0.999)) return PlanOutcome::no_plan; // float positions near a step of 1
  try {
    plan.base.resize(vectors);
    plan.entry.resize(2 * vectors * lanes);
  } catch (...) {
    return PlanOutcome::out_of_memory;
  }
  hwy_visit(level, false,
            [&](auto t) { plan_magnified_row(t, x, step, pixels, texels, plan.base.data(), plan.entry.data()); });
  plan.x = x, plan.s = s, plan.n = n, plan.texels = texels, plan.lanes = lanes, plan.level = level;
  plan.period = vectors, plan.advance = advance;
  return PlanOutcome::made;
}

/// h[c] for the channels c in [first, last) of `plan`'s row (first a multiple of `plan.lanes`)
/// from `v`, its camera row's channels (16-bit linear values or floats, unscaled) from the first
/// pair's left texel on, readable from `plan.base_of(first / lanes)` to `plan.lanes` + 3 values
/// past the last vector's: the row resampled as `detail::resample_row_portable` does (with a
/// scale of 1), at the plan's level. With `acc` (nullptr: none), also acc[c - first] +=
/// w0 above[c] + w1 h[c] in the same pass.
template <class V>
inline void resample_planned_hwy(const MagnifiedPlan& plan, const V* v, float* h, std::size_t first, std::size_t last,
                                 const float* above = nullptr, float w0 = 0, float w1 = 0,
                                 float* acc = nullptr) noexcept {
  hwy_visit(plan.level, false, [&](auto t) {
    resample_planned_row(t, v, plan.base.data(), plan.entry.data(), plan.period, plan.advance, h, first, last, above,
                         w0, w1, acc);
  });
}

} // namespace mpr::kernels
#endif // MPR_HAVE_HWY
