// The body of the projective-row kernel for one Highway target: kernels/projective_row_hwy.hpp
// includes it once per target, in a namespace of its own with `hn` naming that target's ops.
// No include guard (included once per target); no includes (the including header has them).

using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;

/// 8-bit codes in 32-bit lanes to their decode-table values as floats: one gather from the table
/// as 256 floats.
class TableDecode {
public:
  explicit TableDecode(const std::uint16_t* lut) noexcept {
    for (std::size_t c = 0; c < 256; ++c) table_[c] = lut[c];
  }
  HWY_INLINE hn::Vec<DF> operator()(hn::Vec<DI> code) const noexcept { return hn::GatherIndex(DF(), table_, code); }

private:
  HWY_ALIGN float table_[256];
};

/// The same values as arithmetic, without lookups in memory: the piecewise cubic of
/// `kSrgbCubic` (kernels/lerp_row_hwy.hpp), for the table it reproduces (`srgb_cubic_matches`),
/// its eight segments' coefficients picked by a lane permute (targets of 8 float lanes or more).
class CubicDecode {
public:
  CubicDecode() noexcept {
    HWY_ALIGN float lanes[5][hn::MaxLanes(DF())];
    for (std::size_t i = 0; i < hn::MaxLanes(DF()); ++i) {
      lanes[0][i] = kSrgbStart[i % kSrgbSegments];
      for (std::size_t k = 0; k < 4; ++k) lanes[k + 1][i] = kSrgbCubic[k][i % kSrgbSegments];
    }
    const DF df;
    start_ = hn::Load(df, lanes[0]);
    c0_ = hn::Load(df, lanes[1]);
    c1_ = hn::Load(df, lanes[2]);
    c2_ = hn::Load(df, lanes[3]);
    c3_ = hn::Load(df, lanes[4]);
  }
  HWY_INLINE hn::Vec<DF> operator()(hn::Vec<DI> code) const noexcept {
    const DF df;
    const DI di;
    const auto seg = hn::Min(hn::ShiftRight<5>(hn::Add(code, hn::Set(di, 21))), hn::Set(di, 7));
    const auto idx = hn::IndicesFromVec(df, seg);
    const auto t = hn::Sub(hn::ConvertTo(df, code), hn::TableLookupLanes(start_, idx));
    auto v = hn::MulAdd(hn::TableLookupLanes(c3_, idx), t, hn::TableLookupLanes(c2_, idx));
    v = hn::MulAdd(v, t, hn::TableLookupLanes(c1_, idx));
    v = hn::MulAdd(v, t, hn::TableLookupLanes(c0_, idx));
    return hn::Round(v);
  }

private:
  hn::Vec<DF> start_, c0_, c1_, c2_, c3_;
};

/// Float channels need no decode.
struct NoDecode {};

/// 8-bit texels read from their 16-bit linear copy (`ProjectiveRow::linear`): the values are
/// the decoded ones, gathered two channels a 32-bit word.
struct LinearTexels {};

/// sum[k] += weight x channel k of the texels at channel offsets `offset`: 8-bit codes by one
/// 32-bit gather per texel (its r g b and the byte past them), decoded together; their 16-bit
/// linear copy (`LinearTexels`) by two; float channels by one gather per channel.
template <class C, class Decode>
HWY_INLINE void projective_tap(const C* HWY_RESTRICT texels, const Decode& decode, hn::Vec<DI> offset,
                               hn::Vec<DF> weight, hn::Vec<DF> (&sum)[3]) noexcept {
  const DF df;
  const DI di;
  if constexpr (std::is_same_v<C, std::uint8_t>) {
    const auto word = hn::GatherOffset(di, reinterpret_cast<const std::int32_t*>(texels), offset);
    const auto byte = hn::Set(di, 0xFF);
    sum[0] = hn::MulAdd(weight, decode(hn::And(word, byte)), sum[0]);
    sum[1] = hn::MulAdd(weight, decode(hn::And(hn::ShiftRight<8>(word), byte)), sum[1]);
    sum[2] = hn::MulAdd(weight, decode(hn::And(hn::ShiftRight<16>(word), byte)), sum[2]);
  } else if constexpr (std::is_same_v<Decode, LinearTexels>) {
    // Channel offset o is byte 2 o of the 16-bit copy: r g in one word, b (and the next
    // texel's r, or padding) in the next.
    const auto at = hn::Add(offset, offset);
    const auto rg = hn::GatherOffset(di, reinterpret_cast<const std::int32_t*>(texels), at);
    const auto b = hn::GatherOffset(di, reinterpret_cast<const std::int32_t*>(texels), hn::Add(at, hn::Set(di, 4)));
    const auto low = hn::Set(di, 0xFFFF);
    sum[0] = hn::MulAdd(weight, hn::ConvertTo(df, hn::And(rg, low)), sum[0]);
    sum[1] = hn::MulAdd(weight, hn::ConvertTo(df, hn::And(hn::ShiftRight<16>(rg), low)), sum[1]);
    sum[2] = hn::MulAdd(weight, hn::ConvertTo(df, hn::And(b, low)), sum[2]);
  } else {
    (void)decode;
    for (int k = 0; k < 3; ++k)
      sum[k] = hn::MulAdd(weight, hn::GatherIndex(df, texels, hn::Add(offset, hn::Set(di, k))), sum[k]);
  }
}

