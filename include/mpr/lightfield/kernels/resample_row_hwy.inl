// No #pragma once, no includes: kernels/lerp_row_hwy.hpp includes this file once per Highway
// target, inside that target's namespace (`hn`, `Target`, `CodeDecoder` are its own).
/// \file
/// One camera row of 8-bit sRGB codes (or float channels) resampled at x + s i
/// (`detail::resample_row_portable`'s inputs, outputs and preconditions), written once with
/// Highway and compiled for every x86 target (SSE4, AVX2, AVX-512, AVX-512 with VBMI), chosen
/// per `SimdLevel` by `hwy_visit` (`resample_row_hwy`, kernels/lerp_row_hwy.hpp). It is the
/// horizontal half of a separable bilinear shift-and-add at another scale below the VBMI level
/// (`detail::resample_row`), and the resampling of `SharedWeightsBatch`'s sums at every level.
///
/// Each step takes one vector of pixels (4, 8 or 16): their positions relative to the group's
/// first texel j0 in float (at most a few dozen camera pixels, so the fractions keep ~1e-6),
/// j = floor and f = the fraction per lane, then the six channels of each lane's texel pair,
/// scale (v0 + f (v1 - v0)), stored interleaved. Steps up to 2 (magnified output, and down to
/// half scale) take the channels from planar float buffers of the row's texels, decoded a block
/// at a time, with lane permutes (`resample_row_window`); longer steps gather them (8-bit codes:
/// two 32-bit gathers, then `CodeDecoder`; floats: six gathers).

/// The loop of the resampling kernels below: for each vector of pixels from pixel i, the
/// group's first texel pair j0 (double), the lanes' pair offsets jl from it (clamped to the row's
/// last pair) and fractions f (float), `lerp(row + 3 j0, jl, f, r, g, b)` for their channels,
/// stored interleaved (the last, partial vector through a buffer); `ahead` prefetched over the
/// span each group reads.
template <class C, class Lerp>
HWY_INLINE void resample_row_lanes(const C* HWY_RESTRICT row, std::size_t texels, double x, double s,
                                   float* HWY_RESTRICT h, std::size_t n, const C* ahead, const Lerp& lerp) noexcept {
  using DF = hn::ScalableTag<float>;
  const DF df;
  const hn::RebindToSigned<DF> di;
  const std::size_t lanes = hn::Lanes(df);
  const long last_pair = static_cast<long>(texels) - 2;
  const auto pair_of = [last_pair](double v) { // floor(v) for v >= 0, clamped
    return std::clamp(static_cast<long>(v), 0L, last_pair);
  };
  const long j_first = pair_of(x);
  // The bytes a group's pixels read (its last pixel's pair included), for the prefetch.
  const std::size_t span = 3 * sizeof(C) * (static_cast<std::size_t>(std::ceil(s * static_cast<double>(lanes))) + 2);
  const auto zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  const auto step = hn::Mul(hn::Set(df, static_cast<float>(s)), hn::Iota(df, 0.0f));
  HWY_ALIGN float tail[3 * hn::MaxLanes(df)];
  for (std::size_t i = 0; i < n; i += lanes) {
    const double xg = x + s * static_cast<double>(i);
    const long j0 = pair_of(xg);
    if (ahead != nullptr)
      for (std::size_t b = 0; b < span; b += 64)
        mpr::detail::prefetch_l2(ahead, 3 * sizeof(C) * static_cast<std::size_t>(j0 - j_first) + b);
    // Positions from texel j0 (float), their pairs (clamped to the row's last) and fractions.
    const auto xl = hn::Add(hn::Set(df, static_cast<float>(xg - static_cast<double>(j0))), step);
    const auto jl = hn::Min(hn::ConvertTo(di, hn::Max(xl, zero)), hn::Set(di, static_cast<int>(last_pair - j0)));
    const auto f = hn::Min(hn::Max(hn::Sub(xl, hn::ConvertTo(df, jl)), zero), one);
    hn::Vec<DF> r, g, b;
    lerp(row + 3 * static_cast<std::size_t>(j0), jl, f, r, g, b);
    if (i + lanes <= n) {
      hn::StoreInterleaved3(r, g, b, df, h + 3 * i);
    } else {
      hn::StoreInterleaved3(r, g, b, df, tail);
      std::copy(tail, tail + 3 * (n - i), h + 3 * i);
    }
  }
}

