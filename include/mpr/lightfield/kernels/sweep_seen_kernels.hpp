#pragma once
/// \file
/// The plane sweep's fused row kernel for many translated neighbours (lightfield/plane_sweep/
/// sweep_row.hpp): the mean of the best costs of each reference pixel among the neighbours that
/// see it, in chunks of pixels whose kept costs stay in registers. Written once as plain C++ with
/// the compiler's vector type and compiled for every level of core/simd.hpp through `run_at`,
/// like the other row kernels of kernels/sweep_kernels.hpp, whose cost (`SweepShiftCost`) it uses.

#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/sweep_kernels.hpp>

#include <algorithm>
#include <cstddef>
#include <cstring>

namespace mpr::detail {

/// A neighbour's translated row (`SweepShiftRow`) with the reference pixels it sees, [xb, xe):
/// element 0 of `row`'s rows is the texel reference pixel xb blends from.
struct SweepSeenRow {
  SweepShiftRow row;
  int xb, xe;
};

/// The pixels `sweep_shift_mean_seen` takes together without the compiler's vectors.
inline constexpr int kSweepSeenChunk = 16;

/// The most kept costs `sweep_shift_mean_seen` takes.
inline constexpr int kSweepSeenBest = 16;

#if defined(__GNUC__)
/// The pixels a chunk takes together at `level`: one register of floats
/// (`simd_register_bytes`: 16 at AVX-512, 8 at AVX2, 4 at the portable level).
[[nodiscard]] constexpr int sweep_seen_lanes(SimdLevel level) noexcept {
  return simd_register_bytes(level) / static_cast<int>(sizeof(float));
}

/// W floats as one vector of the compiler's, and the same lanes' bits as integers (|x| as x's
/// bits without the sign bit: one AND, where x < 0 ? -x : x takes a compare and a blend).
template <int W>
struct SweepSeenVectors {
  typedef float Lanes __attribute__((vector_size(W * sizeof(float))));
  typedef unsigned Bits __attribute__((vector_size(W * sizeof(float))));
};

/// The lanes of a vector of floats.
template <class V>
inline constexpr int kSweepSeenWidth = static_cast<int>(sizeof(V) / sizeof(float));

/// The lanes of V from p (any alignment) times w (through a reference: a vector return value
/// would change the ABI between levels).
template <class V>
MPR_ALWAYS_INLINE void sweep_lanes(V& v, float w, const float* p) noexcept {
  std::memcpy(&v, p, sizeof v);
  v *= w;
}
#endif

#if defined(__GNUC__)
/// v = neighbour `r`'s costs (`SweepShiftCost`) of the lanes of V, pixels from x0, of which
/// it sees [lo, hi) (non-empty): tau for the others (through a reference, as `sweep_lanes`);
/// q: the reference's channels at those pixels, loaded once a chunk (read where hi - lo is the
/// whole chunk).
template <class V>
MPR_ALWAYS_INLINE void sweep_seen_cost(V& v, const V q[3], const float* const ref[3], const SweepSeenRow& r, float tau,
                                       int x0, int lo, int hi) noexcept {
  constexpr int W = kSweepSeenWidth<V>;
  using Bits = typename SweepSeenVectors<W>::Bits;
  const V t = V{} + tau;
  const float* seen_ref[3] = {ref[0] + r.xb, ref[1] + r.xb, ref[2] + r.xb};
  const SweepShiftCost cost(seen_ref, r.row, tau);
  const std::size_t at = static_cast<std::size_t>(x0 - r.xb);
  v = t;
  if (hi - lo == W) {
    V s{};
    for (int c = 0; c < 3; ++c) {
      V p00, p10, p01, p11;
      sweep_lanes(p00, cost.w00, cost.a[c] + at);
      sweep_lanes(p10, cost.w10, cost.a[c] + at + 1);
      sweep_lanes(p01, cost.w01, cost.b[c] + at);
      sweep_lanes(p11, cost.w11, cost.b[c] + at + 1);
      const V d = p00 + p10 + p01 + p11 - q[c];
      const V e = (V)((Bits)d & 0x7fffffffu);
      s = c == 0 ? e : s + e;
    }
    v = s < t ? s : t;
  } else {
    for (int x = lo; x < hi; ++x) v[x - x0] = cost(static_cast<std::size_t>(x - r.xb));
  }
}

/// out[x] = the mean of the `best` smallest of the m costs of pixel x as in
/// `sweep_shift_mean_seen_body`, for K = m - best < best, computed as (the sum of all m costs -
/// the sum of the K largest) / best: K insertions a neighbour instead of `best`. The same values
/// up to the rounding of the sums (within a few ulp of 3 m).
template <int W, int K>
MPR_ALWAYS_INLINE void sweep_shift_drop_seen_body(const float* const ref[3], const SweepSeenRow* rows, int m, float tau,
                                                  float* MPR_RESTRICT out, int width) noexcept {
  using SweepLanes = typename SweepSeenVectors<W>::Lanes;
  using SweepLaneBits = typename SweepSeenVectors<W>::Bits;
  const SweepLanes t = SweepLanes{} + tau;
  for (int x0 = 0; x0 < width; x0 += W) {
    const int len = std::min(W, width - x0);
    SweepLanes q[3] = {};
    if (len == W)
      for (int c = 0; c < 3; ++c) sweep_lanes(q[c], 1.0f, ref[c] + x0);
    // The costs are >= 0 and not NaN, so their bits order as unsigned integers as the floats
    // do: the largest are kept by integer min and max (one instruction each, on the integer
    // units, where a float select takes a compare and two blends).
    SweepLaneBits drop[K > 0 ? K : 1];
    for (int i = 0; i < K; ++i) drop[i] = SweepLaneBits{}; // the bits of 0.0f
    SweepLanes sum{};
    for (int j = 0; j < m; ++j) {
      const SweepSeenRow& r = rows[j];
      const int lo = std::max(r.xb, x0), hi = std::min(r.xe, x0 + len);
      SweepLanes c = t;
      if (lo < hi) sweep_seen_cost(c, q, ref, r, tau, x0, lo, hi);
      sum += c;
      SweepLaneBits v = (SweepLaneBits)c;
#pragma GCC unroll 16
      for (int i = 0; i < K; ++i) {
        const SweepLaneBits k = drop[i];
        drop[i] = v < k ? k : v;
        v = v < k ? v : k;
      }
    }
#pragma GCC unroll 16
    for (int i = 0; i < K; ++i) sum -= (SweepLanes)drop[i];
    SweepLanes s = sum / static_cast<float>(m - K);
    s = s < 0 ? SweepLanes{} : s;
    if (len == W)
      std::memcpy(out + x0, &s, sizeof s);
    else
      for (int w = 0; w < len; ++w) out[x0 + w] = s[w];
  }
}
#endif

/// out[x] = the mean of the B smallest costs (`SweepShiftCost`) of pixel x among the m
/// neighbours rows[0..m) that see it, an unseen neighbour counting as tau, for x in [0, width):
/// what filling B rows with tau, then for every neighbour in order `sweep_shift_keep` over the
/// pixels it sees, and `sweep_mean_best` give (the same insertions and sums), in chunks of W
/// pixels (one register of the level) whose kept costs stay there. An unseen neighbour is
/// skipped: inserting tau into costs that are all <= tau changes nothing. A chunk a neighbour
/// sees only in part takes its costs pixel by pixel.
template <int W, int B>
MPR_ALWAYS_INLINE void sweep_shift_mean_seen_body(const float* const ref[3], const SweepSeenRow* rows, int m, float tau,
                                                  float* MPR_RESTRICT out, int width) noexcept {
#if defined(__GNUC__)
  using SweepLanes = typename SweepSeenVectors<W>::Lanes;
  const SweepLanes t = SweepLanes{} + tau;
  for (int x0 = 0; x0 < width; x0 += W) {
    const int len = std::min(W, width - x0);
    SweepLanes q[3] = {};
    if (len == W)
      for (int c = 0; c < 3; ++c) sweep_lanes(q[c], 1.0f, ref[c] + x0);
    SweepLanes keep[B];
    for (int i = 0; i < B; ++i) keep[i] = t;
    for (int j = 0; j < m; ++j) {
      const SweepSeenRow& r = rows[j];
      const int lo = std::max(r.xb, x0), hi = std::min(r.xe, x0 + len);
      if (lo >= hi) continue;
      SweepLanes v;
      sweep_seen_cost(v, q, ref, r, tau, x0, lo, hi);
#pragma GCC unroll 16
      for (int i = 0; i < B; ++i) {
        const SweepLanes k = keep[i];
        keep[i] = v < k ? v : k;
        v = k < v ? v : k;
      }
    }
    SweepLanes s = keep[0];
#pragma GCC unroll 16
    for (int i = 1; i < B; ++i) s += keep[i];
    s = s / static_cast<float>(B);
    if (len == W)
      std::memcpy(out + x0, &s, sizeof s);
    else
      for (int w = 0; w < len; ++w) out[x0 + w] = s[w];
  }
#else
  for (int x0 = 0; x0 < width; x0 += W) {
    const int len = std::min(W, width - x0);
    float keep[B][W];
    for (int i = 0; i < B; ++i)
      for (int w = 0; w < W; ++w) keep[i][w] = tau;
    for (int j = 0; j < m; ++j) {
      const SweepSeenRow& r = rows[j];
      const int lo = std::max(r.xb, x0), hi = std::min(r.xe, x0 + len);
      const float* seen_ref[3] = {ref[0] + r.xb, ref[1] + r.xb, ref[2] + r.xb};
      const SweepShiftCost cost(seen_ref, r.row, tau);
      for (int x = lo; x < hi; ++x) {
        float v = cost(static_cast<std::size_t>(x - r.xb));
        for (int i = 0; i < B; ++i) {
          const float k = keep[i][x - x0];
          keep[i][x - x0] = std::min(k, v);
          v = std::max(k, v);
        }
      }
    }
    for (int w = 0; w < len; ++w) {
      float s = keep[0][w];
      for (int i = 1; i < B; ++i) s += keep[i][w];
      out[x0 + w] = s / static_cast<float>(B);
    }
  }
#endif
}

/// `sweep_shift_mean_seen_body<W, B>` for a run-time `best` in [B, kSweepSeenBest].
template <int W, int B>
MPR_ALWAYS_INLINE void sweep_shift_mean_seen_best(const float* const ref[3], const SweepSeenRow* rows, int m, int best,
                                                  float tau, float* out, int width) noexcept {
  if constexpr (B < kSweepSeenBest)
    if (best > B) return sweep_shift_mean_seen_best<W, B + 1>(ref, rows, m, best, tau, out, width);
  sweep_shift_mean_seen_body<W, B>(ref, rows, m, tau, out, width);
}

#if defined(__GNUC__)
/// `sweep_shift_drop_seen_body<W, K>` for a run-time m - best = `drop` in [K, kSweepSeenBest).
template <int W, int K>
MPR_ALWAYS_INLINE void sweep_shift_drop_seen_count(const float* const ref[3], const SweepSeenRow* rows, int m, int drop,
                                                   float tau, float* out, int width) noexcept {
  if constexpr (K + 1 < kSweepSeenBest)
    if (drop > K) return sweep_shift_drop_seen_count<W, K + 1>(ref, rows, m, drop, tau, out, width);
  sweep_shift_drop_seen_body<W, K>(ref, rows, m, tau, out, width);
}
#endif

/// The mean of the `best` (1..kSweepSeenBest) smallest costs of m (1..32) neighbours over the
/// reference row's `width` pixels: `sweep_shift_mean_seen_body`, or where fewer are dropped than
/// kept (0 <= m - best < best, such as the best 8 of 12), `sweep_shift_drop_seen_body` (fewer
/// insertions; equal up to rounding). Neighbours left out of `rows` count as tau: with m >= best
/// they are not among the best.
inline void sweep_shift_mean_seen(const float* const ref[3], const SweepSeenRow* rows, int m, int best, float tau,
                                  float* out, int width, SimdLevel level = dispatch_level()) noexcept {
#if defined(__GNUC__)
  const bool drop = m >= best && m - best < best;
  run_at(level, [&](auto tag) MPR_INLINE_LAMBDA {
    constexpr int W = sweep_seen_lanes(decltype(tag)::value);
    if (drop)
      sweep_shift_drop_seen_count<W, 0>(ref, rows, m, m - best, tau, out, width);
    else
      sweep_shift_mean_seen_best<W, 1>(ref, rows, m, best, tau, out, width);
  });
#else
  run_at(level, [&]() { sweep_shift_mean_seen_best<kSweepSeenChunk, 1>(ref, rows, m, best, tau, out, width); });
#endif
}

} // namespace mpr::detail
