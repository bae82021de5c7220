// The body of the cylinder-weights kernel for one Highway target: kernels/cylinder_weights.hpp
// includes it once per target, in a namespace of its own with `hn` naming that target's ops.
// No include guard (included once per target); no includes (the including header has them).

/// `detail::cylinder_weights_portable` for float at this target, a vector of rays at a time,
/// the same arithmetic with fused multiply-adds where the target has them; the tail goes
/// through the portable loop.
inline std::array<std::size_t, 2> cylinder_weights(const float* HWY_RESTRICT xu, const float* HWY_RESTRICT xv,
                                                   const float* HWY_RESTRICT du, const float* HWY_RESTRICT dv,
                                                   const float* HWY_RESTRICT inv_dd, std::size_t n, float cu, float cv,
                                                   float inv_radius, float* HWY_RESTRICT w) noexcept {
  const hn::ScalableTag<float> df;
  const std::size_t lanes = hn::Lanes(df);
  const auto vcu = hn::Set(df, cu), vcv = hn::Set(df, cv), vinv = hn::Set(df, inv_radius);
  const auto one = hn::Set(df, 1.0f), zero = hn::Zero(df);
  detail::PositiveSpan span{n, n, n};
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes) {
    const auto eu = hn::Sub(vcu, hn::LoadU(df, xu + i)), ev = hn::Sub(vcv, hn::LoadU(df, xv + i));
    const auto ed = hn::MulAdd(eu, hn::LoadU(df, du + i), hn::Mul(ev, hn::LoadU(df, dv + i)));
    const auto r2 = hn::MulAdd(eu, eu, hn::Mul(ev, ev));
    const auto d2 = hn::Max(hn::NegMulAdd(hn::Mul(ed, ed), hn::LoadU(df, inv_dd + i), r2), zero);
    const auto wi = hn::Max(hn::NegMulAdd(hn::Sqrt(d2), vinv, one), zero);
    hn::StoreU(wi, df, w + i);
    std::uint8_t bits[8] = {};
    hn::StoreMaskBits(df, wi > zero, bits);
    span.add(i, static_cast<unsigned>(bits[0]) | static_cast<unsigned>(bits[1]) << 8);
  }
  return span.with_tail(i, detail::cylinder_weights_portable(xu + i, xv + i, du + i, dv + i, inv_dd + i, n - i, cu, cv,
                                                             inv_radius, w + i));
}
