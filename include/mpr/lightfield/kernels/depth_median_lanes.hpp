#pragma once
/// \file
/// The joint weighted median of lightfield/depth_median.hpp for a row of pixels, a chunk of
/// `median_lanes(level)` neighbouring pixels at a time (one register), one pixel per lane:
/// every lane walks the same window taps, so the loads, the weights and the counting are vector
/// operations and no lane waits on another's data-dependent branches. Written once as plain C++
/// with the compiler's vector type and compiled for every level of core/simd.hpp through
/// `run_at`, like kernels/sweep_code_kernels.hpp.
///
/// The median of a lane: the smallest window value v whose weight sum W(v) (the weights of the
/// values <= v, summed in a fixed order of the taps, the same for every pixel and level) reaches
/// half the window's total. The search keeps u <= answer <= b (u: the smallest value above
/// those whose W is below half; b: a value whose W is not) and each round makes one pass over the
/// taps at a threshold p in [u, b): where the half would be reached if the weight between were
/// spread evenly (interpolation search). The pass gives W(p), the largest value <= p and the
/// smallest > p: the first becomes b where W(p) reaches half, the second u where it does not.
/// It ends when u = b. No sorting and no histogram: a few passes of a compare, a masked add, a
/// min and a max per tap; the result depends on the order of the sums only, not on the path, so
/// every level gives the same value.

#include <mpr/core/simd.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#if defined(MPR_SIMD_X86)
#include <immintrin.h>
#endif

namespace mpr::detail {

/// The inputs of `weighted_median_row`: planes of `width` x `height` pixels, rows `stride`
/// elements apart, each pointer at pixel (0, 0) of a plane padded by `radius` pixels on every
/// side and on the right to a whole number of kMedianChunk chunks (every tap of every chunk
/// is readable): padding values repeat the nearest pixel's (a value of the clipped window) and
/// padding confidences are -1 (weight 0, the tap left out). The guide as three planar channels
/// of sRGB codes (as 32-bit integers: lanes load them as they are). The colour weight of the
/// colour distance d (sum over channels of |code difference|, 0..765) is coarse[d / 32] x
/// fine[d % 32], each the float nearest exp(-(its part of d) / 255 / range): two 32-entry
/// tables, which AVX-512 reads with register permutes instead of a gather.
struct MedianRowInputs {
  const float* values;
  const float* confidence;
  const std::int32_t* channel[3];
  const float* coarse; ///< 32 floats (24 used)
  const float* fine;   ///< 32 floats
  int width, height, radius;
  std::ptrdiff_t stride;
  float flat;  ///< windows whose values span no more than this keep the centre value
  float floor; ///< the least confidence a neighbour counts with
};

/// The most pixels a chunk of `weighted_median_row` takes together (one AVX-512 vector): the
/// unit the planes are padded to on the right.
inline constexpr int kMedianChunk = 16;

/// The most window taps (radius 7: 15 x 15).
inline constexpr int kMedianTaps = 225;

/// The pixels a chunk takes together at `level`: one register of floats
/// (`simd_register_bytes`: 16 at AVX-512, 8 at AVX2, 4 at the portable level; 1 without
/// GCC/Clang vectors).
[[nodiscard]] constexpr int median_lanes(SimdLevel level) noexcept {
#if defined(__GNUC__)
  return simd_register_bytes(level) / static_cast<int>(sizeof(float));
#else
  (void)level;
  return 1;
#endif
}

/// Lane types of the median: N lanes as vectors of the compiler's; plain scalars when N is 1.
template <int N>
struct MedianVectors {
#if defined(__GNUC__)
  typedef float Lanes __attribute__((vector_size(N * sizeof(float))));
  typedef int Ints __attribute__((vector_size(N * sizeof(int))));
#endif
};
template <>
struct MedianVectors<1> {
  using Lanes = float;
  using Ints = int;
};

/// Lane l of a lane vector (or the scalar itself), read and written.
template <class V>
MPR_ALWAYS_INLINE auto median_lane(const V& v, int l) noexcept {
  if constexpr (std::is_arithmetic_v<V>) {
    (void)l;
    return v;
  } else {
    return v[l];
  }
}
template <class V, class S>
MPR_ALWAYS_INLINE void set_median_lane(V& v, int l, S s) noexcept {
  if constexpr (std::is_arithmetic_v<V>) {
    (void)l;
    v = s;
  } else {
    v[l] = s;
  }
}

/// The lanes of V (1 for a scalar).
template <class V>
inline constexpr int kMedianWidth = std::is_arithmetic_v<V> ? 1 : static_cast<int>(sizeof(V) / 4);

/// Whether any lane of a comparison's result is set.
template <class M>
MPR_ALWAYS_INLINE bool median_any(const M& m) noexcept {
  if constexpr (std::is_arithmetic_v<M>) {
    return m != 0;
  } else {
    for (int l = 0; l < kMedianWidth<M>; ++l)
      if (m[l]) return true;
    return false;
  }
}

/// v = the lanes of V: consecutive values from p (any alignment; through a reference: a vector
/// return value would change the ABI between levels).
template <class V, class T>
MPR_ALWAYS_INLINE void median_load(V& v, const T* p) noexcept {
  if constexpr (std::is_arithmetic_v<V>)
    v = static_cast<V>(*p);
  else
    std::memcpy(&v, p, sizeof v);
}

#if defined(MPR_SIMD_X86) && defined(__GNUC__)
/// g = coarse[d / 32] x fine[d % 32] of every lane with AVX-512's two-register permutes (built
/// for that level: `median_colour_weight` calls it only there).
MPR_TARGET_AVX512 inline void median_colour_weight_avx512(MedianVectors<16>::Lanes& g, const float* coarse,
                                                          const float* fine,
                                                          const MedianVectors<16>::Ints& d) noexcept {
  const MedianVectors<16>::Ints top = d >> 5;
  __m512i i, j;
  std::memcpy(&i, &top, sizeof i);
  std::memcpy(&j, &d, sizeof j);
  const __m512 c = _mm512_permutex2var_ps(_mm512_loadu_ps(coarse), i, _mm512_loadu_ps(coarse + 16));
  const __m512 f = _mm512_permutex2var_ps(_mm512_loadu_ps(fine), j, _mm512_loadu_ps(fine + 16));
  MedianVectors<16>::Lanes a, b;
  std::memcpy(&a, &c, sizeof a);
  std::memcpy(&b, &f, sizeof b);
  g = a * b;
}

/// t[k] of every lane of the 32-entry table t (k in [0, 32)) with AVX2: a permute of each
/// quarter, chosen by bits 3 and 4 of k.
MPR_TARGET_AVX2 inline __m256 median_table_avx2(const float* t, __m256i k) noexcept {
  const __m256 q0 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(t), k);
  const __m256 q1 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(t + 8), k);
  const __m256 q2 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(t + 16), k);
  const __m256 q3 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(t + 24), k);
  const __m256 bit3 = _mm256_castsi256_ps(_mm256_slli_epi32(k, 28)),
               bit4 = _mm256_castsi256_ps(_mm256_slli_epi32(k, 27));
  return _mm256_blendv_ps(_mm256_blendv_ps(q0, q1, bit3), _mm256_blendv_ps(q2, q3, bit3), bit4);
}

