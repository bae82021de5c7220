#pragma once
/// \file
/// The lane kernels of `DepthProxy`'s batch path (lightfield/depth_proxy.hpp,
/// (depth_proxy/depth_proxy_lanes.hpp)), written once with Highway and compiled for SSE4, AVX2 and
/// AVX-512 (`depth_lanes_target` picks one for a `SimdLevel`). Sixteen rays go through together,
/// one per lane (kernels/depth_lane_data.hpp); each target takes them in vectors of its width
/// (4, 8 or 16 floats), each vector to the end of the step before the next, since the lanes never
/// mix. The steps: the distance from every camera centre to each ray line (`scan_cameras`), the
/// walk of a depth map (`walk_lanes`, kernels/depth_walk_hwy.inl), the blend's choice of
/// the k + 1 cameras that see each point with the smallest angles (`choose_cameras`), and the
/// weighing of 8-bit frames (`weigh_lanes`, kernels/depth_weigh_hwy.inl).
///
/// Each step computes what the per-ray code computes, in the same order of operations and with no
/// fused multiply-add (every product goes through `mul`, which the compiler cannot fuse), so the
/// lanes answer bit for bit as `DepthProxy::sample(ray)` does where the per-ray code is not
/// contracted either (builds without -march or -mfma; with them the compiler fuses some of the
/// per-ray code's products, and a decision at a threshold may go the other way).
///
/// Header-only use: Highway's ops exist once per target in a translation unit (its
/// foreach_target.h runs once, here through kernels/lerp_row_hwy.hpp, for every attainable
/// target), so the kernels' body (kernels/depth_*_hwy.inl) is included below once per
/// target, in a namespace of its own (`depth_sse4`, `depth_avx2`, `depth_avx512`) under that
/// target's attributes, with `hn` naming that target's ops. The target is mpr's choice
/// (core/simd.hpp), not `HWY_DYNAMIC_DISPATCH`. x86 only (other CPUs answer per ray); only when
/// Highway's headers are there (`MPR_HAVE_HWY`, core/config.hpp).

#include <mpr/core/config.hpp>
#if MPR_HAVE_HWY && defined(MPR_SIMD_X86)
#include <mpr/core/simd.hpp>
#include <mpr/lightfield/depth_proxy/depth_walk.hpp>
#include <mpr/lightfield/kernels/depth_lane_data.hpp>
#include <mpr/lightfield/kernels/lerp_row_hwy.hpp> // Highway's ops for every attainable target
#include <mpr/lightfield/kernels/unit_acos.hpp>

#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

// The kernels' body, once per target (AVX-512 with VBMI runs the AVX-512 one).
#if HWY_TARGETS & HWY_SSE4
HWY_PUSH_ATTRIBUTES(HWY_TARGET_STR_SSE4)
namespace mpr::kernels::depth_sse4 {
namespace hn = hwy::N_SSE4;
#include <mpr/lightfield/kernels/depth_lane_ops_hwy.inl>
#include <mpr/lightfield/kernels/depth_walk_hwy.inl>
#include <mpr/lightfield/kernels/depth_weigh_hwy.inl>
} // namespace mpr::kernels::depth_sse4
HWY_POP_ATTRIBUTES
#endif

#if HWY_TARGETS & HWY_AVX2
HWY_PUSH_ATTRIBUTES(HWY_TARGET_STR_AVX2)
namespace mpr::kernels::depth_avx2 {
namespace hn = hwy::N_AVX2;
#include <mpr/lightfield/kernels/depth_lane_ops_hwy.inl>
#include <mpr/lightfield/kernels/depth_walk_hwy.inl>
#include <mpr/lightfield/kernels/depth_weigh_hwy.inl>
} // namespace mpr::kernels::depth_avx2
HWY_POP_ATTRIBUTES
#endif

#if HWY_TARGETS & HWY_AVX3
HWY_PUSH_ATTRIBUTES(HWY_TARGET_STR_AVX3)
namespace mpr::kernels::depth_avx512 {
namespace hn = hwy::N_AVX3;
#include <mpr/lightfield/kernels/depth_lane_ops_hwy.inl>
#include <mpr/lightfield/kernels/depth_walk_hwy.inl>
#include <mpr/lightfield/kernels/depth_weigh_hwy.inl>
} // namespace mpr::kernels::depth_avx512
HWY_POP_ATTRIBUTES
#endif

