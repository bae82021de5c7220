#pragma once
/// \file
/// The plane sweep's chunked row kernel for many translated neighbours on 16-bit integers: what
/// `sweep_shift_mean_seen` (kernels/sweep_seen_kernels.hpp) computes in float, here on the
/// images' 8-bit sRGB codes with bilinear weights in 1/256 and costs in 1/32 of a code, a
/// register of 16-bit lanes a chunk (32 pixels at AVX-512): half the loads and twice the lanes of
/// the float kernel. Every sum is exact (no saturation, no rounding), so the values are the same
/// at every level; they differ from the float kernel's by the weights' rounding to 1/256 (a
/// shift of at most about 1/256 pixel) and the costs' to 1/32 code. Written once as plain C++
/// with the compiler's vector type and compiled for every level of core/simd.hpp through
/// `run_at`.

#include <mpr/core/simd.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace mpr::detail {

/// The most pixels the 16-bit kernel takes together (`sweep_code_lanes`).
inline constexpr int kSweepCodeChunk = 32;

/// The most kept costs the 16-bit kernel takes (as `kSweepSeenBest`).
inline constexpr int kSweepCodeBest = 16;

/// Cost units per 1.0 of the float costs (channel values code / 255): 32 units a code.
inline constexpr int kSweepCodeUnit = 255 * 32;

/// Codes an image of 16-bit codes holds past both ends of its channels (`SweepPlanes::words`):
/// the kernel reads whole chunks, up to kSweepCodeChunk + 1 codes past a row's seen pixels on
/// either side, and masks what it does not see.
inline constexpr std::ptrdiff_t kSweepCodePad = 2 * kSweepCodeChunk + 16;

/// A neighbour's translated row on codes: per channel the texel rows v0 (`top`) and v0 + 1
/// (`bottom`), element 0 the texel reference pixel xb blends from (as `SweepSeenRow`), the
/// bilinear weights w00, w10, w01, w11 in 1/256 (`sweep_code_weights`), and the reference
/// pixels it sees, [xb, xe).
struct SweepCodeRow {
  const std::uint16_t* top[3];
  const std::uint16_t* bottom[3];
  std::uint16_t w[4];
  int xb, xe;
};