/// `median_colour_weight_avx512` for 8 lanes with AVX2's permutes (`median_table_avx2`).
MPR_TARGET_AVX2 inline void median_colour_weight_avx2(MedianVectors<8>::Lanes& g, const float* coarse,
                                                      const float* fine, const MedianVectors<8>::Ints& d) noexcept {
  const MedianVectors<8>::Ints top = (d >> 5) & 31, low = d & 31;
  const __m256 c = median_table_avx2(coarse, __builtin_bit_cast(__m256i, top));
  const __m256 f = median_table_avx2(fine, __builtin_bit_cast(__m256i, low));
  g = __builtin_bit_cast(MedianVectors<8>::Lanes, c) * __builtin_bit_cast(MedianVectors<8>::Lanes, f);
}
#endif

/// g = coarse[d / 32] x fine[d % 32] of every lane (`MedianRowInputs`): register permutes at
/// AVX-512 and AVX2, two loads per lane otherwise; the same product at every level.
template <class Tag, class V, class I>
MPR_ALWAYS_INLINE void median_colour_weight(V& g, const MedianRowInputs& in, const I& d, Tag) noexcept {
#if defined(MPR_SIMD_X86) && defined(__GNUC__)
  if constexpr (Tag::value >= SimdLevel::avx512 && kMedianWidth<V> == 16)
    return median_colour_weight_avx512(g, in.coarse, in.fine, d);
  if constexpr (Tag::value == SimdLevel::avx2 && kMedianWidth<V> == 8)
    return median_colour_weight_avx2(g, in.coarse, in.fine, d);
#endif
  for (int l = 0; l < kMedianWidth<V>; ++l) {
    const int k = median_lane(d, l);
    set_median_lane(g, l, in.coarse[k >> 5] * in.fine[k & 31]);
  }
}

