#pragma once
/// \file
/// AVX-512 steps of `DepthProxy`'s batch path (lightfield/depth_proxy.hpp), sixteen rays to a
/// register (lanes = rays): the distance from a camera centre to each ray line, the depth-map
/// lookup of `depth_lookup` with gathers, the visibility test and angle of one camera for
/// sixteen surface points, and the k + 1 best cameras per lane kept sorted by an insertion
/// network. Each step computes what the per-ray code computes, in the same order of operations
/// and with no fused multiply-add, so the batch path answers bit for bit as `sample(ray)` does
/// where the per-ray code is not contracted either (builds without -march or -mfma; with them the
/// compiler fuses some of the per-ray code's products, and a decision at a threshold, e.g. the
/// nearest depth pixel at x = 117.49995, may go the other way).

#include <mpr/core/config.hpp>
#include <mpr/core/simd.hpp>
#include <mpr/lightfield/detail/unit_acos.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace mpr::detail {

#if defined(MPR_SIMD_X86)

/// The most cameras a lane keeps (k + 1 of `DepthProxy`); larger k takes the per-ray path.
inline constexpr int kDepthLaneSlots = 8;

/// a x b, lane by lane, never fused with an addition: the per-ray code rounds each product
/// (builds without -march have no FMA), and so must the lanes to give the same bits. GCC may
/// contract the plain vector product of the unmasked intrinsic into an FMA.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 mul16(__m512 a, __m512 b) noexcept {
  return _mm512_maskz_mul_ps(0xFFFF, a, b);
}

/// -a, lane by lane (the sign flipped, as the scalar negation does: -(+0) is -0).
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 neg16(__m512 a) noexcept {
  return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a), _mm512_set1_epi32(INT32_MIN)));
}

/// a + (b + c): the order in which Eigen sums the three terms of a fixed-size 3-vector's dot
/// product or squared norm (its unrolled reduction splits them into halves of one and two).
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 sum3(__m512 a, __m512 b, __m512 c) noexcept {
  return _mm512_add_ps(a, _mm512_add_ps(b, c));
}

/// (p[0] x + p[1] y) + p[2] z for each lane: one row of a projection matrix applied to sixteen
/// directions, added as the per-ray code adds it.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 linear_row16(const float* p, __m512 x, __m512 y, __m512 z) noexcept {
  return _mm512_add_ps(_mm512_add_ps(mul16(_mm512_set1_ps(p[0]), x), mul16(_mm512_set1_ps(p[1]), y)),
                       mul16(_mm512_set1_ps(p[2]), z));
}

/// `linear_row16` + p[3]: the row applied to sixteen points, added as `FrameTable::project_any`
/// and `depth_walk` add it.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 project_row16(const float* p, __m512 X, __m512 Y, __m512 Z) noexcept {
  return _mm512_add_ps(linear_row16(p, X, Y, Z), _mm512_set1_ps(p[3]));
}

/// Sixteen rays, one per lane: origins o, directions v, 1 / |v|^2 and |v|.
struct RayLanes {
  alignas(64) float ox[16], oy[16], oz[16], vx[16], vy[16], vz[16], inverse_length2[16], length[16];
};

/// `RayLanes` in registers.
struct RayLanes16 {
  __m512 ox, oy, oz, vx, vy, vz, inverse_length2, length;
};

MPR_TARGET_AVX512 MPR_ALWAYS_INLINE RayLanes16 load_lanes(const RayLanes& r) noexcept {
  return {_mm512_load_ps(r.ox),
          _mm512_load_ps(r.oy),
          _mm512_load_ps(r.oz),
          _mm512_load_ps(r.vx),
          _mm512_load_ps(r.vy),
          _mm512_load_ps(r.vz),
          _mm512_load_ps(r.inverse_length2),
          _mm512_load_ps(r.length)};
}

