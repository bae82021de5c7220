#pragma once
/// \file
/// The AVX2 kernels of the packet walk (bvh/packet.hpp). `Avx2PacketKernels` tests a child box against eight rays per
/// AVX2 instruction and the beam against four boxes per SSE instruction, with the operations of
/// `PortablePacketKernels<float>` in the same order, so the same masks. The walk is compiled for
/// AVX2 *without* FMA (`MPR_TARGET_AVX2_NOFMA`): the compiler can then fuse no multiply-add of
/// the box or triangle tests, and the hits stay those of the single-ray walk bit for bit.
/// kernels/packet_closest_hits.hpp picks them at run time.

#include <mpr/core/config.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/scene/bvh/kernels/walk_kernels.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/packet.hpp>
#include <mpr/scene/bvh/slab.hpp>

#include <algorithm>
#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <utility>

#if MPR_BVH_PACKET_AVX2
#include <immintrin.h>
#endif

namespace mpr::scene::detail {

MPR_EXACT_FP_BEGIN

#if MPR_BVH_PACKET_AVX2

/// `PortablePacketKernels<float>` with SSE (beam, four boxes) and AVX2 (rays, eight per
/// instruction). Only for code compiled with `MPR_TARGET_AVX2_NOFMA`. `_mm*_max_ps(b, a)` is
/// `std::max(a, b)` exactly, hence the swapped operands (no NaN arises here anyway: the packet's
/// constants are finite).
struct Avx2PacketKernels {
  /// `RayPacket<float>::make` for `rays` (at most `kPacketRays`) with no hit yet (t_max), eight
  /// rays per instruction: the same values in every field the AVX2 walk reads, bit for bit,
  /// but false also when the rays' axis permutations differ (the result is `same_axes`; the
  /// per-ray `shear` records are not filled).
  [[nodiscard]] MPR_TARGET_AVX2_NOFMA static bool make(std::span<const Ray<float>> rays, float t_max,
                                                       RayPacket<float>& p) noexcept {
    const int n = static_cast<int>(rays.size());
    p.active = 0;
    p.same_axes = true;
    for (int r = 0; r < kPacketRays; ++r) p.cull[r] = -std::numeric_limits<float>::infinity();
    if (n == 0) return true;
    // The rays' components, eight rays per vector (lanes past the last ray repeat it), built in
    // registers: storing scalars and loading them as a vector would stall on store forwarding.
    __m256 dg[2][3], og[2][3];
    for (int g = 0; g < kPacketRays / 8; ++g) {
      const Ray<float>* q[8];
      for (int k = 0; k < 8; ++k) q[k] = &rays[static_cast<std::size_t>(std::min(8 * g + k, n - 1))];
      for (int a = 0; a < 3; ++a) {
        dg[g][a] = _mm256_setr_ps(q[0]->direction[a], q[1]->direction[a], q[2]->direction[a], q[3]->direction[a],
                                  q[4]->direction[a], q[5]->direction[a], q[6]->direction[a], q[7]->direction[a]);
        og[g][a] = _mm256_setr_ps(q[0]->origin[a], q[1]->origin[a], q[2]->origin[a], q[3]->origin[a], q[4]->origin[a],
                                  q[5]->origin[a], q[6]->origin[a], q[7]->origin[a]);
      }
    }
    const __m256 sign = _mm256_set1_ps(-0.0f), zero = _mm256_setzero_ps();
    const __m256 tiny = _mm256_set1_ps(1e-30f), inf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
    __m256 ok[2];
    std::uint32_t valid = 0, axis0 = 0, axis1 = 0, bad = 0, negative[3] = {0, 0, 0};
    for (int g = 0; g < kPacketRays / 8; ++g) {
      const int in_group = n - 8 * g;
      const std::uint32_t lanes = in_group >= 8 ? 0xFFU : in_group > 0 ? (1U << in_group) - 1U : 0U;
      __m256 dv[3], ad[3];
      for (int a = 0; a < 3; ++a) {
        dv[a] = dg[g][a];
        ad[a] = _mm256_andnot_ps(sign, dv[a]);
      }
      // Shear::make's largest axis: x if |x| > |y| and |x| > |z|, y if not and |y| > |z|, else z.
      const __m256 xy = _mm256_cmp_ps(ad[0], ad[1], _CMP_GT_OQ), xz = _mm256_cmp_ps(ad[0], ad[2], _CMP_GT_OQ);
      const __m256 yz = _mm256_cmp_ps(ad[1], ad[2], _CMP_GT_OQ);
      const __m256 is0 = _mm256_and_ps(xy, xz), is1 = _mm256_andnot_ps(xy, yz);
      const __m256 largest = _mm256_blendv_ps(_mm256_blendv_ps(ad[2], ad[1], is1), ad[0], is0);
      ok[g] = _mm256_cmp_ps(largest, zero, _CMP_GT_OQ);
      const std::uint32_t vm = static_cast<std::uint32_t>(_mm256_movemask_ps(ok[g])) & lanes;
      ok[g] = _mm256_and_ps(ok[g], _mm256_castsi256_ps(_mm256_cmpeq_epi32(
                                       _mm256_and_si256(_mm256_set1_epi32(static_cast<int>(lanes)),
                                                        _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128)),
                                       _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128))));
      valid |= vm << (8 * g);
      axis0 |= (static_cast<std::uint32_t>(_mm256_movemask_ps(is0)) & vm) << (8 * g);
      axis1 |= (static_cast<std::uint32_t>(_mm256_movemask_ps(is1)) & vm) << (8 * g);
      // BoxRay::make: components below 1e-30 in magnitude become +-1e-30; t = p * inv + offset.
      for (int a = 0; a < 3; ++a) {
        const __m256 da = _mm256_blendv_ps(dv[a], _mm256_or_ps(_mm256_and_ps(dv[a], sign), tiny),
                                           _mm256_cmp_ps(ad[a], tiny, _CMP_LT_OQ));
        const __m256 inv = _mm256_div_ps(_mm256_set1_ps(1.0f), da);
        const __m256 off = _mm256_mul_ps(_mm256_xor_ps(og[g][a], sign), inv);
        _mm256_store_ps(p.inv[a] + 8 * g, inv);
        _mm256_store_ps(p.offset[a] + 8 * g, off);
        negative[a] |= (static_cast<std::uint32_t>(_mm256_movemask_ps(inv)) & vm) << (8 * g);
        const __m256 finite = _mm256_and_ps(_mm256_cmp_ps(_mm256_andnot_ps(sign, inv), inf, _CMP_LT_OQ),
                                            _mm256_cmp_ps(_mm256_andnot_ps(sign, off), inf, _CMP_LT_OQ));
        bad |= (~static_cast<std::uint32_t>(_mm256_movemask_ps(finite)) & vm) << (8 * g);
      }
    }
    if (valid == 0) return true;
    if (bad != 0) return false;
    for (int a = 0; a < 3; ++a)
      if (negative[a] != 0 && negative[a] != valid) return false;
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
    const __m256 lo_fill = inf, hi_fill = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
    __m256 ilo[3], ihi[3], olo[3], ohi[3];
    for (int g = 0; g < kPacketRays / 8; ++g) {
      const __m256 dz = dg[g][p.kz];
      _mm256_store_ps(p.sx + 8 * g, _mm256_div_ps(dg[g][p.kx], dz));
      _mm256_store_ps(p.sy + 8 * g, _mm256_div_ps(dg[g][p.ky], dz));
      _mm256_store_ps(p.sz + 8 * g, _mm256_div_ps(_mm256_set1_ps(1.0f), dz));
      _mm256_store_ps(p.ox + 8 * g, og[g][p.kx]);
      _mm256_store_ps(p.oy + 8 * g, og[g][p.ky]);
      _mm256_store_ps(p.oz + 8 * g, og[g][p.kz]);
      for (int a = 0; a < 3; ++a) {
        const __m256 inv = _mm256_load_ps(p.inv[a] + 8 * g), off = _mm256_load_ps(p.offset[a] + 8 * g);
        const __m256 il = _mm256_blendv_ps(lo_fill, inv, ok[g]), ih = _mm256_blendv_ps(hi_fill, inv, ok[g]);
        const __m256 ol = _mm256_blendv_ps(lo_fill, off, ok[g]), oh = _mm256_blendv_ps(hi_fill, off, ok[g]);
        ilo[a] = g == 0 ? il : _mm256_min_ps(ilo[a], il);
        ihi[a] = g == 0 ? ih : _mm256_max_ps(ihi[a], ih);
        olo[a] = g == 0 ? ol : _mm256_min_ps(olo[a], ol);
        ohi[a] = g == 0 ? oh : _mm256_max_ps(ohi[a], oh);
      }
    }
    for (int a = 0; a < 3; ++a) {
      p.inv_lo[a] = least(ilo[a]);
      p.inv_hi[a] = greatest(ihi[a]);
      p.off_lo[a] = least(olo[a]);
      p.off_hi[a] = greatest(ohi[a]);
    }
    const float cull = cull_bound(t_max);
    for (std::uint32_t m = valid; m != 0; m &= m - 1) {
      p.cull[std::countr_zero(m)] = cull;
      p.best[std::countr_zero(m)] = t_max;
    }
    p.active = valid;
    return true;
  }

  /// `rays` gives the entry parameters of the rays that enter (+inf in the other lanes); the
  /// walk reduces them with `least_value` only when it orders several children.
  using Least = __m256;
  [[nodiscard]] MPR_TARGET_AVX2_NOFMA static float least_value(const __m256& v) noexcept { return least(v); }

  /// The least and the greatest of the eight lanes.
  [[nodiscard]] MPR_TARGET_AVX2_NOFMA static float least(__m256 v) noexcept {
    __m128 h = _mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
    h = _mm_min_ps(h, _mm_movehl_ps(h, h));
    return _mm_cvtss_f32(_mm_min_ss(h, _mm_shuffle_ps(h, h, 1)));
  }
  [[nodiscard]] MPR_TARGET_AVX2_NOFMA static float greatest(__m256 v) noexcept {
    __m128 h = _mm_max_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
    h = _mm_max_ps(h, _mm_movehl_ps(h, h));
    return _mm_cvtss_f32(_mm_max_ss(h, _mm_shuffle_ps(h, h, 1)));
  }

  [[nodiscard]] MPR_TARGET_AVX2_NOFMA static std::uint32_t beyond(const RayPacket<float>& p, float t) noexcept {
    const __m256 tv = _mm256_set1_ps(t);
    std::uint32_t mask = 0;
    for (int g = 0; g < kPacketRays / 8; ++g)
      mask |=
          static_cast<std::uint32_t>(_mm256_movemask_ps(_mm256_cmp_ps(tv, _mm256_load_ps(p.cull + 8 * g), _CMP_LT_OQ)))
          << (8 * g);
    return mask;
  }

  [[nodiscard]] MPR_TARGET_AVX2_NOFMA static unsigned beam4(const WideNode<float>& node, const RayPacket<float>& p,
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

  [[nodiscard]] MPR_TARGET_AVX2_NOFMA static std::uint32_t
  rays(const WideNode<float>& node, int lane, const RayPacket<float>& p, std::uint32_t active, __m256& entry) noexcept {
    __m256 bn[3], bf[3];
    for (int a = 0; a < 3; ++a) {
      bn[a] = _mm256_set1_ps(node.bounds[p.near[a]][lane]);
      bf[a] = _mm256_set1_ps(node.bounds[p.far[a]][lane]);
    }
    const __m256 widen = _mm256_set1_ps(kBoxWiden<float>);
    const __m256 inf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
    const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    entry = inf;
    std::uint32_t mask = 0;
    for (int g = 0; g < kPacketRays / 8; ++g) {
      const std::uint32_t in = (active >> (8 * g)) & 0xFFU;
      if (in == 0) continue;
      __m256 n[3], f[3];
      for (int a = 0; a < 3; ++a) {
        const __m256 inv = _mm256_load_ps(p.inv[a] + 8 * g), off = _mm256_load_ps(p.offset[a] + 8 * g);
        n[a] = _mm256_add_ps(_mm256_mul_ps(bn[a], inv), off);
        f[a] = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(bf[a], inv), off), widen);
      }
      const __m256 cull = _mm256_load_ps(p.cull + 8 * g);
      const __m256 tn = _mm256_max_ps(_mm256_max_ps(_mm256_setzero_ps(), n[2]), _mm256_max_ps(n[1], n[0]));
      const __m256 tf = _mm256_min_ps(_mm256_min_ps(cull, f[2]), _mm256_min_ps(f[1], f[0]));
      const __m256 sel =
          _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(static_cast<int>(in)), bit), bit));
      const __m256 enter =
          _mm256_and_ps(sel, _mm256_and_ps(_mm256_cmp_ps(tn, tf, _CMP_LE_OQ), _mm256_cmp_ps(tn, cull, _CMP_LT_OQ)));
      const std::uint32_t m = static_cast<std::uint32_t>(_mm256_movemask_ps(enter));
      if (m == 0) continue;
      mask |= m << (8 * g);
      entry = _mm256_min_ps(entry, _mm256_blendv_ps(inf, tn, enter));
    }
    return mask;
  }

  /// Leaf `first` for the rays of `rays`: each triangle's edge functions for eight rays per
  /// instruction, with the operations of `edges4_sse` in the same order (so the same values),
  /// then the rest of `watertight_finish` eight rays at once with its operations (scalar, per
  /// ray, where an edge function is zero and needs the exact recomputation). The hit test is
  /// `watertight_finish`'s: t > 0 and (t < best, or t == best and a lower triangle index). Rays
  /// with different axis permutations (`!p.same_axes`) go one by one.
  MPR_TARGET_AVX2_NOFMA static void leaf(const BvhTree<float>& tree, std::uint32_t first, RayPacket<float>& p,
                                         std::uint32_t rays, Hit<float>* hits) noexcept {
    if (!p.same_axes) {
      packet_leaf_per_ray<SseKernels>(tree, first, p, rays, hits);
      return;
    }
    const int kx = p.kx, ky = p.ky, kz = p.kz;
    const __m256 zero = _mm256_setzero_ps();
    for (std::uint32_t b = first;; ++b) {
      const TriBlock<float>& block = tree.blocks[b];
      for (std::uint32_t t = 0; t < block.count; ++t) {
        __m256 v[3][3];
        for (int k = 0; k < 3; ++k) {
          v[k][0] = _mm256_set1_ps(block.p[k][kx][t]);
          v[k][1] = _mm256_set1_ps(block.p[k][ky][t]);
          v[k][2] = _mm256_set1_ps(block.p[k][kz][t]);
        }
        for (int g = 0; g < kPacketRays / 8; ++g) {
          const std::uint32_t in = (rays >> (8 * g)) & 0xFFU;
          if (in == 0) continue;
          const __m256 vox = _mm256_load_ps(p.ox + 8 * g), voy = _mm256_load_ps(p.oy + 8 * g);
          const __m256 voz = _mm256_load_ps(p.oz + 8 * g);
          const __m256 vsx = _mm256_load_ps(p.sx + 8 * g), vsy = _mm256_load_ps(p.sy + 8 * g);
          const __m256 az = _mm256_sub_ps(v[0][2], voz);
          const __m256 bz = _mm256_sub_ps(v[1][2], voz);
          const __m256 cz = _mm256_sub_ps(v[2][2], voz);
          const __m256 Ax = _mm256_sub_ps(_mm256_sub_ps(v[0][0], vox), _mm256_mul_ps(vsx, az));
          const __m256 Ay = _mm256_sub_ps(_mm256_sub_ps(v[0][1], voy), _mm256_mul_ps(vsy, az));
          const __m256 Bx = _mm256_sub_ps(_mm256_sub_ps(v[1][0], vox), _mm256_mul_ps(vsx, bz));
          const __m256 By = _mm256_sub_ps(_mm256_sub_ps(v[1][1], voy), _mm256_mul_ps(vsy, bz));
          const __m256 Cx = _mm256_sub_ps(_mm256_sub_ps(v[2][0], vox), _mm256_mul_ps(vsx, cz));
          const __m256 Cy = _mm256_sub_ps(_mm256_sub_ps(v[2][1], voy), _mm256_mul_ps(vsy, cz));
          const __m256 U = _mm256_sub_ps(_mm256_mul_ps(Cx, By), _mm256_mul_ps(Cy, Bx));
          const __m256 V = _mm256_sub_ps(_mm256_mul_ps(Ax, Cy), _mm256_mul_ps(Ay, Cx));
          const __m256 W = _mm256_sub_ps(_mm256_mul_ps(Bx, Ay), _mm256_mul_ps(By, Ax));
          const __m256 neg =
              _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(U, zero, _CMP_LT_OQ), _mm256_cmp_ps(V, zero, _CMP_LT_OQ)),
                           _mm256_cmp_ps(W, zero, _CMP_LT_OQ));
          const __m256 pos =
              _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(U, zero, _CMP_GT_OQ), _mm256_cmp_ps(V, zero, _CMP_GT_OQ)),
                           _mm256_cmp_ps(W, zero, _CMP_GT_OQ));
          const __m256 any_zero =
              _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(U, zero, _CMP_EQ_OQ), _mm256_cmp_ps(V, zero, _CMP_EQ_OQ)),
                           _mm256_cmp_ps(W, zero, _CMP_EQ_OQ));
          const std::uint32_t rejected =
              static_cast<std::uint32_t>(_mm256_movemask_ps(_mm256_andnot_ps(any_zero, _mm256_and_ps(neg, pos))));
          const std::uint32_t candidates = in & ~rejected;
          if (candidates == 0) continue;
          // Lanes with a zero edge function need the exact recomputation: scalar, as single rays.
          std::uint32_t exact = candidates & static_cast<std::uint32_t>(_mm256_movemask_ps(any_zero));
          if (exact != 0) {
            alignas(32) float e[12][8];
            _mm256_store_ps(e[0], Ax);
            _mm256_store_ps(e[1], Ay);
            _mm256_store_ps(e[2], Bx);
            _mm256_store_ps(e[3], By);
            _mm256_store_ps(e[4], Cx);
            _mm256_store_ps(e[5], Cy);
            _mm256_store_ps(e[6], az);
            _mm256_store_ps(e[7], bz);
            _mm256_store_ps(e[8], cz);
            _mm256_store_ps(e[9], U);
            _mm256_store_ps(e[10], V);
            _mm256_store_ps(e[11], W);
            for (; exact != 0; exact &= exact - 1) {
              const int k = std::countr_zero(exact), r = 8 * g + k;
              const Edges<float> edges{e[0][k], e[1][k], e[2][k], e[3][k], e[4][k],  e[5][k],
                                       e[6][k], e[7][k], e[8][k], e[9][k], e[10][k], e[11][k]};
              watertight_finish(edges, p.sz[r], block.index[t], hits[r]);
              p.best[r] = hits[r].t;
              p.cull[r] = cull_bound(hits[r].t);
            }
          }
          const std::uint32_t plain = candidates & ~static_cast<std::uint32_t>(_mm256_movemask_ps(any_zero));
          if (plain == 0) continue;
          // The rest of watertight_finish for the others (no zero edge function, so not of mixed
          // sign either), eight at once: the same operations in the same order.
          const __m256 szv = _mm256_load_ps(p.sz + 8 * g);
          const __m256 det = _mm256_add_ps(_mm256_add_ps(U, V), W);
          const __m256 ts = _mm256_add_ps(
              _mm256_add_ps(_mm256_mul_ps(U, _mm256_mul_ps(szv, az)), _mm256_mul_ps(V, _mm256_mul_ps(szv, bz))),
              _mm256_mul_ps(W, _mm256_mul_ps(szv, cz)));
          const __m256 ahead =
              _mm256_or_ps(_mm256_and_ps(_mm256_cmp_ps(det, zero, _CMP_GT_OQ), _mm256_cmp_ps(ts, zero, _CMP_GT_OQ)),
                           _mm256_and_ps(_mm256_cmp_ps(det, zero, _CMP_LT_OQ), _mm256_cmp_ps(ts, zero, _CMP_LT_OQ)));
          const __m256 rcp = _mm256_div_ps(_mm256_set1_ps(1.0f), det);
          const __m256 tv = _mm256_mul_ps(ts, rcp);
          const __m256 best = _mm256_load_ps(p.best + 8 * g);
          const std::uint32_t closer =
              plain &
              static_cast<std::uint32_t>(_mm256_movemask_ps(_mm256_and_ps(ahead, _mm256_cmp_ps(tv, best, _CMP_LT_OQ))));
          const std::uint32_t tie =
              plain &
              static_cast<std::uint32_t>(_mm256_movemask_ps(_mm256_and_ps(ahead, _mm256_cmp_ps(tv, best, _CMP_EQ_OQ))));
          if ((closer | tie) == 0) continue;
          alignas(32) float tt[8], b1[8], b2[8];
          _mm256_store_ps(tt, tv);
          _mm256_store_ps(b1, _mm256_mul_ps(V, rcp));
          _mm256_store_ps(b2, _mm256_mul_ps(W, rcp));
          for (std::uint32_t m = closer | tie; m != 0; m &= m - 1) {
            const int k = std::countr_zero(m), r = 8 * g + k;
            Hit<float>& h = hits[r];
            if ((tie >> k & 1U) && !(h.valid() && block.index[t] < h.triangle)) continue;
            h.t = tt[k];
            h.b1 = b1[k];
            h.b2 = b2[k];
            h.triangle = block.index[t];
            p.best[r] = h.t;
            p.cull[r] = cull_bound(h.t);
          }
        }
      }
      if (block.last) return;
    }
  }
};

/// The packet walk with the AVX2 kernels (and the SSE leaf kernels), compiled for AVX2 without
/// FMA. Precondition: the CPU has AVX2.
MPR_TARGET_AVX2_NOFMA inline void packet_walk_avx2(const BvhTree<float>& tree, RayPacket<float>& p,
                                                   Hit<float>* hits) noexcept {
  packet_walk<Avx2PacketKernels, SseKernels>(tree, p, hits);
}

#endif

MPR_EXACT_FP_END

} // namespace mpr::scene::detail
