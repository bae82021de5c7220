// No #pragma once, no includes: kernels/lerp_row_hwy.hpp includes this file once per Highway
// target, inside that target's namespace (`hn`, `Target`, `CodeDecoder` are its own).
/// \file
/// One camera row of 8-bit sRGB codes resampled at x + s i (`detail::resample_row_portable`'s
/// inputs, outputs and preconditions), written once with Highway and compiled for every x86
/// target (SSE4, AVX2, AVX-512, AVX-512 with VBMI), chosen per `SimdLevel` by `hwy_visit`
/// (`resample_row_hwy`, kernels/lerp_row_hwy.hpp). It is the horizontal half of a separable
/// bilinear shift-and-add at another scale below the VBMI level (`detail::resample_row`).
///
/// Each step takes one vector of pixels (4, 8 or 16): their positions relative to the group's
/// first texel j0 in float (at most a few dozen camera pixels, so the fractions keep ~1e-6),
/// j = floor and f = the fraction per lane, two 32-bit gathers of codes at byte offsets 3 j and
/// 3 j + 2 (r0 g0 b0 r1 and b0 r1 g1 b1: the six codes of the texel pair, nothing past the pair
/// read), the six channels decoded (`CodeDecoder`: the cubic decode or a table gather), then
/// scale (v0 + f (v1 - v0)) stored interleaved.

/// `detail::resample_row_portable` for 8-bit codes at this target (the kernel tag `Target`
/// selects it, see `hwy_visit`). Reads only the row's texel pairs it interpolates.
inline void resample_row_codes(Target, const std::uint8_t* HWY_RESTRICT row, std::size_t texels,
                               const std::uint16_t* HWY_RESTRICT lut, double x, double s, float scale,
                               float* HWY_RESTRICT h, std::size_t n, const std::uint8_t* ahead) noexcept {
  using DF = hn::ScalableTag<float>;
  const DF df;
  const hn::RebindToSigned<DF> di;
  const std::size_t lanes = hn::Lanes(df);
  const CodeDecoder decode(lut);
  const long last_pair = static_cast<long>(texels) - 2;
  const auto pair_of = [last_pair](double v) noexcept { // floor(v) for v >= 0, clamped
    return std::clamp(static_cast<long>(v), 0L, last_pair);
  };
  const long j_first = pair_of(x);
  // The bytes a group's pixels read (its last pixel's pair included), for the prefetch.
  const std::size_t span = 3 * static_cast<std::size_t>(std::ceil(s * static_cast<double>(lanes))) + 6;
  const auto zero = hn::Zero(df), one = hn::Set(df, 1.0f), vscale = hn::Set(df, scale);
  const auto step = hn::Mul(hn::Set(df, static_cast<float>(s)), hn::Iota(df, 0.0f));
  const auto mask8 = hn::Set(di, 0xFF);
  HWY_ALIGN float tail[3 * hn::MaxLanes(df)];
  for (std::size_t i = 0; i < n; i += lanes) {
    const double xg = x + s * static_cast<double>(i);
    const long j0 = pair_of(xg);
    if (ahead != nullptr)
      for (std::size_t b = 0; b < span; b += 64)
        mpr::detail::prefetch_l2(ahead, 3 * static_cast<std::size_t>(j0 - j_first) + b);
    // Positions from texel j0 (float), their pairs (clamped to the row's last) and fractions.
    const auto xl = hn::Add(hn::Set(df, static_cast<float>(xg - static_cast<double>(j0))), step);
    const auto jl = hn::Min(hn::ConvertTo(di, hn::Max(xl, zero)), hn::Set(di, static_cast<int>(last_pair - j0)));
    const auto f = hn::Min(hn::Max(hn::Sub(xl, hn::ConvertTo(df, jl)), zero), one);
    const auto offset = hn::Add(jl, hn::Add(jl, jl)); // 3 j
    const auto* base = reinterpret_cast<const std::int32_t*>(row + 3 * static_cast<std::size_t>(j0));
    const auto a = hn::GatherOffset(di, base, offset);                          // r0 g0 b0 r1
    const auto b = hn::GatherOffset(di, base, hn::Add(offset, hn::Set(di, 2))); // b0 r1 g1 b1
    // Byte k of each lane (the shift is arithmetic on signed lanes: masked after it).
    const auto code = [&](auto v, auto k) noexcept { return hn::And(hn::ShiftRight<8 * k()>(v), mask8); };
    const auto lerp = [&](auto code0, auto code1) noexcept {
      const auto v0 = decode(code0);
      return hn::Mul(vscale, hn::MulAdd(f, hn::Sub(decode(code1), v0), v0));
    };
    using B0 = std::integral_constant<int, 0>;
    using B1 = std::integral_constant<int, 1>;
    using B2 = std::integral_constant<int, 2>;
    using B3 = std::integral_constant<int, 3>;
    const auto r = lerp(code(a, B0{}), code(a, B3{}));
    const auto g = lerp(code(a, B1{}), code(b, B2{}));
    const auto bl = lerp(code(a, B2{}), code(b, B3{}));
    if (i + lanes <= n) {
      hn::StoreInterleaved3(r, g, bl, df, h + 3 * i);
    } else {
      hn::StoreInterleaved3(r, g, bl, df, tail);
      std::copy(tail, tail + 3 * (n - i), h + 3 * i);
    }
  }
}