/// |(c - o) x v|^2 / |v|^2 for each lane: the squared distance from the point c to each ray
/// line (`line_distance2`).
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 line_distance2_x16(const RayLanes16& r, float cx, float cy,
                                                              float cz) noexcept {
  const __m512 ax = _mm512_sub_ps(_mm512_set1_ps(cx), r.ox);
  const __m512 ay = _mm512_sub_ps(_mm512_set1_ps(cy), r.oy);
  const __m512 az = _mm512_sub_ps(_mm512_set1_ps(cz), r.oz);
  const __m512 x = _mm512_sub_ps(mul16(ay, r.vz), mul16(az, r.vy));
  const __m512 y = _mm512_sub_ps(mul16(az, r.vx), mul16(ax, r.vz));
  const __m512 z = _mm512_sub_ps(mul16(ax, r.vy), mul16(ay, r.vx));
  const __m512 s = sum3(mul16(x, x), mul16(y, y), mul16(z, z));
  return mul16(s, r.inverse_length2);
}

/// `depth_lookup` of map d (`width` x `height`, fewer than 2^31 pixels) at (x, y) in the lanes
/// of `m` (others: 0); `smooth` = 1 + 4 x the tolerance. Lanes outside the image read the
/// clamped edge, as the scalar lookup does.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 depth_lookup_x16(const float* d, int width, int height, __m512 x, __m512 y,
                                                            float smooth, __mmask16 m) noexcept {
  const __m512 fx = _mm512_maskz_roundscale_ps(0xFFFF, x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
  const __m512 fy = _mm512_maskz_roundscale_ps(0xFFFF, y, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
  const __m512i x0 = _mm512_maskz_cvttps_epi32(0xFFFF, fx), y0 = _mm512_maskz_cvttps_epi32(0xFFFF, fy);
  const __m512i zero = _mm512_setzero_si512(), one = _mm512_set1_epi32(1);
  const __m512i xm = _mm512_set1_epi32(width - 1), ym = _mm512_set1_epi32(height - 1);
  const __m512i xa = _mm512_maskz_min_epi32(0xFFFF, _mm512_maskz_max_epi32(0xFFFF, x0, zero), xm);
  const __m512i xb =
      _mm512_maskz_min_epi32(0xFFFF, _mm512_maskz_max_epi32(0xFFFF, _mm512_add_epi32(x0, one), zero), xm);
  const __m512i w = _mm512_set1_epi32(width);
  const __m512i ra =
      _mm512_mullo_epi32(_mm512_maskz_min_epi32(0xFFFF, _mm512_maskz_max_epi32(0xFFFF, y0, zero), ym), w);
  const __m512i rb = _mm512_mullo_epi32(
      _mm512_maskz_min_epi32(0xFFFF, _mm512_maskz_max_epi32(0xFFFF, _mm512_add_epi32(y0, one), zero), ym), w);
  const __m512 none = _mm512_setzero_ps();
  const __m512 d00 = _mm512_mask_i32gather_ps(none, m, _mm512_add_epi32(ra, xa), d, 4);
  const __m512 d10 = _mm512_mask_i32gather_ps(none, m, _mm512_add_epi32(ra, xb), d, 4);
  const __m512 d01 = _mm512_mask_i32gather_ps(none, m, _mm512_add_epi32(rb, xa), d, 4);
  const __m512 d11 = _mm512_mask_i32gather_ps(none, m, _mm512_add_epi32(rb, xb), d, 4);
  const __m512 lo =
      _mm512_maskz_min_ps(0xFFFF, _mm512_maskz_min_ps(0xFFFF, d00, d10), _mm512_maskz_min_ps(0xFFFF, d01, d11));
  const __m512 hi =
      _mm512_maskz_max_ps(0xFFFF, _mm512_maskz_max_ps(0xFFFF, d00, d10), _mm512_maskz_max_ps(0xFFFF, d01, d11));
  const __m512 ax = _mm512_sub_ps(x, fx), ay = _mm512_sub_ps(y, fy);
  const __m512 one_f = _mm512_set1_ps(1), half = _mm512_set1_ps(0.5f);
  const __m512 bx = _mm512_sub_ps(one_f, ax), by = _mm512_sub_ps(one_f, ay);
  const __m512 top = _mm512_add_ps(mul16(d00, bx), mul16(d10, ax));
  const __m512 bottom = _mm512_add_ps(mul16(d01, bx), mul16(d11, ax));
  const __m512 bilinear = _mm512_add_ps(mul16(top, by), mul16(bottom, ay));
  const __mmask16 right = _mm512_cmp_ps_mask(ax, half, _CMP_NLT_UQ), lower = _mm512_cmp_ps_mask(ay, half, _CMP_NLT_UQ);
  const __m512 nearest =
      _mm512_mask_blend_ps(lower, _mm512_mask_blend_ps(right, d00, d10), _mm512_mask_blend_ps(right, d01, d11));
  const __mmask16 even = _mm512_cmp_ps_mask(hi, _mm512_set1_ps(__builtin_inff()), _CMP_LT_OQ) &
                         _mm512_cmp_ps_mask(hi, mul16(lo, _mm512_set1_ps(smooth)), _CMP_LE_OQ);
  return _mm512_mask_blend_ps(even, nearest, bilinear);
}

/// The cameras each lane keeps, best first, in the order in which `DepthProxy::blend` tries
/// them (see `slot_before`): cosine of the angle to the ray, clamped to 1 (-inf in an empty
/// slot), whether the cosine as computed exceeded 1 (`over`), the camera (-1: empty), its
/// distance from the ray line and its pixel (x, y).
struct LaneSlots16 {
  __m512 cosine[kDepthLaneSlots], distance[kDepthLaneSlots], x[kDepthLaneSlots], y[kDepthLaneSlots];
  __m512i camera[kDepthLaneSlots];
  __mmask16 over[kDepthLaneSlots];
};

MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void clear_slots(LaneSlots16& s, int slots) noexcept {
  for (int j = 0; j < slots; ++j) {
    s.cosine[j] = _mm512_set1_ps(-__builtin_inff());
    s.distance[j] = s.x[j] = s.y[j] = _mm512_setzero_ps();
    s.camera[j] = _mm512_set1_epi32(-1);
    s.over[j] = 0;
  }
}

/// The lanes where a camera with cosine `cs` (clamped), `over`, distance `d` and index `camera`
/// goes before the one in slot j. `blend` sorts its candidates, taken by increasing (distance,
/// index), by insertion, comparing each new cosine as computed with the clamped ones kept: so
/// cosines above 1 come first, the later candidate first among them, then the others by
/// decreasing cosine, the earlier candidate first among equals. This is that order.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __mmask16 slot_before(const LaneSlots16& s, int j, __m512 cs, __mmask16 over,
                                                          __m512 d, __m512i camera) noexcept {
  const __mmask16 nearer =
      _mm512_cmp_ps_mask(d, s.distance[j], _CMP_LT_OQ) |
      (_mm512_cmp_ps_mask(d, s.distance[j], _CMP_EQ_OQ) & _mm512_cmp_epi32_mask(camera, s.camera[j], _MM_CMPINT_LT));
  const __mmask16 farther =
      _mm512_cmp_ps_mask(d, s.distance[j], _CMP_GT_OQ) |
      (_mm512_cmp_ps_mask(d, s.distance[j], _CMP_EQ_OQ) & _mm512_cmp_epi32_mask(camera, s.camera[j], _MM_CMPINT_GT));
  const __mmask16 larger =
      _mm512_cmp_ps_mask(cs, s.cosine[j], _CMP_GT_OQ) | (_mm512_cmp_ps_mask(cs, s.cosine[j], _CMP_EQ_OQ) & nearer);
  const __mmask16 y = s.over[j];
  return static_cast<__mmask16>((over & y & farther) | (over & ~y) | (~over & ~y & larger));
}

/// Inserts camera `camera` with cosines `cs` (clamped to 1; `over`: the lanes where it was
/// above), distances `d` and pixels (x, y) into the lanes of `m`, keeping the first `slots` in
/// the order of `slot_before`.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void insert_slots(LaneSlots16& s, int slots, __mmask16 m, __m512 cs, __mmask16 over,
                                                      __m512 d, int camera, __m512 x, __m512 y) noexcept {
  __m512i cam = _mm512_set1_epi32(camera);
  __mmask16 shifting = 0; // lanes that placed their entry: the rest moves down one slot
  for (int j = 0; j < slots && m != 0; ++j) {
    const __mmask16 swap = m & (shifting | slot_before(s, j, cs, over, d, cam));
    shifting |= swap;
    const __m512 c0 = s.cosine[j], d0 = s.distance[j], x0 = s.x[j], y0 = s.y[j];
    const __m512i k0 = s.camera[j];
    const __mmask16 o0 = s.over[j];
    s.cosine[j] = _mm512_mask_blend_ps(swap, c0, cs);
    s.distance[j] = _mm512_mask_blend_ps(swap, d0, d);
    s.x[j] = _mm512_mask_blend_ps(swap, x0, x);
    s.y[j] = _mm512_mask_blend_ps(swap, y0, y);
    s.camera[j] = _mm512_mask_blend_epi32(swap, k0, cam);
    s.over[j] = static_cast<__mmask16>((o0 & ~swap) | (over & swap));
    cs = _mm512_mask_blend_ps(swap, cs, c0);
    d = _mm512_mask_blend_ps(swap, d, d0);
    x = _mm512_mask_blend_ps(swap, x, x0);
    y = _mm512_mask_blend_ps(swap, y, y0);
    cam = _mm512_mask_blend_epi32(swap, cam, k0);
    over = static_cast<__mmask16>((over & ~swap) | (o0 & swap));
    // A lane whose displaced entry was empty is done.
    m &= static_cast<__mmask16>(~(swap & _mm512_cmp_epi32_mask(cam, _mm512_set1_epi32(-1), _MM_CMPINT_EQ)));
  }
}

