// Scenes from Python: the classroom demo scene and OBJ files (with tinyobjloader), ray cast into
// numpy arrays with the same views and pixel sampling as light-field renders (mpr::render_chosen,
// the dispatch mpr-render renders through).

#include "policies.hpp"

#include <mpr/render/policy_dispatch.hpp>
#include <mpr/render/renderer.hpp>
#include <mpr/scene/classroom.hpp>
#include <mpr/scene/scene_sampler.hpp>
#ifdef MPR_HAVE_TINYOBJLOADER
#include <mpr/scene/obj_loader.hpp>
#endif

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

namespace mpr_py {
namespace {

using Sampler = mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>;

/// A scene with its BVH, built once and shared by every render.
struct Scene {
  std::shared_ptr<const Sampler> sampler;
};

template <class OutPx, class Channel>
py::array render_scene(const Scene& scene, const View& view, int width, int height, int spp, const std::string& filter,
                       double filter_radius, int threads) {
  if (width < 1 || height < 1 || width > (1 << 15) || height > (1 << 15))
    throw mpr::argument_error("width/height", "each must lie in [1, 32768] pixels");
  const mpr::FilterChoice choice = checked_filter(spp, filter, filter_radius); // before any allocation
  const mpr::PixelSamplingVariant sampling = mpr::make_pixel_sampling(spp, mpr::make_filter(choice, filter_radius));
  py::array_t<Channel> out({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width), py::ssize_t{3}});
  const mpr::ImageView<OutPx> image(reinterpret_cast<OutPx*>(out.mutable_data()), width, height);
  {
    py::gil_scoped_release release;
    mpr::render_chosen(view.plane, view.selector, view.plane, *scene.sampler, sampling, nullptr, image,
                       mpr::Region(0, 0, width, height), mpr::RenderOptions{threads});
  }
  return out;
}

} // namespace

void bind_scenes(py::module_& m) {
  py::class_<Scene>(m, "Scene", "A triangle scene with its BVH, ray cast with simple shading (world units).");
  m.def(
      "classroom", [] { return Scene{std::make_shared<const Sampler>(mpr::scene::classroom<T>())}; },
      py::call_guard<py::gil_scoped_release>(),
      "The built-in classroom demo scene (deterministic; about 14 world units across, see mpr/scene/classroom.hpp).");
#ifdef MPR_HAVE_TINYOBJLOADER
  m.def(
      "read_obj",
      [](const std::filesystem::path& path, double scale) {
        mpr::scene::Scene<T> scene;
        mpr::scene::ObjOptions options;
        options.scale = scale;
        (void)mpr::scene::add_obj(scene, path, options);
        return Scene{std::make_shared<const Sampler>(std::move(scene))};
      },
      py::arg("path"), py::arg("scale") = 1.0, py::call_guard<py::gil_scoped_release>(),
      "Reads an OBJ file (and its MTL materials) as a scene, vertex positions times `scale` world units. Raises "
      "OSError naming the file and line.");
#endif
  m.def(
      "render_scene",
      [](const Scene& scene, const View& view, int width, int height, int spp, const std::string& filter,
         double filter_radius, bool linear, int threads) {
        if (linear)
          return render_scene<mpr::Color, float>(scene, view, width, height, spp, filter, filter_radius, threads);
        return render_scene<mpr::Rgb8, std::uint8_t>(scene, view, width, height, spp, filter, filter_radius, threads);
      },
      py::arg("scene"), py::arg("view"), py::arg("width"), py::arg("height"), py::arg("spp") = 1,
      py::arg("filter") = "box", py::arg("filter_radius") = 0.0, py::arg("linear") = false, py::arg("threads") = 0,
      "Ray casts `view` of `scene` into a new height x width x 3 array (uint8 sRGB, or float32 linear with "
      "linear=True); pixel sampling as `render`. The GIL is released while rendering.");
}

} // namespace mpr_py
