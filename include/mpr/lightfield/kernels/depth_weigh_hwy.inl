// No #pragma once, no includes: kernels/depth_lanes_hwy.hpp includes this file once per Highway
// target, after kernels/depth_lane_ops_hwy.inl (the ops used here).
/// \file
/// The blend of `DepthProxy`'s batch path for 8-bit frames, sixteen rays at once: the
/// Unstructured-Lumigraph weights of each ray's chosen cameras (`DepthProxy::weigh`) and their
/// bilinear texels (`FrameTable::fetch_add`). The weights and tap positions go in lanes; the
/// texels of each lane's camera are read and decoded to linear light per lane (the lanes'
/// cameras differ). Every sum is formed in the per-ray code's order with no fused multiply-add.

/// acc[c][l] and weight[l] for the lanes l of `lanes`: `DepthProxy::weigh` of lane l's chosen
/// cameras `choice` (slots [0, slots) filled from the first, by increasing penalty; camera -1 in
/// the empty ones) with k blended, each camera's texels bilinear at its pixel
/// (`FrameTable::fetch_add` with the bilinear filter, `scale` the texel scale, `lut` the 16-bit
/// decode table). `cameras[i]` describes camera i. Other lanes: zero.
inline void weigh_lanes(const WeighCamera* cameras, const LaneChoice& choice, int slots, int k, unsigned lanes,
                        const std::uint16_t* lut, float scale, float (*acc)[16], float* weight) noexcept {
  const DF df;
  const DI di;
  const VF zero = hn::Zero(df), one = set(1.0f), tiny = set(1e-6f);
  const VI none = hn::Set(di, -1), ione = hn::Set(di, 1), izero = hn::Zero(di);
  for (int o = 0; o < kDepthLanes; o += width()) {
    const MF here = mask_of(lanes, o);
    // The threshold per lane: the (k+1)-th smallest penalty when more than k cameras see the
    // point, else twice the largest (the last filled slot's).
    MF filled[kDepthLaneSlots];
    VF last = zero;
    for (int j = 0; j < slots; ++j) {
      filled[j] = hn::And(here, hn::RebindMask(df, hn::Ne(hn::LoadU(di, choice.camera[j] + o), none)));
      last = hn::IfThenElse(filled[j], load(choice.penalty[j], o), last);
    }
    VF threshold = hn::Add(mul(set(2.0f), last), tiny);
    if (k < slots) threshold = hn::IfThenElse(filled[k], hn::Max(load(choice.penalty[k], o), tiny), threshold);
    VF sum[3] = {zero, zero, zero}, total = zero;
    for (int j = 0; j < slots; ++j) {
      const VF p = load(choice.penalty[j], o);
      const MF m = hn::And(filled[j], hn::Lt(p, threshold));
      if (hn::AllFalse(df, m)) continue;
      // (1 - p / threshold) / (p + 1e-6), as `weigh` computes it.
      const VF w = hn::Div(hn::Sub(one, hn::Div(p, threshold)), hn::Add(p, tiny));
      total = hn::IfThenElse(m, hn::Add(total, w), total);
      // Each lane's camera size.
      HWY_ALIGN_MAX int wide[16], high[16];
      const unsigned bits = bits_of(m, 0);
      for (int l = 0; l < width(); ++l) {
        const int i = (bits >> l & 1u) != 0 ? choice.camera[j][o + l] : -1;
        wide[l] = i >= 0 ? cameras[i].width : 1;
        high[l] = i >= 0 ? cameras[i].height : 1;
      }
      const VI wv = hn::Load(di, wide), hv = hn::Load(di, high);
      const VF x = hn::IfThenElseZero(m, load(choice.x[j], o)), y = hn::IfThenElseZero(m, load(choice.y[j], o));
      const VF fx = hn::Floor(x), fy = hn::Floor(y);
      const VF ax = hn::Sub(x, fx), ay = hn::Sub(y, fy);
      const VI x0 = hn::ConvertTo(di, fx), y0 = hn::ConvertTo(di, fy);
      const VI xa = hn::Max(x0, izero), xb = hn::Min(hn::Add(x0, ione), hn::Sub(wv, ione));
      const VI ya = hn::Mul(hn::Max(y0, izero), wv), yb = hn::Mul(hn::Min(hn::Add(y0, ione), hn::Sub(hv, ione)), wv);
      // fetch_add: w00 = (1 - ax) (1 - ay) s, ..., acc += w00 v00 + w10 v10 + w01 v01 + w11 v11.
      const VF s = mul(w, set(scale));
      const VF bx = hn::Sub(one, ax), by = hn::Sub(one, ay);
      const VF tap_weight[4] = {mul(mul(bx, by), s), mul(mul(ax, by), s), mul(mul(bx, ay), s), mul(mul(ax, ay), s)};
      HWY_ALIGN_MAX int tap[4][16];
      hn::Store(hn::Add(ya, xa), di, tap[0]);
      hn::Store(hn::Add(ya, xb), di, tap[1]);
      hn::Store(hn::Add(yb, xa), di, tap[2]);
      hn::Store(hn::Add(yb, xb), di, tap[3]);
      // The texels of each lane's camera, decoded to linear light (0 in the other lanes).
      HWY_ALIGN_MAX float value[4][3][16] = {};
      for (unsigned b = bits; b != 0; b &= b - 1) {
        const int l = __builtin_ctz(b);
        const std::uint8_t* texels = cameras[choice.camera[j][o + l]].texels;
        for (int t = 0; t < 4; ++t) {
          const std::uint8_t* v = texels + 3 * static_cast<std::ptrdiff_t>(tap[t][l]);
          for (int c = 0; c < 3; ++c) value[t][c][l] = static_cast<float>(lut[v[c]]);
        }
      }
      for (int c = 0; c < 3; ++c) {
        VF part = mul(tap_weight[0], hn::Load(df, value[0][c]));
        for (int t = 1; t < 4; ++t) part = hn::Add(part, mul(tap_weight[t], hn::Load(df, value[t][c])));
        sum[c] = hn::IfThenElse(m, hn::Add(sum[c], part), sum[c]);
      }
    }
    for (int c = 0; c < 3; ++c) hn::StoreU(sum[c], df, acc[c] + o);
    hn::StoreU(total, df, weight + o);
  }
}
