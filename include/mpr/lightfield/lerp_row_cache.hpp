#pragma once
/// \file
/// `mpr::LerpRowCache`: camera rows interpolated horizontally for a shift-and-add (`shift_add`,
/// frame_runs.hpp), kept for the next output row that reads them.

#include <mpr/lightfield/kernels/lerp_row_or_linear.hpp>
#include <mpr/lightfield/kernels/resample_row.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mpr {

/// Camera rows interpolated horizontally (`detail::lerp_row`), kept for the next output row: on
/// a plane parallel to the camera plane at the cameras' scale, output rows r and r + 1 read
/// camera rows (k, k + 1) and (k + 1, k + 2) at the same sub-pixel offset, so each camera row is
/// interpolated once and blended twice (the separable form of the bilinear shift-and-add). One
/// per thread, for runs of one camera after another; reuse needs the same texels, length and
/// horizontal offset (within 1e-4 pixel, below 0.03 of an 8-bit level).
class LerpRowCache {
public:
  /// The row of `m` channels from `texels` (flat, m + 3 read; 8-bit codes decoded by `lut`) at
  /// offset `ax`, computed or kept; nullptr when memory runs out.
  /// With `stride` k > 1 (an output pixel every k camera pixels), the row holds the `m / 3`
  /// pixels 0, k, 2k, ... of the interpolated row (which reads k (m / 3 - 1) + 2 texels).
  /// `ahead` (nullptr: none): texels of the row to be asked for next, prefetched while this one
  /// is computed (`detail::lerp_row`). `linear` (nullptr: none): the same channels as 16-bit
  /// decode-table values (`CameraFrameSet::linear16`), read in place of the codes where the
  /// level's row kernel is the Highway one (`detail::lerp_row_or_linear`: the same row), with
  /// `linear_ahead` prefetched in place of `ahead`.
  template <class C>
  [[nodiscard]] const float* row(const C* texels, const std::uint16_t* lut, std::size_t m, float ax, float scale,
                                 std::size_t stride = 1, const C* ahead = nullptr,
                                 const std::uint16_t* linear = nullptr,
                                 const std::uint16_t* linear_ahead = nullptr) noexcept {
    for (int k = 0; k < 2; ++k) {
      const Entry& e = entries_[k];
      if (e.texels == static_cast<const void*>(texels) && e.m == m && e.stride == stride &&
          std::abs(e.ax - static_cast<double>(ax)) <= 1e-4) {
        last_ = k;
        return e.h.data();
      }
    }
    last_ ^= 1; // replaces the row not returned last: the blend of a run asks for two
    Entry& e = entries_[last_];
    const std::size_t pixels = m / 3, wide = 3 * (stride * (pixels - 1) + 1);
    try {
      if (e.h.size() < wide) e.h.resize(wide);
    } catch (...) {
      e.texels = nullptr;
      return nullptr;
    }
    detail::lerp_row_or_linear(texels, linear, lut, ax, scale, e.h.data(), wide, ahead, linear_ahead);
    if (stride > 1) // keep every stride-th pixel, in place (each moves left or stays)
      for (std::size_t i = 1; i < pixels; ++i)
        for (std::size_t k = 0; k < 3; ++k) e.h[3 * i + k] = e.h[3 * stride * i + k];
    e.texels = texels;
    e.m = m;
    e.stride = stride;
    e.ax = ax;
    return e.h.data();
  }

  /// The `pixels` pixels of the camera row `texels` (of `width` texels; 8-bit codes decoded by
  /// `lut`) at positions x + s i (`detail::resample_row`), computed or kept; nullptr when memory
  /// runs out. Reuse needs the same row and length, x within 1e-4 pixel and s within 1e-4 pixel
  /// over the row. `ahead` as in `row` (from the next row's first texel read).
  template <class C>
  [[nodiscard]] const float* resampled(const C* texels, std::size_t width, const std::uint16_t* lut, std::size_t pixels,
                                       double x, double s, float scale, const C* ahead = nullptr) noexcept {
    const std::size_t m = 3 * pixels;
    for (int k = 0; k < 2; ++k) {
      const Entry& e = entries_[k];
      if (e.texels == static_cast<const void*>(texels) && e.m == m && e.stride == 0 && std::abs(e.ax - x) <= 1e-4 &&
          std::abs(e.step - s) * static_cast<double>(pixels) <= 1e-4) {
        last_ = k;
        return e.h.data();
      }
    }
    last_ ^= 1;
    Entry& e = entries_[last_];
    try {
      if (e.h.size() < m) e.h.resize(m);
    } catch (...) {
      e.texels = nullptr;
      return nullptr;
    }
    detail::resample_row(texels, width, lut, x, s, scale, e.h.data(), pixels, ahead);
    e.texels = texels;
    e.m = m;
    e.stride = 0; // marks a resampled row
    e.ax = x;
    e.step = s;
    return e.h.data();
  }

  /// Forgets every row (call before rows of other frames, or texels that may have changed).
  void clear() noexcept {
    for (Entry& e : entries_) e.texels = nullptr;
  }

private:
  struct Entry {
    const void* texels = nullptr;
    std::size_t m = 0, stride = 1; // stride 0: a row of `resampled`
    double ax = 0, step = 0;
    std::vector<float> h;
  };
  Entry entries_[2];
  int last_ = 0;
};

} // namespace mpr
