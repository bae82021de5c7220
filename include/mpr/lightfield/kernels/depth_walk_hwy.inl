// No #pragma once, no includes: kernels/depth_lanes_hwy.hpp includes this file once per Highway
// target, after kernels/depth_lane_ops_hwy.inl (the ops used here: `mul`, `depth_lookup` ...).
/// \file
/// `depth_walk` ((depth_proxy/depth_walk.hpp)) for sixteen rays at once in one camera: the rays of
/// `DepthProxy`'s batch path whose camera is the same walk its depth map together, one lane per
/// ray, each lane stepping and narrowing the crossing as the per-ray walk does, with the same
/// operations in the same order and no fused multiply-add, and ending as it ends: on the
/// surface, escaped, or passed on to the next camera with the search where the per-ray walk
/// leaves it. Each lane's walk starts from its own search (`DepthSearch`: where it stands, and
/// the stretch seen free by the cameras before).

/// The walk's ray as h(s) = a + s b in homogeneous pixels of one camera.
struct Walk {
  VF a0, a1, a2, b0, b1, b2;
};

/// f(s) = ray depth - map depth at the ray's pixel, and the ray depth z (`depth_walk`'s f): -inf
/// where z <= 0 or outside `m`.
HWY_INLINE VF walk_f(const Walk& h, const LaneCamera& c, float smooth, VF s, MF m, VF& z) noexcept {
  z = hn::Add(h.a2, mul(s, h.b2));
  const MF front = hn::And(m, hn::Gt(z, hn::Zero(DF())));
  const VF inv = hn::Div(set(1), z);
  const VF x = mul(hn::Add(h.a0, mul(s, h.b0)), inv);
  const VF y = mul(hn::Add(h.a1, mul(s, h.b1)), inv);
  const VF depth = depth_lookup(c.depth, c.width, c.height, x, y, smooth);
  return hn::IfThenElse(front, hn::Sub(z, depth), set(-__builtin_inff()));
}

/// `depth_walk`'s clip: keeps u + s w >= 0 in [lo, hi]; lanes where w is 0 (or NaN) and u < 0
/// leave `live`.
HWY_INLINE void clip(VF u, VF w, VF& lo, VF& hi, MF& live) noexcept {
  const VF zero = hn::Zero(DF());
  const VF bound = hn::Div(hn::Neg(u), w);
  const MF up = hn::Gt(w, zero), down = hn::Lt(w, zero);
  lo = hn::IfThenElse(up, hn::Max(bound, lo), lo);
  hi = hn::IfThenElse(down, hn::Min(bound, hi), hi);
  live = hn::AndNot(hn::AndNot(up, hn::AndNot(down, hn::Lt(u, zero))), live);
}

/// Keeps the lanes of `live` whose interval [lo, hi) is not empty and starts at a finite lo.
HWY_INLINE void keep_in_view(VF lo, VF hi, MF& live) noexcept {
  live = hn::And(live, hn::And(hn::Lt(lo, hi), hn::Lt(hn::Abs(lo), set(__builtin_inff()))));
}

/// The search of the walks (`DepthSearch` per lane) in one camera, which sees each ray from
/// `view` on (`gap`: the lanes where that lies beyond the search's t).
struct Search {
  VF t, skip_begin, skip_end, view;
  MF gap;

