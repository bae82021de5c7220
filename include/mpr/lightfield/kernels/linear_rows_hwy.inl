// No #pragma once, no includes: kernels/lerp_row_hwy.hpp includes this file once per Highway
// target, inside that target's namespace (`hn`, `Target` are its own).
/// \file
/// The shift-and-add rows on frames held as 16-bit linear values (`CameraFrameSet::linear16`:
/// each 8-bit code replaced once, at load, by its entry of `Srgb8Texel::linear16()`), written
/// once with Highway: the same sums as `sum_code_rows` and `lerp_row_codes` over the same
/// values, with a widening load and a conversion in place of the per-code decode. Each of their
/// results is bit-identical to theirs (the same operations in the same order on the same
/// floats); they read twice the bytes, which the prefetches keep ahead of.

/// `v` lanes of 16-bit values at p as floats (exact: below 2^16).
template <class DF>
HWY_INLINE hn::Vec<DF> load_linear16(DF df, const std::uint16_t* HWY_RESTRICT p) noexcept {
  const hn::RebindToSigned<DF> di;
  const hn::Rebind<std::uint16_t, DF> d16;
  return hn::ConvertTo(df, hn::BitCast(di, hn::PromoteTo(hn::RebindToUnsigned<DF>(), hn::LoadU(d16, p))));
}

/// acc[j] += scale sum_c rows[c][j] for j in [0, m), c in [0, k): k rows of 16-bit values summed
/// in 32-bit integer lanes (exact: 256 of them at a time, as `sum_code_rows` sums its decoded
/// values in floats, so each result is that kernel's), converted and added once. Reads
/// rows[c][0, m); each row is asked for 4 KiB ahead: the k rows are k streams, too many for the
/// hardware prefetcher, and this loop (two loads a line) is bound by how far ahead they are asked
/// for (AMD VM, reference workload at `avx2`: 17.5 ms 1 KiB ahead, 14.4 ms 2 KiB, 12.9 ms 4 KiB,
/// 13.7 ms 8 KiB). Past the row's end the prefetches reach the camera's next row, which the
/// next output row reads.
inline void sum_linear_rows(Target, const std::uint16_t* const* rows, std::size_t k, float scale,
                            float* HWY_RESTRICT acc, std::size_t m) noexcept {
  constexpr std::size_t kExact = 256, kAhead = 4096; // kAhead in bytes
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const hn::RebindToUnsigned<decltype(df)> du;
  const hn::Rebind<std::uint16_t, decltype(df)> d16;
  const std::size_t lanes = hn::Lanes(df), step = 4 * lanes;
  const auto w = hn::Set(df, scale);
  for (std::size_t c = 0; c < k; ++c)
    for (std::size_t b = 0; b < std::min(2 * m, kAhead); b += 64) mpr::detail::prefetch_l2(rows[c], b);
  std::size_t j = 0;
  for (; j + step <= m; j += step)
    for (std::size_t c0 = 0; c0 < k; c0 += kExact) {
      auto s0 = hn::Zero(du), s1 = hn::Zero(du), s2 = hn::Zero(du), s3 = hn::Zero(du);
      for (std::size_t c = c0; c < std::min(k, c0 + kExact); ++c) {
        const std::uint16_t* p = rows[c] + j;
        for (std::size_t b = j; b < j + step; b += 32) // one line (32 values) at a time
          if (b % 32 == 0) mpr::detail::prefetch_l2(rows[c], 2 * b + kAhead);
        s0 = hn::Add(s0, hn::PromoteTo(du, hn::LoadU(d16, p)));
        s1 = hn::Add(s1, hn::PromoteTo(du, hn::LoadU(d16, p + lanes)));
        s2 = hn::Add(s2, hn::PromoteTo(du, hn::LoadU(d16, p + 2 * lanes)));
        s3 = hn::Add(s3, hn::PromoteTo(du, hn::LoadU(d16, p + 3 * lanes)));
      }
      float* at = acc + j;
      hn::StoreU(hn::MulAdd(w, hn::ConvertTo(df, hn::BitCast(di, s0)), hn::LoadU(df, at)), df, at);
      hn::StoreU(hn::MulAdd(w, hn::ConvertTo(df, hn::BitCast(di, s1)), hn::LoadU(df, at + lanes)), df, at + lanes);
      hn::StoreU(hn::MulAdd(w, hn::ConvertTo(df, hn::BitCast(di, s2)), hn::LoadU(df, at + 2 * lanes)), df,
                 at + 2 * lanes);
      hn::StoreU(hn::MulAdd(w, hn::ConvertTo(df, hn::BitCast(di, s3)), hn::LoadU(df, at + 3 * lanes)), df,
                 at + 3 * lanes);
    }
  for (; j < m; ++j) {
    float s = 0;
    for (std::size_t c = 0; c < k; ++c) s += static_cast<float>(rows[c][j]);
    acc[j] += scale * s;
  }
}

/// `lerp_row_codes` on 16-bit values: h[j] = (1 - ax) scale a[j] + ax scale a[j + 3] for j in
/// [0, m), reading a[0, m + 3); `ahead` (nullptr: none), 16-bit values too, is prefetched a line
/// per 32 values. With `acc` (nullptr: none), also acc[j] += wy0 hp[j] + wy1 h[j] in the same
/// pass.
inline void lerp_row_linear(Target, const std::uint16_t* HWY_RESTRICT a, float ax, float scale, float* HWY_RESTRICT h,
                            std::size_t m, const std::uint16_t* ahead, const float* HWY_RESTRICT hp = nullptr,
                            float wy0 = 0, float wy1 = 0, float* HWY_RESTRICT acc = nullptr) noexcept {
  const hn::ScalableTag<float> df;
  const std::size_t lanes = hn::Lanes(df);
  const float s0 = (1 - ax) * scale, s1 = ax * scale;
  const auto w0 = hn::Set(df, s0), w1 = hn::Set(df, s1), v0 = hn::Set(df, wy0), v1 = hn::Set(df, wy1);
  std::size_t j = 0;
  for (; j + lanes <= m; j += lanes) {
    if (ahead != nullptr && j % 32 < lanes) mpr::detail::prefetch_l2(ahead, 2 * j);
    const auto v = hn::MulAdd(w1, load_linear16(df, a + j + 3), hn::Mul(w0, load_linear16(df, a + j)));
    hn::StoreU(v, df, h + j);
    if (acc != nullptr)
      hn::StoreU(hn::Add(hn::LoadU(df, acc + j), hn::MulAdd(v1, v, hn::Mul(v0, hn::LoadU(df, hp + j)))), df, acc + j);
  }
  for (; j < m; ++j) {
    const float left = a[j], right = a[j + 3];
    h[j] = s0 * left + s1 * right;
    if (acc != nullptr) acc[j] += wy0 * hp[j] + wy1 * h[j];
  }
}
