#pragma once
/// \file
/// Many cameras' 2-D shifts at whole-pixel offsets added to a tile together. Each such camera
/// adds one decoded texel per output channel (the refocus on the reference plane of rectified
/// data: every camera of Chess at z = 1000); added a camera at a time, every accumulator of the
/// tile is read and written once per camera. Here each output row takes, 64 channels at a time,
/// the codes of every camera that reads it, summed in registers, and adds the sum once. The
/// decoded values are whole multiples of the table's unit (`decode_spread64`), so the sum is
/// exact in 32-bit integers and in its one conversion to float (up to `kShiftSumCameras` cameras
/// at once), and the result differs from the camera-at-a-time one by float rounding only. Blocks
/// cover whole runs: partial ones, whose pixels outside the shared span would go camera by camera
/// per row, scattered the reads and were slower (docs/performance.md).

#include <mpr/core/detail/prefetch.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/decode_vbmi.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mpr::detail {

/// One camera's part of a tile at a whole-pixel shift, over whole runs: output row r in
/// [r_begin, r_end), pixel i gets the camera's texel at `texels` + (r - r_begin) `stride` + 3 i
/// (flat channels; 8-bit codes).
struct ShiftedBlock {
  const std::uint8_t* texels = nullptr;
  std::ptrdiff_t stride = 0;
  std::size_t r_begin = 0, r_end = 0;
  /// The same channels as 16-bit linear values (`CameraFrameSet::linear16`, same stride), or
  /// nullptr when the frames hold none.
  const std::uint16_t* linear = nullptr;
};

/// The blocks of one tile, to be added together (`add_shifted_blocks`), and working memory.
struct ShiftBatch {
  std::vector<ShiftedBlock> blocks;
  std::vector<const std::uint8_t*> rows;    // per output row: the cameras' codes
  std::vector<const std::uint16_t*> rows16; // or their 16-bit linear values
};

/// Cameras summed in one register pass: the decoded values are below 2^24 and multiples of 2^8,
/// so 127 of them fit a 32-bit lane, and their sum (below 2^24 units of 2^8) a float, exactly.
inline constexpr std::size_t kShiftSumCameras = 127;

/// acc[j] += scale sum_c v(rows[c][j]) for j in [0, m), v the table value of the code (`lut`):
/// the plain loop, camera by camera.
inline void add_code_rows_portable(const std::uint8_t* const* rows, std::size_t k, const std::uint16_t* lut,
                                   float scale, float* acc, std::size_t m, SimdLevel level) noexcept {
  for (std::size_t c = 0; c < k; ++c) add_scaled_row(rows[c], lut, scale, acc, m, level);
}

#if defined(MPR_SIMD_X86)
/// The same on AVX-512 with VBMI: 64 channels a step, the cameras' decoded codes summed in
/// 32-bit lanes (at most `kShiftSumCameras` at a time), converted and added once. Each camera's
/// row is asked for a few cache lines ahead (the cameras' rows are too many streams for the
/// hardware prefetcher).
MPR_TARGET_AVX512_VBMI inline void add_code_rows_vbmi(const std::uint8_t* const* rows, std::size_t k,
                                                      const std::uint16_t* lut, float scale, float* acc,
                                                      std::size_t m) noexcept {
  constexpr std::size_t kAhead = 256; // bytes
  const DecodeBytes d = load_decode_bytes(lut);
  const __m512 w = _mm512_set1_ps(scale / kDecodedScale);
  for (std::size_t j = 0; j < m; j += 64) {
    const std::size_t count = std::min<std::size_t>(64, m - j);
    for (std::size_t c0 = 0; c0 < k; c0 += kShiftSumCameras) {
      __m512i sum[4] = {_mm512_setzero_si512(), _mm512_setzero_si512(), _mm512_setzero_si512(), _mm512_setzero_si512()};
      for (std::size_t c = c0; c < std::min(k, c0 + kShiftSumCameras); ++c) {
        prefetch_l2(rows[c], j + kAhead);
        __m512i v[4];
        decode_spread64(d, rows[c] + j, count, v);
        for (int q = 0; q < 4; ++q) sum[q] = _mm512_add_epi32(sum[q], v[q]);
      }
      for (std::size_t q = 0; q < 4 && 16 * q < count; ++q) {
        const __mmask16 keep =
            count >= 16 * q + 16 ? __mmask16(0xFFFF) : static_cast<__mmask16>((1u << (count - 16 * q)) - 1);
        float* at = acc + j + 16 * q;
        _mm512_mask_storeu_ps(
            at, keep, _mm512_fmadd_ps(w, _mm512_maskz_cvtepi32_ps(0xFFFF, sum[q]), _mm512_maskz_loadu_ps(keep, at)));
      }
    }
  }
}
#endif

