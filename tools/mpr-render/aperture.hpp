#pragma once
// mpr-render's finite aperture (issue 15): --aperture SHAPE:SIZE[:DISTANCE] and
// --focus D | DU,DV parsed into mpr::glc::FiniteAperture around each view's selector
// (include/mpr/glc/finite_aperture.hpp). Needs --spp N > 1: each sample gets its own aperture
// point.

#include "cli_args.hpp"

#include <mpr/glc.hpp>

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace mpr_cli {

/// A finite aperture: shape, size and lens-plane distance (world units), and the focus.
struct ApertureSpec {
  mpr::glc::AnyAperture shape;
  double size = 0;                ///< radius (disc, polygon), half side (square), sigma (gaussian)
  std::optional<double> distance; ///< lens plane behind the image plane; default: the plane's width
  std::vector<double> focus;      ///< {} (on the image plane), {D} or {DU, DV} in front of the image plane
};

/// --aperture SHAPE:SIZE[:DISTANCE]: SHAPE disc, square, gaussian or polygonN (N blades, 3 to 64).
inline mpr::glc::AnyAperture parse_aperture_shape(const std::string& name) {
  if (name == "disc") return mpr::glc::DiscAperture{};
  if (name == "square") return mpr::glc::SquareAperture{};
  if (name == "gaussian") return mpr::glc::GaussianAperture{};
  if (name.rfind("polygon", 0) == 0 && name.size() > 7)
    return mpr::glc::PolygonAperture(parse_int(name.substr(7), "--aperture", 3, 64));
  throw mpr::argument_error("--aperture", "'" + name + "' is not disc, square, gaussian or polygonN (N = 3..64)");
}

inline ApertureSpec parse_aperture(const std::string& text) {
  const std::vector<std::string> parts = split(text, ':');
  if (parts.size() < 2 || parts.size() > 3)
    throw mpr::argument_error("--aperture", "'" + text + "' is not SHAPE:SIZE or SHAPE:SIZE:DISTANCE");
  ApertureSpec spec;
  spec.shape = parse_aperture_shape(parts[0]);
  spec.size = parse_number(parts[1], "--aperture");
  if (!(spec.size >= 0)) throw mpr::argument_error("--aperture", "size " + parts[1] + " is negative");
  if (parts.size() == 3) {
    spec.distance = parse_number(parts[2], "--aperture");
    if (!(*spec.distance > 0)) throw mpr::argument_error("--aperture", "distance " + parts[2] + " must be positive");
  }
  return spec;
}

/// --focus D (anastigmatic, at D in front of the image plane) or DU,DV (astigmatic).
inline std::vector<double> parse_focus(const std::string& text) {
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() > 2) throw mpr::argument_error("--focus", "'" + text + "' is not D or DU,DV");
  std::vector<double> depths;
  for (const std::string& p : parts) depths.push_back(parse_number(p, "--focus"));
  return depths;
}

/// The lens-plane distance of `spec` on a plane `plane_width` wide.
[[nodiscard]] inline double lens_distance(const ApertureSpec& spec, double plane_width) {
  return spec.distance ? *spec.distance : plane_width;
}

/// The focus matrix of `spec` with lens distance `h`; library errors renamed to --focus.
template <std::floating_point T>
mpr::glc::Mat2<T> focus_matrix(const ApertureSpec& spec, T h) {
  try {
    if (spec.focus.empty()) return mpr::glc::Mat2<T>::Zero();
    if (spec.focus.size() == 1) return mpr::glc::focus_at_depth(h, static_cast<T>(spec.focus[0]));
    return mpr::glc::astigmatic_focus(h, static_cast<T>(spec.focus[0]), static_cast<T>(spec.focus[1]));
  } catch (const mpr::argument_error&) {
    throw mpr::argument_error("--focus", "every depth must lie in front of the lens plane, which is " +
                                             std::to_string(h) + " behind the image plane");
  }
}

/// `selector` with the finite aperture of `spec` on `plane`; a view whose rays run parallel to
/// the image plane (no focal-plane crossing) is refused naming --focus.
template <std::floating_point T, class Selector>
mpr::glc::FiniteAperture<Selector, mpr::glc::AnyAperture>
with_aperture(const ApertureSpec& spec, const mpr::PlanarSurface<T>& plane, const Selector& selector) {
  const T h = static_cast<T>(lens_distance(spec, plane.width_vector().norm()));
  const mpr::glc::Mat2<T> f = focus_matrix<T>(spec, h);
  try {
    return {plane, selector, spec.shape, static_cast<T>(spec.size), h, f};
  } catch (const mpr::argument_error& e) {
    if (e.parameter() != "focus") throw;
    throw mpr::argument_error("--focus", "the view's rays run parallel to the image plane (no focal plane crossing)");
  }
}

/// The --print-camera line of the focus (glc::classify_focus) of `spec` on `plane`.
template <std::floating_point T>
void print_focus(std::ostream& out, const ApertureSpec& spec, const mpr::PlanarSurface<T>& plane) {
  const T h = static_cast<T>(lens_distance(spec, plane.width_vector().norm()));
  const mpr::glc::FocusClassification<T> c = mpr::glc::classify_focus(focus_matrix<T>(spec, h), h);
  out << "  focus: " << mpr::glc::to_string(c.type);
  if (c.count == 1) out << " at depth " << c.depths[0];
  if (c.count == 2) out << ", focal lines at depths " << c.depths[0] << " and " << c.depths[1];
  out << " (aperture size " << spec.size << ", lens plane " << h << " behind the image plane)\n";
}

} // namespace mpr_cli