/// `detail::resample_row_portable` for 8-bit codes at this target, any step: two 32-bit gathers
/// of codes per vector, at byte offsets 3 j and
/// 3 j + 2 (r0 g0 b0 r1 and b0 r1 g1 b1: the pair's six codes, nothing past the pair read),
/// decoded by `CodeDecoder`.
inline void resample_row_codes_gather(Target, const std::uint8_t* HWY_RESTRICT row, std::size_t texels,
                                      const std::uint16_t* HWY_RESTRICT lut, double x, double s, float scale,
                                      float* HWY_RESTRICT h, std::size_t n, const std::uint8_t* ahead) noexcept {
  using DF = hn::ScalableTag<float>;
  const DF df;
  const hn::RebindToSigned<DF> di;
  const CodeDecoder decode(lut);
  const auto vscale = hn::Set(df, scale);
  const auto mask8 = hn::Set(di, 0xFF);
  using VI = hn::Vec<decltype(di)>;
  using VF = hn::Vec<DF>;
  resample_row_lanes(
      row, texels, x, s, h, n, ahead, [&](const std::uint8_t* at, VI jl, VF f, VF& r, VF& g, VF& b) HWY_ATTR {
        const auto offset = hn::Add(jl, hn::Add(jl, jl)); // 3 j
        const auto* base = reinterpret_cast<const std::int32_t*>(at);
        const auto lo = hn::GatherOffset(di, base, offset);                          // r0 g0 b0 r1
        const auto hi = hn::GatherOffset(di, base, hn::Add(offset, hn::Set(di, 2))); // b0 r1 g1 b1
        // Byte k of each lane (the shift is arithmetic on signed lanes: masked after it).
        const auto code = [&](VI v, auto k) HWY_ATTR { return hn::And(hn::ShiftRight<8 * k()>(v), mask8); };
        const auto lerp = [&](VI code0, VI code1) HWY_ATTR {
          const VF v0 = decode(code0);
          return hn::Mul(vscale, hn::MulAdd(f, hn::Sub(decode(code1), v0), v0));
        };
        using B0 = std::integral_constant<int, 0>;
        using B1 = std::integral_constant<int, 1>;
        using B2 = std::integral_constant<int, 2>;
        using B3 = std::integral_constant<int, 3>;
        r = lerp(code(lo, B0{}), code(lo, B3{}));
        g = lerp(code(lo, B1{}), code(hi, B2{}));
        b = lerp(code(lo, B2{}), code(hi, B3{}));
      });
}

/// `detail::resample_row_portable` for float channels at this target, any step: six float
/// gathers per vector (the pair's channels at 3 j + k and 3 j + 3 + k).
inline void resample_row_floats_gather(Target, const float* HWY_RESTRICT row, std::size_t texels, double x, double s,
                                       float scale, float* HWY_RESTRICT h, std::size_t n, const float* ahead) noexcept {
  using DF = hn::ScalableTag<float>;
  const DF df;
  const hn::RebindToSigned<DF> di;
  const auto vscale = hn::Set(df, scale);
  using VI = hn::Vec<decltype(di)>;
  using VF = hn::Vec<DF>;
  resample_row_lanes(row, texels, x, s, h, n, ahead, [&](const float* at, VI jl, VF f, VF& r, VF& g, VF& b) HWY_ATTR {
    const auto offset = hn::Add(jl, hn::Add(jl, jl)); // 3 j
    const auto lerp = [&](int k) HWY_ATTR {
      const VF v0 = hn::GatherIndex(df, at + k, offset), v1 = hn::GatherIndex(df, at + k + 3, offset);
      return hn::Mul(vscale, hn::MulAdd(f, hn::Sub(v1, v0), v0));
    };
    r = lerp(0);
    g = lerp(1);
    b = lerp(2);
  });
}

/// Texels a step of `resample_row_window` takes at most.
inline constexpr std::size_t kResampleWindowBlock = 256;

/// The largest step `resample_row_window` takes: a vector of N pixels then reads its pairs
/// from the 2N texels from its first pair on (its last pair's right texel is at most
/// floor(f + s (N - 1)) + 1 <= 2N - 1 on).
inline constexpr double kResampleWindowMaxStep = 2.0;

