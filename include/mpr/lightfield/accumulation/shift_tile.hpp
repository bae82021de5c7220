#pragma once
/// \file
/// The 2-D shift-and-add: one camera's bilinear contribution to a block of output rows that it
/// sees as its own image shifted by a fixed sub-pixel offset, one camera pixel per output pixel
/// (refocusing on a plane parallel to the camera plane at the cameras' scale; Isaksen et al.
/// 2000, Vaish et al. 2004). In its separable form each camera row is interpolated horizontally
/// once and blended into the two output rows that read it; on AVX-512 with VBMI the
/// interpolation of a row and the blend of the output row above it are one pass over the row.

#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/decode_vbmi.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace mpr::detail {

/// A block of output rows as one camera sees it. Output row r (r in [0, rows)) gets, for each
/// channel j in [0, m) (flat r g b channels of m / 3 pixels),
///   acc[r acc_stride + j] += (1 - ay) h_r[j] + ay h_{r+1}[j],
///   h_k[j] = scale ((1 - ax) v(t[k stride + j]) + ax v(t[k stride + j + 3])),
/// with t = `texels` (flat channels of the camera's texel under the block's first pixel) and v
/// the value of a stored channel (`channel_value`: 8-bit codes decoded by `lut`). Reads camera
/// rows 0 .. rows (m + 3 channels each); with ay = 0, rows 0 .. rows - 1 only, and with ax = ay
/// = 0 their first m channels only.
template <class C>
struct ShiftTile {
  const C* texels = nullptr;          ///< first camera row of the block, from its first texel read
  std::ptrdiff_t stride = 0;          ///< channels from one camera row to the next
  std::size_t rows = 0;               ///< output rows (rows + 1 camera rows are read)
  std::size_t m = 0;                  ///< channels per output row, a multiple of 3
  float ax = 0, ay = 0;               ///< sub-pixel offsets in [0, 1], horizontal and vertical
  float scale = 1;                    ///< channel scale of the texel type (`Srgb8Texel::scale`, ...)
  const std::uint16_t* lut = nullptr; ///< decode table of 8-bit codes (unused otherwise)
  float* acc = nullptr;               ///< the output rows' accumulators (flat r g b)
  std::ptrdiff_t acc_stride = 0;      ///< channels from one output row's accumulators to the next
  /// `texels` as 16-bit linear values (8-bit codes replaced by their `lut` entries: the frames'
  /// `CameraFrameSet::linear16`, same stride), or nullptr when the frames hold none.
  const std::uint16_t* linear = nullptr;
};

/// One camera row added at a horizontal offset alone (a vertical offset of 0), in one pass:
/// acc[j] += r_i scale ((1 - ax) v(a[j]) + ax v(a[j + 3])) for j in [0, m), i = j / 3, with r_i =
/// rw[i] (rw nullptr: 1), and then weight[i] += max(rw[i], 0) (weight is read only with rw). On
/// AVX-512 with VBMI and 8-bit codes (`lerp_add_row_codes_vbmi`,
/// `lerp_add_weighted_row_codes_vbmi`): true. Elsewhere nothing is added and false is returned
/// (the caller interpolates into a working row and blends it). Reads a[0, m + 3), a[0, m) when
/// ax = 0; `ahead` as in `lerp_row`.
template <class C>
[[nodiscard]] bool add_row_one_pass(const C* a, const std::uint16_t* lut, float ax, float scale, const float* rw,
                                    float* acc, float* weight, std::size_t m, const C* ahead = nullptr,
                                    SimdLevel level = dispatch_level()) noexcept {
#if defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<C, std::uint8_t>) {
    if (level >= SimdLevel::avx512vbmi) {
      if (rw != nullptr)
        lerp_add_weighted_row_codes_vbmi(a, lut, ax, scale, rw, acc, weight, m, ahead);
      else
        lerp_add_row_codes_vbmi(a, lut, ax, scale, acc, m, ahead);
      return true;
    }
  }
#endif
  (void)a, (void)lut, (void)ax, (void)scale, (void)rw, (void)acc, (void)weight, (void)m, (void)ahead, (void)level;
  return false;
}

/// Floats of working memory `shift_tile` needs for rows of m channels.
[[nodiscard]] constexpr std::size_t shift_tile_work(std::size_t m) noexcept { return 2 * (m + 32); }

#if MPR_HAVE_HWY
/// `shift_tile` reading the block's 16-bit linear values (`t.linear`, non-null) with the Highway
/// rows of kernels/linear_rows_hwy.inl: the same sums as the 8-bit rows below the VBMI level
/// over the same values, without a decode. `ahead` (nullptr: none): the 16-bit values of the
/// next camera's block, `ahead_stride` apart.
template <class C>
void shift_tile_linear(const ShiftTile<C>& t, float* work, const std::uint16_t* ahead, std::ptrdiff_t ahead_stride,
                       SimdLevel level) noexcept {
  const auto next_ahead = [&](std::size_t k) noexcept -> const std::uint16_t* {
    return ahead != nullptr ? ahead + static_cast<std::ptrdiff_t>(k) * ahead_stride : nullptr;
  };
  const auto row_of = [&](std::size_t k) noexcept { return t.linear + static_cast<std::ptrdiff_t>(k) * t.stride; };
  float *const h0 = work, *const h1 = work + t.m + 16;
  if (t.ay == 0) { // each output row reads one camera row
    for (std::size_t r = 0; r < t.rows; ++r) {
      float* acc = t.acc + static_cast<std::ptrdiff_t>(r) * t.acc_stride;
      const std::uint16_t* row = row_of(r);
      if (t.ax == 0) {
        kernels::sum_linear_rows_hwy(&row, 1, t.scale, acc, t.m, level);
        continue;
      }
      kernels::lerp_row_linear_hwy(row, t.ax, t.scale, h0, t.m, next_ahead(r), level);
      blend_rows(h0, h0, 1.0f, 0.0f, nullptr, acc, t.m / 3, level);
    }
    return;
  }
  float *hp = h0, *h = h1;
  kernels::lerp_row_linear_hwy(row_of(0), t.ax, t.scale, hp, t.m, next_ahead(0), level);
  for (std::size_t r = 0; r < t.rows; ++r) {
    float* acc = t.acc + static_cast<std::ptrdiff_t>(r) * t.acc_stride;
    kernels::lerp_blend_row_linear_hwy(row_of(r + 1), t.ax, t.scale, h, t.m, next_ahead(r + 1), hp, 1 - t.ay, t.ay, acc,
                                       level);
    std::swap(hp, h);
  }
}
#endif

