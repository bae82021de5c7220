#pragma once
/// \file
/// The inner loops of `CameraFrameSampler`'s row paths, with the instruction set chosen at run
/// time: shift-and-add of two camera rows with fixed bilinear weights (refocusing as in
/// Isaksen et al. 2000; the "shift-and-add" of synthetic-aperture photography, Vaish et al.
/// 2004), on rows stored as flat channel arrays (r g b r g b ..., see `FixedTexel`), and the
/// test that proves one camera nearest to each ray of a run (planar arrays).
///
/// Each kernel is written once as plain C++ and compiled up to three times (core/simd.hpp): for
/// the baseline of the build, and, on x86 with GCC or Clang, for AVX2+FMA and for AVX-512,
/// which the compiler's vectoriser fills at full width.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <mpr/core/simd.hpp>
#include <mpr/geometry/detail/plane_kernels.hpp>

namespace mpr::detail {

/// The bilinear weights of one shift-and-add row, the channel scale of the texel type folded in.
struct RowWeights {
  float w00, w10, w01, w11;
};

/// acc[j] += rw[j] * (w00 a[j] + w10 a[j + 3] + w01 b[j] + w11 b[j + 3]) for j in [0, m): the
/// bilinear blend of rows a and b at a fixed sub-pixel offset, over flat RGB rows (so j + 3 is
/// the same channel one pixel to the right). `rw` (nullptr: weight 1) holds one weight per
/// channel slot. Reads a[0, m + 3) and b[0, m + 3); acc must not overlap them.
template <class C>
MPR_ALWAYS_INLINE void shift_add_flat_body(const C* MPR_RESTRICT a, const C* MPR_RESTRICT b, RowWeights w,
                                           const float* MPR_RESTRICT rw, float* MPR_RESTRICT acc,
                                           std::size_t m) noexcept {
  if (rw == nullptr) {
    for (std::size_t j = 0; j < m; ++j)
      acc[j] += w.w00 * static_cast<float>(a[j]) + w.w10 * static_cast<float>(a[j + 3]) +
                w.w01 * static_cast<float>(b[j]) + w.w11 * static_cast<float>(b[j + 3]);
  } else {
    for (std::size_t j = 0; j < m; ++j)
      acc[j] += rw[j] * (w.w00 * static_cast<float>(a[j]) + w.w10 * static_cast<float>(a[j + 3]) +
                         w.w01 * static_cast<float>(b[j]) + w.w11 * static_cast<float>(b[j + 3]));
  }
}

/// `shift_add_flat_body` compiled for `level` (default: the widest this CPU runs).
template <class C>
inline void shift_add_flat(const C* a, const C* b, RowWeights w, const float* rw, float* acc, std::size_t m,
                           SimdLevel level = simd_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { shift_add_flat_body(a, b, w, rw, acc, m); });
}

/// h[j] = scale ((1 - ax) a[j] + ax a[j + 3]) for j in [0, m): one camera row interpolated
/// horizontally at a fixed sub-pixel offset, over flat RGB channels (the first half of a
/// separable bilinear shift-and-add). Reads a[0, m + 3).
template <class C>
MPR_ALWAYS_INLINE void lerp_row_body(const C* MPR_RESTRICT a, float ax, float scale, float* MPR_RESTRICT h,
                                     std::size_t m) noexcept {
  const float w0 = (1 - ax) * scale, w1 = ax * scale;
  for (std::size_t j = 0; j < m; ++j) h[j] = w0 * static_cast<float>(a[j]) + w1 * static_cast<float>(a[j + 3]);
}

/// `lerp_row_body` compiled for `level`.
template <class C>
inline void lerp_row(const C* a, float ax, float scale, float* h, std::size_t m,
                     SimdLevel level = simd_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { lerp_row_body(a, ax, scale, h, m); });
}

/// acc[j] += rw[j] (w0 h0[j] + w1 h1[j]) for j in [0, m) (rw nullptr: weight 1): the vertical
/// half of a separable bilinear shift-and-add, on rows from `lerp_row`.
MPR_ALWAYS_INLINE void blend_rows_body(const float* MPR_RESTRICT h0, const float* MPR_RESTRICT h1, float w0, float w1,
                                       const float* MPR_RESTRICT rw, float* MPR_RESTRICT acc, std::size_t m) noexcept {
  if (rw == nullptr) {
    for (std::size_t j = 0; j < m; ++j) acc[j] += w0 * h0[j] + w1 * h1[j];
  } else {
    for (std::size_t j = 0; j < m; ++j) acc[j] += rw[j] * (w0 * h0[j] + w1 * h1[j]);
  }
}

