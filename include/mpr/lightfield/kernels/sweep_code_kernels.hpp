#pragma once
/// \file
/// The plane sweep's chunked row kernel for many translated neighbours on 16-bit integers: what
/// `sweep_shift_mean_seen` (kernels/sweep_seen_kernels.hpp) computes in float, here on the
/// images' 8-bit sRGB codes with bilinear weights in 1/128 and costs in 1/32 of a code, two
/// registers of 16-bit lanes a chunk (64 pixels at AVX-512): a quarter of the bytes and twice the
/// lanes of the float kernel. The images are held as 8-bit codes: a load of 16-bit words at x holds
/// the *pair words* code[x + 2i] | code[x + 2i + 1] << 8, both taps of the even pixels' blends,
/// and at x + 1 those of the odd ones, so that a chunk of 2N pixels is two vectors of N lanes
/// (even and odd pixels, interleaved again when stored) and at the x86 levels a row's two taps
/// are one byte multiply-add (kernels/sweep_code_pairs.hpp). A blend is at most 255 x
/// 128 = 32640 and a cost at most tau <= 3 x 8160: both fit *signed* 16-bit lanes, so |blend -
/// reference| is a signed abs (SSSE3 on), the truncation and the selection signed min / max (SSE2
/// on); only the sum of up to 26 costs is unsigned. Every sum is exact
/// (no saturation, no rounding), so the values are the same at every level; they differ from the
/// float kernel's by the weights' rounding to 1/128 (a shift of at most about 1/128 pixel) and
/// the costs' to 1/32 code. Written once as plain C++ with the compiler's vector type and
/// compiled for every level of core/simd.hpp through `run_at`.

#include <mpr/core/detail/prefetch.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/sweep_code_pairs.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>