/// Adds the block `t` (see `ShiftTile`) to its accumulators at `level`. `work` holds
/// `shift_tile_work(t.m)` floats (working rows, overwritten; they must not overlap the
/// accumulators). `ahead` (nullptr: none): the texels of the block's first row in the camera to
/// be added next, and `ahead_stride` its row stride in channels, prefetched along the way
/// (`lerp_row`). The working rows are placed so that each row's accumulators and the row
/// written beside them share their alignment: the AVX-512 pass then splits a row into a head of
/// up to 15 channels and a body whose 64-byte accesses do not straddle cache lines. Below the
/// VBMI level, a block with its 16-bit linear values (`t.linear`) is added from those
/// (`shift_tile_linear`, `ahead_linear` the next camera's, prefetched in place of `ahead`).
template <class C>
void shift_tile(const ShiftTile<C>& t, float* work, const C* ahead = nullptr, std::ptrdiff_t ahead_stride = 0,
                const std::uint16_t* ahead_linear = nullptr, SimdLevel level = dispatch_level()) noexcept {
  if (t.rows == 0 || t.m == 0) return;
#if MPR_HAVE_HWY
  if (t.linear != nullptr && level < SimdLevel::avx512vbmi)
    return shift_tile_linear(t, work, ahead_linear, ahead_stride, level);
#endif
  (void)ahead_linear;
  const auto next_ahead = [&](std::size_t k) noexcept -> const C* {
    return ahead != nullptr ? ahead + static_cast<std::ptrdiff_t>(k) * ahead_stride : nullptr;
  };
  // Two rows of m + 32 floats from the first 64-byte boundary; row k at misalignment p (floats).
  float* const base = work + (16 - (reinterpret_cast<std::uintptr_t>(work) / sizeof(float)) % 16) % 16;
  const auto misalignment = [](const float* p) noexcept {
    return static_cast<std::size_t>((reinterpret_cast<std::uintptr_t>(p) / sizeof(float)) % 16);
  };
  const auto working = [&](std::size_t k, const float* acc) noexcept {
    return base + (k % 2) * (t.m + 16) + misalignment(acc);
  };
  if (t.ay == 0) { // each output row reads one camera row: no vertical blend, no working rows kept
    for (std::size_t r = 0; r < t.rows; ++r) {
      const C* row = t.texels + static_cast<std::ptrdiff_t>(r) * t.stride;
      float* acc = t.acc + static_cast<std::ptrdiff_t>(r) * t.acc_stride;
      if (add_row_one_pass(row, t.lut, t.ax, t.scale, nullptr, acc, nullptr, t.m, next_ahead(r), level)) continue;
      if (t.ax == 0) {
        add_scaled_row(row, t.lut, t.scale, acc, t.m, level);
        continue;
      }
      float* h = working(0, acc);
      lerp_row(row, t.lut, t.ax, t.scale, h, t.m, next_ahead(r), level);
      blend_rows(h, h, 1.0f, 0.0f, nullptr, acc, t.m / 3, level);
    }
    return;
  }
  float* hp = working(0, t.acc);
  lerp_row(t.texels, t.lut, t.ax, t.scale, hp, t.m, next_ahead(0), level);
  for (std::size_t r = 0; r < t.rows; ++r) {
    const C* row = t.texels + static_cast<std::ptrdiff_t>(r + 1) * t.stride;
    float* acc = t.acc + static_cast<std::ptrdiff_t>(r) * t.acc_stride;
    float* h = working(r + 1, acc);
#if defined(MPR_SIMD_X86)
    if constexpr (std::is_same_v<C, std::uint8_t>) {
      if (level >= SimdLevel::avx512vbmi) {
        const std::size_t head = std::min(t.m, (16 - misalignment(acc)) % 16);
        if (head > 0) lerp_blend_row_codes_vbmi(row, t.lut, t.ax, t.scale, h, head, nullptr, hp, 1 - t.ay, t.ay, acc);
        lerp_blend_row_codes_vbmi(row + head, t.lut, t.ax, t.scale, h + head, t.m - head, next_ahead(r + 1), hp + head,
                                  1 - t.ay, t.ay, acc + head);
        hp = h;
        continue;
      }
    }
#endif
#if MPR_HAVE_HWY // below AVX-512: the Highway row, blended in the same pass
    if constexpr (std::is_same_v<C, std::uint8_t>) {
      if (level < SimdLevel::avx512) {
        kernels::lerp_blend_row_hwy(row, t.lut, t.ax, t.scale, h, t.m, next_ahead(r + 1), hp, 1 - t.ay, t.ay, acc,
                                    level);
        hp = h;
        continue;
      }
    }
#endif
    lerp_row(row, t.lut, t.ax, t.scale, h, t.m, next_ahead(r + 1), level);
    blend_rows(hp, h, 1 - t.ay, t.ay, nullptr, acc, t.m / 3, level);
    hp = h;
  }
}

} // namespace mpr::detail
