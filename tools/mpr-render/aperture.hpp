#pragma once
// mpr-render's finite aperture (issue 15): --aperture SHAPE:SIZE (SIZE animatable, e.g.
// disc:0:0.5 opens the aperture over an animation), --lens-distance D and --focus D | DU,DV
// parsed into mpr::glc::FiniteAperture around each view's selector
// (include/mpr/glc/finite_aperture.hpp). Needs --spp N > 1: each sample gets its own aperture
// point.

#include "animation.hpp"
#include "cli_args.hpp"

#include <mpr/glc.hpp>
#include <mpr/render/policy_dispatch.hpp>
#include <mpr/render/policy_names.hpp>

#include <algorithm>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace mpr_cli {

/// `v` as std::ostream writes a double (6 significant digits): "0.2", "4", "12.5".
inline std::string format_number(double v) {
  std::ostringstream text;
  text << v;
  return text.str();
}

/// A finite aperture: shape, size and lens-plane distance (world units), and the focus.
struct ApertureSpec {
  mpr::glc::AnyAperture shape;
  Track size{0};                  ///< radius (disc, polygon), half side (square), sigma (gaussian); over the animation
  std::optional<double> distance; ///< lens plane behind the image plane; default: the plane's width
  std::vector<double> focus;      ///< {} (on the image plane), {D} or {DU, DV} in front of the image plane
};

/// SHAPE of --aperture: disc, square, gaussian or polygonN (N blades, 3 to 64): `mpr::aperture_by_name`.
inline mpr::glc::AnyAperture parse_aperture_shape(const std::string& name) {
  return mpr::aperture_by_name(name, "--aperture");
}

/// --aperture SHAPE:SIZE, SIZE a number, FROM:TO or keyframes T=V,T=V,... (animation.hpp), each
/// >= 0 (0: the pinhole).
inline ApertureSpec parse_aperture(const std::string& text) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos || colon + 1 == text.size())
    throw mpr::argument_error("--aperture", "'" + text + "' is not SHAPE:SIZE, SHAPE:FROM:TO or SHAPE:T=V,T=V,...");
  ApertureSpec spec;
  spec.shape = parse_aperture_shape(text.substr(0, colon));
  spec.size = parse_track(text.substr(colon + 1), "--aperture");
  for (const Track::Key& k : spec.size.keys())
    if (!(k.value >= 0)) throw mpr::argument_error("--aperture", "size " + format_number(k.value) + " is negative");
  return spec;
}

/// --lens-distance D: the lens plane D > 0 behind the image plane (world units).
inline double parse_lens_distance(const std::string& text) {
  const double d = parse_number(text, "--lens-distance");
  if (!(d > 0)) throw mpr::argument_error("--lens-distance", text + " must be positive");
  return d;
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

/// The finite aperture of `spec` opened to `size` (the frame's value of spec.size) on `plane`,
/// as the library's render dispatch takes it (mpr::render_chosen).
template <std::floating_point T>
[[nodiscard]] mpr::LensChoice<T> lens_choice(const ApertureSpec& spec, double size,
                                             const mpr::PlanarSurface<T>& plane) {
  const T h = static_cast<T>(lens_distance(spec, plane.width_vector().norm()));
  return {spec.shape, static_cast<T>(size), h, focus_matrix<T>(spec, h)};
}

/// Rethrows `e`, an error of mpr::glc::FiniteAperture, naming the option that set the value: a
/// view whose rays run (nearly) parallel to the image plane ("focus") names --focus (--aperture
/// when no --focus was given). Call it only from a handler of `e`.
[[noreturn]] inline void rethrow_aperture_error(const ApertureSpec& spec, const mpr::argument_error& e) {
  if (e.parameter() != "focus") throw;
  throw mpr::argument_error(spec.focus.empty() ? "--aperture" : "--focus",
                            "the view's rays run parallel to the image plane, so they cross no focal plane "
                            "(the lens and focal planes are parallel to the image plane)");
}

/// `selector` with the finite aperture of `spec`, opened to `size` (the frame's value of
/// spec.size), on `plane`; errors as `rethrow_aperture_error`.
template <std::floating_point T, class Selector>
mpr::glc::FiniteAperture<Selector, mpr::glc::AnyAperture>
with_aperture(const ApertureSpec& spec, double size, const mpr::PlanarSurface<T>& plane, const Selector& selector) {
  const mpr::LensChoice<T> lens = lens_choice<T>(spec, size, plane);
  try {
    return {plane, selector, lens.shape, lens.size, lens.distance, lens.focus};
  } catch (const mpr::argument_error& e) {
    rethrow_aperture_error(spec, e);
  }
}

/// The focus of `spec` on `plane` (glc::classify_focus) in words: "anastigmatic at depth 9",
/// "astigmatic, focal lines at depths 4 and 12"; `brief`: "anastigmatic at 9", "astigmatic at 4
/// and 12".
template <std::floating_point T>
std::string focus_text(const ApertureSpec& spec, const mpr::PlanarSurface<T>& plane, bool brief = false) {
  const T h = static_cast<T>(lens_distance(spec, plane.width_vector().norm()));
  const mpr::glc::FocusClassification<T> c = mpr::glc::classify_focus(focus_matrix<T>(spec, h), h);
  std::string text(mpr::glc::to_string(c.type));
  if (c.count == 1) text += (brief ? " at " : " at depth ") + format_number(static_cast<double>(c.depths[0]));
  if (c.count == 2)
    text += (brief ? " at " : ", focal lines at depths ") + format_number(static_cast<double>(c.depths[0])) + " and " +
            format_number(static_cast<double>(c.depths[1]));
  return text;
}

/// The --print-camera line of the focus (glc::classify_focus) of `spec` on `plane`, with the
/// aperture size (its smallest and largest over an animation).
template <std::floating_point T>
void print_focus(std::ostream& out, const ApertureSpec& spec, const mpr::PlanarSurface<T>& plane) {
  const T h = static_cast<T>(lens_distance(spec, plane.width_vector().norm()));
  double lo = spec.size.keys().front().value, hi = lo;
  for (const Track::Key& k : spec.size.keys()) {
    lo = std::min(lo, k.value);
    hi = std::max(hi, k.value);
  }
  out << "  focus: " << focus_text(spec, plane) << " (aperture size " << format_number(lo);
  if (hi != lo) out << " to " << format_number(hi);
  out << ", lens plane " << format_number(static_cast<double>(h)) << " behind the image plane)\n";
}

} // namespace mpr_cli
