#pragma once
/// \file
/// The AVX-512 kernels of the packet walk (bvh/packet.hpp): `Avx512PacketKernels` holds all
/// `kPacketRays` (16) rays of a packet in one 512-bit vector, with mask registers for the rays
/// in play, and does the operations of `PortablePacketKernels<float>` (set-up, child box per ray,
/// leaf) in the same order, so the same masks and hits bit for bit; the beam test stays on four
/// boxes per 128-bit instruction. bvh/kernels/packet_closest_hits.hpp picks them at run time
/// (`SimdLevel::avx512`).
///
/// AVX-512F implies FMA, so these functions cannot be compiled for a target without it, as the
/// AVX2 kernels are. Instead every multiply, add, subtract and divide is an explicit-rounding
/// intrinsic (`_mm512_mul_round_ps` and kin, round to nearest, which is the default rounding):
/// compilers never contract those into a fused multiply-add. The scalar code the leaf needs
/// (the exact recomputation of a zero edge function, rays with different axis permutations)
/// runs in functions compiled for AVX2 *without* FMA that are never inlined here.

#include <mpr/core/config.hpp>
#include <mpr/scene/bvh/kernels/walk_kernels.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/packet.hpp>
#include <mpr/scene/bvh/slab.hpp>
#include <mpr/scene/bvh/watertight.hpp>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>

#if MPR_BVH_PACKET_AVX512
#include <immintrin.h>
#endif

namespace mpr::scene::detail {

MPR_EXACT_FP_BEGIN

#if MPR_BVH_PACKET_AVX512

/// `watertight_finish` out of line, compiled without FMA (the AVX-512 leaf's scalar step): the
/// values of the single-ray walk. Precondition: the CPU has AVX2.
MPR_NOINLINE MPR_TARGET_AVX2_NOFMA inline void
watertight_finish_nofma(const Edges<float>& e, float sz, std::uint32_t triangle, Hit<float>& hit) noexcept {
  watertight_finish(e, sz, triangle, hit);
}

/// `packet_leaf_per_ray<SseKernels>` out of line, compiled without FMA. Precondition: AVX2.
MPR_NOINLINE MPR_TARGET_AVX2_NOFMA inline void packet_leaf_per_ray_nofma(const BvhTree<float>& tree,
                                                                         std::uint32_t first, RayPacket<float>& p,
                                                                         std::uint32_t rays,
                                                                         Hit<float>* hits) noexcept {
  packet_leaf_per_ray<SseKernels>(tree, first, p, rays, hits);
}

/// `PortablePacketKernels<float>` with all 16 rays in one AVX-512 vector. Only for code compiled
/// with `MPR_TARGET_AVX512`. The arithmetic goes through `mul`, `add`, `sub` and `div` (explicit
/// rounding, never fused), min and max through their masked forms with every lane (`kAll`);
/// `max(b, a)` is `std::max(a, b)`, hence swapped operands.
struct Avx512PacketKernels {
  static constexpr int kRound = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
  /// Every lane: the masked forms with it are the unmasked operations (GCC 12 warns of an
  /// uninitialised operand in the unmasked explicit-rounding intrinsics, GCC bug 105593).
  static constexpr __mmask16 kAll = 0xFFFF;

  [[nodiscard]] MPR_TARGET_AVX512 static __m512 mul(__m512 a, __m512 b) noexcept {
    return _mm512_maskz_mul_round_ps(kAll, a, b, kRound);
  }
  [[nodiscard]] MPR_TARGET_AVX512 static __m512 add(__m512 a, __m512 b) noexcept {
    return _mm512_maskz_add_round_ps(kAll, a, b, kRound);
  }
  [[nodiscard]] MPR_TARGET_AVX512 static __m512 sub(__m512 a, __m512 b) noexcept {
    return _mm512_maskz_sub_round_ps(kAll, a, b, kRound);
  }
  [[nodiscard]] MPR_TARGET_AVX512 static __m512 div(__m512 a, __m512 b) noexcept {
    return _mm512_maskz_div_round_ps(kAll, a, b, kRound);
  }

