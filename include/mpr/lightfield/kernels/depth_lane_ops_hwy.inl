// No #pragma once, no includes: kernels/depth_lanes_hwy.hpp includes this file once per
// Highway target, inside a namespace of its own with `hn` naming Highway's ops of that target.
/// \file
/// The ops of the depth lanes and the scan and choice kernels (see kernels/depth_lanes_hwy.hpp),
/// the body shared by every target.

using detail::kDepthLanes;
using detail::kDepthLaneSlots;
using detail::LaneCamera;
using detail::LaneChoice;
using detail::RayLanes;
using detail::WalkLanesResult;
using detail::WeighCamera;

/// The float and int32 vectors of this target (at most sixteen lanes).
using DF = hn::CappedTag<float, 16>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;

/// Lanes per vector here.
HWY_INLINE int width() noexcept { return static_cast<int>(hn::Lanes(DF())); }

/// The mask of lanes [o, o + width) of the bits `bits` (bit l: lane l).
HWY_INLINE MF mask_of(unsigned bits, int o) noexcept {
  const unsigned part = (bits >> o) & ((1u << width()) - 1u);
  const std::uint8_t b[8] = {static_cast<std::uint8_t>(part), static_cast<std::uint8_t>(part >> 8)};
  return hn::LoadMaskBits(DF(), b);
}

/// The bits of `m` placed at lanes [o, o + width).
HWY_INLINE unsigned bits_of(MF m, int o) noexcept {
  std::uint8_t b[8] = {};
  hn::StoreMaskBits(DF(), m, b);
  return (static_cast<unsigned>(b[0]) | static_cast<unsigned>(b[1]) << 8) << o;
}

/// a x b, lane by lane, never fused with an addition: the product leaves through an empty asm,
/// which the compiler cannot see into (the per-ray code, built without FMA, rounds each product).
HWY_INLINE VF mul(VF a, VF b) noexcept {
  VF p = hn::Mul(a, b);
  asm("" : "+v"(p.raw));
  return p;
}

HWY_INLINE VF set(float v) noexcept { return hn::Set(DF(), v); }
HWY_INLINE VF load(const float* p, int o) noexcept { return hn::LoadU(DF(), p + o); }

/// a + (b + c): the order in which Eigen sums a fixed-size 3-vector's dot product or squared norm.
HWY_INLINE VF sum3(VF a, VF b, VF c) noexcept { return hn::Add(a, hn::Add(b, c)); }

/// (p[0] x + p[1] y) + p[2] z: one row of a projection applied to directions, as the per-ray
/// code adds it; `project_row` adds p[3] for points.
HWY_INLINE VF linear_row(const float* p, VF x, VF y, VF z) noexcept {
  return hn::Add(hn::Add(mul(set(p[0]), x), mul(set(p[1]), y)), mul(set(p[2]), z));
}
HWY_INLINE VF project_row(const float* p, VF x, VF y, VF z) noexcept {
  return hn::Add(linear_row(p, x, y, z), set(p[3]));
}

/// The rays of lanes [o, o + width).
struct Rays {
  VF ox, oy, oz, vx, vy, vz, inverse_length2, length;
};
HWY_INLINE Rays load_rays(const RayLanes& r, int o) noexcept {
  return {load(r.ox, o),
          load(r.oy, o),
          load(r.oz, o),
          load(r.vx, o),
          load(r.vy, o),
          load(r.vz, o),
          load(r.inverse_length2, o),
          load(r.length, o)};
}

/// |(c - o) x v|^2 / |v|^2: the squared distance from the point c to each ray line
/// (`line_distance2`).
HWY_INLINE VF line_distance2(const Rays& r, float cx, float cy, float cz) noexcept {
  const VF ax = hn::Sub(set(cx), r.ox), ay = hn::Sub(set(cy), r.oy), az = hn::Sub(set(cz), r.oz);
  const VF x = hn::Sub(mul(ay, r.vz), mul(az, r.vy));
  const VF y = hn::Sub(mul(az, r.vx), mul(ax, r.vz));
  const VF z = hn::Sub(mul(ax, r.vy), mul(ay, r.vx));
  return mul(sum3(mul(x, x), mul(y, y), mul(z, z)), r.inverse_length2);
}