/// `detail::resample_row_portable` without gathers, for steps s <= `kResampleWindowMaxStep`: the
/// texels the row's pixels read taken a block at a time into three planar float buffers
/// (`fill(a, count, planes)`: the channel values of the `count` texels at a, unscaled); each
/// vector of N pixels picks its pairs' channels out of the 2N texels from its first pair on, two
/// vectors per channel, with lane permutes (`TableLookupLanes`).
template <class C, class Fill>
HWY_INLINE void resample_row_window(const C* HWY_RESTRICT row, std::size_t texels, double x, double s, float scale,
                                    float* HWY_RESTRICT h, std::size_t n, const C* ahead, const Fill& fill) noexcept {
  using DF = hn::ScalableTag<float>;
  const DF df;
  const hn::RebindToSigned<DF> di;
  constexpr std::size_t kMax = hn::MaxLanes(DF());
  const std::size_t lanes = hn::Lanes(df);
  if (n == 0) return;
  const long last_pair = static_cast<long>(texels) - 2;
  const auto pair_of = [last_pair](double v) { return std::clamp(static_cast<long>(v), 0L, last_pair); };
  // Texels [j_begin, j_end) are read; buffers hold a block and the 2N texels a window may load.
  const long j_end = pair_of(x + s * static_cast<double>(n - 1)) + 2;
  HWY_ALIGN float plane[3][kResampleWindowBlock + 2 * kMax];
  float* const planes[3] = {plane[0], plane[1], plane[2]};
  for (auto& p : plane) std::fill(p, p + kResampleWindowBlock + 2 * kMax, 0.0f); // no lane reads garbage
  const auto zero = hn::Zero(df), one = hn::Set(df, 1.0f), vscale = hn::Set(df, scale);
  const auto step = hn::Mul(hn::Set(df, static_cast<float>(s)), hn::Iota(df, 0.0f));
  const auto low = hn::Set(di, static_cast<int>(lanes - 1));
  HWY_ALIGN float tail[3 * kMax];
  const long j_first = pair_of(x);
  long ja = -1, jb = -1; // the block decoded: texels [ja, jb)
  for (std::size_t i = 0; i < n; i += lanes) {
    const double xg = x + s * static_cast<double>(i);
    const long j0 = pair_of(xg);
    if (ja < 0 || (j0 + 2 * static_cast<long>(lanes) > jb && jb < j_end)) { // decode the next block
      ja = j0;
      jb = std::min<long>(j_end, ja + static_cast<long>(kResampleWindowBlock));
      if (ahead != nullptr)
        for (long b = 0; b < 3 * static_cast<long>(sizeof(C)) * (jb - ja); b += 64)
          mpr::detail::prefetch_l2(ahead, 3 * sizeof(C) * static_cast<std::size_t>(ja - j_first) +
                                              static_cast<std::size_t>(b));
      fill(row + 3 * ja, static_cast<std::size_t>(jb - ja), planes);
    }
    const auto xl = hn::Add(hn::Set(df, static_cast<float>(xg - static_cast<double>(j0))), step);
    const auto jl = hn::Min(hn::ConvertTo(di, hn::Max(xl, zero)), hn::Set(di, static_cast<int>(last_pair - j0)));
    const auto f = hn::Min(hn::Max(hn::Sub(xl, hn::ConvertTo(df, jl)), zero), one);
    // Lane j of the window [j0, j0 + 2N): lane j mod N of its first or second vector.
    const auto pick = [&](const float* w, decltype(jl) j) HWY_ATTR {
      const auto idx = hn::IndicesFromVec(df, hn::And(j, low));
      const auto second = hn::RebindMask(df, hn::Gt(j, low)); // j >= N
      return hn::IfThenElse(second, hn::TableLookupLanes(hn::LoadU(df, w + lanes), idx),
                            hn::TableLookupLanes(hn::LoadU(df, w), idx));
    };
    const auto right = hn::Add(jl, hn::Set(di, 1));
    hn::Vec<DF> v[3];
    for (std::size_t q = 0; q < 3; ++q) {
      const float* w = plane[q] + (j0 - ja);
      const auto v0 = pick(w, jl);
      v[q] = hn::Mul(vscale, hn::MulAdd(f, hn::Sub(pick(w, right), v0), v0));
    }
    if (i + lanes <= n) {
      hn::StoreInterleaved3(v[0], v[1], v[2], df, h + 3 * i);
    } else {
      hn::StoreInterleaved3(v[0], v[1], v[2], df, tail);
      std::copy(tail, tail + 3 * (n - i), h + 3 * i);
    }
  }
}

