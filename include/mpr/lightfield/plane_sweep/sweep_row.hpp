#pragma once
/// \file
/// One reference row's matching cost at one depth plane in the plane sweep of `estimate_depth`
/// (lightfield/depth_estimation.hpp): how each neighbour camera sees the row (a translated row
/// over the pixels it sees, or a projective one), then per pixel the mean of the best few
/// neighbours' truncated costs, by the row kernels of (kernels/sweep_kernels.hpp).

#include <mpr/core/simd.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/kernels/sweep_code_kernels.hpp>
#include <mpr/lightfield/kernels/sweep_kernels.hpp>
#include <mpr/lightfield/kernels/sweep_seen_kernels.hpp>
#include <mpr/lightfield/plane_sweep/sweep_workspace.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace mpr::detail {

/// What `sweep_cost_row` reads: the reference image, the neighbours' images and the maps from
/// reference pixels to neighbour pixels (neighbour j sees reference pixel p at depth d at the
/// homogeneous point A[j] + d M[j] p), the neighbours (1..32) and kept costs (1..m), the
/// truncation and the kernels' instruction set; `codes`: rows of many translated neighbours take
/// the 16-bit kernel (kernels/sweep_code_kernels.hpp) where it fits, else the float one.
struct SweepRowInputs {
  const SweepPlanes* reference;
  const SweepPlanes* neighbours;
  const Mat3<float>* M;
  const Vec3<float>* A;
  int m, best;
  float tau;
  SimdLevel level;
  bool codes = true;
};

/// How neighbour j sees reference row y at depth d: not at all, as a translated row over the
/// reference pixels [xb, xe) (pixel x at (x + s + fu, v0 + fv), bilinear between rows v0 and
/// v1), or as a projective row.
struct SweepNeighbourRow {
  enum Kind { unseen, shift, projective } kind = unseen;
  int xb = 0, xe = 0, s = 0, v0 = 0, v1 = 0;
  float fu = 0, fv = 0;
  SweepProjectiveRow row{};

  /// The translated row on 8-bit codes from reference pixel xb on (kind shift), its weights in
  /// 1/128, each at most 127 (a whole-pixel shift: 64 + 64 on one tap of a single row,
  /// `sweep_code_set_weights`).
  [[nodiscard]] SweepCodeRow coded(const SweepPlanes& image) const noexcept {
    SweepCodeRow r{};
    for (int c = 0; c < 3; ++c) {
      r.top[c] = image.channel_codes(c) + static_cast<std::ptrdiff_t>(v0) * image.stride + s + xb;
      r.bottom[c] = image.channel_codes(c) + static_cast<std::ptrdiff_t>(v1) * image.stride + s + xb;
    }
    sweep_code_set_weights(r, sweep_code_weights(fu, fv));
    r.xb = xb;
    r.xe = xe;
    return r;
  }

  /// The translated row from reference pixel `from` on (kind shift, from in [xb, xe)).
  [[nodiscard]] SweepShiftRow shifted(const SweepPlanes& image, int from) const noexcept {
    SweepShiftRow r{};
    r.fu = fu;
    r.fv = fv;
    for (int c = 0; c < 3; ++c) {
      r.top[c] = image.channel(c) + static_cast<std::ptrdiff_t>(v0) * image.stride + s + from;
      r.bottom[c] = image.channel(c) + static_cast<std::ptrdiff_t>(v1) * image.stride + s + from;
    }
    return r;
  }
};

