// No #pragma once: Highway's foreach_target.h includes this file again once per target; the
// parts below are guarded by hand (the outer guard, the per-target toggle, HWY_ONCE).
/// \file
/// The synthetic aperture's fractional-shift row, h[j] = scale ((1 - ax) v(a[j]) + ax v(a[j + 3]))
/// for 8-bit sRGB codes a (v: their entry of the 16-bit linear table, `Srgb8Texel::linear16()`),
/// written once with Highway (https://github.com/google/highway) and compiled by it for every x86
/// target (SSE4, AVX2, AVX-512, AVX-512 with VBMI; NEON or SVE elsewhere) through its
/// `#pragma` target regions, so a build with no `-march` flag holds every target. Same inputs,
/// outputs and preconditions as `detail::lerp_row_portable` (kernels.hpp) for 8-bit codes.
///
/// Each step decodes a block of codes into a float buffer (the table as 256 floats, one gather
/// per vector), then blends each value with the one three channels on (unaligned loads).
///
/// Header-only use: the per-target functions are `inline` in Highway's per-target namespaces
/// (`hwy::N_AVX2` ...), and the choice of target is mpr's (`lerp_row_hwy` below takes the
/// `SimdLevel`), not `HWY_DYNAMIC_DISPATCH`, which needs libhwy's run-time target detection
/// (`hwy::GetChosenTarget()`, a symbol of libhwy.so). Only available when Highway's headers are
/// (`MPR_HAVE_HWY`, core/config.hpp).

#include <mpr/core/config.hpp>
#if MPR_HAVE_HWY
#ifndef MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_OUTER
#define MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_OUTER
#include <mpr/core/detail/prefetch.hpp>
#include <mpr/core/simd.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace mpr::kernels {

/// The sRGB decode as arithmetic: code c in segment k (k = min((c + 21) / 32, 7): codes [0, 11),
/// [11, 43), ..., [171, 203), [203, 256)) has the value p_k(c - start_k) rounded to the nearest
/// integer, p_k the cubic `kSrgbCubic[k]` (coefficients of t^0 .. t^3; segment 0 is the linear
/// part of the sRGB curve). Fitted to 65535 x the exact decode so that the rounded value is
/// `Srgb8Texel::linear16()` for every code, whether the cubic is evaluated with fused
/// multiply-adds or with products and sums rounded apart (the least slack to a wrong rounding is
/// 0.0068 of a unit). Kernels decode with it, in registers and without table lookups, when the
/// decode table they are given is this one (`srgb_cubic_matches`).
inline constexpr std::size_t kSrgbSegments = 8;
inline constexpr float kSrgbStart[kSrgbSegments] = {0, 11, 43, 75, 107, 139, 171, 203};
inline constexpr float kSrgbCubic[4][kSrgbSegments] = {
    {0.0f, 219.418213f, 1583.22412f, 4611.11914f, 9635.44238f, 16920.0234f, 26688.4922f, 39137.6484f},
    {19.8916416f, 20.9521523f, 66.6008301f, 124.274422f, 191.066681f, 265.361206f, 346.176971f, 432.790833f},
    {0.0f, 0.601439714f, 0.822427034f, 0.981109619f, 1.10675085f, 1.21503747f, 1.31054115f, 1.39773977f},
    {0.0f, 0.00236744387f, 0.00166357204f, 0.00130912324f, 0.00113359257f, 0.000998683972f, 0.000899677863f,
     0.000802012801f}};

/// The table the cubic decode reproduces: entry c = p_k(c - start_k) rounded (fused
/// multiply-adds), as 16-bit values.
[[nodiscard]] inline const std::array<std::uint16_t, 256>& srgb_cubic_table() noexcept {
  static const std::array<std::uint16_t, 256> table = [] {
    std::array<std::uint16_t, 256> t{};
    for (int c = 0; c < 256; ++c) {
      const int k = std::min((c + 21) / 32, 7);
      const float x = static_cast<float>(c) - kSrgbStart[k];
      const float v =
          std::fma(std::fma(std::fma(kSrgbCubic[3][k], x, kSrgbCubic[2][k]), x, kSrgbCubic[1][k]), x, kSrgbCubic[0][k]);
      t[static_cast<std::size_t>(c)] = static_cast<std::uint16_t>(std::nearbyint(v));
    }
    return t;
  }();
  return table;
}

