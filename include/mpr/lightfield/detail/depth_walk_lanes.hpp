#pragma once
/// \file
/// `depth_walk` (detail/depth_walk.hpp) for sixteen rays at once in one camera, on AVX-512: the
/// rays of `DepthProxy`'s batch path whose nearest camera is the same walk its depth map
/// together, one lane per ray, each lane stepping and narrowing the crossing as the per-ray walk
/// does, with the same operations in the same order and no fused multiply-add, and ending as it
/// ends: on the surface, escaped, or passed on to the next camera with the search where the
/// per-ray walk leaves it, for the next camera. Each lane's walk starts from its own search
/// (`DepthSearch`: where it stands, and the stretch seen free by the cameras before).

#include <mpr/core/config.hpp>
#include <mpr/lightfield/detail/depth_lanes.hpp>
#include <mpr/lightfield/detail/depth_walk.hpp>

namespace mpr::detail {

#if defined(MPR_SIMD_X86)

/// The walk's ray as h(s) = a + s b in homogeneous pixels of one camera, for sixteen lanes.
struct WalkLanes16 {
  __m512 a0, a1, a2, b0, b1, b2;
};

/// f(s) = ray depth - map depth at the ray's pixel, and the ray depth z (`depth_walk`'s f): -inf
/// where z <= 0, the map read in the lanes of `m` only.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __m512 walk_f16(const WalkLanes16& h, const float* d, int width, int height,
                                                    float smooth, __m512 s, __mmask16 m, __m512& z) noexcept {
  z = _mm512_add_ps(h.a2, mul16(s, h.b2));
  const __mmask16 front = m & _mm512_cmp_ps_mask(z, _mm512_setzero_ps(), _CMP_GT_OQ);
  const __m512 inv = _mm512_maskz_div_ps(front, _mm512_set1_ps(1), z);
  const __m512 x = mul16(_mm512_add_ps(h.a0, mul16(s, h.b0)), inv);
  const __m512 y = mul16(_mm512_add_ps(h.a1, mul16(s, h.b1)), inv);
  const __m512 depth = depth_lookup_x16(d, width, height, x, y, smooth, front);
  return _mm512_mask_blend_ps(front, _mm512_set1_ps(-__builtin_inff()), _mm512_sub_ps(z, depth));
}

/// `depth_walk`'s clip: keeps u + s w >= 0 in [lo, hi]; lanes where w is 0 (or NaN) and u < 0
/// leave `live`.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void clip16(__m512 u, __m512 w, __m512& lo, __m512& hi, __mmask16& live) noexcept {
  const __m512 zero = _mm512_setzero_ps();
  const __m512 bound = _mm512_div_ps(neg16(u), w);
  const __mmask16 up = _mm512_cmp_ps_mask(w, zero, _CMP_GT_OQ), down = _mm512_cmp_ps_mask(w, zero, _CMP_LT_OQ);
  lo = _mm512_mask_max_ps(lo, up, bound, lo);
  hi = _mm512_mask_min_ps(hi, down, bound, hi);
  live &= static_cast<__mmask16>(~(~up & ~down & _mm512_cmp_ps_mask(u, zero, _CMP_LT_OQ)));
}

/// Keeps the lanes of `live` whose interval [lo, hi) is not empty and starts at a finite lo.
MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void keep_in_view16(__m512 lo, __m512 hi, __mmask16& live) noexcept {
  live &= static_cast<__mmask16>(_mm512_cmp_ps_mask(lo, hi, _CMP_LT_OQ) &
                                 _mm512_cmp_ps_mask(_mm512_abs_ps(lo), _mm512_set1_ps(__builtin_inff()), _CMP_LT_OQ));
}

/// The search of sixteen walks (`DepthSearch` per lane) in one camera, which sees each
/// ray from `view` on (`gap`: the lanes where that lies beyond the search's t).
struct SearchLanes16 {
  __m512 t, skip_begin, skip_end, view;
  __mmask16 gap;