/// The cameras each lane keeps (slot j of lane l), in the order of `LaneSlots16`: the angle to the
/// ray (`unit_acos` of the cosine), the pixel, the camera (-1: empty).
struct LaneChoice {
  alignas(64) float penalty[kDepthLaneSlots][16], x[kDepthLaneSlots][16], y[kDepthLaneSlots][16];
  alignas(64) int camera[kDepthLaneSlots][16];
};

/// For each camera i of `table`: near[i] = the lanes of `valid` whose ray line passes within
/// sqrt(radius2) of the camera's centre, distance[i][l] = that distance (every lane, for the
/// cameras of some lane; the others' rows are not written); first[l] =
/// the nearest of those cameras to lane l's ray line (the lowest index among equals), or -1.
template <class Table>
MPR_TARGET_AVX512 void scan_cameras16(const Table& table, const RayLanes& lanes, float radius2, unsigned valid,
                                      std::uint16_t* near, float (*distance)[16], int* first) noexcept {
  const RayLanes16 r = load_lanes(lanes);
  const __m512 limit = _mm512_set1_ps(radius2);
  __m512 best = _mm512_set1_ps(__builtin_inff());
  __m512i nearest = _mm512_set1_epi32(-1);
  for (std::size_t i = 0; i < table.size(); ++i) {
    const auto& C = table.camera(i).centre;
    const __m512 d2 = line_distance2_x16(r, C.x(), C.y(), C.z());
    const __mmask16 m = static_cast<__mmask16>(valid & _mm512_cmp_ps_mask(d2, limit, _CMP_LT_OQ));
    near[i] = m;
    if (m == 0) continue; // its distances are never read
    const __m512 d = _mm512_maskz_sqrt_ps(0xFFFF, d2);
    _mm512_store_ps(distance[i], d);
    const __mmask16 nearer = m & _mm512_cmp_ps_mask(d, best, _CMP_LT_OQ);
    best = _mm512_mask_blend_ps(nearer, best, d);
    nearest = _mm512_mask_blend_epi32(nearer, nearest, _mm512_set1_epi32(static_cast<int>(i)));
  }
  _mm512_storeu_si512(first, nearest);
}