/// The taps' values and weights of one chunk, tap-major (tap t of every lane together).
template <class V>
struct MedianTaps {
  V value[kMedianTaps];
  V weight[kMedianTaps];
};

/// One pass over the taps at the threshold p of every lane: W(p), the weights of the taps whose
/// value is <= p, summed in four interleaved partial sums (tap t into sum t mod 4) added pairwise
/// (the same order for every pixel and pass, so W(max) is the window's total exactly and W never
/// decreases with p); `below` the largest tap value <= p (-infinity where none) and `above` the
/// smallest > p (+infinity where none).
template <class V>
struct MedianCount {
  V weight, below, above;
};
template <class V>
MPR_ALWAYS_INLINE void median_count(MedianCount<V>& out, const MedianTaps<V>& taps, int n, const V& p) noexcept {
  const V zero = V{} + 0.0f, inf = V{} + std::numeric_limits<float>::infinity();
  // Four of each running sum, max and min: short dependency chains (a max or min, not a
  // compare and a blend, on the chain).
  V s[4] = {zero, zero, zero, zero}, lo[4] = {-inf, -inf, -inf, -inf}, hi[4] = {inf, inf, inf, inf};
  const auto tap = [&](int t, int k) MPR_INLINE_LAMBDA {
    const V v = taps.value[t];
    const auto in = v <= p;
    const V below = in ? v : -inf, above = in ? inf : v;
    s[k] += in ? taps.weight[t] : zero;
    lo[k] = below > lo[k] ? below : lo[k];
    hi[k] = above < hi[k] ? above : hi[k];
  };
  int t = 0;
  for (; t + 4 <= n; t += 4) {
    tap(t, 0);
    tap(t + 1, 1);
    tap(t + 2, 2);
    tap(t + 3, 3);
  }
  for (int k = 0; t < n; ++t, ++k) tap(t, k);
  out.weight = (s[0] + s[1]) + (s[2] + s[3]);
  const V l01 = lo[0] > lo[1] ? lo[0] : lo[1], l23 = lo[2] > lo[3] ? lo[2] : lo[3];
  const V h01 = hi[0] < hi[1] ? hi[0] : hi[1], h23 = hi[2] < hi[3] ? hi[2] : hi[3];
  out.below = l01 > l23 ? l01 : l23;
  out.above = h01 < h23 ? h01 : h23;
}

/// b = the weighted median of every lane (see the file comment) given the lanes' smallest and
/// largest values and total weight (W(hi), `median_weights`); lanes clear in `lanes` are left
/// as they are in the result (hi).
template <class V, class M>
MPR_ALWAYS_INLINE void median_search(V& b, const MedianTaps<V>& taps, int n, const V& lo, const V& hi, const V& total,
                                     const M& lanes) noexcept {
  // a < answer <= b with W(a) < half <= W(b); u: the smallest tap value > a.
  M open = lanes;
  MedianCount<V> c;
  const V half = total * 0.5f;
  V u = lo, wa = V{} + 0.0f, wb = total;
  b = hi;
  // Each round moves b down onto a tap value or u up past one: at most n rounds.
  for (int round = 0; round <= n; ++round) {
    open = open & (u < b);
    if (!median_any(open)) break;
    // Where the half would be reached with the weight of (a, b] spread evenly over [u, b].
    V p = u + (b - u) * ((half - wa) / (wb - wa));
    p = p < b ? p : u;
    median_count(c, taps, n, p);
    const auto reached = c.weight >= half;
    b = (open & reached) ? c.below : b;
    wb = (open & reached) ? c.weight : wb;
    u = (open & !reached) ? c.above : u;
    wa = (open & !reached) ? c.weight : wa;
  }
}

/// The tap values of the chunk at (x0, y) and their smallest and largest per lane.
template <class V>
MPR_ALWAYS_INLINE void median_values(const MedianRowInputs& in, int x0, int y, MedianTaps<V>& taps, V& lo,
                                     V& hi) noexcept {
  const int r = in.radius, n = (2 * r + 1) * (2 * r + 1);
  int t = 0;
  for (int dy = -r; dy <= r; ++dy) {
    const float* row = in.values + static_cast<std::ptrdiff_t>(y + dy) * in.stride + x0;
    for (int dx = -r; dx <= r; ++dx, ++t) median_load(taps.value[t], row + dx);
  }
  // Two running minima and maxima (short dependency chains).
  V a0 = taps.value[0], a1 = a0, b0 = a0, b1 = a0;
  for (t = 1; t + 2 <= n; t += 2) {
    const V u = taps.value[t], v = taps.value[t + 1];
    a0 = u < a0 ? u : a0;
    b0 = u > b0 ? u : b0;
    a1 = v < a1 ? v : a1;
    b1 = v > b1 ? v : b1;
  }
  if (t < n) {
    const V u = taps.value[t];
    a0 = u < a0 ? u : a0;
    b0 = u > b0 ? u : b0;
  }
  lo = a0 < a1 ? a0 : a1;
  hi = b0 > b1 ? b0 : b1;
}

