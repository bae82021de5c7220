#pragma once
/// \file
/// Aperture shapes of finite-aperture GLCs (finite_aperture.hpp), each a policy type: `at(p)`
/// maps a lens sample p in [0, 1)^2 to a point of the aperture in units of the aperture size,
/// uniformly over the shape (Gaussian: distributed as the Gaussian), so an unweighted average
/// of the rays is the aperture integral.

#include <mpr/core/error.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/sampling/pixel_sampling.hpp>

#include <cmath>
#include <concepts>
#include <numbers>
#include <utility>
#include <variant>

namespace mpr::glc {

// clang-format off
/// An aperture shape: `at(lens)` in units of the aperture size (noexcept, deterministic).
template <class A>
concept ApertureShape = std::copy_constructible<A> && requires(const A& a, SamplePoint p) {
  { a.at(p) } noexcept -> std::same_as<Vec2<double>>;
};
// clang-format on

/// The disc of radius 1 (size = radius), by Shirley and Chiu's concentric map (area-preserving,
/// so stratified samples stay stratified).
struct DiscAperture {
  [[nodiscard]] Vec2<double> at(SamplePoint p) const noexcept {
    const double a = 2 * p.x - 1, b = 2 * p.y - 1;
    if (a == 0 && b == 0) return {0, 0};
    const double quarter = std::numbers::pi / 4;
    if (std::fabs(a) > std::fabs(b)) return {a * std::cos(quarter * b / a), a * std::sin(quarter * b / a)};
    return {b * std::sin(quarter * a / b), b * std::cos(quarter * a / b)};
  }
};

/// The square [-1, 1]^2 (size = half the side), aligned with the image plane's axes.
struct SquareAperture {
  [[nodiscard]] Vec2<double> at(SamplePoint p) const noexcept { return {2 * p.x - 1, 2 * p.y - 1}; }
};

/// The regular polygon of `blades` sides (3 to 64) inscribed in the unit circle (size =
/// circumradius), a vertex on the +u axis: a diaphragm of straight blades.
class PolygonAperture {
public:
  /// Throws `argument_error` naming "aperture blades" outside [3, 64].
  explicit PolygonAperture(int blades) : blades_(blades) {
    if (blades < 3 || blades > 64) throw argument_error("aperture blades", "must be in [3, 64]");
  }
  [[nodiscard]] int blades() const noexcept { return blades_; }
  /// p.x chooses the triangle (centre, vertex k, vertex k + 1) and, rescaled, with p.y a uniform
  /// point in it. p.x outside [0, 1] is clamped onto it (NaN reads 0) before the conversion to k.
  [[nodiscard]] Vec2<double> at(SamplePoint p) const noexcept {
    const double scaled = (p.x >= 0 ? std::min(p.x, 1.0) : 0.0) * blades_;
    const int k = std::min(static_cast<int>(scaled), blades_ - 1);
    const double s = scaled - k, t = p.y;
    const double step = 2 * std::numbers::pi / blades_;
    const Vec2<double> v0(std::cos(k * step), std::sin(k * step)),
        v1(std::cos((k + 1) * step), std::sin((k + 1) * step));
    // Uniform in the triangle (0, v0, v1): radius sqrt(s) towards the edge, t along it.
    const double r = std::sqrt(s);
    return Vec2<double>(r * ((1 - t) * v0 + t * v1));
  }

private:
  int blades_;
};

/// An isotropic Gaussian of standard deviation 1 (size = sigma), by the Box-Muller map, cut at
/// 4 sigma (the map's tail beyond is folded onto the circle of radius 4).
struct GaussianAperture {
  [[nodiscard]] Vec2<double> at(SamplePoint p) const noexcept {
    const double r = std::fmin(std::sqrt(-2 * std::log1p(-p.x)), 4.0);
    const double phi = 2 * std::numbers::pi * p.y;
    return {r * std::cos(phi), r * std::sin(phi)};
  }
};

/// One of the shipped aperture shapes chosen at run time (e.g. from a command line): one
/// `std::visit` per lens sample.
class AnyAperture {
public:
  using variant_type = std::variant<DiscAperture, SquareAperture, PolygonAperture, GaussianAperture>;
  AnyAperture() = default;
  template <class A>
  requires std::constructible_from<variant_type, A> AnyAperture(A shape) : shape_(std::move(shape)) {}
  [[nodiscard]] Vec2<double> at(SamplePoint p) const noexcept {
    return std::visit([&](const auto& a) noexcept { return a.at(p); }, shape_);
  }
  [[nodiscard]] const variant_type& variant() const noexcept { return shape_; }

private:
  variant_type shape_{DiscAperture{}};
};

} // namespace mpr::glc