  /// `depth_walk`'s pass(at) for the lanes of m: where the camera sees the ray at t, the search
  /// moves on to `at` (over the stretch seen free when it reaches it, which is then used up);
  /// where it does not, [view, at) is recorded as seen free, merged with the stretch there when
  /// they overlap.
  HWY_INLINE void pass(MF m, VF at) noexcept {
    const VF inf = set(__builtin_inff());
    const VF sb = skip_begin, se = skip_end;
    // t = at >= sb ? std::max(at, se) : at; then a t at or past sb clears the stretch.
    const MF moved = hn::AndNot(gap, m);
    const MF reached = hn::And(moved, hn::Ge(at, sb));
    const VF over = hn::IfThenElse(hn::Lt(at, se), se, at);
    t = hn::IfThenElse(moved, hn::IfThenElse(reached, over, at), t);
    const MF used = hn::And(moved, hn::Ge(t, sb));
    // sb = none ? view : std::min(sb, view), se = none ? at : std::max(se, at).
    const MF none = hn::Not(hn::Lt(sb, se));
    const MF overlap = hn::And(hn::Le(view, se), hn::Ge(at, sb));
    const MF record = hn::And(hn::And(m, gap), hn::And(hn::Lt(view, at), hn::Or(none, overlap)));
    const VF begin = hn::IfThenElse(none, view, hn::IfThenElse(hn::Lt(view, sb), view, sb));
    const VF end = hn::IfThenElse(none, at, hn::IfThenElse(hn::Lt(se, at), at, se));
    skip_begin = hn::IfThenElse(record, begin, hn::IfThenElse(used, inf, sb));
    skip_end = hn::IfThenElse(record, end, hn::IfThenElse(used, inf, se));
  }

  /// `depth_walk`'s start_behind for the lanes of m whose walk starts (or resumes) at `at` at or
  /// behind the surface c sees (f(at) = `fat` >= 0, ray depth `zat`): the surface itself within
  /// the tolerance (added to `hit`), else c is occluded from there (passed). Returns those lanes.
  HWY_INLINE MF start_behind(MF m, VF at, VF fat, VF zat, VF tolerance, MF& hit) noexcept {
    const MF behind = hn::AndNot(hn::Lt(fat, hn::Zero(DF())), m);
    const MF on = hn::And(behind, hn::Le(fat, mul(tolerance, zat)));
    hit = hn::Or(hit, on);
    t = hn::IfThenElse(on, at, t);
    pass(hn::AndNot(on, behind), at);
    return behind;
  }
};

/// Where each lane of `bracketed` narrows its crossing: [s0, s1], f0 = f(s0), f1 = f(s1), ray
/// depths z0, z1.
struct Bracket {
  VF s0, f0, s1, f1, z0, z1;
};