/// `resample_row_window` for 8-bit codes: each block's codes decoded (`CodeDecoder` on
/// consecutive codes) and deinterleaved (`LoadInterleaved3`).
inline void resample_row_codes_window(Target, const std::uint8_t* HWY_RESTRICT row, std::size_t texels,
                                      const std::uint16_t* HWY_RESTRICT lut, double x, double s, float scale,
                                      float* HWY_RESTRICT h, std::size_t n, const std::uint8_t* ahead) noexcept {
  using DF = hn::ScalableTag<float>;
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  const CodeDecoder decode(lut);
  HWY_ALIGN float mixed[3 * hn::MaxLanes(DF())];
  resample_row_window(row, texels, x, s, scale, h, n, ahead,
                      [&](const std::uint8_t* a, std::size_t count, float* const* plane) HWY_ATTR {
                        std::size_t t = 0;
                        for (; t + lanes <= count; t += lanes) {
                          for (std::size_t q = 0; q < 3; ++q)
                            hn::Store(decode(a + 3 * t + q * lanes), df, mixed + q * lanes);
                          hn::Vec<DF> r, g, b;
                          hn::LoadInterleaved3(df, mixed, r, g, b);
                          hn::Store(r, df, plane[0] + t);
                          hn::Store(g, df, plane[1] + t);
                          hn::Store(b, df, plane[2] + t);
                        }
                        for (; t < count; ++t)
                          for (std::size_t q = 0; q < 3; ++q) plane[q][t] = decode[a[3 * t + q]];
                      });
}

/// `detail::resample_row_portable` for 8-bit codes at this target (the kernel tag `Target`
/// selects it, see `hwy_visit`): `resample_row_codes_window` for steps up to
/// `kResampleWindowMaxStep`, `resample_row_codes_gather` for longer ones.
inline void resample_row_codes(Target t, const std::uint8_t* HWY_RESTRICT row, std::size_t texels,
                               const std::uint16_t* HWY_RESTRICT lut, double x, double s, float scale,
                               float* HWY_RESTRICT h, std::size_t n, const std::uint8_t* ahead) noexcept {
  if (s <= kResampleWindowMaxStep)
    resample_row_codes_window(t, row, texels, lut, x, s, scale, h, n, ahead);
  else
    resample_row_codes_gather(t, row, texels, lut, x, s, scale, h, n, ahead);
}

/// `detail::resample_row_portable` for float channels at this target: `resample_row_window`
/// (each block deinterleaved with `LoadInterleaved3`) for steps up to `kResampleWindowMaxStep`,
/// `resample_row_floats_gather` for longer ones.
inline void resample_row_floats(Target t, const float* HWY_RESTRICT row, std::size_t texels, double x, double s,
                                float scale, float* HWY_RESTRICT h, std::size_t n, const float* ahead) noexcept {
  if (s > kResampleWindowMaxStep) return resample_row_floats_gather(t, row, texels, x, s, scale, h, n, ahead);
  using DF = hn::ScalableTag<float>;
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  resample_row_window(row, texels, x, s, scale, h, n, ahead,
                      [&](const float* a, std::size_t count, float* const* plane) HWY_ATTR {
                        std::size_t t = 0;
                        for (; t + lanes <= count; t += lanes) {
                          hn::Vec<DF> r, g, b;
                          hn::LoadInterleaved3(df, a + 3 * t, r, g, b);
                          hn::Store(r, df, plane[0] + t);
                          hn::Store(g, df, plane[1] + t);
                          hn::Store(b, df, plane[2] + t);
                        }
                        for (; t < count; ++t)
                          for (std::size_t q = 0; q < 3; ++q) plane[q][t] = a[3 * t + q];
                      });
}

/// Float lanes of this target's vectors: the unit of `plan_magnified_row`'s layout.
inline std::size_t magnified_lanes(Target) noexcept { return hn::Lanes(hn::ScalableTag<float>()); }

