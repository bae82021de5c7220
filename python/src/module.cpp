// The Python module `mpr._mpr`: registers the error translation and the bindings of each unit.

#include "bindings.hpp"

#include <exception>

PYBIND11_MODULE(_mpr, m) {
  m.doc() = "mpr: multi-perspective rendering (General Linear Cameras, light fields from camera arrays, depth from "
            "images). Lengths are world units, pixel coordinates have pixel centres at integers (OpenCV).";
  // mpr's errors carry one line ("mpr: FILE:LINE: reason", "mpr: invalid PARAMETER: reason"): the
  // Python exception carries the same text.
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const mpr::io_error& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const mpr::error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  mpr_py::bind_lightfields(m);
  mpr_py::bind_cameras(m);
  mpr_py::bind_render(m);
  mpr_py::bind_depth(m);
  mpr_py::bind_scenes(m);
}