/// Whether `lut` (256 entries) is the table the cubic decode reproduces (`Srgb8Texel::linear16()`
/// is: tests/lightfield/kernels/lerp_row_hwy_test.cpp).
[[nodiscard]] inline bool srgb_cubic_matches(const std::uint16_t* lut) noexcept {
  return std::memcmp(lut, srgb_cubic_table().data(), 256 * sizeof(std::uint16_t)) == 0;
}

} // namespace mpr::kernels

// Every target this compiler can build (not only those above the build's baseline), so that
// MPR_SIMD can lower the choice in a -march=native build too; and AVX-512 with VBMI (AVX3_DL).
#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE
#endif
#ifndef HWY_WANT_AVX3_DL
#define HWY_WANT_AVX3_DL
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "mpr/lightfield/kernels/lerp_row_hwy.hpp"
#include <hwy/foreach_target.h> // includes this file once per target
#endif

#include <hwy/highway.h>

#if defined(MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_TOGGLE) == defined(HWY_TARGET_TOGGLE)
#ifdef MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_TOGGLE
#undef MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_TOGGLE
#else
#define MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_TOGGLE
#endif

HWY_BEFORE_NAMESPACE();
namespace mpr::kernels::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Targets with 8 float lanes or more decode sRGB codes arithmetically (`kSrgbCubic`): a
// lane-permute lookup of each coefficient, a cubic, a rounding. Narrower targets gather.
#undef MPR_LERP_ROW_HWY_CUBIC
#if HWY_TARGET != HWY_SCALAR && !HWY_HAVE_SCALABLE && HWY_MAX_BYTES >= 32
#define MPR_LERP_ROW_HWY_CUBIC 1
#else
#define MPR_LERP_ROW_HWY_CUBIC 0
#endif

#if MPR_LERP_ROW_HWY_CUBIC
/// The cubic decode's per-segment constants as vectors (the 8 entries, repeated to fill wider
/// vectors), for `TableLookupLanes`.
template <class DF>
struct SrgbCubic {
  hn::Vec<DF> start, c0, c1, c2, c3;
  explicit SrgbCubic(DF df) noexcept {
    HWY_ALIGN float lanes[5][hn::MaxLanes(DF())];
    for (std::size_t i = 0; i < hn::MaxLanes(DF()); ++i) {
      lanes[0][i] = kSrgbStart[i % kSrgbSegments];
      for (std::size_t k = 0; k < 4; ++k) lanes[k + 1][i] = kSrgbCubic[k][i % kSrgbSegments];
    }
    start = hn::Load(df, lanes[0]);
    c0 = hn::Load(df, lanes[1]);
    c1 = hn::Load(df, lanes[2]);
    c2 = hn::Load(df, lanes[3]);
    c3 = hn::Load(df, lanes[4]);
  }
};

/// The decoded values (`linear16()` entries, as floats) of the codes in the 32-bit lanes `code`.
template <class DF, class P, class VI>
HWY_INLINE hn::Vec<DF> decode_srgb_cubic(DF df, const P& p, VI code) noexcept {
  const hn::RebindToSigned<DF> di;
  const auto seg = hn::Min(hn::ShiftRight<5>(hn::Add(code, hn::Set(di, 21))), hn::Set(di, 7));
  const auto idx = hn::IndicesFromVec(df, seg);
  const auto t = hn::Sub(hn::ConvertTo(df, code), hn::TableLookupLanes(p.start, idx));
  auto v = hn::MulAdd(hn::TableLookupLanes(p.c3, idx), t, hn::TableLookupLanes(p.c2, idx));
  v = hn::MulAdd(v, t, hn::TableLookupLanes(p.c1, idx));
  v = hn::MulAdd(v, t, hn::TableLookupLanes(p.c0, idx));
  return hn::Round(v);
}
#endif