namespace mpr::detail {

/// The most pixels the 16-bit kernel takes together: twice its lanes (`sweep_code_lanes`).
inline constexpr int kSweepCodeChunk = 64;

/// The most kept costs the 16-bit kernel takes (as `kSweepSeenBest`).
inline constexpr int kSweepCodeBest = 16;

/// Cost units per 1.0 of the float costs (channel values code / 255): 32 units a code.
inline constexpr int kSweepCodeUnit = 255 * 32;

/// Codes an image of 8-bit codes holds past both ends of its channels
/// (`SweepPlanes::code_planes`): the kernel reads whole chunks, up to kSweepCodeChunk + 1 codes
/// past a row's seen pixels on either side, and masks what it does not see.
inline constexpr std::ptrdiff_t kSweepCodePad = 2 * kSweepCodeChunk + 16;

/// A neighbour's translated row on 8-bit codes: per channel the texel rows v0 (`top`) and v0 + 1
/// (`bottom`), element 0 the texel reference pixel xb blends from (as `SweepSeenRow`), the
/// bilinear weights w00, w10, w01, w11 in 1/128 (`sweep_code_weights`), each at most 127
/// (`sweep_code_set_weights`), and the reference pixels it sees, [xb, xe).
struct SweepCodeRow {
  const std::uint8_t* top[3];
  const std::uint8_t* bottom[3];
  std::uint16_t w[4];
  int xb, xe;
};

/// The bilinear weights (1 - fu)(1 - fv), fu (1 - fv), (1 - fu) fv, fu fv of offsets fu, fv in
/// [0, 1] in 1/128, each rounded to the nearest, the largest then corrected so that they sum to
/// 128 (a blend of codes is then at most 255 x 128, exact in signed 16 bits).
[[nodiscard]] inline std::array<std::uint16_t, 4> sweep_code_weights(float fu, float fv) noexcept {
  const float u = std::clamp(fu, 0.0f, 1.0f), v = std::clamp(fv, 0.0f, 1.0f);
  const float f[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
  std::array<int, 4> w{};
  int sum = 0, largest = 0;
  for (int i = 0; i < 4; ++i) {
    // Rounded half up, as std::lround for these non-negative values (x - floor(x) is exact).
    const float x = 128.0f * f[i];
    const int whole = static_cast<int>(x);
    w[static_cast<std::size_t>(i)] = whole + (x - static_cast<float>(whole) >= 0.5f ? 1 : 0);
    sum += w[static_cast<std::size_t>(i)];
    if (f[i] > f[largest]) largest = i;
  }
  w[static_cast<std::size_t>(largest)] += 128 - sum;
  return {static_cast<std::uint16_t>(w[0]), static_cast<std::uint16_t>(w[1]), static_cast<std::uint16_t>(w[2]),
          static_cast<std::uint16_t>(w[3])};
}

/// Row r's weights `w` (`sweep_code_weights`), its `top` and `bottom` already set: the byte
/// multiply-add takes weights up to 127, so a weight of 128 (the other three 0: a whole-pixel
/// shift in both directions) becomes 64 on that tap of both rows, `top` and `bottom` both that
/// tap's row: the same blend, 64 c + 64 c = 128 c.
inline void sweep_code_set_weights(SweepCodeRow& r, const std::array<std::uint16_t, 4>& w) noexcept {
  for (int i = 0; i < 4; ++i) r.w[i] = w[static_cast<std::size_t>(i)];
  for (int i = 0; i < 4; ++i) {
    if (w[static_cast<std::size_t>(i)] < 128) continue;
    for (int c = 0; c < 3; ++c) {
      if (i < 2)
        r.bottom[c] = r.top[c];
      else
        r.top[c] = r.bottom[c];
    }
    const std::uint16_t left = i % 2 == 0 ? 64 : 0;
    r.w[0] = r.w[2] = left;
    r.w[1] = r.w[3] = static_cast<std::uint16_t>(64 - left);
  }
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
/// of the four codes in 1/128, |blend - 128 ref|, divided by 4
/// (dropping the remainder), summed, then at most tau. What the vector body computes lane by
/// lane (the same unit as |blend in 1/256 - 256 ref| / 8 with even weights: 1/32 code).
[[nodiscard]] inline unsigned sweep_code_cost_at(const std::uint8_t* const ref[3], const SweepCodeRow& r, unsigned tau,
                                                 int x) noexcept {
  const std::ptrdiff_t at = x - r.xb;
  unsigned s = 0;
  for (int c = 0; c < 3; ++c) {
    const int p =
        r.w[0] * r.top[c][at] + r.w[1] * r.top[c][at + 1] + r.w[2] * r.bottom[c][at] + r.w[3] * r.bottom[c][at + 1];
    const int q = 128 * ref[c][x];
    s += static_cast<unsigned>(p > q ? p - q : q - p) >> 2;
  }
  return std::min(s, tau);
}

#if defined(__GNUC__)
/// N 16-bit lanes as vectors of the compiler's (unsigned: words and sums; signed: blends and
/// costs), and the same lanes as floats: N is the level's register width (`sweep_code_lanes`), a
/// wider vector type is lowered badly at AVX2.
template <int N>
struct SweepCodeVectors {
  typedef std::uint16_t Lanes __attribute__((vector_size(N * sizeof(std::uint16_t))));
  typedef std::int16_t Signed __attribute__((vector_size(N * sizeof(std::int16_t))));
  typedef float Floats __attribute__((vector_size(N * sizeof(float))));
};

/// The 16-bit lanes of a register at `level` (`simd_register_bytes`: 32 at AVX-512, 16 at AVX2,
/// 8 at the portable level); a chunk of the kernel is twice as many pixels.
[[nodiscard]] constexpr int sweep_code_lanes(SimdLevel level) noexcept { return simd_register_bytes(level) / 2; }

/// N words (2N codes) from p (any alignment), through a reference (a vector return value would
/// change the ABI between levels).
template <class V>
MPR_ALWAYS_INLINE void sweep_code_load(V& v, const std::uint8_t* p) noexcept {
  std::memcpy(&v, p, sizeof v);
}

/// Row r's weights as lanes: `pairs` for the byte multiply-add (top row w00 | w10 << 8, bottom
/// row w01 | w11 << 8), `w` one weight a vector for the plain multiplies.
template <int N>
struct SweepCodeWeights {
  using U = typename SweepCodeVectors<N>::Lanes;
  U top, bottom, w[4];
};

/// Whether level L blends with the byte multiply-add (kernels/sweep_code_pairs.hpp).
template <SimdLevel L>
inline constexpr bool kSweepCodeMaddubs =
#if defined(MPR_SIMD_X86) && defined(__SSSE3__)
    true;
#elif defined(MPR_SIMD_X86)
    L >= SimdLevel::avx2;
#else
    false;
#endif

/// k = row r's weights as lanes, for level L's blend.
template <SimdLevel L, int N>
MPR_ALWAYS_INLINE void sweep_code_row_weights(SweepCodeWeights<N>& k, const SweepCodeRow& r) noexcept {
  using U = typename SweepCodeVectors<N>::Lanes;
  if constexpr (kSweepCodeMaddubs<L>) {
    k.top = U{} + static_cast<std::uint16_t>(r.w[0] | r.w[1] << 8);
    k.bottom = U{} + static_cast<std::uint16_t>(r.w[2] | r.w[3] << 8);
  } else {
    for (int i = 0; i < 4; ++i) k.w[i] = U{} + r.w[i];
  }
}

/// p = the blends (in 1/128 code) of the N pixels 2 apart whose left taps are top[2i] and
/// bottom[2i] (the pair words of a load from `top` and `bottom`).
template <SimdLevel L, int N, class S = typename SweepCodeVectors<N>::Signed>
MPR_ALWAYS_INLINE void sweep_code_blend(S& p, const std::uint8_t* top, const std::uint8_t* bottom,
                                        const SweepCodeWeights<N>& k) noexcept {
  using U = typename SweepCodeVectors<N>::Lanes;
#if defined(MPR_SIMD_X86)
  if constexpr (kSweepCodeMaddubs<L>) {
    if constexpr (N == 32) {
      __m512i x;
      sweep_pairs_blend(x, top, bottom, __builtin_bit_cast(__m512i, k.top), __builtin_bit_cast(__m512i, k.bottom));
      p = __builtin_bit_cast(S, x);
    } else if constexpr (N == 16) {
      __m256i x;
      sweep_pairs_blend(x, top, bottom, __builtin_bit_cast(__m256i, k.top), __builtin_bit_cast(__m256i, k.bottom));
      p = __builtin_bit_cast(S, x);
    }
#if defined(__SSSE3__)
    else {
      __m128i x;
      sweep_pairs_blend(x, top, bottom, __builtin_bit_cast(__m128i, k.top), __builtin_bit_cast(__m128i, k.bottom));
      p = __builtin_bit_cast(S, x);
    }
#endif
    return;
  }
#endif
  U a, b;
  sweep_code_load(a, top);
  sweep_code_load(b, bottom);
  const U lo = U{} + 0xff;
  const U blend = (a & lo) * k.w[0] + (a >> 8) * k.w[1] + (b & lo) * k.w[2] + (b >> 8) * k.w[3];
  p = __builtin_bit_cast(S, blend);
}

/// v = row r's costs (`sweep_code_cost_at`) of the N pixels x0 + 2i + odd of the chunk of 2N
/// pixels from x0, of which it sees [lo, hi) (non-empty), tau for the others; q: 128 x the
/// reference's codes at those pixels.
template <SimdLevel L, int N, class S = typename SweepCodeVectors<N>::Signed>
MPR_ALWAYS_INLINE void sweep_code_cost(S& v, const S q[3], const SweepCodeRow& r, const S& tau, int x0, int odd, int lo,
                                       int hi) noexcept {
  using U = typename SweepCodeVectors<N>::Lanes;
  const std::ptrdiff_t at = x0 + odd - r.xb;
  SweepCodeWeights<N> k;
  sweep_code_row_weights<L, N>(k, r);
  S s{};
  for (int c = 0; c < 3; ++c) {
    if (odd == 0) {
      // The codes two chunks on, into the first-level cache: a row reads 6 streams a neighbour,
      // more than the hardware prefetchers follow (about 1.15x the kernel's speed on Chess).
      prefetch_l1(r.top[c] + at, 4 * N);
      prefetch_l1(r.bottom[c] + at, 4 * N);
    }
    S p;
    sweep_code_blend<L, N>(p, r.top[c] + at, r.bottom[c] + at, k);
    const S d = p - q[c]; // in [-32640, 32640]
    s += (d < 0 ? -d : d) >> 2;
  }
  v = s < tau ? s : tau;
  if (hi - lo < 2 * N) {
    // The lanes outside [lo, hi) read codes the row does not see (inside the padded buffers):
    // tau there.
    U lane;
    for (int i = 0; i < N; ++i) lane[i] = static_cast<std::uint16_t>(2 * i);
    const U from = lane - static_cast<std::uint16_t>(lo - x0 - odd);
    v = from < static_cast<std::uint16_t>(hi - lo) ? v : tau;
  }
}

/// v = row r's costs of the even or odd pixels of the chunk of len pixels from x0
/// (`sweep_code_cost`), tau where it sees none of the chunk; returns whether it sees one.
template <SimdLevel L, int N, class S = typename SweepCodeVectors<N>::Signed>
MPR_ALWAYS_INLINE bool sweep_code_chunk(S& v, const S q[3], const SweepCodeRow& r, const S& tau, int x0, int odd,
                                        int len) noexcept {
  const int lo = std::max(r.xb, x0), hi = std::min(r.xe, x0 + len);
  v = tau;
  if (lo >= hi) return false;
  sweep_code_cost<L, N>(v, q, r, tau, x0, odd, lo, hi);
  return true;
}

/// Inserts v into sel[0..n), n <= S (the largest first for Drop, the smallest first otherwise):
/// a compare-exchange per element; v leaves with what falls out.
template <bool Drop, int S, class V>
MPR_ALWAYS_INLINE void sweep_code_insert(V* sel, V& v, int n) noexcept {
#pragma GCC unroll 16
  for (int i = 0; i < S; ++i) {
    if (i >= n) break;
    const V k = sel[i];
    if constexpr (Drop) {
      sel[i] = v > k ? v : k;
      v = v > k ? k : v;
    } else {
      sel[i] = v < k ? v : k;
      v = v < k ? k : v;
    }
  }
}

/// v = lanes From / 2 .. From / 2 + N / 2 of a and b interleaved (a's first).
template <int From, class U, std::size_t... I>
MPR_ALWAYS_INLINE void sweep_code_interleave(U& v, const U& a, const U& b, std::index_sequence<I...>) noexcept {
  constexpr int N = static_cast<int>(sizeof...(I));
  v = __builtin_shufflevector(a, b, (static_cast<int>(I % 2) * N + From / 2 + static_cast<int>(I / 2))...);
}

/// out[x] = sum / (best kSweepCodeUnit) for the chunk's len pixels from x0, the sums of its even
/// pixels in `even`, of its odd ones in `odd`.
template <int N, class U = typename SweepCodeVectors<N>::Lanes>
MPR_ALWAYS_INLINE void sweep_code_store(const U& even, const U& odd, int best, float* MPR_RESTRICT out, int x0,
                                        int len) noexcept {
  using F = typename SweepCodeVectors<N>::Floats;
  const float scale = static_cast<float>(best * kSweepCodeUnit);
  U first, second;
  sweep_code_interleave<0>(first, even, odd, std::make_index_sequence<N>{});
  sweep_code_interleave<N>(second, even, odd, std::make_index_sequence<N>{});
  const F lo = __builtin_convertvector(first, F) / scale, hi = __builtin_convertvector(second, F) / scale;
  if (len == 2 * N) {
    std::memcpy(out + x0, &lo, sizeof lo);
    std::memcpy(out + x0 + N, &hi, sizeof hi);
  } else {
    for (int w = 0; w < len; ++w) out[x0 + w] = w < N ? lo[w] : hi[w - N];
  }
}

/// The sum of the `best` smallest of the m costs of each of the N pixels x0 + 2i + odd of the
/// chunk of len pixels from x0 (q: 128 x their reference codes): the sum of all m less the S =
/// m - best largest (Drop, S < best), or the sum of the S = best smallest kept from tau (unseen
/// neighbours beyond rows[0..m) count as tau). The selection starts full of zeros (Drop) or
/// tau, which the first S neighbours' costs cannot pass: neighbour j < S is compared with the j
/// already in and lands at place j.
template <SimdLevel L, int N, bool Drop, int S, class U = typename SweepCodeVectors<N>::Lanes,
          class V = typename SweepCodeVectors<N>::Signed>
MPR_ALWAYS_INLINE void sweep_code_sum(U& sum, const V q[3], const SweepCodeRow* rows, int m, const V& t, int x0,
                                      int odd, int len) noexcept {
  V sel[S > 0 ? S : 1];
  sum = U{};
  for (int i = 0; i < S; ++i) sel[i] = Drop ? V{} : t;
#pragma GCC unroll 16
  for (int j = 0; j < S; ++j) {
    if (j >= m) break;
    V v;
    sweep_code_chunk<L, N>(v, q, rows[j], t, x0, odd, len);
    if (Drop) sum += __builtin_bit_cast(U, v);
    sweep_code_insert<Drop, S>(sel, v, j);
    sel[j] = v;
  }
  for (int j = S; j < m; ++j) {
    V v;
    if (!sweep_code_chunk<L, N>(v, q, rows[j], t, x0, odd, len) && !Drop) continue; // tau changes no kept cost
    if (Drop) sum += __builtin_bit_cast(U, v);
    sweep_code_insert<Drop, S>(sel, v, S);
  }
#pragma GCC unroll 16
  for (int i = 0; i < S; ++i) {
    if (Drop)
      sum -= __builtin_bit_cast(U, sel[i]);
    else
      sum += __builtin_bit_cast(U, sel[i]);
  }
}

/// Drop or keep bodies (`sweep_code_sum`) in chunks of 2N pixels, the even ones, then the odd
/// ones (whose codes the even pass left in the first-level cache).
template <SimdLevel L, int N, bool Drop, int S>
MPR_ALWAYS_INLINE void sweep_code_mean_body(const std::uint8_t* const ref[3], const SweepCodeRow* rows, int m, int best,
                                            unsigned tau, float* MPR_RESTRICT out, int width) noexcept {
  using U = typename SweepCodeVectors<N>::Lanes;
  using V = typename SweepCodeVectors<N>::Signed;
  const V t = V{} + static_cast<std::int16_t>(tau);
  for (int x0 = 0; x0 < width; x0 += 2 * N) {
    const int len = std::min(2 * N, width - x0);
    V even[3], odd[3];
    for (int c = 0; c < 3; ++c) {
      U w;
      sweep_code_load(w, ref[c] + x0);
      even[c] = __builtin_bit_cast(V, (w << 8) >> 1); // 128 x the low bytes
      odd[c] = __builtin_bit_cast(V, (w >> 8) << 7);  // and the high ones
    }
    U sum_even, sum_odd;
    sweep_code_sum<L, N, Drop, S>(sum_even, even, rows, m, t, x0, 0, len);
    sweep_code_sum<L, N, Drop, S>(sum_odd, odd, rows, m, t, x0, 1, len);
    sweep_code_store<N>(sum_even, sum_odd, best, out, x0, len);
  }
}

/// `sweep_code_mean_body<L, N, Drop, S>` for a run-time count `n` (drop m - best or keep best)
/// in [S, kSweepCodeBest].
template <SimdLevel L, int N, bool Drop, int S>
MPR_ALWAYS_INLINE void sweep_code_mean_count(const std::uint8_t* const ref[3], const SweepCodeRow* rows, int m,
                                             int best, int n, unsigned tau, float* out, int width) noexcept {
  if constexpr (S < kSweepCodeBest)
    if (n > S) return sweep_code_mean_count<L, N, Drop, S + 1>(ref, rows, m, best, n, tau, out, width);
  sweep_code_mean_body<L, N, Drop, S>(ref, rows, m, best, tau, out, width);
}
#endif

/// out[x] = the mean of the `best` smallest costs (`sweep_code_cost_at`, in units) of pixel x
/// among the m neighbours rows[0..m) that see it, tau for the others, over kSweepCodeUnit, for x
/// in [0, width); `ref`: the reference row's codes. Preconditions: `sweep_code_fits(m, best,
/// tau)`; every weight at most 127 (`sweep_code_set_weights`); rows and `ref` readable
/// kSweepCodePad codes past their ends (`SweepPlanes::code_planes`).
inline void sweep_code_mean_seen(const std::uint8_t* const ref[3], const SweepCodeRow* rows, int m, int best,
                                 float truncation, float* out, int width, SimdLevel level = dispatch_level()) noexcept {
  const unsigned tau = static_cast<unsigned>(sweep_code_tau(truncation));
#if defined(__GNUC__)
  const bool drop = m >= best && m - best < best;
  run_at(level, [&](auto tag) MPR_INLINE_LAMBDA {
    constexpr SimdLevel L = decltype(tag)::value;
    constexpr int N = sweep_code_lanes(L);
    if (drop)
      sweep_code_mean_count<L, N, true, 0>(ref, rows, m, best, m - best, tau, out, width);
    else
      sweep_code_mean_count<L, N, false, 1>(ref, rows, m, best, best, tau, out, width);
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
