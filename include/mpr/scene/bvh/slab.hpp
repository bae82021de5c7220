#pragma once
/// \file
/// The ray/box test of the BVH walk: slabs (Kay & Kajiya 1986) against the four child boxes of
/// a `WideNode`, with the exit parameter widened so that rounding never culls a box the ray
/// crosses (Ize, "Robust BVH ray traversal", JCGT 2(2), 2013). This is the portable reference;
/// bvh/kernels/box4_sse.hpp has its x86 twin.

#include <mpr/core/config.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/scene/bvh/node.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>

namespace mpr::scene::detail {

MPR_EXACT_FP_BEGIN

/// Per-ray slab set-up: t = p * inv + offset for each axis; `near`, `far` are the rows of
/// `WideNode::bounds` holding each axis' near and far plane (they follow the direction's sign).
/// Direction components smaller than 1e-30 in magnitude are replaced by +-1e-30 so that `inv`
/// is finite.
template <std::floating_point T>
struct BoxRay {
  std::array<T, 3> inv, offset;
  std::array<int, 3> near, far;
  [[nodiscard]] static BoxRay make(const Ray<T>& ray) noexcept {
    BoxRay r;
    for (int a = 0; a < 3; ++a) {
      const T d = ray.direction[a];
      const T da = std::abs(d) < T(1e-30) ? std::copysign(T(1e-30), d) : d;
      r.inv[a] = T(1) / da;
      r.offset[a] = -ray.origin[a] * r.inv[a];
      r.near[a] = r.inv[a] < 0 ? a + 3 : a;
      r.far[a] = r.inv[a] < 0 ? a : a + 3;
    }
    return r;
  }
};

/// Factor that widens a box's exit parameter so that rounding never culls a box the ray
/// crosses (Ize, "Robust BVH ray traversal", JCGT 2(2), 2013): 1 + 2 gamma(3).
template <std::floating_point T>
inline constexpr T kBoxWiden = [] {
  constexpr T eps = std::numeric_limits<T>::epsilon() / 2;
  return T(1) + 2 * (3 * eps / (1 - 3 * eps));
}();

/// Factor on the closest hit's parameter below which boxes are still entered: a box whose
/// entry rounds slightly beyond the hit (a triangle lying in its box's face, hit at the same t as
/// the current hit through a shared edge) must still be tested, so that the least (t, index) hit
/// is found whatever order the boxes are visited in (single rays and packets alike). 1 + 2^-12
/// for float, 1 + 2^-26 for double: far above rounding, far below any cost.
template <std::floating_point T>
inline constexpr T kCullWiden = T(1) + T(1) / static_cast<T>(std::uint64_t(1) << (std::numeric_limits<T>::digits / 2));

/// The parameter bound for box tests and stack pops given the closest hit so far at `t`.
template <std::floating_point T>
[[nodiscard]] constexpr T cull_bound(T t) noexcept {
  return t * kCullWiden<T>;
}

/// The four child boxes of `node` against the ray: bit `lane` of the result is set when the ray
/// enters that box at a parameter in [0, t_max) (and leaves it no earlier); `t_near[lane]` is
/// then the entry parameter. Other lanes of `t_near` are unspecified. Portable reference.
template <std::floating_point T>
[[nodiscard]] unsigned box4_portable(const WideNode<T>& node, const BoxRay<T>& r, T t_max, T* t_near) noexcept {
  unsigned mask = 0;
  for (int lane = 0; lane < 4; ++lane) {
    T n[3], f[3];
    for (int a = 0; a < 3; ++a) {
      n[a] = node.bounds[r.near[a]][lane] * r.inv[a] + r.offset[a];
      f[a] = (node.bounds[r.far[a]][lane] * r.inv[a] + r.offset[a]) * kBoxWiden<T>;
    }
    const T tn = std::max(std::max(n[0], n[1]), std::max(n[2], T(0)));
    const T tf = std::min(std::min(f[0], f[1]), std::min(f[2], t_max));
    t_near[lane] = tn;
    if (tn <= tf && tn < t_max) mask |= 1U << lane;
  }
  return mask;
}

MPR_EXACT_FP_END

} // namespace mpr::scene::detail