/// Neighbour j's view of reference row y (`width` pixels) at depth d: a translation when three
/// points of the row (ends and middle) are shifted alike within 1e-3 pixel.
[[nodiscard]] inline SweepNeighbourRow sweep_neighbour_row(const SweepRowInputs& in, int j, int width, int y,
                                                           float d) noexcept {
  SweepNeighbourRow p;
  const SweepPlanes& nb = in.neighbours[j];
  const Mat3<float>& Mj = in.M[j];
  const Vec3<float>& Aj = in.A[j];
  const auto project = [&](int x) -> Vec3<float> {
    return Aj + d * (Mj * Vec3<float>(static_cast<float>(x), static_cast<float>(y), 1.0f));
  };
  const Vec3<float> h0 = project(0), hm = project(width / 2), h1 = project(width - 1);
  bool shift = h0.z() > 0 && hm.z() > 0 && h1.z() > 0;
  const float off = h0.x() / h0.z(), v = h0.y() / h0.z();
  if (shift) {
    constexpr float eps = 1e-3f;
    shift = std::abs(hm.x() / hm.z() - (off + static_cast<float>(width / 2))) <= eps &&
            std::abs(h1.x() / h1.z() - (off + static_cast<float>(width - 1))) <= eps &&
            std::abs(hm.y() / hm.z() - v) <= eps && std::abs(h1.y() / h1.z() - v) <= eps;
  }
  if (!shift) {
    p.kind = SweepNeighbourRow::projective;
    p.row =
        SweepProjectiveRow{{Aj.x(), Aj.y(), Aj.z()},
                           {Mj(0, 1) * static_cast<float>(y) + Mj(0, 2), Mj(1, 1) * static_cast<float>(y) + Mj(1, 2),
                            Mj(2, 1) * static_cast<float>(y) + Mj(2, 2)},
                           {Mj(0, 0), Mj(1, 0), Mj(2, 0)},
                           d};
    return p;
  }
  // Reference pixel x sees the neighbour at (x + off, v): seen for x in [xb, xe).
  if (!(v >= 0 && v <= static_cast<float>(nb.height - 1))) return p;
  const double lo = std::ceil(-static_cast<double>(off));
  const double hi = std::floor(static_cast<double>(nb.width - 1) - static_cast<double>(off)) + 1;
  int xb = static_cast<int>(std::clamp(lo, 0.0, static_cast<double>(width)));
  int xe = static_cast<int>(std::clamp(hi, 0.0, static_cast<double>(width)));
  // The ends as the per-pixel projection decides them (it rounds differently from x + off by a
  // few ulp, which decides pixels on the image's border).
  const float max_u = static_cast<float>(nb.width - 1), max_v = static_cast<float>(nb.height - 1);
  const auto seen = [&](int x) {
    const Vec3<float> h = project(x);
    const float u = h.x() / h.z(), hv = h.y() / h.z();
    return h.z() > 0 && u >= 0 && hv >= 0 && u <= max_u && hv <= max_v;
  };
  while (xb < xe && !seen(xb)) ++xb;
  while (xe > xb && !seen(xe - 1)) --xe;
  while (xb > 0 && xb < xe && xb - 1 + off > -0.5f && seen(xb - 1)) --xb;
  while (xe < width && xb < xe && xe + off < max_u + 0.5f && seen(xe)) ++xe;
  if (xb >= xe) return p;
  p.kind = SweepNeighbourRow::shift;
  p.xb = xb;
  p.xe = xe;
  p.v0 = std::min(static_cast<int>(v), std::max(nb.height - 2, 0));
  p.v1 = std::min(p.v0 + 1, nb.height - 1);
  // Here a reference pixel of [xb, xe) lands inside the neighbour, so off lies in
  // (-width, nb.width) and the conversion is in range; the clamp (in float, before converting)
  // keeps it so for any input (docs/reliability.md, Numerics on the render path).
  p.s = static_cast<int>(std::floor(std::clamp(off, -static_cast<float>(width) - 1, static_cast<float>(nb.width))));
  p.fu = off - static_cast<float>(p.s);
  p.fv = v - static_cast<float>(p.v0);
  return p;
}

