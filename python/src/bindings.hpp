#pragma once
// Shared by the translation units of the Python module `mpr._mpr`: the scalar the module uses,
// the frame-set and view handles the units pass between them, and numpy conversions.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/selector/glc_selector.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <variant>

namespace mpr_py {

namespace py = pybind11;

/// The module renders in single precision, as mpr-render does by default.
using T = float;

using FrameSet8 = mpr::CameraFrameSet<T, mpr::Rgb8>;
using FrameSetLinear = mpr::CameraFrameSet<T, mpr::Color>;

/// A light field as Python holds it: 8-bit sRGB frames or linear float frames, shared.
struct FrameSet {
  std::variant<std::shared_ptr<const FrameSet8>, std::shared_ptr<const FrameSetLinear>> frames;
  [[nodiscard]] std::size_t size() const {
    return std::visit([](const auto& f) { return f->size(); }, frames);
  }
  [[nodiscard]] const mpr::PinholeCamera<T>& camera(std::size_t i) const {
    return std::visit([&](const auto& f) -> const mpr::PinholeCamera<T>& { return f->camera(i); }, frames);
  }
};

/// A view: an image plane (its uv square is the output image) and the GLC that picks each
/// pixel's ray.
struct View {
  mpr::PlanarSurface<T> plane;
  mpr::GlcSelector<T> selector;
};

void bind_lightfields(py::module_& m);
void bind_cameras(py::module_& m);
void bind_render(py::module_& m);
void bind_depth(py::module_& m);
void bind_scenes(py::module_& m);

/// A numpy (3,) or (3, 3) float64 array as an Eigen value; throws ValueError naming `name` for a
/// wrong shape.
mpr::Vec3<T> to_vec3(const py::handle& value, const char* name);
mpr::Mat3<T> to_mat3(const py::handle& value, const char* name);
py::array_t<double> from_vec3(const mpr::Vec3<T>& v);
py::array_t<double> from_mat3(const mpr::Mat3<T>& m);

} // namespace mpr_py
