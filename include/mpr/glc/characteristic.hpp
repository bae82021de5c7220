#pragma once
/// \file
/// The characteristic equation of a GLC, A z^2 + B z + C = 0, whose roots are the depths of its
/// slits (Yu & McMillan, "General Linear Cameras", ECCV 2004, sec. 4), in the translation-invariant
/// edge form, with a sign-safe discriminant and cancellation-free roots.

#include <mpr/glc/two_plane.hpp>

#include <cmath>
#include <concepts>
#include <limits>

namespace mpr::glc {

/// Coefficients of D(z) = A z^2 + B z + C: twice the signed area, in plane (uv) coordinates, of
/// the triangle in which the three generators cross the plane at depth z. D(z) = 0 exactly at
/// the depths where the generators meet one line (a slit) or one point (a pinhole centre).
/// Only the ratios A : B : C mean anything (re-choosing generators scales all three).
template <std::floating_point T>
struct Characteristic {
  T a = 0;
  T b = 0;
  T c = 0;
  /// B^2 - 4AC, computed so that its sign is right near a double root (see `discriminant`).
  T discriminant = 0;

  /// D(z), evaluated in Horner form.
  [[nodiscard]] T operator()(T z) const noexcept { return (a * z + b) * z + c; }
};

namespace detail {
[[nodiscard]] inline double cross2(double ax, double ay, double bx, double by) noexcept {
  // Kahan's FMA trick: ax*by - ay*bx with one rounding error instead of a cancellation.
  const double w = ay * bx;
  const double e = std::fma(-ay, bx, w);
  const double f = std::fma(ax, by, -w);
  return f + e;
}
} // namespace detail

/// B^2 - 4AC with Kahan's compensated algorithm ("On the cost of floating-point computation
/// without extra-precise arithmetic", 2004): exact products via FMA when the two terms nearly
/// cancel, so the result carries the right sign whenever A, B, C are the true coefficients.
[[nodiscard]] inline double discriminant(double a, double b, double c) noexcept {
  const double p = b * b;
  const double q = 4 * a * c;
  const double d = p - q;
  if (3 * std::abs(d) >= p + q) return d; // no dangerous cancellation
  const double dp = std::fma(b, b, -p);
  const double dq = std::fma(4 * a, c, -q);
  return (p - q) + (dp - dq);
}

/// The characteristic coefficients of `glc`, computed in double precision with the edge form
///   A = f2 x f3,  B = e2 x f3 + f2 x e3,  C = e2 x e3,
/// e_k = (u_k - u_0, v_k - v_0), f_k = (sigma_k - sigma_0, tau_k - tau_0): invariant under
/// translation of the scene (the raw 3x3 determinants of the paper lose everything at 1e8).
/// The discriminant uses the direction-gradient form C^2 [(K11 - K22)^2 + 4 K12 K21],
/// K = [f2 f3][e2 e3]^-1, when the image triangle is well shaped (no cancellation between B^2 and
/// 4AC: it is exactly 0 for a pinhole written with K = kI), and `discriminant()` otherwise.
template <std::floating_point T>
[[nodiscard]] Characteristic<double> characteristic(const TwoPlane<T>& glc) noexcept {
  const auto& g = glc.generators();
  const double e2x = double(g[1].u) - double(g[0].u), e2y = double(g[1].v) - double(g[0].v);
  const double e3x = double(g[2].u) - double(g[0].u), e3y = double(g[2].v) - double(g[0].v);
  const double f2x = double(g[1].sigma) - double(g[0].sigma), f2y = double(g[1].tau) - double(g[0].tau);
  const double f3x = double(g[2].sigma) - double(g[0].sigma), f3y = double(g[2].tau) - double(g[0].tau);
  Characteristic<double> ch;
  ch.a = detail::cross2(f2x, f2y, f3x, f3y);
  ch.b = detail::cross2(e2x, e2y, f3x, f3y) + detail::cross2(f2x, f2y, e3x, e3y);
  ch.c = detail::cross2(e2x, e2y, e3x, e3y);
  const double e_size = std::hypot(e2x, e2y) * std::hypot(e3x, e3y);
  if (ch.c != 0 && std::abs(ch.c) >= 0.25 * e_size) {
    // K = [f2 f3] adj([e2 e3]) / C.
    const double k11 = (f2x * e3y - f3x * e2y) / ch.c, k12 = (f3x * e2x - f2x * e3x) / ch.c;
    const double k21 = (f2y * e3y - f3y * e2y) / ch.c, k22 = (f3y * e2x - f2y * e3x) / ch.c;
    const double diff = k11 - k22;
    ch.discriminant = ch.c * ch.c * std::fma(diff, diff, 4 * k12 * k21);
  } else {
    ch.discriminant = discriminant(ch.a, ch.b, ch.c);
  }
  return ch;
}

/// The roots of A z^2 + B z + C, as depths. Roots at infinity (A = 0) are +infinity.
struct Roots {
  /// True for a complex-conjugate pair `real +- i imag` (then `first`, `second` are unused).
  bool complex = false;
  /// True when A = B = C = 0 (every depth is a root: an EPI or degenerate generators).
  bool all = false;
  double first = 0;  ///< real root of smaller magnitude (or +inf)
  double second = 0; ///< real root of larger magnitude (or +inf)
  double real = 0;   ///< complex pair: real part, -B / 2A
  double imag = 0;   ///< complex pair: imaginary part, > 0
};

/// The roots of `ch` by the cancellation-free formula q = -(B + sign(B) sqrt(disc)) / 2,
/// z1 = q / A, z2 = C / q (Numerical Recipes, sec. 5.6); a root whose formula divides by zero is
/// at infinity. Uses `ch.discriminant` for the sign decision.
[[nodiscard]] inline Roots roots(const Characteristic<double>& ch) noexcept {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Roots r;
  if (ch.a == 0 && ch.b == 0 && ch.c == 0) {
    r.all = true;
    return r;
  }
  if (ch.discriminant < 0 && ch.a != 0) {
    r.complex = true;
    r.real = -ch.b / (2 * ch.a);
    r.imag = std::sqrt(-ch.discriminant) / (2 * std::abs(ch.a));
    return r;
  }
  const double s = std::sqrt(std::max(ch.discriminant, 0.0));
  const double q = -0.5 * (ch.b + std::copysign(s, ch.b));
  double z1, z2;
  if (q != 0) {
    z1 = ch.a != 0 ? q / ch.a : inf;
    z2 = ch.c / q;
  } else { // B = 0 and disc = 0: A C = 0
    z1 = z2 = ch.a != 0 ? 0.0 : inf;
  }
  if (std::abs(z2) < std::abs(z1)) std::swap(z1, z2);
  r.first = z1;
  r.second = z2;
  return r;
}

} // namespace mpr::glc