  /// The least and the greatest of the 16 lanes (exact whatever the order: no arithmetic).
  [[nodiscard]] MPR_TARGET_AVX512 static float least(__m512 v) noexcept {
    const __m256 h8 = _mm256_min_ps(_mm512_extractf32x8_ps(v, 0), _mm512_extractf32x8_ps(v, 1));
    __m128 h = _mm_min_ps(_mm256_castps256_ps128(h8), _mm256_extractf128_ps(h8, 1));
    h = _mm_min_ps(h, _mm_movehl_ps(h, h));
    return _mm_cvtss_f32(_mm_min_ss(h, _mm_shuffle_ps(h, h, 1)));
  }
  [[nodiscard]] MPR_TARGET_AVX512 static float greatest(__m512 v) noexcept {
    const __m256 h8 = _mm256_max_ps(_mm512_extractf32x8_ps(v, 0), _mm512_extractf32x8_ps(v, 1));
    __m128 h = _mm_max_ps(_mm256_castps256_ps128(h8), _mm256_extractf128_ps(h8, 1));
    h = _mm_max_ps(h, _mm_movehl_ps(h, h));
    return _mm_cvtss_f32(_mm_max_ss(h, _mm_shuffle_ps(h, h, 1)));
  }

  /// `RayPacket<float>::make` for `rays` (at most `kPacketRays`) with no hit yet (t_max): the
  /// same values in every field the AVX-512 walk reads, bit for bit, and false also when the
  /// rays' axis permutations differ (`Avx2PacketKernels::make`'s contract; `shear` not filled).
  /// The rays are loaded as 96 consecutive floats (6 loads) and transposed in registers.
  [[nodiscard]] MPR_TARGET_AVX512 static bool make(std::span<const Ray<float>> rays, float t_max,
                                                   RayPacket<float>& p) noexcept {
    static_assert(sizeof(Ray<float>) == 6 * sizeof(float), "a Ray<float> is its origin, then its direction");
    const int n = static_cast<int>(rays.size());
    p.same_axes = true;
    const __m512 minus_inf = _mm512_set1_ps(-std::numeric_limits<float>::infinity());
    const __m512 inf = _mm512_set1_ps(std::numeric_limits<float>::infinity());
    p.active = 0;
    _mm512_store_ps(p.cull, minus_inf);
    if (n == 0) return true;
    // Float k of the rays is component k % 6 (origin x, y, z, direction x, y, z) of ray k / 6;
    // lanes past the last ray read zeros (a zero direction: not valid).
    const float* src = rays.data()->origin.data();
    __m512 raw[6];
    if (n == kPacketRays) {
      // Plain loads: masked ones of data not in the cache are far slower (Zen 4).
      for (int j = 0; j < 6; ++j) raw[j] = _mm512_loadu_ps(src + 16 * j);
    } else {
      for (int j = 0; j < 6; ++j) {
        const int left = 6 * n - 16 * j;
        const __mmask16 m = left >= 16 ? kAll : left > 0 ? __mmask16((1U << left) - 1U) : __mmask16(0);
        raw[j] = _mm512_maskz_loadu_ps(m, src + 16 * j);
      }
    }
    // Component c of lane r is float 6 r + c: register (6 r + c) / 16, i.e. pair (6 r + c) / 32
    // of registers, element (6 r + c) % 32 of that pair.
    const __m512i six_r = _mm512_mullo_epi32(_mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
                                             _mm512_set1_epi32(6));
    __m512 comp[6];
    for (int c = 0; c < 6; ++c) {
      const __m512i f = _mm512_add_epi32(six_r, _mm512_set1_epi32(c));
      const __m512i idx = _mm512_and_si512(f, _mm512_set1_epi32(31));
      const __mmask16 pair1 = _mm512_cmpge_epi32_mask(f, _mm512_set1_epi32(32));
      const __mmask16 pair2 = _mm512_cmpge_epi32_mask(f, _mm512_set1_epi32(64));
      __m512 v = _mm512_permutex2var_ps(raw[0], idx, raw[1]);
      v = _mm512_mask_blend_ps(pair1, v, _mm512_permutex2var_ps(raw[2], idx, raw[3]));
      comp[c] = _mm512_mask_blend_ps(pair2, v, _mm512_permutex2var_ps(raw[4], idx, raw[5]));
    }
    const __m512* og = comp;
    const __m512* dv = comp + 3;
    const __mmask16 lanes = n >= 16 ? __mmask16(0xFFFF) : __mmask16((1U << n) - 1U);
    const __m512 sign = _mm512_set1_ps(-0.0f), zero = _mm512_setzero_ps(), tiny = _mm512_set1_ps(1e-30f);
    __m512 ad[3];
    for (int a = 0; a < 3; ++a) ad[a] = _mm512_andnot_ps(sign, dv[a]);
    // Shear::make's largest axis: x if |x| > |y| and |x| > |z|, y if not and |y| > |z|, else z.
    const __mmask16 xy = _mm512_cmp_ps_mask(ad[0], ad[1], _CMP_GT_OQ);
    const __mmask16 xz = _mm512_cmp_ps_mask(ad[0], ad[2], _CMP_GT_OQ);
    const __mmask16 yz = _mm512_cmp_ps_mask(ad[1], ad[2], _CMP_GT_OQ);
    const __mmask16 is0 = xy & xz, is1 = static_cast<__mmask16>(~xy & yz);
    const __m512 largest = _mm512_mask_blend_ps(is0, _mm512_mask_blend_ps(is1, ad[2], ad[1]), ad[0]);
    const __mmask16 valid = _mm512_mask_cmp_ps_mask(lanes, largest, zero, _CMP_GT_OQ);
    __mmask16 bad = 0, negative[3];
    // BoxRay::make: components below 1e-30 in magnitude become +-1e-30; t = p * inv + offset.
    for (int a = 0; a < 3; ++a) {
      const __m512 da = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(ad[a], tiny, _CMP_LT_OQ), dv[a],
                                             _mm512_or_ps(_mm512_and_ps(dv[a], sign), tiny));
      const __m512 inv = div(_mm512_set1_ps(1.0f), da);
      const __m512 off = mul(_mm512_xor_ps(og[a], sign), inv);
      _mm512_store_ps(p.inv[a], inv);
      _mm512_store_ps(p.offset[a], off);
      negative[a] = _mm512_movepi32_mask(_mm512_castps_si512(inv)) & valid;
      const __mmask16 finite = _mm512_cmp_ps_mask(_mm512_andnot_ps(sign, inv), inf, _CMP_LT_OQ) &
                               _mm512_cmp_ps_mask(_mm512_andnot_ps(sign, off), inf, _CMP_LT_OQ);
      bad |= static_cast<__mmask16>(~finite & valid);
    }
    if (valid == 0) return true;
    if (bad != 0) return false;
    for (int a = 0; a < 3; ++a)
      if (negative[a] != 0 && negative[a] != valid) return false;
    const __mmask16 axis0 = is0 & valid, axis1 = is1 & valid;
    if (axis0 == valid)
      p.kz = 0;
    else if (axis1 == valid)
      p.kz = 1;
    else if ((axis0 | axis1) == 0)
      p.kz = 2;
    else
      return false;
    for (int a = 0; a < 3; ++a) {
      p.near[a] = negative[a] != 0 ? a + 3 : a;
      p.far[a] = negative[a] != 0 ? a : a + 3;
    }
    p.kx = p.kz + 1 == 3 ? 0 : p.kz + 1;
    p.ky = p.kx + 1 == 3 ? 0 : p.kx + 1;
    if (negative[p.kz] != 0) std::swap(p.kx, p.ky);
    const __m512 dz = dv[p.kz];
    _mm512_store_ps(p.sx, div(dv[p.kx], dz));
    _mm512_store_ps(p.sy, div(dv[p.ky], dz));
    _mm512_store_ps(p.sz, div(_mm512_set1_ps(1.0f), dz));
    _mm512_store_ps(p.ox, og[p.kx]);
    _mm512_store_ps(p.oy, og[p.ky]);
    _mm512_store_ps(p.oz, og[p.kz]);
    for (int a = 0; a < 3; ++a) {
      const __m512 inv = _mm512_load_ps(p.inv[a]), off = _mm512_load_ps(p.offset[a]);
      p.inv_lo[a] = least(_mm512_mask_blend_ps(valid, inf, inv));
      p.inv_hi[a] = greatest(_mm512_mask_blend_ps(valid, minus_inf, inv));
      p.off_lo[a] = least(_mm512_mask_blend_ps(valid, inf, off));
      p.off_hi[a] = greatest(_mm512_mask_blend_ps(valid, minus_inf, off));
    }
    _mm512_store_ps(p.cull, _mm512_mask_blend_ps(valid, minus_inf, _mm512_set1_ps(cull_bound(t_max))));
    _mm512_store_ps(p.best, _mm512_mask_blend_ps(valid, zero, _mm512_set1_ps(t_max)));
    p.active = valid;
    return true;
  }

