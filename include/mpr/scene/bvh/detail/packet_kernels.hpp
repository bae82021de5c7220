#pragma once
/// \file
/// The x86 kernels of the packet walk (bvh/packet.hpp) and `packet_closest_hits`, the entry
/// point that picks them. `Avx2PacketKernels` tests a child box against eight rays per AVX2
/// instruction and the beam against four boxes per SSE instruction, with the operations of
/// `PortablePacketKernels<float>` in the same order, so the same masks. The walk is compiled for
/// AVX2 *without* FMA (`MPR_TARGET_AVX2_NOFMA`): the compiler can then fuse no multiply-add of
/// the box or triangle tests, and the hits stay those of the single-ray walk bit for bit. Chosen
/// at run time when the CPU has AVX2 (and `MPR_SIMD` allows it, core/simd.hpp); float only, the
/// portable kernels otherwise.

#include <mpr/core/config.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/scene/bvh/detail/kernels.hpp>
#include <mpr/scene/bvh/node.hpp>
#include <mpr/scene/bvh/packet.hpp>
#include <mpr/scene/bvh/slab.hpp>

#include <concepts>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>

#if MPR_BVH_PACKET_AVX2
#include <immintrin.h>
#endif

namespace mpr::scene::detail {

#if MPR_BVH_PACKET_AVX2

/// `PortablePacketKernels<float>` with SSE (beam, four boxes) and AVX2 (rays, eight per
/// instruction). Only for code compiled with `MPR_TARGET_AVX2_NOFMA`. `_mm*_max_ps(b, a)` is
/// `std::max(a, b)` exactly, hence the swapped operands (no NaN arises here anyway: the packet's
/// constants are finite).
struct Avx2PacketKernels {
  MPR_TARGET_AVX2_NOFMA [[nodiscard]] static unsigned beam4(const WideNode<float>& node, const RayPacket<float>& p,
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

  MPR_TARGET_AVX2_NOFMA [[nodiscard]] static std::uint32_t
  rays(const WideNode<float>& node, int lane, const RayPacket<float>& p, std::uint32_t active, float& t_min) noexcept {
    __m256 bn[3], bf[3];
    for (int a = 0; a < 3; ++a) {
      bn[a] = _mm256_set1_ps(node.bounds[p.near[a]][lane]);
      bf[a] = _mm256_set1_ps(node.bounds[p.far[a]][lane]);
    }
    const __m256 widen = _mm256_set1_ps(kBoxWiden<float>);
    const __m256 inf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
    const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    __m256 least = inf;
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
      least = _mm256_min_ps(least, _mm256_blendv_ps(inf, tn, enter));
    }
    __m128 h = _mm_min_ps(_mm256_castps256_ps128(least), _mm256_extractf128_ps(least, 1));
    h = _mm_min_ps(h, _mm_movehl_ps(h, h));
    h = _mm_min_ss(h, _mm_shuffle_ps(h, h, 1));
    t_min = _mm_cvtss_f32(h);
    return mask;
  }
};

/// The packet walk with the AVX2 kernels (and the SSE leaf kernels), compiled for AVX2 without
/// FMA. Precondition: the CPU has AVX2.
MPR_TARGET_AVX2_NOFMA inline void packet_walk_avx2(const BvhTree<float>& tree, RayPacket<float>& p,
                                                   Hit<float>* hits) noexcept {
  packet_walk<Avx2PacketKernels, SseKernels>(tree, p, hits);
}

#endif

/// `hits[r]` = the closest hit of `rays[r]` in (0, t_max) for each r (at most `kPacketRays`
/// rays, equal lengths): `packet_closest_hits_with` with the widest kernels this CPU runs. The
/// same hits as `closest_hit_walk<WalkKernels<T>>` per ray, bit for bit.
template <std::floating_point T>
void packet_closest_hits(const BvhTree<T>& tree, std::span<const Ray<T>> rays, std::span<Hit<T>> hits,
                         T t_max) noexcept {
#if MPR_BVH_PACKET_AVX2
  if constexpr (std::is_same_v<T, float>) {
    if (mpr::detail::simd_level() >= mpr::detail::SimdLevel::avx2) {
      for (Hit<T>& h : hits) h = Hit<T>{t_max};
      RayPacket<T> p;
      if (RayPacket<T>::make(rays, hits.data(), p)) {
        packet_walk_avx2(tree, p, hits.data());
      } else {
        for (std::size_t r = 0; r < rays.size(); ++r) hits[r] = closest_hit_walk<SseKernels>(tree, rays[r], t_max);
      }
      return;
    }
  }
#endif
  packet_closest_hits_with<PortablePacketKernels<T>, WalkKernels<T>>(tree, rays, hits, t_max);
}

} // namespace mpr::scene::detail