/// The blend's choice of cameras for the points `point` (x, y, z rows) of the rays `lanes`,
/// in the lanes of `blended`: every camera i (at `distance[i]` from each ray line) tried for
/// the lanes of near[i] -- in front of the ray (positive cosine), projecting the point inside
/// its image, and its depth map there not nearer than the point's depth by more than the
/// relative `tolerance` (`DepthProxy::visibility_tolerance`) -- and the `slots` with the
/// largest cosines kept per lane (`LaneChoice`, camera -1 in an empty slot), as
/// `DepthProxy::blend` chooses them. Undistorted cameras only; maps of fewer than 2^31 pixels.
template <class Table>
MPR_TARGET_AVX512 void choose_cameras16(const Table& table, const RayLanes& lanes, const float (*point)[16],
                                        const float (*distance)[16], const std::uint16_t* near, unsigned blended,
                                        int slots, float tolerance, LaneChoice& out) noexcept {
  const RayLanes16 r = load_lanes(lanes);
  const __m512 X = _mm512_load_ps(point[0]), Y = _mm512_load_ps(point[1]), Z = _mm512_load_ps(point[2]);
  LaneSlots16 best;
  clear_slots(best, slots);
  const float smooth = 1 + 4 * tolerance;
  const __m512 keep = _mm512_set1_ps(1 - tolerance), zero = _mm512_setzero_ps(), edge = _mm512_set1_ps(-0.5f);
  const __m512 inf = _mm512_set1_ps(__builtin_inff()), one = _mm512_set1_ps(1);
  // The cameras any lane has, nearest to the first blended lane's ray first: inserted in that
  // order, the lanes fill their slots with the best cameras early, and a camera that cannot
  // enter a lane's full slots skips the insertion.
  int order[64];
  int cameras = 0;
  const int reference = blended != 0 ? __builtin_ctz(blended) : 0;
  for (std::size_t i = 0; i < table.size() && cameras < 64; ++i) {
    if ((near[i] & blended) == 0) continue;
    int at = cameras++;
    for (; at > 0 && distance[i][reference] < distance[order[at - 1]][reference]; --at) order[at] = order[at - 1];
    order[at] = static_cast<int>(i);
  }
  // First every camera's cosines, pixels and visibility, each camera apart from the others (so
  // that the depth lookups of several cameras are in flight at once), then the choice in order.
  alignas(64) float cosine[64][16], px[64][16], py[64][16];
  __mmask16 seen[64], above[64];
  for (int o = 0; o < cameras; ++o) {
    const std::size_t i = static_cast<std::size_t>(order[o]);
    __mmask16 m = static_cast<__mmask16>(near[i] & blended);
    seen[o] = 0;
    const auto& cam = table.camera(i);
    // The cosine of the angle between X - centre and the ray, as `blend` computes it.
    const __m512 tx = _mm512_sub_ps(X, _mm512_set1_ps(cam.centre.x()));
    const __m512 ty = _mm512_sub_ps(Y, _mm512_set1_ps(cam.centre.y()));
    const __m512 tz = _mm512_sub_ps(Z, _mm512_set1_ps(cam.centre.z()));
    const __m512 dot = sum3(mul16(tx, r.vx), mul16(ty, r.vy), mul16(tz, r.vz));
    const __m512 norm = _mm512_maskz_sqrt_ps(0xFFFF, sum3(mul16(tx, tx), mul16(ty, ty), mul16(tz, tz)));
    const __m512 raw = _mm512_div_ps(dot, mul16(norm, r.length));
    m &= _mm512_cmp_ps_mask(raw, zero, _CMP_GT_OQ);
    if (m == 0) continue;
    _mm512_store_ps(cosine[o], _mm512_maskz_min_ps(0xFFFF, raw, one));
    above[o] = _mm512_cmp_ps_mask(raw, one, _CMP_GT_OQ);
    // `FrameTable::project`: in front, finite, inside the image.
    const float* P = cam.P;
    const __m512 w = project_row16(P + 8, X, Y, Z);
    m &= _mm512_cmp_ps_mask(w, zero, _CMP_GT_OQ);
    if (m == 0) continue;
    const __m512 inv = _mm512_maskz_div_ps(m, one, w);
    const __m512 x = mul16(project_row16(P, X, Y, Z), inv), y = mul16(project_row16(P + 4, X, Y, Z), inv);
    m &= _mm512_cmp_ps_mask(x, edge, _CMP_GE_OQ) & _mm512_cmp_ps_mask(y, edge, _CMP_GE_OQ) &
         _mm512_cmp_ps_mask(x, _mm512_set1_ps(static_cast<float>(cam.width) - 0.5f), _CMP_LT_OQ) &
         _mm512_cmp_ps_mask(y, _mm512_set1_ps(static_cast<float>(cam.height) - 0.5f), _CMP_LT_OQ) &
         _mm512_cmp_ps_mask(_mm512_abs_ps(x), inf, _CMP_LT_OQ) & _mm512_cmp_ps_mask(_mm512_abs_ps(y), inf, _CMP_LT_OQ);
    if (m == 0) continue;
    _mm512_store_ps(px[o], x);
    _mm512_store_ps(py[o], y);
    // Visible unless the map shows something nearer by more than the tolerance.
    const float* map = table.frames().depth(i).data();
    const __m512 depth = depth_lookup_x16(map, cam.width, cam.height, x, y, smooth, m);
    {
      // The map rows the next sixteen rays of the row will likely read here, 16 pixels on.
      const int last = 31 - __builtin_clz(static_cast<unsigned>(m));
      const int ax = std::min(static_cast<int>(px[o][last]) + 16, cam.width - 1);
      const int ay = std::clamp(static_cast<int>(py[o][last]), 0, cam.height - 1);
      const float* row = map + static_cast<std::ptrdiff_t>(ay) * cam.width + ax;
      __builtin_prefetch(row);
      if (ay + 1 < cam.height) __builtin_prefetch(row + cam.width);
    }
    seen[o] = m & _mm512_cmp_ps_mask(depth, mul16(w, keep), _CMP_NLT_UQ);
  }
  for (int o = 0; o < cameras; ++o) {
    __mmask16 m = seen[o];
    if (m == 0) continue;
    const std::size_t i = static_cast<std::size_t>(order[o]);
    const __m512 cs = _mm512_load_ps(cosine[o]), d = _mm512_load_ps(distance[i]);
    // Lanes whose slots are full of cameras that go before this one do not need it.
    m &= static_cast<__mmask16>(_mm512_cmp_epi32_mask(best.camera[slots - 1], _mm512_set1_epi32(-1), _MM_CMPINT_EQ) |
                                slot_before(best, slots - 1, cs, above[o], d, _mm512_set1_epi32(static_cast<int>(i))));
    if (m == 0) continue;
    insert_slots(best, slots, m, cs, above[o], d, static_cast<int>(i), _mm512_load_ps(px[o]), _mm512_load_ps(py[o]));
  }
  for (int j = 0; j < slots; ++j) {
    _mm512_store_ps(out.penalty[j], unit_acos16(best.cosine[j]));
    _mm512_store_ps(out.x[j], best.x[j]);
    _mm512_store_ps(out.y[j], best.y[j]);
    _mm512_store_si512(out.camera[j], best.camera[j]);
  }
}

#endif

} // namespace mpr::detail
