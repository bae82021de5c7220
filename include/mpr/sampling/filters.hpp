#pragma once
/// \file
/// Reconstruction filters as in pbrt-v4 (section 8.8 of Physically Based Rendering, 4th ed.):
/// separable products f(dx) f(dy) of a 1-D profile on the square support [-radius, radius]^2,
/// offsets and radius in pixels. The defaults are pbrt-v4's. `BoxFilter` is in
/// pixel_sampling.hpp. Every constructor throws `argument_error` naming the parameter for a
/// radius (or sigma) that is not finite and > 0.

#include <mpr/sampling/pixel_sampling.hpp>

#include <cmath>
#include <numbers>

namespace mpr {

namespace detail {

inline void check_filter_parameter(double value, const char* name) {
  if (!(value > 0) || !(value < 1e6)) throw argument_error(name, "must be finite and > 0");
}

} // namespace detail

/// Tent (pbrt's triangle): (r - |dx|) (r - |dy|) inside the support. Default radius 2 (pbrt-v4);
/// radius 1 gives bilinear reconstruction, whose shifted copies sum to 1.
class TentFilter {
public:
  static constexpr bool nonnegative = true;
  explicit TentFilter(double radius = 2) : radius_(radius) { detail::check_filter_parameter(radius, "filter radius"); }
  [[nodiscard]] double radius() const noexcept { return radius_; }
  [[nodiscard]] double evaluate(double dx, double dy) const noexcept { return profile(dx) * profile(dy); }
  [[nodiscard]] double profile(double x) const noexcept { return std::fmax(0.0, radius_ - std::fabs(x)); }

private:
  double radius_;
};

/// Gaussian of standard deviation `sigma`, shifted down to reach 0 at the radius and clamped
/// there: g(x) - g(r) per axis with g(x) = exp(-x^2 / (2 sigma^2)) / sqrt(2 pi sigma^2).
/// Defaults radius 1.5, sigma 0.5 (pbrt-v4).
class GaussianFilter {
public:
  static constexpr bool nonnegative = true;
  explicit GaussianFilter(double radius = 1.5, double sigma = 0.5) : radius_(radius), sigma_(sigma) {
    detail::check_filter_parameter(radius, "filter radius");
    detail::check_filter_parameter(sigma, "gaussian sigma");
    edge_ = gauss(radius);
  }
  [[nodiscard]] double radius() const noexcept { return radius_; }
  [[nodiscard]] double sigma() const noexcept { return sigma_; }
  [[nodiscard]] double evaluate(double dx, double dy) const noexcept { return profile(dx) * profile(dy); }
  [[nodiscard]] double profile(double x) const noexcept {
    return std::fabs(x) > radius_ ? 0.0 : std::fmax(0.0, gauss(x) - edge_);
  }

private:
  [[nodiscard]] double gauss(double x) const noexcept {
    return std::exp(-x * x / (2 * sigma_ * sigma_)) / std::sqrt(2 * std::numbers::pi * sigma_ * sigma_);
  }
  double radius_, sigma_, edge_ = 0;
};

/// Mitchell-Netravali cubic with parameters B and C (default 1/3, 1/3), stretched so its support
/// [-2, 2] spans [-radius, radius]: f(x) = k(2x / r) with Mitchell and Netravali's piecewise
/// cubic k. Default radius 2 (pbrt-v4): one pixel per unit of k, so for B + 2C = 1 the shifted
/// copies of the profile sum to 1. The lobes between 1 and 2 units are negative.
class MitchellFilter {
public:
  explicit MitchellFilter(double radius = 2, double b = 1.0 / 3, double c = 1.0 / 3) : radius_(radius), b_(b), c_(c) {
    detail::check_filter_parameter(radius, "filter radius");
    if (!std::isfinite(b) || !std::isfinite(c)) throw argument_error("mitchell B and C", "must be finite");
  }
  [[nodiscard]] double radius() const noexcept { return radius_; }
  [[nodiscard]] double evaluate(double dx, double dy) const noexcept { return profile(dx) * profile(dy); }
  [[nodiscard]] double profile(double x) const noexcept { return cubic(2 * x / radius_); }

  /// Mitchell and Netravali's (1988) cubic k(x): 0 for |x| >= 2.
  [[nodiscard]] double cubic(double x) const noexcept {
    x = std::fabs(x);
    if (x <= 1) return ((12 - 9 * b_ - 6 * c_) * x * x * x + (-18 + 12 * b_ + 6 * c_) * x * x + (6 - 2 * b_)) / 6;
    if (x < 2)
      return ((-b_ - 6 * c_) * x * x * x + (6 * b_ + 30 * c_) * x * x + (-12 * b_ - 48 * c_) * x + (8 * b_ + 24 * c_)) /
             6;
    return 0;
  }

private:
  double radius_, b_, c_;
};

/// Lanczos windowed sinc: sinc(x) sinc(x / tau) for |x| <= radius, else 0, with
/// sinc(x) = sin(pi x) / (pi x). Defaults radius 4, tau 3 (pbrt-v4's "sinc" filter); tau = radius
/// is the classic Lanczos-a kernel. Negative lobes.
class LanczosFilter {
public:
  explicit LanczosFilter(double radius = 4, double tau = 3) : radius_(radius), tau_(tau) {
    detail::check_filter_parameter(radius, "filter radius");
    detail::check_filter_parameter(tau, "lanczos tau");
  }
  [[nodiscard]] double radius() const noexcept { return radius_; }
  [[nodiscard]] double evaluate(double dx, double dy) const noexcept { return profile(dx) * profile(dy); }
  [[nodiscard]] double profile(double x) const noexcept {
    return std::fabs(x) > radius_ ? 0.0 : sinc(x) * sinc(x / tau_);
  }
  /// sin(pi x) / (pi x), 1 at 0 (its Taylor series below 1e-5, where it is exact in double).
  [[nodiscard]] static double sinc(double x) noexcept {
    const double px = std::numbers::pi * x;
    return std::fabs(x) < 1e-5 ? 1 - px * px / 6 : std::sin(px) / px;
  }

private:
  double radius_, tau_;
};

} // namespace mpr