/// Regula falsi (Illinois) in each lane's bracket, as `depth_walk` narrows it; then the crossing
/// within the tolerance is the surface (added to `hit`, t in the search), else c is occluded from
/// s0 on (passed).
HWY_INLINE void narrow(const Walk& h, const LaneCamera& c, float smooth, float tol, MF bracketed, Bracket b,
                       Search& search, MF& hit) noexcept {
  const DF df;
  const VF zero = hn::Zero(df), half = set(0.5f);
  VF g0 = b.f0, g1 = b.f1;
  const VF resolution = mul(hn::Sub(b.s1, b.s0), set(1.0f / 256));
  const VF half_tol = set(0.5f * tol);
  MF kept_low = hn::FirstN(df, 0), kept_high = kept_low; // the last step moved s0 / s1
  MF narrowing = bracketed, agreed = kept_low;
  VF t_agreed = zero;
  const VF agreement = set(tol * detail::kDepthAgreement);
  for (int it = 0; !hn::AllFalse(df, narrowing) && it < detail::kDepthRefineLimit; ++it) {
    const MF loose = hn::Gt(hn::Sub(b.z1, b.z0), mul(half_tol, b.z1));
    if (it >= detail::kDepthRefineSteps) narrowing = hn::And(narrowing, loose);
    narrowing = hn::And(narrowing, hn::Or(hn::Gt(hn::Sub(b.s1, b.s0), resolution), loose));
    if (hn::AllFalse(df, narrowing)) break;
    const VF width_g = hn::Sub(g1, g0);
    const VF centre = mul(half, hn::Add(b.s0, b.s1));
    VF mid = hn::Add(b.s0, mul(hn::Sub(b.s1, b.s0), hn::Div(hn::Neg(g0), width_g)));
    mid = hn::IfThenElse(hn::Gt(width_g, zero), mid, centre);
    mid = hn::IfThenElse(hn::And(hn::Gt(mid, b.s0), hn::Lt(mid, b.s1)), mid, centre);
    VF zm;
    const VF fm = walk_f(h, c, smooth, mid, narrowing, zm);
    // A point where the depths agree is the surface.
    const MF agree = hn::And(narrowing, hn::Le(hn::Abs(fm), mul(agreement, zm)));
    agreed = hn::Or(agreed, agree);
    t_agreed = hn::IfThenElse(agree, mid, t_agreed);
    narrowing = hn::AndNot(agree, narrowing);
    const MF below = hn::And(narrowing, hn::Lt(fm, zero));
    const MF above = hn::AndNot(below, narrowing);
    b.s0 = hn::IfThenElse(below, mid, b.s0);
    b.z0 = hn::IfThenElse(below, zm, b.z0);
    b.f0 = hn::IfThenElse(below, fm, b.f0);
    g0 = hn::IfThenElse(below, fm, g0);
    g1 = hn::IfThenElse(hn::And(below, kept_low), mul(g1, half), g1);
    b.s1 = hn::IfThenElse(above, mid, b.s1);
    b.f1 = hn::IfThenElse(above, fm, b.f1);
    g1 = hn::IfThenElse(above, fm, g1);
    b.z1 = hn::IfThenElse(above, zm, b.z1);
    g0 = hn::IfThenElse(hn::And(above, kept_high), mul(g0, half), g0);
    kept_low = hn::Or(hn::AndNot(narrowing, kept_low), below);
    kept_high = hn::Or(hn::AndNot(narrowing, kept_high), above);
  }
  // A crossing within the tolerance is the surface; else c is occluded from s0 on.
  const VF limit = mul(set(tol), b.z1);
  const MF crossed = hn::And(hn::AndNot(agreed, bracketed), hn::And(hn::Le(b.f1, limit), hn::Le(hn::Neg(b.f0), limit)));
  const VF denom = hn::Sub(b.f1, b.f0);
  const VF cross = hn::Add(b.s0, mul(hn::Sub(b.s1, b.s0), hn::Div(hn::Neg(b.f0), denom)));
  search.t = hn::IfThenElse(crossed, hn::IfThenElse(hn::Gt(denom, zero), cross, b.s1), search.t);
  search.t = hn::IfThenElse(agreed, t_agreed, search.t);
  search.pass(hn::AndNot(agreed, hn::AndNot(crossed, bracketed)), b.s0);
  hit = hn::Or(hit, hn::Or(crossed, agreed));
}

