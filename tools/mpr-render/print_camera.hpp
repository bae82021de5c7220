#pragma once
// mpr-render --print-camera: the GLC type, slits and centre of a view (mpr::glc::classify).

#include "framing.hpp"

#include <mpr/glc.hpp>

#include <cstdio>
#include <ostream>
#include <string>
#include <variant>

namespace mpr_cli {

/// Prints the classification of a planar GLC view.
template <std::floating_point T>
void print_camera(std::ostream& out, const std::string& spec, const CameraVariant<T>& camera) {
  const auto v3 = [](const mpr::Vec3<T>& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", static_cast<double>(v.x()), static_cast<double>(v.y()),
                  static_cast<double>(v.z()));
    return std::string(buf);
  };
  const mpr::PlanarSurface<T>& plane = std::holds_alternative<PlanarCamera<T>>(camera)
                                           ? std::get<PlanarCamera<T>>(camera).surface
                                           : std::get<mpr::glc::Rectified<T>>(camera).surface.plane();
  const mpr::GlcSelector<T>& glc = std::holds_alternative<PlanarCamera<T>>(camera)
                                       ? std::get<PlanarCamera<T>>(camera).selector
                                       : std::get<mpr::glc::Rectified<T>>(camera).selector.selector();
  const mpr::glc::Classification<T> c = mpr::glc::classify(plane, glc);
  out << "view " << spec << ": " << mpr::glc::to_string(c.type);
  if (std::holds_alternative<mpr::glc::Rectified<T>>(camera)) out << " (rectified)";
  out << "\n";
  out << "  image plane: centre " << v3(plane.centre()) << ", normal " << v3(plane.normal()) << "\n";
  for (int i = 0; i < c.slit_count; ++i)
    out << "  slit " << i + 1 << ": point " << v3(c.slits[static_cast<std::size_t>(i)].point) << ", direction "
        << v3(c.slits[static_cast<std::size_t>(i)].direction) << ", depth " << c.depths[static_cast<std::size_t>(i)]
        << "\n";
  if (c.type == mpr::glc::Type::pinhole) out << "  centre: " << v3(c.centre) << ", depth " << c.depths[0] << "\n";
  if (c.type == mpr::glc::Type::orthographic) out << "  direction: " << v3(c.direction) << "\n";
}

} // namespace mpr_cli