/// The bilinear weights (1 - fu)(1 - fv), fu (1 - fv), (1 - fu) fv, fu fv of offsets fu, fv in
/// [0, 1] in 1/256, each rounded to the nearest, the largest then corrected so that they sum to
/// 256 (a blend of codes is then at most 255 x 256, exact in 16 bits).
[[nodiscard]] inline std::array<std::uint16_t, 4> sweep_code_weights(float fu, float fv) noexcept {
  const float u = std::clamp(fu, 0.0f, 1.0f), v = std::clamp(fv, 0.0f, 1.0f);
  const float f[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
  std::array<int, 4> w{};
  int sum = 0, largest = 0;
  for (int i = 0; i < 4; ++i) {
    w[static_cast<std::size_t>(i)] = static_cast<int>(std::lround(256.0f * f[i]));
    sum += w[static_cast<std::size_t>(i)];
    if (f[i] > f[largest]) largest = i;
  }
  w[static_cast<std::size_t>(largest)] += 256 - sum;
  return {static_cast<std::uint16_t>(w[0]), static_cast<std::uint16_t>(w[1]), static_cast<std::uint16_t>(w[2]),
          static_cast<std::uint16_t>(w[3])};
}

/// The truncation tau (float cost units, >= 0) in cost units, at most the largest cost (3 x
/// kSweepCodeUnit).
[[nodiscard]] inline int sweep_code_tau(float tau) noexcept {
  return static_cast<int>(std::lround(std::clamp(tau, 0.0f, 3.0f) * static_cast<float>(kSweepCodeUnit)));
}

/// Whether the 16-bit kernel takes m neighbours' rows keeping `best` (1..kSweepCodeBest) at
/// truncation tau: its sums of up to max(m, best) costs of at most tau stay within 16 bits.
[[nodiscard]] inline bool sweep_code_fits(int m, int best, float tau) noexcept {
  return best >= 1 && best <= kSweepCodeBest && m >= 0 && m <= 32 && std::max(m, best) * sweep_code_tau(tau) <= 0xffff;
}

/// The cost of reference pixel x of row r (seen: x in [xb, xe)) in units: per channel the blend
/// of the four codes, |blend - 256 ref|, divided by 8 (dropping the remainder), summed, then at
/// most tau. What the vector body computes lane by lane.
[[nodiscard]] inline unsigned sweep_code_cost_at(const std::uint16_t* const ref[3], const SweepCodeRow& r, unsigned tau,
                                                 int x) noexcept {
  const std::ptrdiff_t at = x - r.xb;
  unsigned s = 0;
  for (int c = 0; c < 3; ++c) {
    const unsigned p =
        r.w[0] * r.top[c][at] + r.w[1] * r.top[c][at + 1] + r.w[2] * r.bottom[c][at] + r.w[3] * r.bottom[c][at + 1];
    const unsigned q = 256u * ref[c][x];
    s += (p > q ? p - q : q - p) >> 3;
  }
  return std::min(s, tau);
}

#if defined(__GNUC__)
/// N 16-bit lanes as one vector of the compiler's, and the same lanes as floats: N is the
/// level's register width (`sweep_code_lanes`), a wider vector type is lowered badly at AVX2.
template <int N>
struct SweepCodeVectors {
  typedef std::uint16_t Lanes __attribute__((vector_size(N * sizeof(std::uint16_t))));
  typedef float Floats __attribute__((vector_size(N * sizeof(float))));
};

/// The pixels a chunk of the 16-bit kernel takes at `level`: one register of 16-bit lanes (32
/// at AVX-512, 16 at AVX2, 8 in the 16-byte registers of the portable level).
[[nodiscard]] constexpr int sweep_code_lanes(SimdLevel level) noexcept {
  return level >= SimdLevel::avx512 ? 32 : level == SimdLevel::avx2 ? 16 : 8;
}

/// N codes from p (any alignment), through a reference (a vector return value would change the
/// ABI between levels).
template <class V>
MPR_ALWAYS_INLINE void sweep_code_load(V& v, const std::uint16_t* p) noexcept {
  std::memcpy(&v, p, sizeof v);
}

/// v = row r's costs (`sweep_code_cost_at`) of the chunk of N pixels from x0, of which it sees
/// [lo, hi) (non-empty), tau for the others; q: 256 x the reference's codes at the chunk's
/// pixels.
template <int N, class V = typename SweepCodeVectors<N>::Lanes>
MPR_ALWAYS_INLINE void sweep_code_cost(V& v, const V q[3], const SweepCodeRow& r, const V& tau, int x0, int lo,
                                       int hi) noexcept {
  const std::ptrdiff_t at = x0 - r.xb;
  const V w00 = V{} + r.w[0], w10 = V{} + r.w[1], w01 = V{} + r.w[2], w11 = V{} + r.w[3];
  V s{};
  for (int c = 0; c < 3; ++c) {
    V a0, a1, b0, b1;
    sweep_code_load(a0, r.top[c] + at);
    sweep_code_load(a1, r.top[c] + at + 1);
    sweep_code_load(b0, r.bottom[c] + at);
    sweep_code_load(b1, r.bottom[c] + at + 1);
    const V p = a0 * w00 + a1 * w10 + b0 * w01 + b1 * w11;
    const V big = p > q[c] ? p : q[c], small = p > q[c] ? q[c] : p;
    s += (big - small) >> 3;
  }
  v = s < tau ? s : tau;
  if (hi - lo < N) {
    // The lanes outside [lo, hi) read codes the row does not see (inside the padded buffers):
    // tau there.
    V lane;
    for (int i = 0; i < N; ++i) lane[i] = static_cast<std::uint16_t>(i);
    const V from = lane - static_cast<std::uint16_t>(lo - x0);
    v = from < static_cast<std::uint16_t>(hi - lo) ? v : tau;
  }
}

/// out[x] = sum / (best kSweepCodeUnit) for the chunk's len pixels from x0.
template <int N, class V = typename SweepCodeVectors<N>::Lanes>
MPR_ALWAYS_INLINE void sweep_code_store(const V& sum, int best, float* MPR_RESTRICT out, int x0, int len) noexcept {
  using F = typename SweepCodeVectors<N>::Floats;
  const F s = __builtin_convertvector(sum, F) / static_cast<float>(best * kSweepCodeUnit);
  if (len == N)
    std::memcpy(out + x0, &s, sizeof s);
  else
    for (int w = 0; w < len; ++w) out[x0 + w] = s[w];
}

/// Drop or keep bodies in chunks of N pixels: the mean of the `best` smallest of the m costs
/// per pixel, as the sum of all m less the S = m - best largest (Drop, S < best), or the sum of
/// the S = best smallest kept from tau (unseen neighbours beyond rows[0..m) count as tau).
template <int N, bool Drop, int S>
MPR_ALWAYS_INLINE void sweep_code_mean_body(const std::uint16_t* const ref[3], const SweepCodeRow* rows, int m,
                                            int best, unsigned tau, float* MPR_RESTRICT out, int width) noexcept {
  using V = typename SweepCodeVectors<N>::Lanes;
  const V t = V{} + static_cast<std::uint16_t>(tau);
  for (int x0 = 0; x0 < width; x0 += N) {
    const int len = std::min(N, width - x0);
    V q[3];
    for (int c = 0; c < 3; ++c) {
      sweep_code_load(q[c], ref[c] + x0);
      q[c] <<= 8;
    }
    V sel[S > 0 ? S : 1], sum{};
    for (int i = 0; i < S; ++i) sel[i] = Drop ? V{} : t;
    for (int j = 0; j < m; ++j) {
      const SweepCodeRow& r = rows[j];
      const int lo = std::max(r.xb, x0), hi = std::min(r.xe, x0 + len);
      V v = t;
      if (lo < hi)
        sweep_code_cost<N>(v, q, r, t, x0, lo, hi);
      else if (!Drop)
        continue; // tau changes no kept cost
      if (Drop) sum += v;
#pragma GCC unroll 16
      for (int i = 0; i < S; ++i) {
        const V k = sel[i];
        if constexpr (Drop) { // the largest first
          sel[i] = v > k ? v : k;
          v = v > k ? k : v;
        } else { // the smallest first
          sel[i] = v < k ? v : k;
          v = v < k ? k : v;
        }
      }
    }
#pragma GCC unroll 16
    for (int i = 0; i < S; ++i) {
      if (Drop)
        sum -= sel[i];
      else
        sum += sel[i];
    }
    sweep_code_store<N>(sum, best, out, x0, len);
  }
}

/// `sweep_code_mean_body<N, Drop, S>` for a run-time count `n` (drop m - best or keep best) in
/// [S, kSweepCodeBest].
template <int N, bool Drop, int S>
MPR_ALWAYS_INLINE void sweep_code_mean_count(const std::uint16_t* const ref[3], const SweepCodeRow* rows, int m,
                                             int best, int n, unsigned tau, float* out, int width) noexcept {
  if constexpr (S < kSweepCodeBest)
    if (n > S) return sweep_code_mean_count<N, Drop, S + 1>(ref, rows, m, best, n, tau, out, width);
  sweep_code_mean_body<N, Drop, S>(ref, rows, m, best, tau, out, width);
}
#endif

/// out[x] = the mean of the `best` smallest costs (`sweep_code_cost_at`, in units) of pixel x
/// among the m neighbours rows[0..m) that see it, tau for the others, over kSweepCodeUnit, for x
/// in [0, width); `ref`: the reference row's codes. Precondition: `sweep_code_fits(m, best,
/// tau)`; rows and `ref` readable kSweepCodePad codes past their ends (`SweepPlanes::words`).
inline void sweep_code_mean_seen(const std::uint16_t* const ref[3], const SweepCodeRow* rows, int m, int best,
                                 float truncation, float* out, int width, SimdLevel level = dispatch_level()) noexcept {
  const unsigned tau = static_cast<unsigned>(sweep_code_tau(truncation));
#if defined(__GNUC__)
  const bool drop = m >= best && m - best < best;
  run_at(level, [&](auto tag) MPR_INLINE_LAMBDA {
    constexpr int N = sweep_code_lanes(decltype(tag)::value);
    if (drop)
      sweep_code_mean_count<N, true, 0>(ref, rows, m, best, m - best, tau, out, width);
    else
      sweep_code_mean_count<N, false, 1>(ref, rows, m, best, best, tau, out, width);
  });
#else
  (void)level;
  for (int x = 0; x < width; ++x) {
    unsigned keep[kSweepCodeBest];
    for (int i = 0; i < best; ++i) keep[i] = tau;
    for (int j = 0; j < m; ++j) {
      if (x < rows[j].xb || x >= rows[j].xe) continue;
      unsigned v = sweep_code_cost_at(ref, rows[j], tau, x);
      for (int i = 0; i < best; ++i) {
        const unsigned k = keep[i];
        keep[i] = std::min(k, v);
        v = std::max(k, v);
      }
    }
    unsigned sum = 0;
    for (int i = 0; i < best; ++i) sum += keep[i];
    out[x] = static_cast<float>(sum) / static_cast<float>(best * kSweepCodeUnit);
  }
#endif
}

} // namespace mpr::detail