/// `depth_lookup` of map d (`width` x `height`, fewer than 2^31 pixels) at (x, y) in every lane
/// (`smooth` = 1 + 4 x the tolerance): clamped to [-1, size] first as the scalar lookup is, so
/// every lane reads inside the map.
HWY_INLINE VF depth_lookup(const float* d, int width, int height, VF x, VF y, float smooth) noexcept {
  const DF df;
  const DI di;
  x = hn::IfThenElse(hn::Ge(x, set(-1)), hn::Min(x, set(static_cast<float>(width))), set(-1));
  y = hn::IfThenElse(hn::Ge(y, set(-1)), hn::Min(y, set(static_cast<float>(height))), set(-1));
  const VF fx = hn::Floor(x), fy = hn::Floor(y);
  const VI x0 = hn::ConvertTo(di, fx), y0 = hn::ConvertTo(di, fy);
  const VI zero = hn::Zero(di), one = hn::Set(di, 1);
  const VI xm = hn::Set(di, width - 1), ym = hn::Set(di, height - 1), w = hn::Set(di, width);
  const VI xa = hn::Min(hn::Max(x0, zero), xm), xb = hn::Min(hn::Max(hn::Add(x0, one), zero), xm);
  const VI ra = hn::Mul(hn::Min(hn::Max(y0, zero), ym), w);
  const VI rb = hn::Mul(hn::Min(hn::Max(hn::Add(y0, one), zero), ym), w);
  const VF d00 = hn::GatherIndex(df, d, hn::Add(ra, xa)), d10 = hn::GatherIndex(df, d, hn::Add(ra, xb));
  const VF d01 = hn::GatherIndex(df, d, hn::Add(rb, xa)), d11 = hn::GatherIndex(df, d, hn::Add(rb, xb));
  const VF lo = hn::Min(hn::Min(d00, d10), hn::Min(d01, d11));
  const VF hi = hn::Max(hn::Max(d00, d10), hn::Max(d01, d11));
  const VF ax = hn::Sub(x, fx), ay = hn::Sub(y, fy);
  const VF bx = hn::Sub(set(1), ax), by = hn::Sub(set(1), ay);
  const VF top = hn::Add(mul(d00, bx), mul(d10, ax)), bottom = hn::Add(mul(d01, bx), mul(d11, ax));
  const VF bilinear = hn::Add(mul(top, by), mul(bottom, ay));
  const MF right = hn::Not(hn::Lt(ax, set(0.5f))), lower = hn::Not(hn::Lt(ay, set(0.5f)));
  const VF nearest = hn::IfThenElse(lower, hn::IfThenElse(right, d11, d01), hn::IfThenElse(right, d10, d00));
  const MF even = hn::And(hn::Lt(hi, set(__builtin_inff())), hn::Le(hi, mul(lo, set(smooth))));
  return hn::IfThenElse(even, bilinear, nearest);
}

/// `unit_acos` in lanes, the same operations in the same order.
HWY_INLINE VF unit_acos(VF x) noexcept {
  const MF high = hn::Ge(x, set(0.5f));
  const VF z = hn::IfThenElse(high, mul(hn::Sub(set(1), x), set(0.5f)), mul(x, x));
  const VF s = hn::IfThenElse(high, hn::Sqrt(z), x);
  VF p = set(detail::kAsinP[0]);
  for (int i = 1; i < 5; ++i) p = hn::Add(mul(p, z), set(detail::kAsinP[i]));
  const VF a = hn::Add(s, mul(mul(s, z), p));
  return hn::IfThenElse(high, mul(set(2), a), hn::Sub(set(1.57079632679489662f), a));
}

/// For each camera i of `cameras` (`count` of them): near[i] = the lanes of `valid` whose ray
/// line passes within sqrt(radius2) of its centre, distance[i][l] = that distance (every lane);
/// first[l] = the nearest of those cameras to lane l's line (the lowest index among equals), or -1.
inline void scan_cameras(const LaneCamera* cameras, std::size_t count, const RayLanes& lanes, float radius2,
                         unsigned valid, std::uint16_t* near, float (*distance)[16], int* first) noexcept {
  const DI di;
  for (std::size_t i = 0; i < count; ++i) near[i] = 0;
  for (int o = 0; o < kDepthLanes; o += width()) {
    const Rays r = load_rays(lanes, o);
    const MF valid_here = mask_of(valid, o);
    VF best = set(__builtin_inff());
    VI nearest = hn::Set(di, -1);
    for (std::size_t i = 0; i < count; ++i) {
      const LaneCamera& c = cameras[i];
      const VF d2 = line_distance2(r, c.cx, c.cy, c.cz);
      const MF m = hn::And(valid_here, hn::Lt(d2, set(radius2)));
      const VF d = hn::Sqrt(d2);
      hn::StoreU(d, DF(), distance[i] + o);
      if (hn::AllFalse(DF(), m)) continue;
      near[i] = static_cast<std::uint16_t>(near[i] | bits_of(m, o));
      const MF nearer = hn::And(m, hn::Lt(d, best));
      best = hn::IfThenElse(nearer, d, best);
      nearest = hn::IfThenElse(hn::RebindMask(di, nearer), hn::Set(di, static_cast<int>(i)), nearest);
    }
    hn::StoreU(nearest, di, first + o);
  }
}