namespace mpr::kernels {

/// The Highway target the depth lanes run at for `level` (0: none, the per-ray path):
/// `avx512` and above the AVX-512 one, `avx2` the AVX2 one, `portable` SSE4 when the CPU has
/// SSE4.2 (x86-64's baseline SSE2 has no lane path). Precondition: the CPU runs `level`.
[[nodiscard]] inline std::int64_t depth_lanes_target(detail::SimdLevel level) noexcept {
  if (level >= detail::SimdLevel::avx512 && (HWY_TARGETS & HWY_AVX3) != 0) return HWY_AVX3;
  if (level >= detail::SimdLevel::avx2 && (HWY_TARGETS & HWY_AVX2) != 0) return HWY_AVX2;
  if ((HWY_TARGETS & HWY_SSE4) != 0 && __builtin_cpu_supports("sse4.2")) return HWY_SSE4;
  return 0;
}

/// `scan_cameras` (above) at `target`.
inline void scan_cameras(std::int64_t target, const detail::LaneCamera* cameras, std::size_t count,
                         const detail::RayLanes& lanes, float radius2, unsigned valid, std::uint16_t* near,
                         float (*distance)[16], int* first) noexcept {
#if HWY_TARGETS & HWY_AVX3
  if (target == HWY_AVX3)
    return depth_avx512::scan_cameras(cameras, count, lanes, radius2, valid, near, distance, first);
#endif
#if HWY_TARGETS & HWY_AVX2
  if (target == HWY_AVX2) return depth_avx2::scan_cameras(cameras, count, lanes, radius2, valid, near, distance, first);
#endif
#if HWY_TARGETS & HWY_SSE4
  return depth_sse4::scan_cameras(cameras, count, lanes, radius2, valid, near, distance, first);
#endif
}

/// `choose_cameras` (above) at `target`, the cameras of some lane of `blended` taken nearest to
/// the first blended lane's ray first: so the lanes fill their slots with the best cameras
/// early, and a camera that cannot enter a lane's full slots skips the insertion.
inline void choose_cameras(std::int64_t target, const detail::LaneCamera* cameras, std::size_t count,
                           const detail::RayLanes& lanes, const float (*point)[16], const float (*distance)[16],
                           const std::uint16_t* near, unsigned blended, int slots, float tolerance,
                           detail::LaneChoice& out) noexcept {
  int order[64];
  int n = 0;
  const int reference = blended != 0 ? __builtin_ctz(blended) : 0;
  for (std::size_t i = 0; i < count && n < 64; ++i) {
    if ((near[i] & blended) == 0) continue;
    int at = n++;
    for (; at > 0 && distance[i][reference] < distance[order[at - 1]][reference]; --at) order[at] = order[at - 1];
    order[at] = static_cast<int>(i);
  }
#if HWY_TARGETS & HWY_AVX3
  if (target == HWY_AVX3)
    return depth_avx512::choose_cameras(cameras, lanes, point, distance, near, blended, order, n, slots, tolerance,
                                        out);
#endif
#if HWY_TARGETS & HWY_AVX2
  if (target == HWY_AVX2)
    return depth_avx2::choose_cameras(cameras, lanes, point, distance, near, blended, order, n, slots, tolerance, out);
#endif
#if HWY_TARGETS & HWY_SSE4
  return depth_sse4::choose_cameras(cameras, lanes, point, distance, near, blended, order, n, slots, tolerance, out);
#endif
}

/// `walk_lanes` (kernels/depth_walk_hwy.inl) at `target`.
inline void walk_lanes(std::int64_t target, const detail::LaneCamera& camera, const detail::RayLanes& lanes,
                       unsigned walk, const detail::WalkLanesResult& from, float tolerance,
                       detail::WalkLanesResult& out) noexcept {
#if HWY_TARGETS & HWY_AVX3
  if (target == HWY_AVX3) return depth_avx512::walk_lanes(camera, lanes, walk, from, tolerance, out);
#endif
#if HWY_TARGETS & HWY_AVX2
  if (target == HWY_AVX2) return depth_avx2::walk_lanes(camera, lanes, walk, from, tolerance, out);
#endif
#if HWY_TARGETS & HWY_SSE4
  return depth_sse4::walk_lanes(camera, lanes, walk, from, tolerance, out);
#endif
}

/// `weigh_lanes` (kernels/depth_weigh_hwy.inl) at `target`.
inline void weigh_lanes(std::int64_t target, const detail::WeighCamera* cameras, const detail::LaneChoice& choice,
                        int slots, int k, unsigned lanes, const std::uint16_t* lut, float scale, float (*acc)[16],
                        float* weight) noexcept {
#if HWY_TARGETS & HWY_AVX3
  if (target == HWY_AVX3) return depth_avx512::weigh_lanes(cameras, choice, slots, k, lanes, lut, scale, acc, weight);
#endif
#if HWY_TARGETS & HWY_AVX2
  if (target == HWY_AVX2) return depth_avx2::weigh_lanes(cameras, choice, slots, k, lanes, lut, scale, acc, weight);
#endif
#if HWY_TARGETS & HWY_SSE4
  return depth_sse4::weigh_lanes(cameras, choice, slots, k, lanes, lut, scale, acc, weight);
#endif
}

} // namespace mpr::kernels
#endif // MPR_HAVE_HWY && MPR_SIMD_X86