/// The tag of this target's kernels: `hwy_visit` hands it to a call, which finds the target's
/// overloads below by argument-dependent lookup.
struct Target {};

/// 8-bit codes to their decode-table values as floats, a vector of codes at a time: the cubic
/// decode when `lut` is the sRGB table it reproduces (and the target has 8 float lanes or more),
/// else one gather from the table as 256 floats.
class CodeDecoder {
public:
  using DF = hn::ScalableTag<float>;
  explicit CodeDecoder(const std::uint16_t* lut) noexcept {
#if MPR_LERP_ROW_HWY_CUBIC
    cubic_ = srgb_cubic_matches(lut);
#endif
    const DF df;
    const hn::Rebind<std::int32_t, DF> di;
    const hn::Rebind<std::uint16_t, DF> d16;
    for (std::size_t k = 0; k < 256; k += hn::Lanes(df))
      hn::Store(hn::ConvertTo(df, hn::PromoteTo(di, hn::LoadU(d16, lut + k))), df, table_ + k);
  }
  /// The values of the Lanes(DF) codes at p.
  HWY_INLINE hn::Vec<DF> operator()(const std::uint8_t* HWY_RESTRICT p) const noexcept {
    const hn::Rebind<std::int32_t, DF> di;
    const hn::Rebind<std::uint8_t, DF> d8;
    return (*this)(hn::PromoteTo(di, hn::LoadU(d8, p)));
  }
  /// The values of the codes (0 to 255) in the 32-bit lanes `code`.
  HWY_INLINE hn::Vec<DF> operator()(hn::Vec<hn::Rebind<std::int32_t, DF>> code) const noexcept {
#if MPR_LERP_ROW_HWY_CUBIC
    if (cubic_) return decode_srgb_cubic(DF(), poly_, code);
#endif
    return hn::GatherIndex(DF(), table_, code);
  }
  /// The value of one code.
  [[nodiscard]] float operator[](std::uint8_t c) const noexcept { return table_[c]; }

private:
  HWY_ALIGN float table_[256];
#if MPR_LERP_ROW_HWY_CUBIC
  bool cubic_ = false;
  SrgbCubic<DF> poly_{DF()};
#endif
};

/// Channels a step of the row kernels: decoded into a stack buffer, then interpolated.
inline constexpr std::size_t kRowBlock = 512;

/// value[0, n + 3) = the decoded codes a[0, n + 3), n <= kRowBlock.
HWY_INLINE void decode_block(const CodeDecoder& decode, const std::uint8_t* HWY_RESTRICT a, std::size_t n,
                             float* HWY_RESTRICT value) noexcept {
  const hn::ScalableTag<float> df;
  const std::size_t lanes = hn::Lanes(df), codes = n + 3;
  std::size_t k = 0;
  for (; k + lanes <= codes; k += lanes) hn::Store(decode(a + k), df, value + k);
  for (; k < codes; ++k) value[k] = decode[a[k]];
}

