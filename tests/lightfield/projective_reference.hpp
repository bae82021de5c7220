#pragma once
// The long-double reference of the projective-row kernels (lightfield/kernels/projective_row.hpp,
// projective_tile.hpp): one point's bilinear pixel, and whether the kernel's float decision
// about it may go either way.
#include <mpr/lightfield/kernels/projective_row.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>

namespace mpr_test {

using LD = long double;

// The reference of one point: whether the camera sees it, whether that decision is too close to
// call in the kernel's precision (within `margin` pixels of an image border, or w near 0), and
// the bilinear value per channel.
struct Expected {
  bool seen = false, ambiguous = false;
  LD value[3] = {0, 0, 0}, size = 0;
};

template <class T, class C>
Expected expected(const mpr::detail::ProjectiveRow<T, C>& r, std::size_t i, LD weight, LD margin) {
  Expected e;
  const LD t = static_cast<LD>(i);
  const LD w = LD(r.h0[2]) + t * LD(r.hs[2]);
  const LD scale_w = std::abs(LD(r.h0[2])) + t * std::abs(LD(r.hs[2]));
  if (std::abs(w) <= 1e-4L * scale_w) e.ambiguous = true;
  if (!(w > 0)) return e;
  const LD x = (LD(r.h0[0]) + t * LD(r.hs[0])) / w, y = (LD(r.h0[1]) + t * LD(r.hs[1])) / w;
  const LD xmax = LD(r.width) - 0.5L, ymax = LD(r.height) - 0.5L;
  for (const LD d : {x + 0.5L, xmax - x, y + 0.5L, ymax - y})
    if (std::abs(d) <= margin) e.ambiguous = true;
  if (!(x >= -0.5L && x < xmax && y >= -0.5L && y < ymax)) return e;
  if (!(weight > 0)) return e;
  e.seen = true;
  // Near an integer coordinate the kernel may pick either cell: bilinear is continuous there.
  const LD fx = std::floor(x), fy = std::floor(y);
  const LD ax = x - fx, ay = y - fy;
  const long x0 = static_cast<long>(fx), y0 = static_cast<long>(fy);
  const long xa = std::max(x0, 0L), xb = std::min(x0 + 1, static_cast<long>(r.width) - 1);
  const long ya = std::max(y0, 0L), yb = std::min(y0 + 1, static_cast<long>(r.height) - 1);
  const auto at = [&](long xx, long yy, int k) {
    return LD(mpr::detail::channel_value(r.texels[3 * (yy * r.width + xx) + k], r.lut)) * LD(r.scale);
  };
  for (int k = 0; k < 3; ++k) {
    const LD v[4] = {(1 - ax) * (1 - ay) * at(xa, ya, k), ax * (1 - ay) * at(xb, ya, k), (1 - ax) * ay * at(xa, yb, k),
                     ax * ay * at(xb, yb, k)};
    e.value[k] = weight * (v[0] + v[1] + v[2] + v[3]);
    for (const LD p : {at(xa, ya, k), at(xb, ya, k), at(xa, yb, k), at(xb, yb, k)})
      e.size = std::max(e.size, weight * std::abs(p));
  }
  return e;
}

/// Whether a kernel's sums at one point (`seen`, `acc[0..3)`) are the values before the call
/// (`seen0`, `acc0`) plus the reference `e` at weight `weight`, within the precision of float
/// coordinates (`single`) or double ones; else false, with both described in `why`.
inline bool matches(const Expected& e, LD weight, bool single, float seen, float seen0, const float* acc,
                    const float* acc0, std::string& why) {
  const LD want_seen = LD(seen0) + (e.seen ? weight : 0);
  bool good = std::abs(LD(seen) - want_seen) <= 1e-6L;
  const LD tolerance = (single ? 2e-3L : 1e-5L) * (e.size + 1) + 1e-6L;
  for (int k = 0; k < 3; ++k) good = good && std::abs(LD(acc[k]) - (LD(acc0[k]) + e.value[k])) <= tolerance;
  if (!good) {
    std::ostringstream text;
    text << "seen " << seen << " (want " << static_cast<double>(want_seen) << "), acc " << acc[0] << " (want "
         << static_cast<double>(LD(acc0[0]) + e.value[0]) << ")";
    why = text.str();
  }
  return good;
}

} // namespace mpr_test