/// The VBMI kernel where `level` and the CPU allow; at `avx2` and `avx512` the Highway kernel
/// (`kernels::sum_code_rows_hwy`: the cameras' decoded codes summed in registers); else (and
/// without Highway) `add_code_rows_portable`. Reads
/// rows[c][0, m); the VBMI kernel reads each row in 64-byte loads (masked at its end) and asks
/// for lines past it (a prefetch, which never faults).
inline void add_code_rows(const std::uint8_t* const* rows, std::size_t k, const std::uint16_t* lut, float scale,
                          float* acc, std::size_t m, SimdLevel level = dispatch_level()) noexcept {
#if defined(MPR_SIMD_X86)
  if (level >= SimdLevel::avx512vbmi) return add_code_rows_vbmi(rows, k, lut, scale, acc, m);
#endif
#if MPR_HAVE_HWY // avx2 and avx512 without VBMI: the Highway kernel (kernels/lerp_row_hwy.hpp)
  if (level >= SimdLevel::avx2) return kernels::sum_code_rows_hwy(rows, k, lut, scale, acc, m, level);
#endif
  add_code_rows_portable(rows, k, lut, scale, acc, m, level);
}

/// Adds every block of `batch` to the tile's accumulators, `rows` output rows of n pixels
/// (output row r's at acc + r `acc_stride`, pixel i's channels at 3 i): per row, one
/// `add_code_rows` over the cameras whose blocks cover it; below the VBMI level, when every
/// block has its 16-bit linear values (and Highway is present), one
/// `kernels::sum_linear_rows_hwy` over those instead (the same result, without a decode).
/// `batch.rows` (and `batch.rows16` for the linear values) holds at least one entry per block.
inline void add_shifted_blocks(ShiftBatch& batch, std::size_t rows, std::size_t n, const std::uint16_t* lut,
                               float scale, float* acc, std::ptrdiff_t acc_stride,
                               SimdLevel level = dispatch_level()) noexcept {
#if MPR_HAVE_HWY
  if (level < SimdLevel::avx512vbmi && batch.rows16.size() >= batch.blocks.size() &&
      std::all_of(batch.blocks.begin(), batch.blocks.end(),
                  [](const ShiftedBlock& b) { return b.linear != nullptr; })) {
    const std::uint16_t** at = batch.rows16.data();
    for (std::size_t r = 0; r < rows; ++r) {
      std::size_t k = 0;
      for (const ShiftedBlock& b : batch.blocks)
        if (r >= b.r_begin && r < b.r_end) at[k++] = b.linear + static_cast<std::ptrdiff_t>(r - b.r_begin) * b.stride;
      if (k > 0)
        kernels::sum_linear_rows_hwy(at, k, scale, acc + static_cast<std::ptrdiff_t>(r) * acc_stride, 3 * n, level);
    }
    return;
  }
#endif
  const std::uint8_t** ptr = batch.rows.data();
  for (std::size_t r = 0; r < rows; ++r) {
    std::size_t k = 0;
    for (const ShiftedBlock& b : batch.blocks)
      if (r >= b.r_begin && r < b.r_end) ptr[k++] = b.texels + static_cast<std::ptrdiff_t>(r - b.r_begin) * b.stride;
    if (k > 0) add_code_rows(ptr, k, lut, scale, acc + static_cast<std::ptrdiff_t>(r) * acc_stride, 3 * n, level);
  }
}

} // namespace mpr::detail