/// `detail::lerp_row_portable` for 8-bit codes at this target: reads a[0, m + 3), writes
/// h[0, m); `ahead` (nullptr: none) is prefetched a line per 64 codes. With `acc` (nullptr:
/// none), also acc[j] += wy0 hp[j] + wy1 h[j] in the same pass (`detail::blend_rows` of the row
/// above, hp, and this one).
inline void lerp_row_codes(Target, const std::uint8_t* HWY_RESTRICT a, const std::uint16_t* HWY_RESTRICT lut, float ax,
                           float scale, float* HWY_RESTRICT h, std::size_t m, const std::uint8_t* ahead,
                           const float* HWY_RESTRICT hp = nullptr, float wy0 = 0, float wy1 = 0,
                           float* HWY_RESTRICT acc = nullptr) noexcept {
  const hn::ScalableTag<float> df;
  const std::size_t lanes = hn::Lanes(df);
  const CodeDecoder decode(lut);
  const float s0 = (1 - ax) * scale, s1 = ax * scale;
  const auto w0 = hn::Set(df, s0), w1 = hn::Set(df, s1), v0 = hn::Set(df, wy0), v1 = hn::Set(df, wy1);
  HWY_ALIGN float value[kRowBlock + 3];
  for (std::size_t j0 = 0; j0 < m; j0 += kRowBlock) {
    const std::size_t n = std::min(kRowBlock, m - j0);
    if (ahead != nullptr)
      for (std::size_t b = 0; b < n; b += 64) mpr::detail::prefetch_l2(ahead, j0 + b);
    decode_block(decode, a + j0, n, value);
    float* HWY_RESTRICT out = h + j0;
    std::size_t j = 0;
    if (acc == nullptr) {
      for (; j + lanes <= n; j += lanes)
        hn::StoreU(hn::MulAdd(w1, hn::LoadU(df, value + j + 3), hn::Mul(w0, hn::Load(df, value + j))), df, out + j);
      for (; j < n; ++j) out[j] = s0 * value[j] + s1 * value[j + 3];
      continue;
    }
    const float* HWY_RESTRICT above = hp + j0;
    float* HWY_RESTRICT sum = acc + j0;
    for (; j + lanes <= n; j += lanes) {
      const auto v = hn::MulAdd(w1, hn::LoadU(df, value + j + 3), hn::Mul(w0, hn::Load(df, value + j)));
      hn::StoreU(v, df, out + j);
      hn::StoreU(hn::Add(hn::LoadU(df, sum + j), hn::MulAdd(v1, v, hn::Mul(v0, hn::LoadU(df, above + j)))), df,
                 sum + j);
    }
    for (; j < n; ++j) {
      out[j] = s0 * value[j] + s1 * value[j + 3];
      sum[j] += wy0 * above[j] + wy1 * out[j];
    }
  }
}

/// acc[j] += scale sum_c v(rows[c][j]) for j in [0, m), c in [0, k): the decoded codes of k
/// camera rows summed in registers (exactly: decoded values are whole numbers below 2^16, so
/// sums of up to 256 are exact in float; more go 256 at a time) and added once. Reads
/// rows[c][0, m); each row is asked for 256 bytes ahead.
inline void sum_code_rows(Target, const std::uint8_t* const* rows, std::size_t k, const std::uint16_t* lut, float scale,
                          float* HWY_RESTRICT acc, std::size_t m) noexcept {
  constexpr std::size_t kExact = 256, kAhead = 256;
  const hn::ScalableTag<float> df;
  const std::size_t lanes = hn::Lanes(df), step = 4 * lanes;
  const CodeDecoder decode(lut);
  const auto w = hn::Set(df, scale);
  // The heads of the rows: the prefetch in the loop runs kAhead bytes ahead of the reads.
  for (std::size_t c = 0; c < k; ++c)
    for (std::size_t b = 0; b < std::min(m, kAhead); b += 64) mpr::detail::prefetch_l2(rows[c], b);
  std::size_t j = 0;
  for (; j + step <= m; j += step)
    for (std::size_t c0 = 0; c0 < k; c0 += kExact) {
      auto s0 = hn::Zero(df), s1 = hn::Zero(df), s2 = hn::Zero(df), s3 = hn::Zero(df);
      for (std::size_t c = c0; c < std::min(k, c0 + kExact); ++c) {
        const std::uint8_t* p = rows[c] + j;
        if (j % 64 < step) mpr::detail::prefetch_l2(rows[c], j + kAhead);
        s0 = hn::Add(s0, decode(p));
        s1 = hn::Add(s1, decode(p + lanes));
        s2 = hn::Add(s2, decode(p + 2 * lanes));
        s3 = hn::Add(s3, decode(p + 3 * lanes));
      }
      float* at = acc + j;
      hn::StoreU(hn::MulAdd(w, s0, hn::LoadU(df, at)), df, at);
      hn::StoreU(hn::MulAdd(w, s1, hn::LoadU(df, at + lanes)), df, at + lanes);
      hn::StoreU(hn::MulAdd(w, s2, hn::LoadU(df, at + 2 * lanes)), df, at + 2 * lanes);
      hn::StoreU(hn::MulAdd(w, s3, hn::LoadU(df, at + 3 * lanes)), df, at + 3 * lanes);
    }
  for (; j < m; ++j) {
    float s = 0;
    for (std::size_t c = 0; c < k; ++c) s += decode[rows[c][j]];
    acc[j] += scale * s;
  }
}