/// `blend_rows_body` compiled for `level`.
inline void blend_rows(const float* h0, const float* h1, float w0, float w1, const float* rw, float* acc,
                       std::size_t m, SimdLevel level = simd_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { blend_rows_body(h0, h1, w0, w1, rw, acc, m); });
}

/// Asks the cache for the bytes of [begin, end) (GCC and Clang; nothing elsewhere).
template <class P>
MPR_ALWAYS_INLINE void prefetch_range(const P* begin, const P* end) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  const char* next = reinterpret_cast<const char*>(begin);
  const char* stop = reinterpret_cast<const char*>(end);
  for (; next < stop; next += 64) __builtin_prefetch(next);
#else
  (void)begin;
  (void)end;
#endif
}

/// Camera k of a planar array as the nearest-camera proof needs it: in-plane centre (cu, cv),
/// the in-plane centres of its listed neighbours, and rho2: rays crossing the plane within
/// sqrt(rho2) of the centre are farther from every unlisted camera (see
/// `CameraFrameSampler::tile_nearest`); margin2 is the absolute slack on squared distances.
template <class T>
struct NearestCandidate {
  T cu, cv, rho2, margin2;
  const T *nu, *nv;
  int neighbours;
};

/// pass[i] = all bits set when ray i of `rays` (i in [0, n)) is proved nearer to camera `k`
/// than to any other camera, 0 otherwise; `scratch` holds n values. The squared distance of an
/// in-plane centre c to the line through x with direction d is (|e|^2 |d|^2 - (e . d)^2) / |d|^2
/// with e = c - x; the test compares these numerators (all scaled by the same |d|^2): every
/// listed neighbour must be farther by a relative 1e-4 plus the margin, and the crossing must lie
/// within rho of the centre.
template <class T>
MPR_ALWAYS_INLINE void prove_nearest_body(const PlaneRays<T>& rays, std::size_t n, const NearestCandidate<T>& k,
                                          typename PlaneRays<T>::Flag* MPR_RESTRICT pass,
                                          T* MPR_RESTRICT scratch) noexcept {
  using Flag = typename PlaneRays<T>::Flag;
  const T* MPR_RESTRICT xu = rays.xu;
  const T* MPR_RESTRICT xv = rays.xv;
  const T* MPR_RESTRICT du = rays.du;
  const T* MPR_RESTRICT dv = rays.dv;
  const T* MPR_RESTRICT dd = rays.dd;
  const Flag* MPR_RESTRICT ok = rays.ok;
  for (std::size_t i = 0; i < n; ++i) {
    const T eu = k.cu - xu[i], ev = k.cv - xv[i];
    const T r2 = eu * eu + ev * ev, ed = eu * du[i] + ev * dv[i];
    scratch[i] = (r2 * dd[i] - ed * ed) * T(1.0001) + k.margin2 * dd[i];
    pass[i] = ok[i] & (r2 < k.rho2 ? Flag(-1) : Flag(0));
  }
  for (int j = 0; j < k.neighbours; ++j) {
    const T cu = k.nu[j], cv = k.nv[j];
    for (std::size_t i = 0; i < n; ++i) {
      const T eu = cu - xu[i], ev = cv - xv[i];
      const T r2 = eu * eu + ev * ev, ed = eu * du[i] + ev * dv[i];
      pass[i] &= (r2 * dd[i] - ed * ed) > scratch[i] ? Flag(-1) : Flag(0);
    }
  }
}

/// `prove_nearest_body` compiled for `level`.
template <class T>
inline void prove_nearest(const PlaneRays<T>& rays, std::size_t n, const NearestCandidate<T>& k,
                          typename PlaneRays<T>::Flag* pass, T* scratch, SimdLevel level = simd_level()) noexcept {
  run_at(level, [&]() MPR_INLINE_LAMBDA { prove_nearest_body(rays, n, k, pass, scratch); });
}

/// w[i] = max(0, 1 - d_i / radius) for i in [0, n), d_i the distance from the in-plane centre
/// (cu, cv) to ray i of a row (see `PlaneRays`; inv_dd[i] = 1 / dd[i]): the linear falloff of
/// `CylinderAperture`. d^2 = |e|^2 - (e . d)^2 / |d|^2 with e = c - x, clamped at 0 against
/// rounding. Zero weight means outside the cylinder.
template <class T>
inline void cylinder_weights_portable(const T* xu, const T* xv, const T* du, const T* dv, const T* inv_dd,
                                      std::size_t n, T cu, T cv, T inv_radius, float* w) noexcept {
  for (std::size_t i = 0; i < n; ++i) {
    const T eu = cu - xu[i], ev = cv - xv[i];
    const T ed = eu * du[i] + ev * dv[i];
    const T d2 = std::max(eu * eu + ev * ev - ed * ed * inv_dd[i], T(0));
    w[i] = static_cast<float>(std::max(T(1) - std::sqrt(d2) * inv_radius, T(0)));
  }
}