/// The tap weights of the chunk at (x0, y): the colour weight of the distance to the lane's
/// pixel x max(confidence, floor); 0 for taps outside the image (confidence < 0). total: their
/// sum in the order of `median_count`, which it equals at any p >= every value.
template <class Tag, class V>
MPR_ALWAYS_INLINE void median_weights(const MedianRowInputs& in, int x0, int y, MedianTaps<V>& taps, V& total,
                                      Tag tag) noexcept {
  using I = typename MedianVectors<kMedianWidth<V>>::Ints;
  const int r = in.radius;
  const std::ptrdiff_t centre = static_cast<std::ptrdiff_t>(y) * in.stride + x0;
  I p[3];
  for (int c = 0; c < 3; ++c) median_load(p[c], in.channel[c] + centre);
  const V floor = V{} + in.floor, zero = V{} + 0.0f;
  int t = 0;
  for (int dy = -r; dy <= r; ++dy) {
    const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(y + dy) * in.stride + x0;
    for (int dx = -r; dx <= r; ++dx, ++t) {
      I d{};
      for (int c = 0; c < 3; ++c) {
        I q;
        median_load(q, in.channel[c] + at + dx);
        q -= p[c];
        d += q < 0 ? -q : q;
      }
      V conf, g;
      median_load(conf, in.confidence + at + dx);
      median_colour_weight(g, in, d, tag);
      const V weight = g * (conf > floor ? conf : floor);
      taps.weight[t] = conf < zero ? zero : weight;
    }
  }
  // Tap t into sum t mod 4, as `median_count`.
  const int n = t;
  V s0 = zero, s1 = zero, s2 = zero, s3 = zero;
  for (t = 0; t + 4 <= n; t += 4) {
    s0 += taps.weight[t];
    s1 += taps.weight[t + 1];
    s2 += taps.weight[t + 2];
    s3 += taps.weight[t + 3];
  }
  if (t < n) s0 += taps.weight[t++];
  if (t < n) s1 += taps.weight[t++];
  if (t < n) s2 += taps.weight[t++];
  total = (s0 + s1) + (s2 + s3);
}

/// Row y of the filter into out[0, width).
template <class Tag>
MPR_ALWAYS_INLINE void weighted_median_row_body(const MedianRowInputs& in, int y, float* out, Tag tag) noexcept {
  constexpr int N = median_lanes(Tag::value);
  using V = typename MedianVectors<N>::Lanes;
  const int r = in.radius, w = in.width, n = (2 * r + 1) * (2 * r + 1);
  MedianTaps<V> taps;
  const float* centre = in.values + static_cast<std::ptrdiff_t>(y) * in.stride;
  for (int x0 = 0; x0 < w; x0 += N) {
    const int lanes = std::min(N, w - x0);
    for (int l = 0; l < lanes; ++l) out[x0 + l] = centre[x0 + l];
    V lo{}, hi{};
    median_values(in, x0, y, taps, lo, hi);
    auto open = hi - lo > V{} + in.flat;
    for (int l = lanes; l < N; ++l) set_median_lane(open, l, 0);
    if (!median_any(open)) continue;
    V total, m;
    median_weights(in, x0, y, taps, total, tag);
    median_search(m, taps, n, lo, hi, total, open);
    for (int l = 0; l < lanes; ++l)
      if (median_lane(open, l)) out[x0 + l] = median_lane(m, l);
  }
}

/// Row y of the joint weighted median (lightfield/depth_median.hpp) into out[0, width), at
/// `level`. Precondition: radius 1..7.
inline void weighted_median_row(const MedianRowInputs& in, int y, float* out,
                                SimdLevel level = dispatch_level()) noexcept {
  run_at(level, [&](auto tag) MPR_INLINE_LAMBDA { weighted_median_row_body(in, y, out, tag); });
}

} // namespace mpr::detail
