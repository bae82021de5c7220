// Depth from Python: the plane sweep of mpr/lightfield/depth_estimation.hpp into numpy arrays.

#include "bindings.hpp"

#include <mpr/core/renderer.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/view_depth.hpp>

#include <pybind11/stl.h>

#include <cstring>
#include <optional>
#include <type_traits>

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

py::array_t<float> view_depth(const FrameSet& frames, const View& view, int width, int height,
                              const std::optional<mpr::PinholeCamera<T>>& along, int threads) {
  if (width < 1 || height < 1 || width > (1 << 15) || height > (1 << 15))
    throw mpr::argument_error("width/height", "each must lie in [1, 32768] pixels");
  py::array_t<float> out({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width)});
  const mpr::ImageView<float> image(out.mutable_data(), width, height);
  std::visit(
      [&](const auto& set) {
        using Px = typename std::remove_cvref_t<decltype(*set)>::pixel_type;
        mpr::FrameDepthSampler<T, Px> sampler(set);
        if (along) sampler = std::move(sampler).along_axis(*along);
        py::gil_scoped_release release;
        mpr::Renderer(view.plane, view.selector, sampler)
            .render(image, mpr::Region(0, 0, width, height), mpr::RenderOptions{threads});
      },
      frames.frames);
  return out;
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
  m.def("view_depth", &view_depth, py::arg("frames"), py::arg("view"), py::arg("width"), py::arg("height"),
        py::arg("along") = py::none(), py::arg("threads") = 0,
        "The depth of any view of a light field that carries depth maps (mpr-render --write-depth): a new height x "
        "width float32 array, per pixel where the surface the cameras' depth maps describe meets the pixel's ray: "
        "the ray parameter (signed distance in front of the view's image plane, world units), or with "
        "`along=camera` the depth along that camera's optical axis; inf where no surface is found.");
}

} // namespace mpr_py