/// Asks for the texel rows of the points from t on (their first and second tap rows, every
/// second lane): a tilted or scaled row walks across camera rows, which the hardware prefetcher
/// does not follow.
template <class Row, class P>
HWY_INLINE void projective_prefetch(const Row& r, const P* texels, hn::Vec<DF> t) noexcept {
  const DF df;
  const DI di;
  const auto inv = hn::ApproximateReciprocal(hn::MulAdd(t, hn::Set(df, r.hs[2]), hn::Set(df, r.h0[2])));
  auto x = hn::Mul(hn::MulAdd(t, hn::Set(df, r.hs[0]), hn::Set(df, r.h0[0])), inv);
  auto y = hn::Mul(hn::MulAdd(t, hn::Set(df, r.hs[1]), hn::Set(df, r.h0[1])), inv);
  x = hn::Min(hn::Max(x, hn::Zero(df)), hn::Set(df, static_cast<float>(r.width - 1)));
  y = hn::Min(hn::Max(y, hn::Zero(df)), hn::Set(df, static_cast<float>(r.height - 1)));
  const auto off =
      hn::Add(hn::Mul(hn::ConvertTo(di, y), hn::Set(di, 3 * r.width)), hn::Mul(hn::ConvertTo(di, x), hn::Set(di, 3)));
  HWY_ALIGN std::int32_t o[hn::MaxLanes(DI())];
  hn::Store(off, di, o);
  for (std::size_t l = 0; l < hn::Lanes(di); l += 2) {
    __builtin_prefetch(texels + o[l]);
    __builtin_prefetch(texels + o[l] + 3 * r.width);
  }
}

/// The channels `Decode` reads: the 16-bit linear copy for `LinearTexels`, else the texels.
template <class Row, class Decode>
HWY_INLINE auto texels_of(const Row& r, const Decode&) noexcept {
  if constexpr (std::is_same_v<Decode, LinearTexels>)
    return r.linear;
  else
    return r.texels;
}

/// One vector of points from i on (`live` of them: the rest are past the row's end): weights at
/// rw (nullptr: 1 each), acc (3 floats a point, interleaved) and seen (a float a point) read and
/// written a whole vector wide. The test of `projective_row_portable`; lanes the camera does not
/// see get zero weights and in-range texel offsets, so every gather reads inside the image, and
/// keep their acc and seen.
template <class Row, class Decode>
HWY_INLINE void projective_step(const Row& r, const Decode& decode, std::size_t i, std::size_t live,
                                const float* HWY_RESTRICT rw, float* HWY_RESTRICT acc,
                                float* HWY_RESTRICT seen) noexcept {
  const DF df;
  const DI di;
  const auto zero = hn::Zero(df), one = hn::Set(df, 1.0f), lo = hn::Set(df, -0.5f);
  const auto t = hn::Add(hn::Set(df, static_cast<float>(i)), hn::Iota(df, 0.0f));
  const auto w = hn::MulAdd(t, hn::Set(df, r.hs[2]), hn::Set(df, r.h0[2]));
  const auto x = hn::Div(hn::MulAdd(t, hn::Set(df, r.hs[0]), hn::Set(df, r.h0[0])), w);
  const auto y = hn::Div(hn::MulAdd(t, hn::Set(df, r.hs[1]), hn::Set(df, r.h0[1])), w);
  const auto wt = rw != nullptr ? hn::LoadU(df, rw) : one;
  auto m = hn::And(hn::FirstN(df, live), hn::And(w > zero, wt > zero));
  m = hn::And(m, hn::And(x >= lo, x < hn::Set(df, static_cast<float>(r.width) - 0.5f)));
  m = hn::And(m, hn::And(y >= lo, y < hn::Set(df, static_cast<float>(r.height) - 0.5f)));
  if (hn::AllFalse(df, m)) return;
  const auto xs = hn::IfThenElseZero(m, x), ys = hn::IfThenElseZero(m, y);
  const auto fx = hn::Floor(xs), fy = hn::Floor(ys);
  const auto ax = hn::Sub(xs, fx), ay = hn::Sub(ys, fy);
  const auto x0 = hn::ConvertTo(di, fx), y0 = hn::ConvertTo(di, fy);
  const auto ione = hn::Set(di, 1), izero = hn::Zero(di), three = hn::Set(di, 3), stride = hn::Set(di, 3 * r.width);
  const auto xa = hn::Mul(hn::Max(x0, izero), three);
  const auto xb = hn::Mul(hn::Min(hn::Add(x0, ione), hn::Set(di, r.width - 1)), three);
  const auto ya = hn::Mul(hn::Max(y0, izero), stride);
  const auto yb = hn::Mul(hn::Min(hn::Add(y0, ione), hn::Set(di, r.height - 1)), stride);
  const auto s = hn::IfThenElseZero(m, hn::Mul(wt, hn::Set(df, r.scale)));
  const auto bx = hn::Sub(one, ax), by = hn::Sub(one, ay);
  hn::Vec<DF> sum[3] = {zero, zero, zero};
  const auto* texels = texels_of(r, decode);
  projective_tap(texels, decode, hn::Add(ya, xa), hn::Mul(hn::Mul(bx, by), s), sum);
  projective_tap(texels, decode, hn::Add(ya, xb), hn::Mul(hn::Mul(ax, by), s), sum);
  projective_tap(texels, decode, hn::Add(yb, xa), hn::Mul(hn::Mul(bx, ay), s), sum);
  projective_tap(texels, decode, hn::Add(yb, xb), hn::Mul(hn::Mul(ax, ay), s), sum);
  hn::Vec<DF> a0, a1, a2;
  hn::LoadInterleaved3(df, acc, a0, a1, a2);
  hn::StoreInterleaved3(hn::IfThenElse(m, hn::Add(a0, sum[0]), a0), hn::IfThenElse(m, hn::Add(a1, sum[1]), a1),
                        hn::IfThenElse(m, hn::Add(a2, sum[2]), a2), df, acc);
  const auto v = hn::LoadU(df, seen);
  hn::StoreU(hn::IfThenElse(m, hn::Add(v, wt), v), df, seen);
}