/// Where the channels of a row of n pixels at x + s i (camera pixels; texel centres at integers,
/// pairs clamped to [0, texels - 2], fractions to [0, 1], as `detail::resample_row_portable`)
/// read their texel pairs, for `resample_planned_row`: vector q holds the row's channels
/// [q N, q N + N) (N lanes; channel c is pixel c / 3's channel c mod 3); lane l takes value
/// `entry[2 N q + l]` of the N values from `base[q]` on as its pair's left value (values counted
/// from the left texel of j_first = the pair of x), the value 3 on as its right, and the float
/// whose bits are `entry[2 N q + N + l]` as its fraction. Every lane's left value lies within the
/// N from `base[q]` (the least of them) when no pixel's pair is more than one texel on from the
/// last's: a step s <= 1 (and, for the float positions, not within 1e-3 of it unless 1 exactly).
/// Writes ceil(3 n / N) entries of `base` and 2 N as many of `entry`.
inline void plan_magnified_row(Target, double x, double s, std::size_t n, std::size_t texels,
                               std::int32_t* HWY_RESTRICT base, std::int32_t* HWY_RESTRICT entry) noexcept {
  using DF = hn::ScalableTag<float>;
  const DF df;
  const hn::RebindToSigned<DF> di;
  constexpr std::size_t kMax = hn::MaxLanes(DF());
  const std::size_t lanes = hn::Lanes(df);
  const long last_pair = static_cast<long>(texels) - 2;
  const auto pair_of = [last_pair](double v) { return std::clamp(static_cast<long>(v), 0L, last_pair); };
  const long j_first = pair_of(x);
  // A group of N pixels fills three vectors; lane l of vector m is pixel (m N + l) / 3 of the
  // group, channel (m N + l) mod 3.
  HWY_ALIGN float pixel[3][kMax];
  HWY_ALIGN std::int32_t channel[3][kMax];
  for (std::size_t m = 0; m < 3; ++m)
    for (std::size_t l = 0; l < lanes; ++l) {
      pixel[m][l] = static_cast<float>((m * lanes + l) / 3);
      channel[m][l] = static_cast<std::int32_t>((m * lanes + l) % 3);
    }
  const auto zero = hn::Zero(df), one = hn::Set(df, 1.0f), vs = hn::Set(df, static_cast<float>(s));
  const auto top = hn::Set(di, static_cast<std::int32_t>(lanes) - 1);
  const std::size_t channels = 3 * n;
  for (std::size_t i = 0; i < n; i += lanes) {
    const double xg = x + s * static_cast<double>(i);
    const long jg = pair_of(xg);
    const auto xr = hn::Set(df, static_cast<float>(xg - static_cast<double>(jg)));
    const auto last = hn::Set(di, static_cast<std::int32_t>(last_pair - jg));
    for (std::size_t m = 0; m < 3; ++m) {
      const std::size_t q0 = 3 * i + m * lanes; // the vector's first channel
      if (q0 >= channels) break;
      const auto xl = hn::MulAdd(vs, hn::Load(df, pixel[m]), xr);
      const auto jl = hn::Min(hn::ConvertTo(di, hn::Max(xl, zero)), last);
      const auto fl = hn::Min(hn::Max(hn::Sub(xl, hn::ConvertTo(df, jl)), zero), one);
      // Each lane's left value from texel jg on, and the least of them.
      const auto at = hn::Add(hn::Add(jl, hn::Add(jl, jl)), hn::Load(di, channel[m]));
      const auto least = hn::MinOfLanes(di, at);
      const std::int32_t b = hn::GetLane(least);
      base[q0 / lanes] = static_cast<std::int32_t>(3 * (jg - j_first)) + b;
      std::int32_t* e = entry + 2 * q0;
      hn::StoreU(hn::Min(hn::Sub(at, least), top), di, e); // (within N by the precondition)
      hn::StoreU(hn::BitCast(di, fl), di, e + lanes);
    }
  }
}