  /// `depth_walk`'s pass(at) for the lanes of m: where the camera sees the ray at t, the search
  /// moves on to `at` (over the stretch seen free when it reaches it, which is then used up);
  /// where it does not, [view, at) is recorded as seen free, merged with the stretch there when
  /// they overlap.
  MPR_TARGET_AVX512 MPR_ALWAYS_INLINE void pass(__mmask16 m, __m512 at) noexcept {
    const __m512 inf = _mm512_set1_ps(__builtin_inff());
    const __m512 sb = skip_begin, se = skip_end;
    // t = at >= sb ? std::max(at, se) : at; then a t at or past sb clears the stretch.
    const __mmask16 moved = m & ~gap;
    const __mmask16 reached = moved & _mm512_cmp_ps_mask(at, sb, _CMP_GE_OQ);
    const __m512 over = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(at, se, _CMP_LT_OQ), at, se);
    t = _mm512_mask_mov_ps(t, moved, _mm512_mask_blend_ps(reached, at, over));
    const __mmask16 used = moved & _mm512_cmp_ps_mask(t, sb, _CMP_GE_OQ);
    // sb = none ? view : std::min(sb, view), se = none ? at : std::max(se, at).
    const __mmask16 none = static_cast<__mmask16>(~_mm512_cmp_ps_mask(sb, se, _CMP_LT_OQ));
    const __mmask16 overlap = _mm512_cmp_ps_mask(view, se, _CMP_LE_OQ) & _mm512_cmp_ps_mask(at, sb, _CMP_GE_OQ);
    const __mmask16 record = m & gap & _mm512_cmp_ps_mask(view, at, _CMP_LT_OQ) & (none | overlap);
    const __m512 begin =
        _mm512_mask_blend_ps(none, _mm512_mask_blend_ps(_mm512_cmp_ps_mask(view, sb, _CMP_LT_OQ), sb, view), view);
    const __m512 end =
        _mm512_mask_blend_ps(none, _mm512_mask_blend_ps(_mm512_cmp_ps_mask(se, at, _CMP_LT_OQ), se, at), at);
    skip_begin = _mm512_mask_mov_ps(_mm512_mask_mov_ps(sb, used, inf), record, begin);
    skip_end = _mm512_mask_mov_ps(_mm512_mask_mov_ps(se, used, inf), record, end);
  }

  /// `depth_walk`'s start_behind for the lanes of m whose walk starts (or resumes) at `at` at or
  /// behind the surface c sees (f(at) = `fat` >= 0, ray depth `zat`): the surface itself within
  /// the tolerance (added to `hit`), else c is occluded from there (passed). Returns those lanes.
  MPR_TARGET_AVX512 MPR_ALWAYS_INLINE __mmask16 start_behind(__mmask16 m, __m512 at, __m512 fat, __m512 zat,
                                                             __m512 tolerance, __mmask16& hit) noexcept {
    const __mmask16 behind = m & ~_mm512_cmp_ps_mask(fat, _mm512_setzero_ps(), _CMP_LT_OQ);
    const __mmask16 on = behind & _mm512_cmp_ps_mask(fat, mul16(tolerance, zat), _CMP_LE_OQ);
    hit |= on;
    t = _mm512_mask_mov_ps(t, on, at);
    pass(behind & ~on, at);
    return behind;
  }
};

/// How the walks of `walk_lanes16` ended, lane by lane: `hit` (t: the surface), `escaped` (the
/// ray runs to its vanishing point in front of everything the camera sees), `passed` (t,
/// skip_begin, skip_end: the search's `DepthSearch` after this camera, for the next).
struct WalkLanesResult {
  unsigned hit = 0, escaped = 0, passed = 0;
  alignas(64) float t[16], skip_begin[16], skip_end[16];
};