/// The cameras a lane keeps, best first (see `slot_before`): cosine of the angle to the ray,
/// clamped to 1 (-inf in an empty slot), whether the cosine as computed exceeded 1 (`over`), the
/// camera (-1: empty), its distance from the ray line and its pixel (x, y).
struct Slots {
  VF cosine[kDepthLaneSlots], distance[kDepthLaneSlots], x[kDepthLaneSlots], y[kDepthLaneSlots];
  VI camera[kDepthLaneSlots];
  MF over[kDepthLaneSlots];
};

/// The lanes where a camera with cosine `cs` (clamped), `over`, distance `d` and index `camera`
/// goes before the one in slot j. `DepthProxy::blend` sorts its candidates, taken by increasing
/// (distance, index), by insertion, comparing each new cosine as computed with the clamped ones
/// kept: so cosines above 1 come first, the later candidate first among them, then the others by
/// decreasing cosine, the earlier candidate first among equals. This is that order.
HWY_INLINE MF slot_before(const Slots& s, int j, VF cs, MF over, VF d, VI camera) noexcept {
  const DF df;
  const MF same = hn::Eq(d, s.distance[j]);
  const MF nearer = hn::Or(hn::Lt(d, s.distance[j]), hn::And(same, hn::RebindMask(df, hn::Lt(camera, s.camera[j]))));
  const MF farther = hn::Or(hn::Gt(d, s.distance[j]), hn::And(same, hn::RebindMask(df, hn::Gt(camera, s.camera[j]))));
  const MF larger = hn::Or(hn::Gt(cs, s.cosine[j]), hn::And(hn::Eq(cs, s.cosine[j]), nearer));
  const MF y = s.over[j];
  return hn::Or(hn::Or(hn::And(hn::And(over, y), farther), hn::AndNot(y, over)),
                hn::AndNot(over, hn::AndNot(y, larger)));
}

/// Inserts `camera` with cosines `cs` (clamped; `over`: where it was above 1), distances `d` and
/// pixels (x, y) into the lanes of `m`, keeping the first `slots` in the order of `slot_before`.
HWY_INLINE void insert_slots(Slots& s, int slots, MF m, VF cs, MF over, VF d, int camera, VF x, VF y) noexcept {
  const DI di;
  VI cam = hn::Set(di, camera);
  MF shifting = hn::FirstN(DF(), 0); // lanes that placed their entry: the rest moves down a slot
  for (int j = 0; j < slots && !hn::AllFalse(DF(), m); ++j) {
    const MF swap = hn::And(m, hn::Or(shifting, slot_before(s, j, cs, over, d, cam)));
    shifting = hn::Or(shifting, swap);
    const VF c0 = s.cosine[j], d0 = s.distance[j], x0 = s.x[j], y0 = s.y[j];
    const VI k0 = s.camera[j];
    const MF o0 = s.over[j];
    const auto swap_i = hn::RebindMask(di, swap);
    s.cosine[j] = hn::IfThenElse(swap, cs, c0);
    s.distance[j] = hn::IfThenElse(swap, d, d0);
    s.x[j] = hn::IfThenElse(swap, x, x0);
    s.y[j] = hn::IfThenElse(swap, y, y0);
    s.camera[j] = hn::IfThenElse(swap_i, cam, k0);
    s.over[j] = hn::Or(hn::AndNot(swap, o0), hn::And(swap, over));
    cs = hn::IfThenElse(swap, c0, cs);
    d = hn::IfThenElse(swap, d0, d);
    x = hn::IfThenElse(swap, x0, x);
    y = hn::IfThenElse(swap, y0, y);
    cam = hn::IfThenElse(swap_i, k0, cam);
    over = hn::Or(hn::AndNot(swap, over), hn::And(swap, o0));
    // A lane whose displaced entry was empty is done.
    m = hn::AndNot(hn::And(swap, hn::RebindMask(DF(), hn::Eq(cam, hn::Set(di, -1)))), m);
  }
}