/// Points ahead of the current ones whose texels are prefetched.
inline constexpr std::size_t kProjectiveAhead = 32;

/// `projective_row_portable` over [0, n) for float coordinates at this target, a vector of
/// points at a time; the last, partial vector goes through stack copies of its weights and sums,
/// so nothing outside [0, n) is read or written.
template <class Row, class Decode>
void projective_row_lanes(const Row& r, const Decode& decode, std::size_t n, const float* HWY_RESTRICT rw,
                          float* HWY_RESTRICT acc, float* HWY_RESTRICT seen) noexcept {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes) {
    projective_prefetch(r, texels_of(r, decode),
                        hn::Add(hn::Set(df, static_cast<float>(i + kProjectiveAhead)), hn::Iota(df, 0.0f)));
    projective_step(r, decode, i, lanes, rw != nullptr ? rw + i : nullptr, acc + 3 * i, seen + i);
  }
  if (i == n) return;
  const std::size_t live = n - i;
  HWY_ALIGN float w[hn::MaxLanes(DF())] = {}, a[3 * hn::MaxLanes(DF())] = {}, v[hn::MaxLanes(DF())] = {};
  for (std::size_t l = 0; l < live; ++l) {
    if (rw != nullptr) w[l] = rw[i + l];
    v[l] = seen[i + l];
    for (std::size_t k = 0; k < 3; ++k) a[3 * l + k] = acc[3 * (i + l) + k];
  }
  projective_step(r, decode, i, live, rw != nullptr ? w : nullptr, a, v);
  for (std::size_t l = 0; l < live; ++l) {
    seen[i + l] = v[l];
    for (std::size_t k = 0; k < 3; ++k) acc[3 * (i + l) + k] = a[3 * l + k];
  }
}

/// The kernel at this target: 8-bit codes read from their 16-bit linear copy where the row has
/// one, else decoded by the cubic where the table is the one it reproduces and vectors are 8
/// floats wide or more, else by the table; float channels as they are.
/// Row: `detail::ProjectiveRow<float, C>`, C std::uint8_t or float.
template <class Row>
void projective_row(const Row& r, std::size_t n, const float* rw, float* acc, float* seen) noexcept {
  using C = std::remove_cv_t<std::remove_pointer_t<decltype(r.texels)>>;
  if constexpr (std::is_same_v<C, std::uint8_t>) {
    // The copy's byte offsets (twice the channel offsets) must fit the gathers' 32-bit lanes.
    if (r.linear != nullptr && 6.0 * r.width * static_cast<double>(r.height) + 8 < 2147483647.0)
      return projective_row_lanes(r, LinearTexels{}, n, rw, acc, seen);
    if constexpr (hn::MaxLanes(DF()) >= 8) {
      if (srgb_cubic_matches(r.lut)) return projective_row_lanes(r, CubicDecode(), n, rw, acc, seen);
    }
    return projective_row_lanes(r, TableDecode(r.lut), n, rw, acc, seen);
  } else {
    return projective_row_lanes(r, NoDecode{}, n, rw, acc, seen);
  }
}
