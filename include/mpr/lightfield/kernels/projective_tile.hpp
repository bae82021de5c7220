#pragma once
/// \file
/// Several projective rows of one camera at once: the rows of a tile of a tilted focal plane (or
/// of any planar focal surface seen off the cameras' rows). Each row is a `ProjectiveRow` with
/// its own outputs and ray weights (`TileRowOut`); the result is that of `projective_row` on
/// every row. On AVX-512 with VBMI and 8-bit codes the tile is walked in chunks of columns: the
/// texels the chunk's rows read (a small box
/// of the image, found from the rows' end points) are decoded to linear light once into planar
/// float rows, and each group of 16 points then takes its bilinear taps from that box with
/// in-register float permutes instead of four gathers from the codes. A chunk whose box is too
/// large, or a group too spread out for a 32-float window, takes the gather step. 8-bit texels
/// need 64 readable bytes past the last one (`HugePageAllocator`'s padding): the box is read
/// 64 bytes at a time.

#include <mpr/core/simd.hpp>
#include <mpr/lightfield/kernels/decode_vbmi.hpp>
#include <mpr/lightfield/kernels/projective_row.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

namespace mpr::detail {

/// Where one row of a tile adds its n points: `acc` (3 floats a point) and `seen` (one a point),
/// each point weighed by `rw` (n weights; nullptr: 1 each), as `projective_row` takes them.
struct TileRowOut {
  float* acc;
  float* seen;
  const float* rw;
};

/// The reference: `projective_row` on row r of `rows` with the outputs of `out[r]`.
template <class T, class C>
inline void projective_tile_rows(std::span<const ProjectiveRow<T, C>> rows, std::span<const TileRowOut> out,
                                 std::size_t n, SimdLevel level) noexcept {
  for (std::size_t r = 0; r < rows.size(); ++r) projective_row(rows[r], n, out[r].rw, out[r].acc, out[r].seen, level);
}

#if defined(MPR_SIMD_X86)
/// Points per row of a chunk, and the largest box a chunk decodes (texels wide, rows high).
inline constexpr std::size_t kTileChunk = 64;
inline constexpr int kBoxTexels = 144, kBoxRows = 24;
/// Floats of padding after a box row: a window load reads 32 floats from any texel of the row.
inline constexpr int kBoxPad = 32;

/// The decoded box: channel k of box texel (bx, by) at c[k][by][bx], linear light times `scale`
/// not yet applied (the table's values).
struct TileBox {
  alignas(64) float c[3][kBoxRows][kBoxTexels + kBoxPad];
};

// Box rows [0, rows) x texels [0, texels) from image rows y0 + by and columns x0 + bx, both
// clamped to the image (edge texels repeated, as the bilinear pixel does).
MPR_TARGET_AVX512_VBMI inline void decode_box(const ProjectiveRow<float, std::uint8_t>& r, const DecodeBytes& d, int x0,
                                              int y0, int texels, int rows, TileBox& box) noexcept {
  // Bytes of 16 texels' codes in planar order: r of texels 0-15, then g, then b (48 of 64).
  alignas(64) static constexpr std::uint8_t kPlanar[64] = {0, 3, 6, 9,  12, 15, 18, 21, 24, 27, 30, 33, 36, 39, 42, 45,
                                                           1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 34, 37, 40, 43, 46,
                                                           2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 32, 35, 38, 41, 44, 47,
                                                           0, 0, 0, 0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0};
  const __m512i planar = _mm512_load_si512(kPlanar);
  const int in0 = std::max(x0, 0), in1 = std::min(x0 + texels, r.width); // texels inside the image
  for (int by = 0; by < rows; ++by) {
    const int y = std::clamp(y0 + by, 0, r.height - 1);
    const std::uint8_t* codes = r.texels + 3 * static_cast<std::size_t>(y) * static_cast<std::size_t>(r.width);
    float* out[3] = {box.c[0][by], box.c[1][by], box.c[2][by]};
    for (int x = in0; x < in1; x += 16) {
      const int m = std::min(16, in1 - x);
      const __m512i raw = _mm512_loadu_si512(codes + 3 * x); // bytes past the 3 m used are not
      __m512i first, second;
      decode16x64(d, _mm512_maskz_permutexvar_epi8(~__mmask64(0), planar, raw), first, second);
      const __mmask16 keep = static_cast<__mmask16>((1u << m) - 1);
      const std::size_t at = static_cast<std::size_t>(x - x0);
      _mm512_mask_storeu_ps(out[0] + at, keep, words_low_ps(first));
      _mm512_mask_storeu_ps(out[1] + at, keep, words_high_ps(first));
      _mm512_mask_storeu_ps(out[2] + at, keep, words_low_ps(second));
    }
    for (int k = 0; k < 3; ++k) { // columns left and right of the image repeat its edge texels
      for (int x = x0; x < in0; ++x) out[k][x - x0] = out[k][in0 - x0];
      for (int x = in1; x < x0 + texels; ++x) out[k][x - x0] = out[k][in1 - 1 - x0];
    }
  }
}

// The box step of 16 points (`projective_lanes`) whose taps lie in box texels [j0, j0 + 31] and
// rows [r0, r0 + kWindowRows): each box row is read as two 16-float windows per channel and
// every lane picks its two taps by permutes. False (nothing added) when the points spread wider.
inline constexpr int kWindowRows = 4;

MPR_TARGET_AVX512_VBMI MPR_ALWAYS_INLINE bool box_step(const TileBox& box, int x0, int y0, int texels, int rows,
                                                       float scale, const ProjectiveLanes& p, std::size_t count,
                                                       float* acc) noexcept {
  constexpr int kFloor = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
  const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f);
  // The lanes' taps in box coordinates. x and y are monotonic along the row, so the seen lanes'
  // extremes are at the first and last of them; those are clamped into the box (found in double
  // from the rows' end points, the lanes in float), and every lane onto them (float rounding
  // may break the monotony by an ulp at an integer; a lane the camera does not see may hold
  // anything, even NaN, and ends with fraction 0 or 1 and weight 0). A clamped lane takes its
  // fraction from the texel it is clamped to: an error of its rounding only, bilinear being
  // continuous.
  __m512i jx = _mm512_sub_epi32(_mm512_maskz_cvttps_epi32(kAll, _mm512_maskz_roundscale_ps(kAll, p.x, kFloor)),
                                _mm512_set1_epi32(x0));
  __m512i jy = _mm512_sub_epi32(_mm512_maskz_cvttps_epi32(kAll, _mm512_maskz_roundscale_ps(kAll, p.y, kFloor)),
                                _mm512_set1_epi32(y0));
  const int first = __builtin_ctz(p.m), last = 31 - __builtin_clz(p.m);
  const __m512i pick = _mm512_setr_epi32(first, last, 16 + first, 16 + last, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
  const __m128i ends = _mm512_maskz_extracti32x4_epi32(0xF, _mm512_permutex2var_epi32(jx, pick, jy), 0);
  const __m128i least = _mm_min_epi32(ends, _mm_shuffle_epi32(ends, 0xB1)),
                most = _mm_max_epi32(ends, _mm_shuffle_epi32(ends, 0xB1));
  const int jx0 = std::clamp(_mm_cvtsi128_si32(least), 0, texels - 2);
  const int jx1 = std::clamp(_mm_cvtsi128_si32(most), 0, texels - 2);
  const int jy0 = std::clamp(_mm_cvtsi128_si32(_mm_srli_si128(least, 8)), 0, rows - 2);
  const int jy1 = std::clamp(_mm_cvtsi128_si32(_mm_srli_si128(most, 8)), 0, rows - 2);
  if (jx1 - jx0 > 30 || jy1 - jy0 > kWindowRows - 2) return false;
  jx = _mm512_maskz_min_epi32(kAll, _mm512_maskz_max_epi32(kAll, jx, _mm512_set1_epi32(jx0)), _mm512_set1_epi32(jx1));
  jy = _mm512_maskz_min_epi32(kAll, _mm512_maskz_max_epi32(kAll, jy, _mm512_set1_epi32(jy0)), _mm512_set1_epi32(jy1));
  // max(NaN, 0) is 0: the second operand when either is NaN.
  const __m512 ax = _mm512_maskz_min_ps(
      kAll,
      _mm512_maskz_max_ps(
          kAll, _mm512_sub_ps(p.x, _mm512_maskz_cvtepi32_ps(kAll, _mm512_add_epi32(jx, _mm512_set1_epi32(x0)))), zero),
      one);
  const __m512 ay = _mm512_maskz_min_ps(
      kAll,
      _mm512_maskz_max_ps(
          kAll, _mm512_sub_ps(p.y, _mm512_maskz_cvtepi32_ps(kAll, _mm512_add_epi32(jy, _mm512_set1_epi32(y0)))), zero),
      one);
  const __m512i left = _mm512_sub_epi32(jx, _mm512_set1_epi32(jx0)),
                right = _mm512_add_epi32(left, _mm512_set1_epi32(1));
  __m512 top[3] = {zero, zero, zero}, bottom[3] = {zero, zero, zero}, previous[3] = {zero, zero, zero};
  for (int row = jy0; row <= jy1 + 1; ++row) {
    // Box row `row` at every lane's x: the top row of the lanes at jy == row, the bottom one of
    // those at jy == row - 1 (rows jy0 and jy0 + 1 set both for all lanes first).
    const __mmask16 lower = _mm512_cmp_epi32_mask(jy, _mm512_set1_epi32(row - 1), _MM_CMPINT_EQ);
    for (int k = 0; k < 3; ++k) {
      const float* at = box.c[k][row] + jx0;
      const __m512 w0 = _mm512_loadu_ps(at), w1 = _mm512_loadu_ps(at + 16);
      const __m512 a = _mm512_permutex2var_ps(w0, left, w1), b = _mm512_permutex2var_ps(w0, right, w1);
      const __m512 h = _mm512_fmadd_ps(ax, _mm512_sub_ps(b, a), a);
      if (row == jy0) {
        top[k] = h;
      } else if (row == jy0 + 1) {
        bottom[k] = h;
      } else {
        top[k] = _mm512_mask_mov_ps(top[k], lower, previous[k]);
        bottom[k] = _mm512_mask_mov_ps(bottom[k], lower, h);
      }
      previous[k] = h;
    }
  }
  const __m512 s = _mm512_maskz_mul_ps(p.m, p.wt, _mm512_set1_ps(scale));
  __m512 sum[3];
  for (int k = 0; k < 3; ++k) sum[k] = _mm512_mul_ps(s, _mm512_fmadd_ps(ay, _mm512_sub_ps(bottom[k], top[k]), top[k]));
  add_rgb_sums(sum, count, acc);
  return true;
}

// Where a chunk of points [i0, i0 + kTileChunk) of every row reads the image: `boxed` with the
// box (texels [x0, x0 + texels) x rows [y0, y0 + rows), image coordinates, may reach one texel
// past the image) when every row has w > 0 at both ends of the chunk and the box is small
// enough; `outside` when no point of the chunk is seen; else `gather`.
struct ChunkBox {
  enum State { boxed, outside, gather } state = gather;
  int x0 = 0, y0 = 0, texels = 0, rows = 0;
};

inline ChunkBox chunk_box(std::span<const ProjectiveRow<float, std::uint8_t>> rows, std::size_t i0, std::size_t n,
                          const ProjectiveRow<float, std::uint8_t>& image) noexcept {
  const std::size_t i1 = std::min(n, i0 + kTileChunk);
  // x and y are monotonic along a row where w > 0 (w is affine in the point index), so the
  // rows' end points bound every point of the chunk.
  // Each row's largest step between neighbouring points (at an end: the step changes
  // monotonically too) must let 16 points fit a box_step window, else every group would gather.
  double xlo = 1e300, xhi = -1e300, ylo = 1e300, yhi = -1e300, sx = 0, sy = 0;
  ChunkBox b;
  for (const ProjectiveRow<float, std::uint8_t>& r : rows)
    for (const std::size_t i : {i0, i1 - 1}) {
      double x = 0, y = 0;
      for (const std::size_t j : {i, i + 1}) { // the point and the next one
        const double t = static_cast<double>(j);
        const double w = static_cast<double>(r.h0[2]) + t * static_cast<double>(r.hs[2]);
        if (!(w > 0)) return b;
        const double xj = (static_cast<double>(r.h0[0]) + t * static_cast<double>(r.hs[0])) / w;
        const double yj = (static_cast<double>(r.h0[1]) + t * static_cast<double>(r.hs[1])) / w;
        if (j == i) {
          x = xj, y = yj;
        } else {
          sx = std::max(sx, std::abs(xj - x)), sy = std::max(sy, std::abs(yj - y));
        }
      }
      xlo = std::min(xlo, x), xhi = std::max(xhi, x), ylo = std::min(ylo, y), yhi = std::max(yhi, y);
    }
  if (!(std::isfinite(xlo) && std::isfinite(xhi) && std::isfinite(ylo) && std::isfinite(yhi))) return b;
  if (!(15 * sx <= 29 && 15 * sy <= kWindowRows - 2)) return b;
  // Seen points lie in [-0.5, width - 0.5) x [-0.5, height - 0.5).
  if (!(xhi >= -1.5 && xlo < image.width + 0.5 && yhi >= -1.5 && ylo < image.height + 0.5)) {
    b.state = ChunkBox::outside;
    return b;
  }
  // Taps floor(x) in [-1, width - 1] and floor(x) + 1. A float lane that rounds across the box's
  // edge is clamped onto it (`box_step`), an error of its rounding only: bilinear is continuous.
  b.x0 = static_cast<int>(std::max(std::floor(xlo), -1.0));
  b.y0 = static_cast<int>(std::max(std::floor(ylo), -1.0));
  b.texels = static_cast<int>(std::min(std::floor(xhi) + 1, static_cast<double>(image.width))) - b.x0 + 1;
  b.rows = static_cast<int>(std::min(std::floor(yhi) + 1, static_cast<double>(image.height))) - b.y0 + 1;
  if (b.texels < 2 || b.rows < 2) // only when every point lies past an edge
    b.state = ChunkBox::outside;
  else if (b.texels <= kBoxTexels && b.rows <= kBoxRows)
    b.state = ChunkBox::boxed;
  return b;
}

// Asks for the cache lines of box rows [from, to). Always inlined: GCC finds an out-of-line
// function of prefetches free of side effects and drops the calls.
MPR_ALWAYS_INLINE void prefetch_box(const ProjectiveRow<float, std::uint8_t>& image, const ChunkBox& b, int from,
                                    int to) noexcept {
  const int in0 = std::max(b.x0, 0), in1 = std::min(b.x0 + b.texels, image.width);
  for (int by = from; by < std::min(to, b.rows); ++by) {
    const int y = std::clamp(b.y0 + by, 0, image.height - 1);
    const std::uint8_t* row = image.texels + 3 * static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width);
    for (int x = 3 * in0; x < 3 * in1; x += 64) __builtin_prefetch(row + x);
    __builtin_prefetch(row + 3 * in1 - 1);
  }
}

