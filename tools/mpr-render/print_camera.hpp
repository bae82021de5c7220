#pragma once
// mpr-render --print-camera: the GLC type, slits and centre of a view (mpr::glc::classify).

#include "framing.hpp"
#include "light_field_views.hpp"

#include <mpr/glc.hpp>
#include <mpr/lightfield/array_view.hpp>

#include <cstdio>
#include <optional>
#include <ostream>
#include <string>
#include <variant>

namespace mpr_cli {

/// Prints the classification of a planar GLC view and, on a light field (`array`), how its rays
/// cover the camera array.
template <std::floating_point T>
void print_camera(std::ostream& out, const std::string& spec, const CameraVariant<T>& camera,
                  const std::optional<mpr::ArrayFootprint<T>>& array = std::nullopt) {
  const auto v3 = [](const mpr::Vec3<T>& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", static_cast<double>(v.x()), static_cast<double>(v.y()),
                  static_cast<double>(v.z()));
    return std::string(buf);
  };
  const mpr::PlanarSurface<T>& plane = plane_of(camera);
  const mpr::GlcSelector<T>& glc = glc_of(camera);
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
  if (array) {
    const mpr::ArrayCoverage cov = view_coverage(camera, *array);
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "  array coverage: %zu cameras over %.4g x %.4g, spacing %.4g; the rays cross %.0f%% x %.0f%% of "
                  "it, %.1f%% off it\n",
                  array->cameras, static_cast<double>(2 * array->half_u), static_cast<double>(2 * array->half_v),
                  static_cast<double>(array->spacing), 100 * cov.span_u, 100 * cov.span_v, 100 * cov.outside);
    out << buf;
  }
}

} // namespace mpr_cli