/// Reference row y's cost at depth d into `out` (the reference's width): per pixel the mean of
/// the `best` smallest neighbour costs, an unseen neighbour counting as the truncation (the
/// worst cost, so that a plane is not preferred because few neighbours see it). Scratch: `keep`
/// `best` rows of the width, consecutive (keep[i] = keep[0] + i width), and `value` one row.
/// Where every neighbour is a translated row (at most kSweepShiftMeanNeighbours of them), the
/// pixels all of them see take the fused kernel (`sweep_shift_mean`: the same values in one
/// pass), the others the kernels neighbour by neighbour; where no neighbour is projective
/// otherwise (more neighbours, as the row-and-column selection gives), the whole row takes the
/// chunked kernel `sweep_shift_mean_seen` (the same values again), or with `in.codes` where its
/// sums fit (`sweep_code_fits`: the defaults, up to 26 neighbours at truncation 0.3) its 16-bit
/// twin `sweep_code_mean_seen` (the weights rounded to 1/128, the costs to 1/32 code: within
/// about 2e-3 of the float values); projective rows go neighbour by neighbour.
inline void sweep_cost_row(const SweepRowInputs& in, int y, float d, float* out, float* const* keep,
                           float* value) noexcept {
  const int width = in.reference->width, best = in.best;
  const float tau = in.tau;
  const SimdLevel level = in.level;
  const float* ref_row[3];
  for (int c = 0; c < 3; ++c)
    ref_row[c] = in.reference->channel(c) + static_cast<std::ptrdiff_t>(y) * in.reference->stride;
  SweepNeighbourRow plan[32];
  bool all_shift = in.m <= kSweepShiftMeanNeighbours, any_projective = false;
  int cb = 0, ce = width; // the pixels every neighbour sees, when all are translated rows
  for (int j = 0; j < in.m; ++j) {
    plan[j] = sweep_neighbour_row(in, j, width, y, d);
    if (plan[j].kind != SweepNeighbourRow::shift) {
      all_shift = false;
      any_projective = any_projective || plan[j].kind == SweepNeighbourRow::projective;
    } else {
      cb = std::max(cb, plan[j].xb);
      ce = std::min(ce, plan[j].xe);
    }
  }
  if (!any_projective && best <= kSweepSeenBest && !(all_shift && cb < ce)) {
    // Translated rows or unseen ones, more than the fused kernel of the common pixels takes (or
    // no pixel seen by all): the whole row in chunks, each neighbour over the pixels it sees, on
    // 8-bit codes in 16-bit lanes where their sums fit.
    if (in.codes && sweep_code_fits(in.m, best, tau)) {
      SweepCodeRow coded[32];
      int count = 0;
      for (int j = 0; j < in.m; ++j)
        if (plan[j].kind == SweepNeighbourRow::shift) coded[count++] = plan[j].coded(in.neighbours[j]);
      const std::uint8_t* ref_codes[3];
      for (int c = 0; c < 3; ++c)
        ref_codes[c] = in.reference->channel_codes(c) + static_cast<std::ptrdiff_t>(y) * in.reference->stride;
      return sweep_code_mean_seen(ref_codes, coded, count, best, tau, out, width, level);
    }
    SweepSeenRow seen[32];
    int count = 0;
    for (int j = 0; j < in.m; ++j)
      if (plan[j].kind == SweepNeighbourRow::shift)
        seen[count++] = SweepSeenRow{plan[j].shifted(in.neighbours[j], plan[j].xb), plan[j].xb, plan[j].xe};
    return sweep_shift_mean_seen(ref_row, seen, count, best, tau, out, width, level);
  }
  // Pixels [a, b) neighbour by neighbour: the best costs kept sorted in keep[0..best), then
  // averaged.
  const auto segment = [&](int a, int b) {
    if (a >= b) return;
    float* seg_keep[32];
    for (int i = 0; i < best; ++i) {
      seg_keep[i] = keep[i] + a;
      std::fill(keep[i] + a, keep[i] + b, tau);
    }
    for (int j = 0; j < in.m; ++j) {
      const SweepNeighbourRow& p = plan[j];
      if (p.kind == SweepNeighbourRow::projective) {
        const std::size_t count = static_cast<std::size_t>(b - a);
        sweep_projective_cost(ref_row, in.neighbours[j].view(), p.row, a, tau, value + a, count, level);
        sweep_keep_best(seg_keep, best, value + a, count, level);
        continue;
      }
      const int lo = std::max(p.xb, a), hi = std::min(p.xe, b);
      if (p.kind != SweepNeighbourRow::shift || lo >= hi) continue;
      const SweepShiftRow row = p.shifted(in.neighbours[j], lo);
      const float* seg_ref[3] = {ref_row[0] + lo, ref_row[1] + lo, ref_row[2] + lo};
      const std::size_t count = static_cast<std::size_t>(hi - lo);
      if (best <= kSweepShiftKeepBest) {
        sweep_shift_keep(seg_ref, row, tau, keep[0] + lo, static_cast<std::ptrdiff_t>(width), best, count, level);
        continue;
      }
      sweep_shift_cost(seg_ref, row, tau, value + lo, count, level);
      float* lo_keep[32];
      for (int i = 0; i < best; ++i) lo_keep[i] = keep[i] + lo;
      sweep_keep_best(lo_keep, best, value + lo, count, level);
    }
    sweep_mean_best(seg_keep, best, out + a, static_cast<std::size_t>(b - a), level);
  };
  if (!all_shift || cb >= ce) return segment(0, width);
  segment(0, cb);
  SweepShiftRow rows[kSweepShiftMeanNeighbours];
  for (int j = 0; j < in.m; ++j) rows[j] = plan[j].shifted(in.neighbours[j], cb);
  const float* core_ref[3] = {ref_row[0] + cb, ref_row[1] + cb, ref_row[2] + cb};
  sweep_shift_mean(core_ref, rows, in.m, best, tau, out + cb, static_cast<std::size_t>(ce - cb), level);
  segment(ce, width);
}

} // namespace mpr::detail