#include <mpr/lightfield/kernels/linear_rows_hwy.inl>  // sum_linear_rows, lerp_row_linear
#include <mpr/lightfield/kernels/resample_row_hwy.inl> // resample_row_codes

} // namespace mpr::kernels::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif // per-target toggle

#if HWY_ONCE && !defined(MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_ONCE)
#define MPR_LIGHTFIELD_KERNELS_LERP_ROW_HWY_ONCE
namespace mpr::kernels {

/// Whether `lerp_row_hwy` has a Highway target compiled for `level` (the byte-permute form of
/// `avx512` counts as `avx512`): the targets of the build are Highway's `HWY_TARGETS`.
[[nodiscard]] inline bool lerp_row_hwy_has(detail::SimdLevel level) noexcept {
  if (level >= detail::SimdLevel::avx512) return (HWY_TARGETS & (HWY_AVX3 | HWY_AVX3_DL)) != 0;
  if (level >= detail::SimdLevel::avx2) return (HWY_TARGETS & HWY_AVX2) != 0;
  return true;
}

/// Calls `call(t)` with `t` the kernel tag (`N_xxx::Target`) of the Highway target for `level`:
/// levels above `avx512` (AVX-512 with VBMI) or `avx512` with `vbmi` take AVX3_DL, `avx512` AVX3,
/// `avx2` AVX2, `portable` SSE4 when the CPU has SSE4.2, else the build's baseline. A level the
/// build has no target for falls to the best lower one. The one place the kernels of this header
/// choose their target. Precondition: the CPU runs `level` (and VBMI with `vbmi`).
template <class Call>
void hwy_visit(detail::SimdLevel level, bool vbmi, const Call& call) noexcept {
#if HWY_ARCH_X86
  const int rank = static_cast<int>(level), avx512 = static_cast<int>(detail::SimdLevel::avx512);
  if (rank >= avx512) {
#if HWY_TARGETS & HWY_AVX3_DL
    if (vbmi || rank > avx512) return call(N_AVX3_DL::Target{});
#endif
#if HWY_TARGETS & HWY_AVX3
    return call(N_AVX3::Target{});
#endif
  }
#if HWY_TARGETS & HWY_AVX2
  if (rank >= static_cast<int>(detail::SimdLevel::avx2)) return call(N_AVX2::Target{});
#endif
#if HWY_TARGETS & HWY_SSE4
  if (__builtin_cpu_supports("sse4.2")) return call(N_SSE4::Target{});
#endif
#endif
  (void)level;
  (void)vbmi;
  call(HWY_STATIC_DISPATCH(Target){}); // the build's baseline target
}

/// `detail::lerp_row_portable` for 8-bit codes, the Highway kernel compiled for `level`
/// (`hwy_visit`).
inline void lerp_row_hwy(const std::uint8_t* a, const std::uint16_t* lut, float ax, float scale, float* h,
                         std::size_t m, const std::uint8_t* ahead = nullptr,
                         detail::SimdLevel level = detail::dispatch_level(), bool vbmi = false) noexcept {
  hwy_visit(level, vbmi, [&](auto t) { lerp_row_codes(t, a, lut, ax, scale, h, m, ahead); });
}

/// `lerp_row_hwy`, and acc[j] += wy0 hp[j] + wy1 h[j] for j in [0, m) in the same pass (the row
/// above, hp, and this one blended into the accumulators: `detail::blend_rows` without weights).
/// acc must not overlap a, h or hp.
inline void lerp_blend_row_hwy(const std::uint8_t* a, const std::uint16_t* lut, float ax, float scale, float* h,
                               std::size_t m, const std::uint8_t* ahead, const float* hp, float wy0, float wy1,
                               float* acc, detail::SimdLevel level = detail::dispatch_level()) noexcept {
  hwy_visit(level, false, [&](auto t) { lerp_row_codes(t, a, lut, ax, scale, h, m, ahead, hp, wy0, wy1, acc); });
}

/// acc[j] += scale sum_c lut[rows[c][j]] for j in [0, m), c in [0, k): k camera rows of 8-bit
/// codes decoded, summed in registers and added once (`detail::add_code_rows`), the Highway
/// kernel compiled for `level` (`hwy_visit`). Reads rows[c][0, m) and prefetches past them.
inline void sum_code_rows_hwy(const std::uint8_t* const* rows, std::size_t k, const std::uint16_t* lut, float scale,
                              float* acc, std::size_t m, detail::SimdLevel level = detail::dispatch_level()) noexcept {
  hwy_visit(level, false, [&](auto t) { sum_code_rows(t, rows, k, lut, scale, acc, m); });
}

/// acc[j] += scale sum_c rows[c][j] for j in [0, m), c in [0, k): k camera rows of 16-bit linear
/// values (`CameraFrameSet::linear16`) summed in registers and added once, the Highway kernel
/// (kernels/linear_rows_hwy.inl) compiled for `level`: `sum_code_rows_hwy`'s result for the
/// codes whose table values they hold. Reads rows[c][0, m) and prefetches past them.
inline void sum_linear_rows_hwy(const std::uint16_t* const* rows, std::size_t k, float scale, float* acc, std::size_t m,
                                detail::SimdLevel level = detail::dispatch_level()) noexcept {
  hwy_visit(level, false, [&](auto t) { sum_linear_rows(t, rows, k, scale, acc, m); });
}

/// `lerp_row_hwy` on 16-bit linear values (the codes' table values), compiled for `level`;
/// `ahead` (16-bit values, nullptr: none) is prefetched along the row.
inline void lerp_row_linear_hwy(const std::uint16_t* a, float ax, float scale, float* h, std::size_t m,
                                const std::uint16_t* ahead = nullptr,
                                detail::SimdLevel level = detail::dispatch_level()) noexcept {
  hwy_visit(level, false, [&](auto t) { lerp_row_linear(t, a, ax, scale, h, m, ahead); });
}

/// `lerp_blend_row_hwy` on 16-bit linear values, compiled for `level`. acc must not overlap a, h
/// or hp.
inline void lerp_blend_row_linear_hwy(const std::uint16_t* a, float ax, float scale, float* h, std::size_t m,
                                      const std::uint16_t* ahead, const float* hp, float wy0, float wy1, float* acc,
                                      detail::SimdLevel level = detail::dispatch_level()) noexcept {
  hwy_visit(level, false, [&](auto t) { lerp_row_linear(t, a, ax, scale, h, m, ahead, hp, wy0, wy1, acc); });
}

/// `detail::resample_row_portable` for 8-bit codes, the Highway kernel
/// (kernels/resample_row_hwy.inl) compiled for `level` (`hwy_visit`). Preconditions as
/// `resample_row_portable`'s: texels >= 2, x >= 0, s > 0.
inline void resample_row_hwy(const std::uint8_t* row, std::size_t texels, const std::uint16_t* lut, double x, double s,
                             float scale, float* h, std::size_t n, const std::uint8_t* ahead = nullptr,
                             detail::SimdLevel level = detail::dispatch_level()) noexcept {
  hwy_visit(level, false, [&](auto t) { resample_row_codes(t, row, texels, lut, x, s, scale, h, n, ahead); });
}

/// The same for float channels (`lut` unused).
inline void resample_row_hwy(const float* row, std::size_t texels, const std::uint16_t* lut, double x, double s,
                             float scale, float* h, std::size_t n, const float* ahead = nullptr,
                             detail::SimdLevel level = detail::dispatch_level()) noexcept {
  (void)lut;
  hwy_visit(level, false, [&](auto t) { resample_row_floats(t, row, texels, x, s, scale, h, n, ahead); });
}

} // namespace mpr::kernels
#endif
#endif // MPR_HAVE_HWY