/// The walk of lanes [o, o + width) (see `walk_lanes`): adds its lanes hit and escaped to `out`.
HWY_INLINE void walk_part(const LaneCamera& c, const RayLanes& lanes, int o, unsigned walk, const WalkLanesResult& from,
                          float tol, WalkLanesResult& out) noexcept {
  const DF df;
  const Rays r = load_rays(lanes, o);
  const float* P = c.P;
  // a = P (o, 1), b = P (v, 0), each row summed as `depth_walk` sums it.
  const Walk h{project_row(P, r.ox, r.oy, r.oz),     project_row(P + 4, r.ox, r.oy, r.oz),
               project_row(P + 8, r.ox, r.oy, r.oz), linear_row(P, r.vx, r.vy, r.vz),
               linear_row(P + 4, r.vx, r.vy, r.vz),  linear_row(P + 8, r.vx, r.vy, r.vz)};
  const VF zero = hn::Zero(df), inf = set(__builtin_inff());
  const VF t0 = load(from.t, o);
  MF hit = hn::FirstN(df, 0), escaped = hit;
  // The interval of s where h projects inside the image in front of c.
  VF lo = t0, hi = inf;
  MF live = mask_of(walk, o);
  const VF e = set(0.499f);
  const VF W = set(static_cast<float>(c.width) - 0.5f - 1e-3f), H = set(static_cast<float>(c.height) - 0.5f - 1e-3f);
  const VF margin = mul(set(1e-6f), hn::Add(hn::Abs(h.a2), hn::Abs(h.b2)));
  clip(hn::Sub(h.a2, margin), h.b2, lo, hi, live);
  clip(hn::Add(h.a0, mul(e, h.a2)), hn::Add(h.b0, mul(e, h.b2)), lo, hi, live);
  clip(hn::Sub(mul(W, h.a2), h.a0), hn::Sub(mul(W, h.b2), h.b0), lo, hi, live);
  clip(hn::Add(h.a1, mul(e, h.a2)), hn::Add(h.b1, mul(e, h.b2)), lo, hi, live);
  clip(hn::Sub(mul(H, h.a2), h.a1), hn::Sub(mul(H, h.b2), h.b1), lo, hi, live);
  keep_in_view(lo, hi, live); // the others pass with the search unchanged
  const VF leave = hi, view = lo;
  const MF bounded_leave = hn::Lt(leave, inf);
  Search search{t0, load(from.skip_begin, o), load(from.skip_end, o), view, hn::Gt(lo, t0)};
  if (__builtin_isfinite(c.near)) {
    const MF before = live;
    clip(hn::Sub(h.a2, mul(set(c.near), set(1 - tol))), h.b2, lo, hi, live);
    keep_in_view(lo, hi, live);
    // In front of all c sees wherever c sees the ray.
    search.pass(hn::AndNot(live, before), hn::IfThenElse(bounded_leave, leave, t0));
  }
  // Pixels moved per unit s: m / z^2.
  const VF mx = hn::Sub(mul(h.b0, h.a2), mul(h.a0, h.b2));
  const VF my = hn::Sub(mul(h.b1, h.a2), mul(h.a1, h.b2));
  const VF m = hn::Sqrt(hn::Add(mul(mx, mx), mul(my, my)));
  const float smooth = 1 + 4 * tol;
  const VF tolerance = set(tol);
  const MF bounded = hn::Lt(hi, inf);
  {
    // A walk that would start inside the stretch seen free starts after it, if c still sees the
    // ray there.
    const MF inside = hn::And(live, hn::And(hn::Ge(lo, search.skip_begin), hn::Lt(lo, search.skip_end)));
    const MF beyond = hn::AndNot(hn::Lt(search.skip_end, hi), inside);
    search.pass(beyond, hn::IfThenElse(bounded_leave, leave, search.skip_end));
    live = hn::AndNot(beyond, live);
    lo = hn::IfThenElse(hn::AndNot(beyond, inside), search.skip_end, lo);
  }
  VF s = lo, z;
  VF fs = walk_f(h, c, smooth, s, live, z);
  live = hn::AndNot(search.start_behind(live, s, fs, z, tolerance, hit), live);
  // Step about a pixel at a time until f >= 0 brackets the crossing in [s, next]. Every lane
  // steps on and reads the map each step until all are done, the finished ones' results unused:
  // then no step waits for the previous step's lookups, only the lanes' masks do.
  const VF half = set(0.5f);
  Bracket b{zero, zero, zero, zero, zero, zero};
  const MF reading = live;
  MF stepping = live, bracketed = hn::FirstN(df, 0);
  for (int step = 0; !hn::AllFalse(df, stepping) && step < 1 << 16; ++step) {
    const MF out_of_view = hn::And(stepping, hn::Ge(s, hi));
    search.pass(out_of_view, hn::IfThenElse(bounded, leave, s));
    stepping = hn::AndNot(out_of_view, stepping);
    const VF zs = hn::Add(h.a2, mul(s, h.b2));
    // Toward the vanishing point, within half a pixel of it: the surface there (if any) is hit
    // where the depths agree; a map that shows nothing there lets the ray escape.
    const MF vanishing =
        hn::AndNot(bounded, hn::And(stepping, hn::Or(hn::Not(hn::Gt(m, zero)), hn::Lt(m, mul(mul(half, h.b2), zs)))));
    if (!hn::AllFalse(df, vanishing)) {
      const VF dv = hn::Sub(zs, fs); // the map's depth at s (zv = zs, fv = fs)
      const MF finite = hn::Lt(hn::Abs(dv), inf);
      const MF there = hn::And(hn::And(vanishing, finite), hn::And(hn::Gt(dv, zs), hn::Gt(h.b2, zero)));
      const MF away = hn::And(hn::AndNot(there, vanishing), hn::And(hn::Gt(zs, zero), hn::Eq(hn::Abs(dv), inf)));
      hit = hn::Or(hit, there);
      search.t = hn::IfThenElse(there, hn::Div(hn::Sub(dv, h.a2), h.b2), search.t);
      escaped = hn::Or(escaped, away);
      search.pass(hn::AndNot(away, hn::AndNot(there, vanishing)), s);
      stepping = hn::AndNot(vanishing, stepping);
    }
    const VF ahead = hn::Add(s, hn::Div(mul(zs, zs), m));
    VF next = hn::IfThenElse(bounded, hn::IfThenElse(hn::Gt(m, zero), hn::Min(ahead, hi), hi), ahead);
    // Up to the stretch seen free, then over it.
    next =
        hn::IfThenElse(hn::And(hn::Lt(s, search.skip_begin), hn::Gt(next, search.skip_begin)), search.skip_begin, next);
    VF zn;
    const VF fn = walk_f(h, c, smooth, next, reading, zn);
    const MF found = hn::And(stepping, hn::Ge(fn, zero));
    b.s0 = hn::IfThenElse(found, s, b.s0);
    b.f0 = hn::IfThenElse(found, fs, b.f0);
    b.s1 = hn::IfThenElse(found, next, b.s1);
    b.f1 = hn::IfThenElse(found, fn, b.f1);
    b.z0 = hn::IfThenElse(found, zs, b.z0);
    b.z1 = hn::IfThenElse(found, zn, b.z1);
    bracketed = hn::Or(bracketed, found);
    stepping = hn::AndNot(found, stepping);
    s = next;
    fs = fn;
    const MF skip = hn::And(stepping, hn::And(hn::Ge(s, search.skip_begin), hn::Lt(s, search.skip_end)));
    if (!hn::AllFalse(df, skip)) {
      const MF beyond = hn::AndNot(hn::Lt(search.skip_end, hi), skip);
      search.pass(beyond, hn::IfThenElse(bounded, leave, s));
      stepping = hn::AndNot(beyond, stepping);
      const MF jump = hn::AndNot(beyond, skip);
      s = hn::IfThenElse(jump, search.skip_end, s);
      VF zj;
      fs = hn::IfThenElse(jump, walk_f(h, c, smooth, s, jump, zj), fs);
      stepping = hn::AndNot(search.start_behind(jump, s, fs, zj, tolerance, hit), stepping);
    }
  }
  search.pass(stepping, hn::IfThenElse(bounded, leave, s)); // out of steps
  narrow(h, c, smooth, tol, bracketed, b, search, hit);
  const unsigned hits = bits_of(hit, o), escapes = bits_of(escaped, o);
  out.hit |= hits;
  out.escaped |= escapes;
  hn::StoreU(search.t, df, out.t + o);
  hn::StoreU(search.skip_begin, df, out.skip_begin + o);
  hn::StoreU(search.skip_end, df, out.skip_end + o);
}

/// Walks the rays `lanes` of the lanes in `walk` through camera `c`'s depth map, each lane l
/// from the search {from.t[l], from.skip_begin[l], from.skip_end[l]} (a first camera: t = -inf
/// for the whole line, 0 for the half-line, no stretch: +inf, +inf), exactly as `depth_walk`
/// does (see the file comment), and says how each walk ended.
inline void walk_lanes(const LaneCamera& c, const RayLanes& lanes, unsigned walk, const WalkLanesResult& from,
                       float tolerance, WalkLanesResult& out) noexcept {
  out.hit = out.escaped = 0;
  for (int o = 0; o < kDepthLanes; o += width()) {
    if (((walk >> o) & ((1u << width()) - 1u)) == 0) {
      for (int l = o; l < o + width(); ++l) {
        out.t[l] = from.t[l];
        out.skip_begin[l] = from.skip_begin[l];
        out.skip_end[l] = from.skip_end[l];
      }
      continue;
    }
    walk_part(c, lanes, o, walk, from, tolerance, out);
  }
  out.passed = walk & ~(out.hit | out.escaped);
}