// The chunked kernel (see the file comment). Rows need w > 0 at both ends of a chunk for its box
// (then along the whole chunk: w is affine in the point index); else the chunk's rows take the
// gather step.
MPR_TARGET_AVX512_VBMI inline void projective_tile_codes_vbmi(std::span<const ProjectiveRow<float, std::uint8_t>> rows,
                                                              std::span<const TileRowOut> out, std::size_t n) noexcept {
  thread_local TileBox box;
  const DecodeBytes d = load_decode_bytes(rows[0].lut);
  const ProjectiveRow<float, std::uint8_t>& image = rows[0];
  // The boxes of the chunk from point i0 (see `chunk_box`), of the next and of the one after:
  // each chunk's texels are prefetched while the chunk two before it is sampled (the second
  // chunk's before the first), a share per row: a box row is a short stretch of its own image
  // row, which the hardware prefetcher does not pick up, and one chunk's sampling was too short
  // to hide the memory's latency; the prefetches are spread out so as not to hold up the loads.
  ChunkBox next = chunk_box(rows, 0, n, image);
  ChunkBox after = kTileChunk < n ? chunk_box(rows, kTileChunk, n, image) : ChunkBox{};
  if (after.state == ChunkBox::boxed) prefetch_box(image, after, 0, after.rows);
  for (std::size_t i0 = 0; i0 < n; i0 += kTileChunk) {
    const std::size_t i1 = std::min(n, i0 + kTileChunk);
    const ChunkBox b = next;
    next = after;
    after = i1 + kTileChunk < n ? chunk_box(rows, i1 + kTileChunk, n, image) : ChunkBox{};
    const bool prefetch = after.state == ChunkBox::boxed;
    const int per_row = (after.rows + static_cast<int>(rows.size()) - 1) / static_cast<int>(rows.size());
    if (b.state == ChunkBox::outside) continue; // nothing of the chunk is seen
    const bool boxed = b.state == ChunkBox::boxed;
    const int x0 = b.x0, y0 = b.y0, texels = b.texels, box_rows = b.rows;
    if (boxed) decode_box(image, d, x0, y0, texels, box_rows, box);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      float* acc_row = out[r].acc;
      float* seen_row = out[r].seen;
      if (prefetch) prefetch_box(image, after, static_cast<int>(r) * per_row, static_cast<int>(r + 1) * per_row);
      for (std::size_t i = i0; i < i1; i += 16) {
        const ProjectiveLanes p = projective_lanes(rows[r], i, i1, out[r].rw);
        if (p.m == 0) continue;
        const std::size_t count = std::min<std::size_t>(16, i1 - i);
        if (!boxed || !box_step(box, x0, y0, texels, box_rows, image.scale, p, count, acc_row + 3 * i)) {
          const Decode16x512 decode = load_decode16(image.lut);
          projective_gather(rows[r], &decode, p, count, acc_row + 3 * i);
        }
        _mm512_mask_storeu_ps(seen_row + i, p.m, _mm512_add_ps(_mm512_maskz_loadu_ps(p.m, seen_row + i), p.wt));
      }
    }
  }
}
#endif

/// `projective_row` on every row of `rows` (one camera: the same image in each), row r over its
/// points [0, n) with the outputs and weights of `out[r]` (as many entries as rows); the chunked
/// kernel on AVX-512 with VBMI for 8-bit codes and float coordinates (images
/// `gather_indexable`), else row by row.
template <class T, class C>
inline void projective_tile(std::span<const ProjectiveRow<T, C>> rows, std::span<const TileRowOut> out, std::size_t n,
                            SimdLevel level = dispatch_level()) noexcept {
  if (rows.empty() || n == 0) return;
#if defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<T, float> && std::is_same_v<C, std::uint8_t>) {
    // Point indices past 2^24 are not exact in float: the lanes and the boxes (found in double)
    // could then disagree by a point; such rows go row by row.
    if (level >= SimdLevel::avx512vbmi && gather_indexable(rows[0].width, rows[0].height) &&
        n <= (std::size_t(1) << 24))
      return projective_tile_codes_vbmi(rows, out, n);
  }
#endif
  projective_tile_rows(rows, out, n, level);
}

} // namespace mpr::detail