#if defined(MPR_SIMD_X86)
// Written with intrinsics: with errno-setting sqrt (the default), compilers do not vectorise
// std::sqrt, and this loop is mostly the square root.
MPR_TARGET_AVX2 inline void cylinder_weights_avx2(const float* xu, const float* xv, const float* du, const float* dv,
                                                  const float* inv_dd, std::size_t n, float cu, float cv,
                                                  float inv_radius, float* w) noexcept {
  const __m256 vcu = _mm256_set1_ps(cu), vcv = _mm256_set1_ps(cv), vinv = _mm256_set1_ps(inv_radius);
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256 eu = _mm256_sub_ps(vcu, _mm256_loadu_ps(xu + i)), ev = _mm256_sub_ps(vcv, _mm256_loadu_ps(xv + i));
    const __m256 ed = _mm256_fmadd_ps(eu, _mm256_loadu_ps(du + i), _mm256_mul_ps(ev, _mm256_loadu_ps(dv + i)));
    const __m256 r2 = _mm256_fmadd_ps(eu, eu, _mm256_mul_ps(ev, ev));
    const __m256 d2 = _mm256_max_ps(_mm256_fnmadd_ps(_mm256_mul_ps(ed, ed), _mm256_loadu_ps(inv_dd + i), r2), zero);
    _mm256_storeu_ps(w + i, _mm256_max_ps(_mm256_fnmadd_ps(_mm256_sqrt_ps(d2), vinv, one), zero));
  }
  cylinder_weights_portable(xu + i, xv + i, du + i, dv + i, inv_dd + i, n - i, cu, cv, inv_radius, w + i);
}
#endif

/// `cylinder_weights_portable`, or the AVX2 kernel (float) when `level` allows.
template <class T>
inline void cylinder_weights(const T* xu, const T* xv, const T* du, const T* dv, const T* inv_dd, std::size_t n, T cu,
                             T cv, T inv_radius, float* w, SimdLevel level = simd_level()) noexcept {
#if defined(MPR_SIMD_X86)
  if constexpr (std::is_same_v<T, float>)
    if (level != SimdLevel::portable) return cylinder_weights_avx2(xu, xv, du, dv, inv_dd, n, cu, cv, inv_radius, w);
#endif
  (void)level;
  cylinder_weights_portable(xu, xv, du, dv, inv_dd, n, cu, cv, inv_radius, w);
}

/// The least of v[0, n) (+inf when n = 0), with eight independent running minima so that the
/// loop is not one chain of dependent comparisons.
template <class T>
[[nodiscard]] inline T min_of(const T* v, std::size_t n) noexcept {
  T m[8];
  for (T& x : m) x = std::numeric_limits<T>::infinity();
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (std::size_t l = 0; l < 8; ++l) m[l] = std::min(m[l], v[i + l]);
  for (; i < n; ++i) m[0] = std::min(m[0], v[i]);
  T out = m[0];
  for (std::size_t l = 1; l < 8; ++l) out = std::min(out, m[l]);
  return out;
}

/// Whether the points (x[i], y[i], z[i]), i in [0, n), lie at p_0 + i (p_{n-1} - p_0) / (n - 1)
/// within `tolerance` per coordinate (NaN never does). Structure of arrays, so that it vectorises.
template <class T>
MPR_ALWAYS_INLINE bool evenly_spaced_body(const T* MPR_RESTRICT x, const T* MPR_RESTRICT y, const T* MPR_RESTRICT z,
                                          int n, T tolerance) noexcept {
  if (n < 3) return true;
  const T span = static_cast<T>(n - 1);
  const T sx = (x[n - 1] - x[0]) / span, sy = (y[n - 1] - y[0]) / span, sz = (z[n - 1] - z[0]) / span;
  const T x0 = x[0], y0 = y[0], z0 = z[0];
  int bad = 0;
  for (int i = 1; i < n - 1; ++i) {
    const T t = static_cast<T>(i);
    const bool good = (std::abs(x[i] - (x0 + t * sx)) <= tolerance) & (std::abs(y[i] - (y0 + t * sy)) <= tolerance) &
                      (std::abs(z[i] - (z0 + t * sz)) <= tolerance);
    bad |= good ? 0 : 1;
  }
  return bad == 0;
}

/// `evenly_spaced_body` compiled for `level`.
template <class T>
inline bool evenly_spaced(const T* x, const T* y, const T* z, int n, T tolerance,
                          SimdLevel level = simd_level()) noexcept {
  bool even = false;
  run_at(level, [&]() MPR_INLINE_LAMBDA { even = evenly_spaced_body(x, y, z, n, tolerance); });
  return even;
}

} // namespace mpr::detail