  /// `rays` gives the entry parameters of the rays that enter (+inf in the other lanes); the
  /// walk reduces them with `least_value` only when it orders several children.
  using Least = __m512;
  [[nodiscard]] MPR_TARGET_AVX512 static float least_value(const __m512& v) noexcept { return least(v); }

  [[nodiscard]] MPR_TARGET_AVX512 static std::uint32_t beyond(const RayPacket<float>& p, float t) noexcept {
    return _mm512_cmp_ps_mask(_mm512_set1_ps(t), _mm512_load_ps(p.cull), _CMP_LT_OQ);
  }

  /// `PortablePacketKernels<float>::beam4`, four boxes per 128-bit instruction (no add follows a
  /// multiply directly, so there is nothing to fuse).
  [[nodiscard]] MPR_TARGET_AVX512 static unsigned beam4(const WideNode<float>& node, const RayPacket<float>& p,
                                                        float cull_max) noexcept {
    const float* b = &node.bounds[0][0];
    const __m128 widen = _mm_set1_ps(kBoxWiden<float>);
    const __m128 cmax = _mm_set1_ps(cull_max);
    __m128 tn = _mm_setzero_ps(), tf = cmax;
    for (int a = 0; a < 3; ++a) {
      const __m128 bn = _mm_load_ps(b + 4 * p.near[a]), bf = _mm_load_ps(b + 4 * p.far[a]);
      const __m128 ilo = _mm_set1_ps(p.inv_lo[a]), ihi = _mm_set1_ps(p.inv_hi[a]);
      const __m128 n = _mm_add_ps(_mm_min_ps(_mm_mul_ps(bn, ihi), _mm_mul_ps(bn, ilo)), _mm_set1_ps(p.off_lo[a]));
      const __m128 f =
          _mm_mul_ps(_mm_add_ps(_mm_max_ps(_mm_mul_ps(bf, ihi), _mm_mul_ps(bf, ilo)), _mm_set1_ps(p.off_hi[a])), widen);
      tn = _mm_max_ps(n, tn);
      tf = _mm_min_ps(f, tf);
    }
    return static_cast<unsigned>(_mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(tn, tf), _mm_cmplt_ps(tn, cmax))));
  }

  [[nodiscard]] MPR_TARGET_AVX512 static std::uint32_t
  rays(const WideNode<float>& node, int lane, const RayPacket<float>& p, std::uint32_t active, __m512& entry) noexcept {
    const __m512 widen = _mm512_set1_ps(kBoxWiden<float>);
    __m512 n[3], f[3];
    for (int a = 0; a < 3; ++a) {
      const __m512 bn = _mm512_set1_ps(node.bounds[p.near[a]][lane]), bf = _mm512_set1_ps(node.bounds[p.far[a]][lane]);
      const __m512 inv = _mm512_load_ps(p.inv[a]), off = _mm512_load_ps(p.offset[a]);
      n[a] = add(mul(bn, inv), off);
      f[a] = mul(add(mul(bf, inv), off), widen);
    }
    const __m512 cull = _mm512_load_ps(p.cull);
    const __m512 tn = _mm512_maskz_max_ps(kAll, _mm512_maskz_max_ps(kAll, _mm512_setzero_ps(), n[2]),
                                          _mm512_maskz_max_ps(kAll, n[1], n[0]));
    const __m512 tf =
        _mm512_maskz_min_ps(kAll, _mm512_maskz_min_ps(kAll, cull, f[2]), _mm512_maskz_min_ps(kAll, f[1], f[0]));
    const __mmask16 enter = _mm512_mask_cmp_ps_mask(
        _mm512_mask_cmp_ps_mask(static_cast<__mmask16>(active), tn, tf, _CMP_LE_OQ), tn, cull, _CMP_LT_OQ);
    entry = _mm512_mask_blend_ps(enter, _mm512_set1_ps(std::numeric_limits<float>::infinity()), tn);
    return enter;
  }

  /// Leaf `first` for the rays of `rays`: each triangle's edge functions for all 16 rays at
  /// once, with the operations of `edges4_sse` in the same order, then the rest of
  /// `watertight_finish` (`watertight_finish_nofma`, per ray, where an edge function is zero and
  /// needs the exact recomputation). The hit test is `watertight_finish`'s: t > 0 and (t < best,
  /// or t == best and a lower triangle index). The packet's `best` stays in a register through
  /// the leaf. Rays with different axis permutations (`!p.same_axes`) go one by one.
  MPR_TARGET_AVX512 static void leaf(const BvhTree<float>& tree, std::uint32_t first, RayPacket<float>& p,
                                     std::uint32_t rays, Hit<float>* hits) noexcept {
    if (!p.same_axes) {
      packet_leaf_per_ray_nofma(tree, first, p, rays, hits);
      return;
    }
    const int kx = p.kx, ky = p.ky, kz = p.kz;
    const __mmask16 in = static_cast<__mmask16>(rays);
    const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f);
    const __m512 vox = _mm512_load_ps(p.ox), voy = _mm512_load_ps(p.oy), voz = _mm512_load_ps(p.oz);
    const __m512 vsx = _mm512_load_ps(p.sx), vsy = _mm512_load_ps(p.sy), vsz = _mm512_load_ps(p.sz);
    __m512 best = _mm512_load_ps(p.best);
    __mmask16 changed = 0;
    for (std::uint32_t b = first;; ++b) {
      const TriBlock<float>& block = tree.blocks[b];
      for (std::uint32_t t = 0; t < block.count; ++t) {
        const __m512 az = sub(_mm512_set1_ps(block.p[0][kz][t]), voz);
        const __m512 bz = sub(_mm512_set1_ps(block.p[1][kz][t]), voz);
        const __m512 cz = sub(_mm512_set1_ps(block.p[2][kz][t]), voz);
        const __m512 Ax = sub(sub(_mm512_set1_ps(block.p[0][kx][t]), vox), mul(vsx, az));
        const __m512 Ay = sub(sub(_mm512_set1_ps(block.p[0][ky][t]), voy), mul(vsy, az));
        const __m512 Bx = sub(sub(_mm512_set1_ps(block.p[1][kx][t]), vox), mul(vsx, bz));
        const __m512 By = sub(sub(_mm512_set1_ps(block.p[1][ky][t]), voy), mul(vsy, bz));
        const __m512 Cx = sub(sub(_mm512_set1_ps(block.p[2][kx][t]), vox), mul(vsx, cz));
        const __m512 Cy = sub(sub(_mm512_set1_ps(block.p[2][ky][t]), voy), mul(vsy, cz));
        const __m512 U = sub(mul(Cx, By), mul(Cy, Bx));
        const __m512 V = sub(mul(Ax, Cy), mul(Ay, Cx));
        const __m512 W = sub(mul(Bx, Ay), mul(By, Ax));
        const __mmask16 neg = _mm512_mask_cmp_ps_mask(in, U, zero, _CMP_LT_OQ) |
                              _mm512_mask_cmp_ps_mask(in, V, zero, _CMP_LT_OQ) |
                              _mm512_mask_cmp_ps_mask(in, W, zero, _CMP_LT_OQ);
        const __mmask16 pos = _mm512_mask_cmp_ps_mask(in, U, zero, _CMP_GT_OQ) |
                              _mm512_mask_cmp_ps_mask(in, V, zero, _CMP_GT_OQ) |
                              _mm512_mask_cmp_ps_mask(in, W, zero, _CMP_GT_OQ);
        const __mmask16 any_zero = _mm512_mask_cmp_ps_mask(in, U, zero, _CMP_EQ_OQ) |
                                   _mm512_mask_cmp_ps_mask(in, V, zero, _CMP_EQ_OQ) |
                                   _mm512_mask_cmp_ps_mask(in, W, zero, _CMP_EQ_OQ);
        // Candidates: rays whose edge functions are not of mixed sign, or one of which is zero.
        const __mmask16 candidates = static_cast<__mmask16>(in & ~(neg & pos & ~any_zero));
        if (candidates == 0) continue;
        // Lanes with a zero edge function need the exact recomputation: scalar, as single rays.
        if (__mmask16 exact = candidates & any_zero; exact != 0) {
          alignas(64) float e[12][16];
          const __m512 parts[12] = {Ax, Ay, Bx, By, Cx, Cy, az, bz, cz, U, V, W};
          for (int k = 0; k < 12; ++k) _mm512_store_ps(e[k], parts[k]);
          for (std::uint32_t m = exact; m != 0; m &= m - 1) {
            const int r = std::countr_zero(m);
            const Edges<float> edges{e[0][r], e[1][r], e[2][r], e[3][r], e[4][r],  e[5][r],
                                     e[6][r], e[7][r], e[8][r], e[9][r], e[10][r], e[11][r]};
            watertight_finish_nofma(edges, p.sz[r], block.index[t], hits[r]);
            if (hits[r].triangle == block.index[t]) { // hit (each triangle is tested once per ray)
              best = _mm512_mask_blend_ps(static_cast<__mmask16>(1U << r), best, _mm512_set1_ps(hits[r].t));
              changed |= static_cast<__mmask16>(1U << r);
            }
          }
        }
        // The rest of watertight_finish for the others (no zero edge function, so not of mixed
        // sign either), 16 at once: the same operations in the same order.
        const __mmask16 plain = static_cast<__mmask16>(candidates & ~any_zero);
        if (plain == 0) continue;
        const __m512 det = add(add(U, V), W);
        const __m512 ts = add(add(mul(U, mul(vsz, az)), mul(V, mul(vsz, bz))), mul(W, mul(vsz, cz)));
        const __mmask16 ahead =
            (_mm512_mask_cmp_ps_mask(plain, det, zero, _CMP_GT_OQ) & _mm512_cmp_ps_mask(ts, zero, _CMP_GT_OQ)) |
            (_mm512_mask_cmp_ps_mask(plain, det, zero, _CMP_LT_OQ) & _mm512_cmp_ps_mask(ts, zero, _CMP_LT_OQ));
        if (ahead == 0) continue;
        const __m512 rcp = _mm512_maskz_div_round_ps(ahead, one, det, kRound);
        const __m512 tv = _mm512_maskz_mul_round_ps(ahead, ts, rcp, kRound);
        const __mmask16 closer = _mm512_mask_cmp_ps_mask(ahead, tv, best, _CMP_LT_OQ);
        __mmask16 tie = _mm512_mask_cmp_ps_mask(ahead, tv, best, _CMP_EQ_OQ);
        for (std::uint32_t m = tie; m != 0; m &= m - 1) {
          const int r = std::countr_zero(m);
          if (!(hits[r].valid() && block.index[t] < hits[r].triangle)) tie &= static_cast<__mmask16>(~(1U << r));
        }
        const __mmask16 take = closer | tie;
        if (take == 0) continue;
        alignas(64) float tt[16], b1[16], b2[16];
        _mm512_store_ps(tt, tv);
        _mm512_store_ps(b1, _mm512_maskz_mul_round_ps(take, V, rcp, kRound));
        _mm512_store_ps(b2, _mm512_maskz_mul_round_ps(take, W, rcp, kRound));
        for (std::uint32_t m = take; m != 0; m &= m - 1) {
          const int r = std::countr_zero(m);
          hits[r] = Hit<float>{tt[r], b1[r], b2[r], block.index[t]};
        }
        best = _mm512_mask_blend_ps(take, best, tv);
        changed |= take;
      }
      if (block.last) break;
    }
    if (changed == 0) return;
    _mm512_store_ps(p.best, best);
    _mm512_mask_store_ps(p.cull, changed, mul(best, _mm512_set1_ps(kCullWiden<float>)));
  }
};

/// The packet walk with the AVX-512 kernels (and the SSE leaf kernels for rays that go one by
/// one). Precondition: the CPU has the `avx512` level (core/simd.hpp).
MPR_TARGET_AVX512 inline void packet_walk_avx512(const BvhTree<float>& tree, RayPacket<float>& p,
                                                 Hit<float>* hits) noexcept {
  packet_walk<Avx512PacketKernels, SseKernels>(tree, p, hits);
}

#endif

MPR_EXACT_FP_END

} // namespace mpr::scene::detail