/// The blend's choice of cameras for the points `point` (x, y, z rows) of the rays `lanes`, in
/// the lanes of `blended`: the cameras `order[0, count)` (each tried for the lanes of its `near`
/// bits, at `distance[i]` from each ray line) -- in front of the ray (positive cosine),
/// projecting the point inside its image, its depth map there not nearer than the point's depth
/// by more than the relative `tolerance` -- and the `slots` with the largest cosines kept per
/// lane (`LaneChoice`, camera -1 in an empty slot), as `DepthProxy::blend` chooses them.
inline void choose_cameras(const LaneCamera* cameras, const RayLanes& lanes, const float (*point)[16],
                           const float (*distance)[16], const std::uint16_t* near, unsigned blended, const int* order,
                           int count, int slots, float tolerance, LaneChoice& out) noexcept {
  const DF df;
  const DI di;
  const float smooth = 1 + 4 * tolerance;
  const VF keep = set(1 - tolerance), zero = hn::Zero(df), edge = set(-0.5f), inf = set(__builtin_inff());
  const VF one = set(1);
  for (int o = 0; o < kDepthLanes; o += width()) {
    const Rays r = load_rays(lanes, o);
    const VF X = load(point[0], o), Y = load(point[1], o), Z = load(point[2], o);
    Slots best;
    for (int j = 0; j < slots; ++j) {
      best.cosine[j] = set(-__builtin_inff());
      best.distance[j] = best.x[j] = best.y[j] = zero;
      best.camera[j] = hn::Set(di, -1);
      best.over[j] = hn::FirstN(df, 0);
    }
    // First every camera's cosines, pixels and visibility, each camera apart from the others (so
    // that the depth lookups of several cameras are in flight at once), then the choice in order.
    HWY_ALIGN_MAX float cosine[64][16], px[64][16], py[64][16];
    MF seen[64], above[64];
    for (int c = 0; c < count; ++c) {
      const std::size_t i = static_cast<std::size_t>(order[c]);
      MF m = mask_of(near[i] & blended, o);
      seen[c] = hn::FirstN(df, 0);
      above[c] = seen[c];
      if (hn::AllFalse(df, m)) continue;
      const LaneCamera& cam = cameras[i];
      const VF tx = hn::Sub(X, set(cam.cx)), ty = hn::Sub(Y, set(cam.cy)), tz = hn::Sub(Z, set(cam.cz));
      const VF dot = sum3(mul(tx, r.vx), mul(ty, r.vy), mul(tz, r.vz));
      const VF norm = hn::Sqrt(sum3(mul(tx, tx), mul(ty, ty), mul(tz, tz)));
      const VF raw = hn::Div(dot, mul(norm, r.length));
      m = hn::And(m, hn::Gt(raw, zero));
      if (hn::AllFalse(df, m)) continue;
      hn::Store(hn::Min(raw, one), df, cosine[c]);
      above[c] = hn::Gt(raw, one);
      // `FrameTable::project`: in front, finite, inside the image.
      const float* P = cam.P;
      const VF w = project_row(P + 8, X, Y, Z);
      m = hn::And(m, hn::Gt(w, zero));
      if (hn::AllFalse(df, m)) continue;
      const VF inv = hn::IfThenElseZero(m, hn::Div(one, w));
      const VF x = mul(project_row(P, X, Y, Z), inv), y = mul(project_row(P + 4, X, Y, Z), inv);
      m = hn::And(m, hn::And(hn::And(hn::Ge(x, edge), hn::Ge(y, edge)),
                             hn::And(hn::Lt(x, set(static_cast<float>(cam.width) - 0.5f)),
                                     hn::Lt(y, set(static_cast<float>(cam.height) - 0.5f)))));
      m = hn::And(m, hn::And(hn::Lt(hn::Abs(x), inf), hn::Lt(hn::Abs(y), inf)));
      if (hn::AllFalse(df, m)) continue;
      hn::Store(x, df, px[c]);
      hn::Store(y, df, py[c]);
      // Visible unless the map shows something nearer by more than the tolerance.
      const VF depth = depth_lookup(cam.depth, cam.width, cam.height, x, y, smooth);
      seen[c] = hn::And(m, hn::Not(hn::Lt(depth, mul(w, keep))));
    }
    for (int c = 0; c < count; ++c) {
      MF m = seen[c];
      if (hn::AllFalse(df, m)) continue;
      const int i = order[c];
      const VF cs = hn::Load(df, cosine[c]), d = load(distance[i], o);
      // Lanes whose slots are full of cameras that go before this one do not need it.
      m = hn::And(m, hn::Or(hn::RebindMask(df, hn::Eq(best.camera[slots - 1], hn::Set(di, -1))),
                            slot_before(best, slots - 1, cs, above[c], d, hn::Set(di, i))));
      if (hn::AllFalse(df, m)) continue;
      insert_slots(best, slots, m, cs, above[c], d, i, hn::Load(df, px[c]), hn::Load(df, py[c]));
    }
    for (int j = 0; j < slots; ++j) {
      hn::StoreU(unit_acos(best.cosine[j]), df, out.penalty[j] + o);
      hn::StoreU(best.x[j], df, out.x[j] + o);
      hn::StoreU(best.y[j], df, out.y[j] + o);
      hn::StoreU(best.camera[j], di, out.camera[j] + o);
    }
  }
}
