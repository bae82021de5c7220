// Depth from Python: the plane sweep of mpr/lightfield/depth_estimation.hpp into numpy arrays.

#include "bindings.hpp"

#include <mpr/lightfield/depth_estimation.hpp>

#include <pybind11/stl.h>

#include <cstring>

namespace mpr_py {
namespace {

py::array_t<float> to_array(const mpr::Image<float>& image) {
  py::array_t<float> out({static_cast<py::ssize_t>(image.height()), static_cast<py::ssize_t>(image.width())});
  std::memcpy(out.mutable_data(), image.data(), sizeof(float) * static_cast<std::size_t>(out.size()));
  return out;
}

mpr::PlaneSweepConfig config_of(double near, double far, int planes, int neighbours, int best, double truncation,
                                double spatial, double range, int threads) {
  mpr::PlaneSweepConfig c;
  c.near = near;
  c.far = far;
  c.planes = planes;
  c.neighbours = neighbours;
  c.best = best;
  c.truncation = truncation;
  c.spatial = spatial;
  c.range = range;
  c.threads = threads;
  mpr::validate(c);
  return c;
}

} // namespace

void bind_depth(py::module_& m) {
  m.def(
      "estimate_depth",
      [](const FrameSet& frames, std::size_t camera, double near, double far, int planes, int neighbours, int best,
         double truncation, double spatial, double range, int threads) {
        const mpr::PlaneSweepConfig c =
            config_of(near, far, planes, neighbours, best, truncation, spatial, range, threads);
        mpr::DepthEstimate e;
        {
          py::gil_scoped_release release;
          e = std::visit([&](const auto& f) { return mpr::estimate_depth(*f, camera, c); }, frames.frames);
        }
        return py::make_tuple(to_array(e.depth), to_array(e.confidence));
      },
      py::arg("frames"), py::arg("camera"), py::arg("near"), py::arg("far"), py::arg("planes") = 64,
      py::arg("neighbours") = 4, py::arg("best") = 2, py::arg("truncation") = 0.3, py::arg("spatial") = 12.0,
      py::arg("range") = 0.2, py::arg("threads") = 0,
      "Plane-sweep depth of camera `camera` against its `neighbours` nearest cameras: returns (depth, confidence), "
      "two H x W float32 arrays; depth along the camera's optical axis in world units within [near, far], "
      "confidence in [0, 1]. The GIL is released while sweeping.");
}

} // namespace mpr_py