/// Walks the rays `lanes` of the lanes in `walk` through camera `c`'s depth map `d` (`near` its
/// nearest depth), each lane l from the search {from.t[l], from.skip_begin[l], from.skip_end[l]}
/// (a first camera: t = -inf for the whole line, 0 for the half-line, no stretch: +inf, +inf),
/// exactly as `depth_walk` does (see the file comment), and says how each walk ended.
template <class Camera>
MPR_TARGET_AVX512 void walk_lanes16(const Camera& c, const float* d, float near, const RayLanes& lanes, unsigned walk,
                                    const WalkLanesResult& from, float tolerance, WalkLanesResult& out) noexcept {
  const RayLanes16 r = load_lanes(lanes);
  const float* P = c.P;
  // a = P (o, 1), b = P (v, 0), each row summed as `depth_walk` sums it.
  WalkLanes16 h;
  h.a0 = project_row16(P, r.ox, r.oy, r.oz);
  h.a1 = project_row16(P + 4, r.ox, r.oy, r.oz);
  h.a2 = project_row16(P + 8, r.ox, r.oy, r.oz);
  h.b0 = linear_row16(P, r.vx, r.vy, r.vz);
  h.b1 = linear_row16(P + 4, r.vx, r.vy, r.vz);
  h.b2 = linear_row16(P + 8, r.vx, r.vy, r.vz);
  const __m512 zero = _mm512_setzero_ps(), inf = _mm512_set1_ps(__builtin_inff());
  const __m512 t0 = _mm512_load_ps(from.t);
  __mmask16 hit = 0, escaped = 0;
  // The interval of s where h projects inside the image in front of c.
  __m512 lo = t0, hi = inf;
  __mmask16 live = static_cast<__mmask16>(walk);
  const __m512 e = _mm512_set1_ps(0.499f);
  const __m512 W = _mm512_set1_ps(static_cast<float>(c.width) - 0.5f - 1e-3f);
  const __m512 H = _mm512_set1_ps(static_cast<float>(c.height) - 0.5f - 1e-3f);
  const __m512 margin = mul16(_mm512_set1_ps(1e-6f), _mm512_add_ps(_mm512_abs_ps(h.a2), _mm512_abs_ps(h.b2)));
  clip16(_mm512_sub_ps(h.a2, margin), h.b2, lo, hi, live);
  clip16(_mm512_add_ps(h.a0, mul16(e, h.a2)), _mm512_add_ps(h.b0, mul16(e, h.b2)), lo, hi, live);
  clip16(_mm512_sub_ps(mul16(W, h.a2), h.a0), _mm512_sub_ps(mul16(W, h.b2), h.b0), lo, hi, live);
  clip16(_mm512_add_ps(h.a1, mul16(e, h.a2)), _mm512_add_ps(h.b1, mul16(e, h.b2)), lo, hi, live);
  clip16(_mm512_sub_ps(mul16(H, h.a2), h.a1), _mm512_sub_ps(mul16(H, h.b2), h.b1), lo, hi, live);
  keep_in_view16(lo, hi, live); // the others pass with the search unchanged
  const __m512 leave = hi, view = lo;
  const __mmask16 gap = _mm512_cmp_ps_mask(lo, t0, _CMP_GT_OQ); // c sees the ray only from beyond t
  SearchLanes16 search{t0, _mm512_load_ps(from.skip_begin), _mm512_load_ps(from.skip_end), view, gap};
  const float tol = tolerance;
  if (__builtin_isfinite(near)) {
    const __mmask16 before = live;
    clip16(_mm512_sub_ps(h.a2, mul16(_mm512_set1_ps(near), _mm512_set1_ps(1 - tol))), h.b2, lo, hi, live);
    keep_in_view16(lo, hi, live);
    // In front of all c sees wherever c sees the ray.
    search.pass(before & ~live, _mm512_mask_blend_ps(_mm512_cmp_ps_mask(leave, inf, _CMP_LT_OQ), t0, leave));
  }
  // Pixels moved per unit s: m / z^2.
  const __m512 mx = _mm512_sub_ps(mul16(h.b0, h.a2), mul16(h.a0, h.b2));
  const __m512 my = _mm512_sub_ps(mul16(h.b1, h.a2), mul16(h.a1, h.b2));
  const __m512 m = _mm512_maskz_sqrt_ps(0xFFFF, _mm512_add_ps(mul16(mx, mx), mul16(my, my)));
  const float smooth = 1 + 4 * tol;
  const __m512 tolerance16 = _mm512_set1_ps(tol);
  const int width = c.width, height = c.height;
  const __mmask16 bounded = _mm512_cmp_ps_mask(hi, inf, _CMP_LT_OQ);
  {
    // A walk that would start inside the stretch seen free starts after it, if c still sees the
    // ray there.
    const __mmask16 inside = live & _mm512_cmp_ps_mask(lo, search.skip_begin, _CMP_GE_OQ) &
                             _mm512_cmp_ps_mask(lo, search.skip_end, _CMP_LT_OQ);
    const __mmask16 beyond = inside & ~_mm512_cmp_ps_mask(search.skip_end, hi, _CMP_LT_OQ);
    search.pass(beyond, _mm512_mask_blend_ps(_mm512_cmp_ps_mask(leave, inf, _CMP_LT_OQ), search.skip_end, leave));
    live &= ~beyond;
    lo = _mm512_mask_mov_ps(lo, inside & ~beyond, search.skip_end);
  }
  __m512 s = lo, z;
  __m512 fs = walk_f16(h, d, width, height, smooth, s, live, z);
  live &= ~search.start_behind(live, s, fs, z, tolerance16, hit);
  // Step about a pixel at a time until f >= 0 brackets the crossing in [s, next].
  const __m512 half = _mm512_set1_ps(0.5f);
  // The bracket [s0, s1] of each lane that finds one (f0 = f(s0), ray depths z0, z1). Every lane
  // steps on and reads the map each step until all are done, the finished ones' results unused:
  // then no step waits for the previous step's lookups (only the lanes' masks do), and the
  // lookups of several steps are in flight at once.
  __m512 s0 = zero, f0 = zero, s1 = zero, f1 = zero, z0 = zero, z1 = zero;
  const __mmask16 reading = live;
  __mmask16 stepping = live, bracketed = 0;
  for (int step = 0; stepping != 0 && step < 1 << 16; ++step) {
    const __mmask16 out_of_view = stepping & _mm512_cmp_ps_mask(s, hi, _CMP_GE_OQ);
    search.pass(out_of_view, _mm512_mask_blend_ps(bounded, s, leave));
    stepping &= ~out_of_view;
    const __m512 zs = _mm512_add_ps(h.a2, mul16(s, h.b2));
    // Toward the vanishing point, within half a pixel of it: the surface there (if any) is hit
    // where the depths agree; a map that shows nothing there lets the ray escape.
    const __mmask16 vanishing =
        stepping & ~bounded &
        (~_mm512_cmp_ps_mask(m, zero, _CMP_GT_OQ) | _mm512_cmp_ps_mask(m, mul16(mul16(half, h.b2), zs), _CMP_LT_OQ));
    if (vanishing != 0) {
      const __m512 dv = _mm512_sub_ps(zs, fs); // the map's depth at s (zv = zs, fv = fs)
      const __mmask16 finite = _mm512_cmp_ps_mask(_mm512_abs_ps(dv), inf, _CMP_LT_OQ);
      const __mmask16 there =
          vanishing & finite & _mm512_cmp_ps_mask(dv, zs, _CMP_GT_OQ) & _mm512_cmp_ps_mask(h.b2, zero, _CMP_GT_OQ);
      const __mmask16 away = vanishing & ~there & _mm512_cmp_ps_mask(zs, zero, _CMP_GT_OQ) &
                             _mm512_cmp_ps_mask(_mm512_abs_ps(dv), inf, _CMP_EQ_OQ);
      hit |= there;
      search.t = _mm512_mask_mov_ps(search.t, there, _mm512_div_ps(_mm512_sub_ps(dv, h.a2), h.b2));
      escaped |= away;
      search.pass(vanishing & ~there & ~away, s);
      stepping &= ~vanishing;
    }
    const __m512 ahead = _mm512_add_ps(s, _mm512_div_ps(mul16(zs, zs), m));
    __m512 next = _mm512_mask_blend_ps(
        bounded, ahead,
        _mm512_mask_blend_ps(_mm512_cmp_ps_mask(m, zero, _CMP_GT_OQ), hi, _mm512_maskz_min_ps(0xFFFF, ahead, hi)));
    // Up to the stretch seen free, then over it.
    next = _mm512_mask_mov_ps(next,
                              _mm512_cmp_ps_mask(s, search.skip_begin, _CMP_LT_OQ) &
                                  _mm512_cmp_ps_mask(next, search.skip_begin, _CMP_GT_OQ),
                              search.skip_begin);
    __m512 zn;
    const __m512 fn = walk_f16(h, d, width, height, smooth, next, reading, zn);
    const __mmask16 found = stepping & _mm512_cmp_ps_mask(fn, zero, _CMP_GE_OQ);
    s0 = _mm512_mask_blend_ps(found, s0, s);
    f0 = _mm512_mask_blend_ps(found, f0, fs);
    s1 = _mm512_mask_blend_ps(found, s1, next);
    f1 = _mm512_mask_blend_ps(found, f1, fn);
    z0 = _mm512_mask_blend_ps(found, z0, zs);
    z1 = _mm512_mask_blend_ps(found, z1, zn);
    bracketed |= found;
    stepping &= ~found;
    s = next;
    fs = fn;
    const __mmask16 skip = stepping & _mm512_cmp_ps_mask(s, search.skip_begin, _CMP_GE_OQ) &
                           _mm512_cmp_ps_mask(s, search.skip_end, _CMP_LT_OQ);
    if (skip != 0) {
      const __mmask16 beyond = skip & ~_mm512_cmp_ps_mask(search.skip_end, hi, _CMP_LT_OQ);
      search.pass(beyond, _mm512_mask_blend_ps(bounded, s, leave));
      stepping &= ~beyond;
      const __mmask16 jump = skip & ~beyond;
      s = _mm512_mask_mov_ps(s, jump, search.skip_end);
      __m512 zj;
      fs = _mm512_mask_mov_ps(fs, jump, walk_f16(h, d, width, height, smooth, s, jump, zj));
      stepping &= ~search.start_behind(jump, s, fs, zj, tolerance16, hit);
    }
  }
  search.pass(stepping, _mm512_mask_blend_ps(bounded, s, leave)); // out of steps
  // Regula falsi (Illinois) in [s0, s1], as `depth_walk` narrows it.
  __m512 g0 = f0, g1 = f1;
  const __m512 resolution = mul16(_mm512_sub_ps(s1, s0), _mm512_set1_ps(1.0f / 256));
  const __m512 half_tol = _mm512_set1_ps(0.5f * tol);
  __mmask16 kept_low = 0, kept_high = 0; // the last step moved s0 / s1
  __mmask16 narrowing = bracketed, agreed = 0;
  __m512 t_agreed = zero;
  const __m512 agreement = _mm512_set1_ps(tol * kDepthAgreement);
  for (int it = 0; narrowing != 0 && it < kDepthRefineLimit; ++it) {
    const __mmask16 loose = _mm512_cmp_ps_mask(_mm512_sub_ps(z1, z0), mul16(half_tol, z1), _CMP_GT_OQ);
    if (it >= kDepthRefineSteps) narrowing &= loose;
    narrowing &= _mm512_cmp_ps_mask(_mm512_sub_ps(s1, s0), resolution, _CMP_GT_OQ) | loose;
    if (narrowing == 0) break;
    const __m512 width_g = _mm512_sub_ps(g1, g0);
    const __m512 centre = mul16(half, _mm512_add_ps(s0, s1));
    __m512 mid = _mm512_add_ps(s0, mul16(_mm512_sub_ps(s1, s0), _mm512_div_ps(neg16(g0), width_g)));
    mid = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(width_g, zero, _CMP_GT_OQ), centre, mid);
    const __mmask16 inside = _mm512_cmp_ps_mask(mid, s0, _CMP_GT_OQ) & _mm512_cmp_ps_mask(mid, s1, _CMP_LT_OQ);
    mid = _mm512_mask_blend_ps(inside, centre, mid);
    __m512 zm;
    const __m512 fm = walk_f16(h, d, width, height, smooth, mid, narrowing, zm);
    // A point where the depths agree is the surface.
    const __mmask16 agree = narrowing & _mm512_cmp_ps_mask(_mm512_abs_ps(fm), mul16(agreement, zm), _CMP_LE_OQ);
    agreed |= agree;
    t_agreed = _mm512_mask_mov_ps(t_agreed, agree, mid);
    narrowing &= static_cast<__mmask16>(~agree);
    const __mmask16 below = narrowing & _mm512_cmp_ps_mask(fm, zero, _CMP_LT_OQ);
    const __mmask16 above = narrowing & ~below;
    s0 = _mm512_mask_blend_ps(below, s0, mid);
    z0 = _mm512_mask_blend_ps(below, z0, zm);
    f0 = _mm512_mask_blend_ps(below, f0, fm);
    g0 = _mm512_mask_blend_ps(below, g0, fm);
    g1 = _mm512_mask_blend_ps(below & kept_low, g1, mul16(g1, half));
    s1 = _mm512_mask_blend_ps(above, s1, mid);
    f1 = _mm512_mask_blend_ps(above, f1, fm);
    g1 = _mm512_mask_blend_ps(above, g1, fm);
    z1 = _mm512_mask_blend_ps(above, z1, zm);
    g0 = _mm512_mask_blend_ps(above & kept_high, g0, mul16(g0, half));
    kept_low = (kept_low & ~narrowing) | below;
    kept_high = (kept_high & ~narrowing) | above;
  }
  // A crossing within the tolerance is the surface; else c is occluded from s0 on.
  const __m512 limit = mul16(tolerance16, z1);
  const __mmask16 crossed = bracketed & ~agreed & _mm512_cmp_ps_mask(f1, limit, _CMP_LE_OQ) &
                            _mm512_cmp_ps_mask(neg16(f0), limit, _CMP_LE_OQ);
  const __m512 denom = _mm512_sub_ps(f1, f0);
  const __m512 cross = _mm512_add_ps(s0, mul16(_mm512_sub_ps(s1, s0), _mm512_div_ps(neg16(f0), denom)));
  search.t = _mm512_mask_mov_ps(search.t, crossed,
                                _mm512_mask_blend_ps(_mm512_cmp_ps_mask(denom, zero, _CMP_GT_OQ), s1, cross));
  search.t = _mm512_mask_mov_ps(search.t, agreed, t_agreed);
  search.pass(bracketed & ~crossed & ~agreed, s0);
  hit |= crossed | agreed;
  out.hit = hit;
  out.escaped = escaped;
  out.passed = walk & ~(hit | escaped);
  _mm512_store_ps(out.t, search.t);
  _mm512_store_ps(out.skip_begin, search.skip_begin);
  _mm512_store_ps(out.skip_end, search.skip_end);
}

#endif

} // namespace mpr::detail