/// N channel values from p as floats: 16-bit linear values or floats.
template <class DF>
HWY_INLINE hn::Vec<DF> load_values(DF df, const std::uint16_t* HWY_RESTRICT p) noexcept {
  const hn::Rebind<std::int32_t, DF> di;
  const hn::Rebind<std::uint16_t, DF> d16;
  return hn::ConvertTo(df, hn::PromoteTo(di, hn::LoadU(d16, p)));
}
template <class DF>
HWY_INLINE hn::Vec<DF> load_values(DF df, const float* HWY_RESTRICT p) noexcept {
  return hn::LoadU(df, p);
}

/// h[c] = v0 + f (v1 - v0) for the channels c in [first, last) (first a multiple of N) of a
/// row planned by `plan_magnified_row` with period P vectors: vector q reads the plan's entries
/// of vector q mod P, from value base[q mod P] + (q / P) advance of `v` (a plan of the whole row:
/// P its length, advance 0). v0 and v1 are the values (16-bit linear values or floats, unscaled)
/// of c's texel pair in `v`, the row's channels from its first pair's left texel on, readable up
/// to N + 3 values past each vector's base. One permute per value: each vector's left values lie
/// within N, its right values within the N three on. With `kBlend`, also
/// acc[c - first] += w0 above[c] + w1 h[c] in the same pass (`detail::blend_rows` of the row
/// above and this one).
template <bool kBlend, class V>
HWY_INLINE void resample_planned_body(const V* HWY_RESTRICT v, const std::int32_t* HWY_RESTRICT base,
                                      const std::int32_t* HWY_RESTRICT entry, std::size_t period, std::size_t advance,
                                      float* HWY_RESTRICT h, std::size_t first, std::size_t last,
                                      const float* HWY_RESTRICT above, float w0, float w1,
                                      float* HWY_RESTRICT acc) noexcept {
  using DF = hn::ScalableTag<float>;
  const DF df;
  const hn::RebindToSigned<DF> di;
  const std::size_t lanes = hn::Lanes(df);
  const auto a0 = hn::Set(df, w0), a1 = hn::Set(df, w1);
  HWY_ALIGN float tail[hn::MaxLanes(DF())];
  std::size_t p = first / lanes % period;             // the plan's vector
  const V* at = v + first / lanes / period * advance; // its period's start in v
  // The channels of the plan's vector p.
  const auto resampled = [&]() HWY_ATTR {
    const V* w = at + base[p];
    const std::int32_t* e = entry + 2 * lanes * p;
    const auto idx = hn::IndicesFromVec(df, hn::LoadU(di, e));
    const auto left = hn::TableLookupLanes(load_values(df, w), idx);
    const auto right = hn::TableLookupLanes(load_values(df, w + 3), idx);
    return hn::MulAdd(hn::BitCast(df, hn::LoadU(di, e + lanes)), hn::Sub(right, left), left);
  };
  std::size_t q0 = first;
  for (; q0 + lanes <= last; q0 += lanes) {
    const auto out = resampled();
    hn::StoreU(out, df, h + q0);
    if constexpr (kBlend) {
      float* sum = acc + (q0 - first);
      hn::StoreU(hn::Add(hn::LoadU(df, sum), hn::MulAdd(a1, out, hn::Mul(a0, hn::LoadU(df, above + q0)))), df, sum);
    }
    if (++p == period) {
      p = 0;
      at += advance;
    }
  }
  if (q0 < last) { // the last, partial vector through a buffer
    hn::Store(resampled(), df, tail);
    for (std::size_t c = q0; c < last; ++c) {
      h[c] = tail[c - q0];
      if constexpr (kBlend) acc[c - first] += w0 * above[c] + w1 * h[c];
    }
  }
}

/// `resample_planned_body` at this target, blending into `acc` when it is not nullptr.
template <class V>
inline void resample_planned_row(Target, const V* HWY_RESTRICT v, const std::int32_t* HWY_RESTRICT base,
                                 const std::int32_t* HWY_RESTRICT entry, std::size_t period, std::size_t advance,
                                 float* HWY_RESTRICT h, std::size_t first, std::size_t last,
                                 const float* HWY_RESTRICT above = nullptr, float w0 = 0, float w1 = 0,
                                 float* HWY_RESTRICT acc = nullptr) noexcept {
  if (acc != nullptr)
    resample_planned_body<true>(v, base, entry, period, advance, h, first, last, above, w0, w1, acc);
  else
    resample_planned_body<false>(v, base, entry, period, advance, h, first, last, above, w0, w1, acc);
}
