#pragma once
/// \file
/// `glc::classify_focus`: the focus type of a finite-aperture GLC and its focal depths, from the
/// eigenvalues of its focus matrix F (finite_aperture.hpp), as `glc::classify` names the
/// perspective type. With x fixed and the aperture point a varying, the point of a pixel's rays at
/// depth z (lens plane 0, image plane 1) is const + ((1 - z) I + z F) a: it collapses where
/// z = 1 / (1 - f) for an eigenvalue f of F (the perspective formula with the planes swapped).

#include <mpr/glc/finite_aperture.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <string_view>

namespace mpr::glc {

/// Focus types (Adams and Levoy 2007; names after the perspective types they mirror).
enum class FocusType {
  anastigmatic, ///< F = f I: every pixel's rays meet in one point at one depth (a thin lens)
  astigmatic,   ///< distinct real eigenvalues: two focal lines at two depths
  pencil,       ///< repeated eigenvalue f != 1 without two eigenvectors: one focal line
  twisted,      ///< repeated eigenvalue 1 without two eigenvectors: focus at infinity, twisted
  none          ///< complex eigenvalues: nothing is ever in focus
};

/// The enumerator's name, e.g. "astigmatic".
[[nodiscard]] constexpr std::string_view to_string(FocusType t) noexcept {
  switch (t) {
  case FocusType::anastigmatic:
    return "anastigmatic";
  case FocusType::astigmatic:
    return "astigmatic";
  case FocusType::pencil:
    return "pencil";
  case FocusType::twisted:
    return "twisted";
  case FocusType::none:
    break;
  }
  return "none";
}

/// The focus of a finite-aperture GLC.
template <std::floating_point T>
struct FocusClassification {
  FocusType type = FocusType::none;
  /// Focal loci: 1 (anastigmatic, pencil, twisted), 2 (astigmatic), 0 (none).
  int count = 0;
  /// Their distances in front of the image plane, world units, nearest first (+infinity for an
  /// eigenvalue 1: rays parallel; negative: behind the image plane, a virtual focus).
  std::array<T, 2> depths{};
  /// The eigenvalues of F behind them (astigmatic: in the order of `depths`).
  std::array<T, 2> eigenvalues{};
};

/// Distance in front of the image plane at which eigenvalue `f` focuses, lens plane `h` behind
/// the image plane: (z - 1) h with z = 1 / (1 - f), i.e. h f / (1 - f).
template <std::floating_point T>
[[nodiscard]] T focal_distance(T f, T h) noexcept {
  if (f == 1) return std::numeric_limits<T>::infinity();
  return h * f / (1 - f);
}

/// Classifies the focus matrix `F` of a finite-aperture GLC whose lens plane lies
/// `lens_distance` behind its image plane. `tolerance`: eigenvalue gaps and off-diagonal
/// residues below it (relative to 1 + |F|) count as zero.
template <std::floating_point T>
[[nodiscard]] FocusClassification<T> classify_focus(const Mat2<T>& F, T lens_distance, T tolerance = T(1e-9)) {
  if (!F.allFinite()) throw argument_error("focus matrix", "not finite");
  if (!std::isfinite(lens_distance) || !(lens_distance > 0))
    throw argument_error("aperture distance", "must be finite and > 0");
  FocusClassification<T> c;
  const double a = F(0, 0), b = F(0, 1), cc = F(1, 0), d = F(1, 1);
  const double scale = 1 + std::fabs(a) + std::fabs(b) + std::fabs(cc) + std::fabs(d);
  const double tol = static_cast<double>(tolerance) * scale;
  const double half_trace = (a + d) / 2, disc = (a - d) * (a - d) / 4 + b * cc;
  const auto depth = [&](double f) {
    return std::fabs(f - 1) <= tol ? std::numeric_limits<T>::infinity()
                                   : focal_distance(static_cast<T>(f), lens_distance);
  };
  if (disc < -tol * tol) {
    c.type = FocusType::none;
    return c;
  }
  if (disc > tol * tol) {
    const double root = std::sqrt(disc);
    double f1 = half_trace - root, f2 = half_trace + root;
    T d1 = depth(f1), d2 = depth(f2);
    if (d2 < d1) std::swap(d1, d2), std::swap(f1, f2);
    c.type = FocusType::astigmatic;
    c.count = 2;
    c.depths = {d1, d2};
    c.eigenvalues = {static_cast<T>(f1), static_cast<T>(f2)};
    return c;
  }
  // Repeated eigenvalue f: a multiple of I (two eigenvectors) or a deficient (Jordan) block.
  const double f = half_trace;
  const bool scalar = std::fabs(a - f) <= tol && std::fabs(d - f) <= tol && std::fabs(b) <= tol && std::fabs(cc) <= tol;
  c.type = scalar ? FocusType::anastigmatic : (std::fabs(f - 1) <= tol ? FocusType::twisted : FocusType::pencil);
  c.count = 1;
  c.depths = {depth(f), depth(f)};
  c.eigenvalues = {static_cast<T>(f), static_cast<T>(f)};
  return c;
}

} // namespace mpr::glc
