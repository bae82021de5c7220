#pragma once
// mpr-render's VIEW grammar (tools/options/help.cpp, view_help): a view spec on an image plane -> the GLC
// ray selector (gallery letters and names, pinhole, orthographic, oblique, pushbroom, cross-slit,
// pencil, twisted, bilinear, explicit corners).

#include "cli_args.hpp"
#include "job.hpp"
#include "loading.hpp"

#include <mpr/glc.hpp>

#include <cctype>
#include <exception>
#include <numbers>
#include <string>
#include <vector>

namespace mpr_cli {

namespace detail {

/// An error's text without the "mpr: invalid " prefix, to nest it in another message.
inline std::string nested(const std::exception& e) {
  std::string what = e.what();
  for (const char* prefix : {"mpr: invalid ", "mpr: "})
    if (what.rfind(prefix, 0) == 0) return what.substr(std::char_traits<char>::length(prefix));
  return what;
}

inline std::string normalized_name(std::string s) {
  for (char& c : s)
    c = (c == ' ' || c == '-' || c == ',') ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string out;
  for (char c : s)
    if (!(c == '_' && !out.empty() && out.back() == '_')) out += c;
  return out;
}

/// The gallery letter of a view name or letter, or 0.
inline char gallery_letter(const std::string& spec) {
  if (spec.size() == 1) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(spec[0])));
    return c >= 'A' && c <= 'I' ? c : 0;
  }
  const std::string n = normalized_name(spec);
  static const std::pair<const char*, char> aliases[] = {{"oblique", 'C'},      {"twisted", 'E'},
                                                         {"twisted_down", 'F'}, {"cross_slit", 'G'},
                                                         {"crossed_slit", 'G'}, {"pinhole", 'A'}};
  for (const auto& a : aliases)
    if (n == a.first) return a.second;
  for (const mpr::glc::GalleryEntry& e : mpr::glc::gallery)
    if (n == normalized_name(std::string(e.name))) return e.id;
  return 0;
}

} // namespace detail

/// The GLC of a view spec (see view_help()) on `plane`. Throws argument_error naming `option`.
template <std::floating_point T>
mpr::GlcSelector<T> make_selector(const std::string& spec, const std::string& option,
                                  const mpr::PlanarSurface<T>& plane, const Job& job, const Loaded<T>& l,
                                  const FrameParams& p) {
  using V = mpr::Vec3<T>;
  try {
    if (spec == "default") {
      if (l.reference) return mpr::pinhole_glc(*l.reference, plane);
      return make_selector<T>("A", option, plane, job, l, p);
    }
    if (const char letter = detail::gallery_letter(spec); letter != 0) {
      V centre;
      T scale;
      if (l.reference) {
        centre = plane.centre() + static_cast<T>(0.1 * p.focal_depth) * plane.normal();
        scale = plane.width_vector().norm();
      } else {
        centre = l.scene_centre.template cast<T>();
        scale = static_cast<T>(l.scene_scale);
      }
      if (job.scene_centre) centre = job.scene_centre->template cast<T>();
      if (job.scene_scale) scale = static_cast<T>(*job.scene_scale);
      const mpr::GlcSelector<T> view = mpr::glc::gallery_view(letter, plane, centre, scale);
      // A light field: the same view in two-plane terms, its rays crossing the camera plane inside
      // the array (lightfield/array_view.hpp); the reference view itself stays the reference camera.
      if (l.footprint) return mpr::fit_to_array(plane, view, *l.footprint);
      return view;
    }
    const std::vector<std::string> parts = split(spec, ':');
    const std::string type = detail::normalized_name(parts[0]);
    const auto need = [&](std::size_t n, const char* form) {
      if (parts.size() != n + 1) throw mpr::argument_error(option, "'" + spec + "': expected " + form);
    };
    const auto vec = [&](std::size_t i) { return V(parse_vec3(parts[i], option).template cast<T>()); };
    const auto num = [&](std::size_t i) { return static_cast<T>(parse_number(parts[i], option)); };
    const auto line = [&](std::size_t i) {
      const V d = vec(i + 1);
      if (!(d.norm() > 0)) throw mpr::argument_error(option, "zero slit direction in '" + spec + "'");
      return mpr::glc::Line<T>{vec(i), V(d.normalized())};
    };
    if (type == "pinhole" || type == "perspective") {
      need(1, "pinhole:X,Y,Z");
      return mpr::glc::perspective(plane, vec(1));
    }
    if (type == "orthographic") {
      need(1, "orthographic:DX,DY,DZ");
      return mpr::glc::orthographic(plane, vec(1));
    }
    if (type == "oblique") {
      need(1, "oblique:AU,AV (degrees)");
      const std::vector<std::string> a = split(parts[1], ',');
      if (a.size() != 2) throw mpr::argument_error(option, "'" + spec + "': expected oblique:AU,AV");
      constexpr double deg = std::numbers::pi / 180;
      return mpr::glc::oblique_orthographic(plane, static_cast<T>(parse_number(a[0], option) * deg),
                                            static_cast<T>(parse_number(a[1], option) * deg));
    }
    if (type == "pushbroom") {
      need(2, "pushbroom:P:D");
      return mpr::glc::pushbroom(plane, line(1));
    }
    if (type == "cross_slit") {
      need(4, "cross_slit:P1:D1:P2:D2");
      return mpr::glc::cross_slit(plane, line(1), line(3));
    }
    if (type == "pencil") {
      need(3, "pencil:P:D:TWIST");
      return mpr::glc::pencil(plane, line(1), num(3));
    }
    if (type == "twisted") {
      need(3, "twisted:D:TILT:TWIST");
      return mpr::glc::twisted_orthographic(plane, vec(1), vec(2), num(3));
    }
    if (type == "bilinear") {
      need(3, "bilinear:D:CONVERGENCE:TWIST");
      return mpr::glc::bilinear(plane, vec(1), num(2), num(3));
    }
    if (type == "corners") {
      need(3, "corners:D00:D10:D01");
      return mpr::GlcSelector<T>(plane, vec(1), vec(2), vec(3));
    }
  } catch (const mpr::argument_error& e) {
    if (e.parameter() == option) throw;
    throw mpr::argument_error(option, "'" + spec + "' is an impossible camera here: " + detail::nested(e));
  }
  throw mpr::argument_error(option, "'" + spec + "' is not a view (see VIEW in --help)");
}

} // namespace mpr_cli
