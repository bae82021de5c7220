#pragma once
/// \file
/// The row kernels of the plane sweep of `estimate_depth` (lightfield/depth_estimation.hpp), with
/// the instruction set chosen at run time: the truncated L1 cost of one reference row against
/// one neighbour camera (a translated row with fixed bilinear weights, or any projective row
/// pixel by pixel), the best-of-m selection over the neighbours' cost rows (a min/max insertion
/// network), the recursive domain-transform passes (a block of rows in lockstep for the
/// horizontal recurrence, whole rows for the vertical one) and the per-pixel argmin bookkeeping.
///
/// Images are planar float channels (sRGB codes / 255), one row after another with a row stride
/// of at least width + 1 floats (the element past a row's end is read with weight 0 and must be
/// finite). Each kernel is written once as plain C++ and compiled for every level of
/// core/simd.hpp through `run_at`, where the compiler vectorises its loops.

#include <mpr/core/simd.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

namespace mpr::detail {

/// One neighbour row seen from a reference row when the map between them is a translation:
/// the reference pixel x sees the neighbour at (x + shift + fu, row + fv), so every pixel blends
/// the same four texels around it with the same bilinear weights.
struct SweepShiftRow {
  /// Per channel, the neighbour rows `row` and `row + 1`, each already offset by the integer
  /// shift (element x is the texel at column x + shift); elements [0, n + 1) are read.
  const float* top[3];
  const float* bottom[3];
  /// Sub-pixel offsets in [0, 1].
  float fu, fv;
};

/// The truncated L1 cost of reference pixel x of a translated row (`SweepShiftRow`), `ref` the
/// three reference channel rows: per channel the bilinear blend of the four texels with the
/// row's fixed weights, |blend - ref|, summed and truncated at tau.
struct SweepShiftCost {
  const float* MPR_RESTRICT r[3];
  const float* MPR_RESTRICT a[3];
  const float* MPR_RESTRICT b[3];
  float w00, w10, w01, w11, tau;
  MPR_ALWAYS_INLINE SweepShiftCost(const float* const ref[3], const SweepShiftRow& row, float truncation) noexcept
      : r{ref[0], ref[1], ref[2]}, a{row.top[0], row.top[1], row.top[2]}, b{row.bottom[0], row.bottom[1],
                                                                            row.bottom[2]},
        w00((1 - row.fu) * (1 - row.fv)), w10(row.fu * (1 - row.fv)), w01((1 - row.fu) * row.fv), w11(row.fu * row.fv),
        tau(truncation) {}
  [[nodiscard]] MPR_ALWAYS_INLINE float channel(int c, std::size_t x) const noexcept {
    return std::abs(w00 * a[c][x] + w10 * a[c][x + 1] + w01 * b[c][x] + w11 * b[c][x + 1] - r[c][x]);
  }
  [[nodiscard]] MPR_ALWAYS_INLINE float operator()(std::size_t x) const noexcept {
    return std::min(channel(0, x) + channel(1, x) + channel(2, x), tau);
  }
};

/// out[x] = the cost of pixel x (`SweepShiftCost`) for x in [0, n).
MPR_ALWAYS_INLINE void sweep_shift_cost_body(const float* const ref[3], const SweepShiftRow& row, float tau,
                                             float* MPR_RESTRICT out, std::size_t n) noexcept {
  const SweepShiftCost cost(ref, row, tau);
  for (std::size_t x = 0; x < n; ++x) out[x] = cost(x);
}

/// The cost of pixel x (`SweepShiftCost`) inserted into the B sorted rows keep + i stride (i <
/// B) for x in [0, n): `sweep_shift_cost_body` then `sweep_keep_best_body` in one pass.
template <int B>
MPR_ALWAYS_INLINE void sweep_shift_keep_body(const float* const ref[3], const SweepShiftRow& row, float tau,
                                             float* MPR_RESTRICT keep, std::ptrdiff_t stride, std::size_t n) noexcept {
  const SweepShiftCost cost(ref, row, tau);
  for (std::size_t x = 0; x < n; ++x) {
    float v = cost(x);
#pragma GCC unroll 4
    for (int i = 0; i < B; ++i) {
      const float k = keep[i * stride + static_cast<std::ptrdiff_t>(x)];
      keep[i * stride + static_cast<std::ptrdiff_t>(x)] = std::min(k, v);
      v = std::max(k, v);
    }
  }
}

/// The most kept costs `sweep_shift_keep` takes.
inline constexpr int kSweepShiftKeepBest = 4;

/// The most neighbours `sweep_shift_mean` takes.
inline constexpr int kSweepShiftMeanNeighbours = 4;

/// out[x] = the mean of the B smallest of the M neighbours' costs of pixel x (`SweepShiftCost`
/// of rows[j], each truncated at tau) for x in [0, n): what filling B rows with tau, then
/// `sweep_shift_keep` for every neighbour in order and `sweep_mean_best` give, in one pass with
/// the kept costs in registers (the same insertions and the same sum, so the same values).
template <int M, int B>
MPR_ALWAYS_INLINE void sweep_shift_mean_body(const float* const ref[3], const SweepShiftRow* rows, float tau,
                                             float* MPR_RESTRICT out, std::size_t n) noexcept {
  static_assert(B >= 1 && B <= M);
  const SweepShiftCost c0(ref, rows[0], tau);
  const SweepShiftCost c1(ref, rows[M > 1 ? 1 : 0], tau);
  const SweepShiftCost c2(ref, rows[M > 2 ? 2 : 0], tau);
  const SweepShiftCost c3(ref, rows[M > 3 ? 3 : 0], tau);
  for (std::size_t x = 0; x < n; ++x) {
    float keep[B];
#pragma GCC unroll 4
    for (int i = 0; i < B; ++i) keep[i] = tau;
#pragma GCC unroll 4
    for (int j = 0; j < M; ++j) {
      float v = j == 0 ? c0(x) : j == 1 ? c1(x) : j == 2 ? c2(x) : c3(x);
#pragma GCC unroll 4
      for (int i = 0; i < B; ++i) {
        const float k = keep[i];
        keep[i] = std::min(k, v);
        v = std::max(k, v);
      }
    }
    float sum = keep[0];
#pragma GCC unroll 4
    for (int i = 1; i < B; ++i) sum += keep[i];
    out[x] = sum / static_cast<float>(B);
  }
}

/// `sweep_shift_mean_body<M, best>` for a run-time `best` in [B, M].
template <int M, int B>
MPR_ALWAYS_INLINE void sweep_shift_mean_best(const float* const ref[3], const SweepShiftRow* rows, int best, float tau,
                                             float* out, std::size_t n) noexcept {
  if constexpr (B < M)
    if (best > B) return sweep_shift_mean_best<M, B + 1>(ref, rows, best, tau, out, n);
  sweep_shift_mean_body<M, B>(ref, rows, tau, out, n);
}

/// A neighbour camera's image for the projective path: planar channels, `stride` floats per row.
struct SweepImage {
  const float* channel[3];
  std::ptrdiff_t stride;
  int width, height;
};

/// One reference row's projections into a neighbour: pixel x maps to the homogeneous point
/// h(x) = origin + depth (base + x step) (the neighbour's pixel h.x / h.z, h.y / h.z).
struct SweepProjectiveRow {
  float origin[3], base[3], step[3];
  float depth;
};

/// out[x] for x in [0, n) (reference pixels first + x): the truncated L1 cost against `image` at
/// the projected point, bilinear, or `tau` where the point is behind the neighbour or outside
/// [0, width - 1] x [0, height - 1]. Any homography, pixel by pixel.
MPR_ALWAYS_INLINE void sweep_projective_cost_body(const float* const ref[3], const SweepImage& image,
                                                  const SweepProjectiveRow& row, int first, float tau,
                                                  float* MPR_RESTRICT out, std::size_t n) noexcept {
  const float max_u = static_cast<float>(image.width - 1), max_v = static_cast<float>(image.height - 1);
  const int last_u = std::max(image.width - 2, 0), last_v = std::max(image.height - 2, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const float x = static_cast<float>(first + static_cast<int>(i));
    const float hx = row.origin[0] + row.depth * (row.base[0] + x * row.step[0]);
    const float hy = row.origin[1] + row.depth * (row.base[1] + x * row.step[1]);
    const float hz = row.origin[2] + row.depth * (row.base[2] + x * row.step[2]);
    float cost = tau;
    if (hz > 0) {
      const float u = hx / hz, v = hy / hz;
      if (u >= 0 && v >= 0 && u <= max_u && v <= max_v) {
        const int u0 = std::min(static_cast<int>(u), last_u), v0 = std::min(static_cast<int>(v), last_v);
        const int u1 = std::min(u0 + 1, image.width - 1), v1 = std::min(v0 + 1, image.height - 1);
        const float fu = u - static_cast<float>(u0), fv = v - static_cast<float>(v0);
        float s = 0;
        for (int c = 0; c < 3; ++c) {
          const float* t = image.channel[c];
          const float* a = t + v0 * image.stride;
          const float* b = t + v1 * image.stride;
          const float top = a[u0] * (1 - fu) + a[u1] * fu, bottom = b[u0] * (1 - fu) + b[u1] * fu;
          s += std::abs((top * (1 - fv) + bottom * fv) - ref[c][first + static_cast<int>(i)]);
        }
        cost = std::min(s, tau);
      }
    }
    out[i] = cost;
  }
}

/// Inserts the cost row `value` into the sorted rows keep[0] <= keep[1] <= ... <= keep[best - 1]
/// (per pixel, x in [0, n)): a min/max insertion network, so that after every neighbour's row
/// keep[i] holds the (i+1)-th smallest cost seen. `value` is overwritten (with the dropped
/// largest). Rows start at the truncation, which stands for an unseen neighbour.
MPR_ALWAYS_INLINE void sweep_keep_best_body(float* const* keep, int best, float* MPR_RESTRICT value,
                                            std::size_t n) noexcept {
  for (int i = 0; i < best; ++i) {
    float* MPR_RESTRICT k = keep[i];
    for (std::size_t x = 0; x < n; ++x) {
      const float a = k[x], v = value[x];
      k[x] = std::min(a, v);
      value[x] = std::max(a, v);
    }
  }
}

/// out[x] = (keep[0][x] + ... + keep[best - 1][x]) / best for x in [0, n): the mean of the kept
/// costs, smallest first.
MPR_ALWAYS_INLINE void sweep_mean_best_body(const float* const* keep, int best, float* MPR_RESTRICT out,
                                            std::size_t n) noexcept {
  const float* MPR_RESTRICT k0 = keep[0];
  for (std::size_t x = 0; x < n; ++x) out[x] = k0[x];
  for (int i = 1; i < best; ++i) {
    const float* MPR_RESTRICT k = keep[i];
    for (std::size_t x = 0; x < n; ++x) out[x] += k[x];
  }
  const float b = static_cast<float>(best);
  for (std::size_t x = 0; x < n; ++x) out[x] /= b;
}

/// `sweep_mean_best_body` for B kept rows in one pass (the same sums in the same order).
template <int B>
MPR_ALWAYS_INLINE void sweep_mean_best_fixed(const float* const* keep, float* MPR_RESTRICT out,
                                             std::size_t n) noexcept {
  const float* MPR_RESTRICT k[B];
  for (int i = 0; i < B; ++i) k[i] = keep[i];
  for (std::size_t x = 0; x < n; ++x) {
    float s = k[0][x];
#pragma GCC unroll 4
    for (int i = 1; i < B; ++i) s += k[i][x];
    out[x] = s / static_cast<float>(B);
  }
}

/// The rows of a block handled in lockstep by the horizontal domain-transform pass.
inline constexpr int kSweepLockstepRows = 8;

/// The horizontal domain-transform pass (forward, then backward) on `kSweepLockstepRows` rows of
/// `n` values at v + r stride, with feedback a + r stride: v[k] += a[k] (v[k - 1] - v[k]) for k
/// = 1..n-1, then v[k] += a[k + 1] (v[k + 1] - v[k]) for k = n-2..0. The recurrence is serial
/// along a row, so the rows run side by side (independent chains), n >= 1.
MPR_ALWAYS_INLINE void sweep_dt_rows_body(float* v, const float* a, std::ptrdiff_t stride, int n) noexcept {
  constexpr int R = kSweepLockstepRows;
  float carry[R];
  for (int r = 0; r < R; ++r) carry[r] = v[r * stride];
  for (int k = 1; k < n; ++k)
    for (int r = 0; r < R; ++r) {
      float& x = v[r * stride + k];
      x += a[r * stride + k] * (carry[r] - x);
      carry[r] = x;
    }
  for (int k = n - 2; k >= 0; --k)
    for (int r = 0; r < R; ++r) {
      float& x = v[r * stride + k];
      x += a[r * stride + k + 1] * (carry[r] - x);
      carry[r] = x;
    }
}

/// The same pass on one row (the rows left over after the lockstep blocks).
MPR_ALWAYS_INLINE void sweep_dt_row_body(float* v, const float* a, int n) noexcept {
  for (int k = 1; k < n; ++k) v[k] += a[k] * (v[k - 1] - v[k]);
  for (int k = n - 2; k >= 0; --k) v[k] += a[k + 1] * (v[k + 1] - v[k]);
}

/// One step of the vertical domain-transform pass over a row segment: cur[x] += a[x] (prev[x] -
/// cur[x]) for x in [0, n), prev the row before (forward) or after (backward) and `a` the
/// feedback of the link between them.
MPR_ALWAYS_INLINE void sweep_dt_link_body(float* MPR_RESTRICT cur, const float* MPR_RESTRICT prev,
                                          const float* MPR_RESTRICT a, std::size_t n) noexcept {
  for (std::size_t x = 0; x < n; ++x) cur[x] += a[x] * (prev[x] - cur[x]);
}

/// One step of the backward vertical pass that leaves the costs in place: carry[x] = cur[x] +
/// a[x] (carry[x] - cur[x]) for x in [0, n), `carry` holding the final row below on entry and
/// row `cur`'s final values on return.
MPR_ALWAYS_INLINE void sweep_dt_carry_body(float* MPR_RESTRICT carry, const float* MPR_RESTRICT cur,
                                           const float* MPR_RESTRICT a, std::size_t n) noexcept {
  for (std::size_t x = 0; x < n; ++x) carry[x] = cur[x] + a[x] * (carry[x] - cur[x]);
}

/// Asks for the n floats at p to be brought into cache (a hint; nothing where the compiler has
/// no prefetch).
inline void sweep_prefetch(const float* p, std::size_t n) noexcept {
#if defined(__GNUC__)
  for (std::size_t i = 0; i < n; i += 16) __builtin_prefetch(p + i);
#else
  (void)p;
  (void)n;
#endif
}

/// The per-pixel state of the argmin over planes: the running sum of costs, the cheapest cost
/// and plane, the costs at the planes before (`left`) and after (`right`) the cheapest, for the
/// parabola, and the last plane's cost (`previous`).
struct SweepTrackRow {
  float* best_cost;
  int* best_plane;
  float* left;
  float* right;
  float* previous;
  float* sum;
};

/// The most planes `sweep_track` takes at once.
inline constexpr int kSweepTrackPlanes = 8;

/// The argmin bookkeeping of one row segment of n pixels for the K planes plane0, plane0 + 1,
/// ... (plane i's costs at c + i stride), in plane order: the state is read and written once;
/// `Start` (plane0 = 0): it is only written (no best cost yet, sums 0), so the caller need not
/// clear it.
template <int K, bool Start>
MPR_ALWAYS_INLINE void
sweep_track_body(const float* MPR_RESTRICT c, std::ptrdiff_t stride, float* MPR_RESTRICT best_cost,
                 int* MPR_RESTRICT best_plane, float* MPR_RESTRICT left, float* MPR_RESTRICT right,
                 float* MPR_RESTRICT previous, float* MPR_RESTRICT sum, int plane0, std::size_t n) noexcept {
  for (std::size_t x = 0; x < n; ++x) {
    float bc = std::numeric_limits<float>::infinity(), l = 0, r = 0, p = 0, s = 0;
    int b = 0;
    if constexpr (!Start) {
      bc = best_cost[x];
      l = left[x];
      r = right[x];
      p = previous[x];
      s = sum[x];
      b = best_plane[x];
    }
#pragma GCC unroll 8
    for (int i = 0; i < K; ++i) {
      const int plane = plane0 + i;
      const float v = c[i * stride + static_cast<std::ptrdiff_t>(x)];
      s += v;
      r = b == plane - 1 ? v : r;
      const bool better = v < bc;
      r = better ? v : r;
      l = better ? (plane > 0 ? p : v) : l;
      bc = better ? v : bc;
      b = better ? plane : b;
      p = v;
    }
    best_cost[x] = bc;
    best_plane[x] = b;
    left[x] = l;
    right[x] = r;
    previous[x] = p;
    sum[x] = s;
  }
}

/// The kernels above compiled for `level` (default: the widest this CPU runs).
inline void sweep_shift_cost(const float* const ref[3], const SweepShiftRow& row, float tau, float* out, std::size_t n,
                             SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { sweep_shift_cost_body(ref, row, tau, out, n); });
}
/// `sweep_shift_keep_body` for `best` (1..kSweepShiftKeepBest) kept rows.
inline void sweep_shift_keep(const float* const ref[3], const SweepShiftRow& row, float tau, float* keep,
                             std::ptrdiff_t stride, int best, std::size_t n,
                             SimdLevel level = dispatch_level()) noexcept {
  static_assert(kSweepShiftKeepBest == 4);
  run_at(level, [&]() MPR_INLINE_LAMBDA {
    if (best == 1)
      sweep_shift_keep_body<1>(ref, row, tau, keep, stride, n);
    else if (best == 2)
      sweep_shift_keep_body<2>(ref, row, tau, keep, stride, n);
    else if (best == 3)
      sweep_shift_keep_body<3>(ref, row, tau, keep, stride, n);
    else
      sweep_shift_keep_body<4>(ref, row, tau, keep, stride, n);
  });
}
/// `sweep_shift_mean_body` for m (1..kSweepShiftMeanNeighbours) neighbours' rows and `best`
/// (1..m) kept costs.
inline void sweep_shift_mean(const float* const ref[3], const SweepShiftRow* rows, int m, int best, float tau,
                             float* out, std::size_t n, SimdLevel level = dispatch_level()) noexcept {
  static_assert(kSweepShiftMeanNeighbours == 4);
  run_at(level, [&]() MPR_INLINE_LAMBDA {
    if (m == 1)
      sweep_shift_mean_best<1, 1>(ref, rows, best, tau, out, n);
    else if (m == 2)
      sweep_shift_mean_best<2, 1>(ref, rows, best, tau, out, n);
    else if (m == 3)
      sweep_shift_mean_best<3, 1>(ref, rows, best, tau, out, n);
    else
      sweep_shift_mean_best<4, 1>(ref, rows, best, tau, out, n);
  });
}
inline void sweep_projective_cost(const float* const ref[3], const SweepImage& image, const SweepProjectiveRow& row,
                                  int first, float tau, float* out, std::size_t n,
                                  SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { sweep_projective_cost_body(ref, image, row, first, tau, out, n); });
}
inline void sweep_keep_best(float* const* keep, int best, float* value, std::size_t n,
                            SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { sweep_keep_best_body(keep, best, value, n); });
}
inline void sweep_mean_best(const float* const* keep, int best, float* out, std::size_t n,
                            SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA {
    if (best == 1)
      sweep_mean_best_fixed<1>(keep, out, n);
    else if (best == 2)
      sweep_mean_best_fixed<2>(keep, out, n);
    else if (best == 3)
      sweep_mean_best_fixed<3>(keep, out, n);
    else if (best == 4)
      sweep_mean_best_fixed<4>(keep, out, n);
    else
      sweep_mean_best_body(keep, best, out, n);
  });
}
inline void sweep_dt_rows(float* v, const float* a, std::ptrdiff_t stride, int n,
                          SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { sweep_dt_rows_body(v, a, stride, n); });
}
inline void sweep_dt_row(float* v, const float* a, int n, SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { sweep_dt_row_body(v, a, n); });
}
inline void sweep_dt_carry(float* carry, const float* cur, const float* a, std::size_t n,
                           SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { sweep_dt_carry_body(carry, cur, a, n); });
}
inline void sweep_dt_link(float* cur, const float* prev, const float* a, std::size_t n,
                          SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { sweep_dt_link_body(cur, prev, a, n); });
}
template <int K>
MPR_ALWAYS_INLINE void sweep_track_count(const float* c, std::ptrdiff_t stride, int count, const SweepTrackRow& t,
                                         int plane0, std::size_t n) noexcept {
  if constexpr (K > 1)
    if (count < K) return sweep_track_count<K - 1>(c, stride, count, t, plane0, n);
  if (plane0 == 0)
    sweep_track_body<K, true>(c, stride, t.best_cost, t.best_plane, t.left, t.right, t.previous, t.sum, plane0, n);
  else
    sweep_track_body<K, false>(c, stride, t.best_cost, t.best_plane, t.left, t.right, t.previous, t.sum, plane0, n);
}

/// `sweep_track_body` for `count` (1..kSweepTrackPlanes) planes.
inline void sweep_track(const float* c, std::ptrdiff_t stride, int count, const SweepTrackRow& t, int plane0,
                        std::size_t n, SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { sweep_track_count<kSweepTrackPlanes>(c, stride, count, t, plane0, n); });
}

} // namespace mpr::detail
