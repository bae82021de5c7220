// Rendering from Python: one view or a grid of views into a new numpy array, 8-bit sRGB or linear
// float32, with the GIL released while rendering.

#include "policies.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace mpr_py {
namespace {

struct ApertureArgs {
  std::string shape = "none";
  double size = 0;
  double lens_distance = 0;
  double focus = 0;
};

RenderJob job_of(const std::string& interpolation, double radius, int spp, const std::string& filter,
                 double filter_radius, int threads, const ApertureArgs& aperture = {}) {
  RenderJob job;
  if (aperture.shape != "none") job.aperture = mpr::aperture_by_name(aperture.shape, "aperture");
  if (job.aperture && spp < 2)
    throw mpr::argument_error("aperture", "a finite aperture needs spp > 1 (each sample gets its own aperture point)");
  if (!(aperture.size >= 0) || !std::isfinite(aperture.size))
    throw mpr::argument_error("aperture_size", "must be finite and >= 0");
  if (!(aperture.lens_distance >= 0) || !std::isfinite(aperture.lens_distance))
    throw mpr::argument_error("lens_distance", "must be finite and >= 0 (0: the image plane's width)");
  if (!(aperture.focus >= 0) || !std::isfinite(aperture.focus))
    throw mpr::argument_error("focus", "must be finite and >= 0 (0: on the image plane)");
  job.aperture_size = aperture.size;
  job.lens_distance = aperture.lens_distance;
  job.focus_depth = aperture.focus;
  job.interpolation = mpr::choose(mpr::interpolation_names, interpolation, "interpolation");
  job.radius = radius;
  job.spp = spp;
  job.filter = checked_filter(spp, filter, filter_radius); // errors before any pixel is written
  job.filter_radius = filter_radius;
  job.threads = threads;
  return job;
}

/// `given` when it is a writable C-contiguous height x width x 3 array of `Channel` (ValueError
/// naming "out" otherwise), else a new array.
template <class Channel>
py::array_t<Channel> output_array(const std::optional<py::array>& given, int width, int height) {
  const std::vector<py::ssize_t> shape{height, width, 3};
  if (!given) return py::array_t<Channel>(shape);
  const py::array& a = *given;
  const char* dtype = std::is_same_v<Channel, float> ? "float32 (linear=True)" : "uint8";
  if (!py::isinstance<py::array_t<Channel>>(a) || !a.dtype().is(py::dtype::of<Channel>()))
    throw mpr::argument_error("out", std::string("dtype must be ") + dtype);
  if (a.ndim() != 3 || a.shape(0) != height || a.shape(1) != width || a.shape(2) != 3)
    throw mpr::argument_error("out",
                              "shape must be (" + std::to_string(height) + ", " + std::to_string(width) + ", 3)");
  if (!(a.flags() & py::array::c_style) || !a.writeable())
    throw mpr::argument_error("out", "must be C-contiguous and writeable");
  return py::reinterpret_borrow<py::array_t<Channel>>(a);
}

template <class OutPx, class Channel>
py::array render_into(const FrameSet& frames, const RenderJob& job, const std::vector<Tile>& tiles, int width,
                      int height, const std::optional<py::array>& given) {
  py::array_t<Channel> out = output_array<Channel>(given, width, height);
  auto* data = reinterpret_cast<OutPx*>(out.mutable_data());
  if (!given && static_cast<long>(tiles.size()) * tiles[0].region.width * tiles[0].region.height <
                    static_cast<long>(width) * height)
    std::memset(out.mutable_data(), 0, static_cast<std::size_t>(out.nbytes())); // tiles without a view stay black
  {
    py::gil_scoped_release release;
    const mpr::ImageView<OutPx> view(data, width, height);
    std::visit([&](const auto& set) { render_tiles(set, job, std::span<const Tile>(tiles), view); }, frames.frames);
  }
  return out;
}

py::array render_grid(const FrameSet& frames, const std::vector<View>& views, int width, int height, int columns,
                      const std::string& interpolation, double radius, int spp, const std::string& filter,
                      double filter_radius, bool linear, int threads, const std::optional<py::array>& out,
                      const std::string& aperture, double aperture_size, double lens_distance, double focus) {
  if (width < 1 || height < 1 || width > (1 << 15) || height > (1 << 15))
    throw mpr::argument_error("width/height", "each must lie in [1, 32768] pixels");
  if (views.empty()) throw mpr::argument_error("views", "no views");
  if (columns < 1) throw mpr::argument_error("columns", "must be positive");
  const RenderJob job = job_of(interpolation, radius, spp, filter, filter_radius, threads,
                               ApertureArgs{aperture, aperture_size, lens_distance, focus});
  const int count = static_cast<int>(views.size());
  const int cols = std::min(columns, count), rows = (count + cols - 1) / cols;
  std::vector<Tile> tiles;
  for (int k = 0; k < count; ++k)
    tiles.push_back(
        Tile{&views[static_cast<std::size_t>(k)], mpr::Region((k % cols) * width, (k / cols) * height, width, height)});
  if (linear) return render_into<mpr::Color, float>(frames, job, tiles, cols * width, rows * height, out);
  return render_into<mpr::Rgb8, std::uint8_t>(frames, job, tiles, cols * width, rows * height, out);
}

} // namespace

void bind_render(py::module_& m) {
  m.def(
      "render",
      [](const FrameSet& frames, const View& view, int width, int height, const std::string& interpolation,
         double radius, int spp, const std::string& filter, double filter_radius, bool linear, int threads,
         const std::optional<py::array>& out, const std::string& aperture, double aperture_size, double lens_distance,
         double focus) {
        return render_grid(frames, {view}, width, height, 1, interpolation, radius, spp, filter, filter_radius, linear,
                           threads, out, aperture, aperture_size, lens_distance, focus);
      },
      py::arg("frames"), py::arg("view"), py::arg("width"), py::arg("height"), py::arg("interpolation") = "synthetic",
      py::arg("radius") = 1.0, py::arg("spp") = 1, py::arg("filter") = "box", py::arg("filter_radius") = 0.0,
      py::arg("linear") = false, py::arg("threads") = 0, py::arg("out") = py::none(), py::arg("aperture") = "none",
      py::arg("aperture_size") = 0.0, py::arg("lens_distance") = 0.0, py::arg("focus") = 0.0,
      "Renders `view` of the light field into a new height x width x 3 array: uint8 sRGB codes, or float32 linear "
      "RGB with linear=True. interpolation (`mpr.interpolations`, mpr-render's --interp names): 'nearest', "
      "'synthetic' (alias 'synthetic_aperture'), 'cylinder' (cameras within `radius` "
      "world units of the ray line) or 'depth' (needs depth maps: the cameras within `radius` of the ray, blended at "
      "the surface the maps give); spp > 1 supersamples each pixel with Owen-scrambled Sobol points weighted by "
      "`filter` ('box', 'tent', 'gaussian', 'mitchell', 'lanczos'; `filter_radius` pixels, 0: its default). "
      "`threads` 0: all cores. The same image for every thread count; the GIL is released while rendering. "
      "`out`: an existing C-contiguous array of the output's shape and dtype to render into (no allocation); it is "
      "returned. `aperture` ('none', or mpr-render's --aperture shapes 'disc', 'square', 'gaussian', 'polygonN' "
      "with N = 3..64 blades; needs spp > 1): a finite aperture around "
      "the view's GLC (Adams and Levoy 2007) of `aperture_size` (radius, half side or sigma, world units) on a lens "
      "plane `lens_distance` behind the image plane (0: the plane's width), focused `focus` in front of the image "
      "plane (0: on it).");
  m.def("render_views", &render_grid, py::arg("frames"), py::arg("views"), py::arg("width"), py::arg("height"),
        py::arg("columns"), py::arg("interpolation") = "synthetic", py::arg("radius") = 1.0, py::arg("spp") = 1,
        py::arg("filter") = "box", py::arg("filter_radius") = 0.0, py::arg("linear") = false, py::arg("threads") = 0,
        py::arg("out") = py::none(), py::arg("aperture") = "none", py::arg("aperture_size") = 0.0,
        py::arg("lens_distance") = 0.0, py::arg("focus") = 0.0,
        "Renders several views into one image: view k into the tile (k % columns, k // columns) of width x height "
        "pixels; tiles without a view are black in a new array and untouched in `out`. Options as `render`.");
  m.def(
      "_render_seconds",
      [](const FrameSet& frames, const View& view, int width, int height, const std::string& interpolation, int repeats,
         int threads, const std::optional<py::array>& out) {
        const RenderJob job = job_of(interpolation, 1.0, 1, "box", 0.0, threads);
        const std::vector<Tile> tiles{Tile{&view, mpr::Region(0, 0, width, height)}};
        mpr::Image<mpr::Rgb8> own(out ? 0 : width, out ? 0 : height);
        py::array_t<std::uint8_t> given;
        if (out) given = output_array<std::uint8_t>(out, width, height);
        const mpr::ImageView<mpr::Rgb8> image =
            out ? mpr::ImageView<mpr::Rgb8>(reinterpret_cast<mpr::Rgb8*>(given.mutable_data()), width, height)
                : own.view();
        py::gil_scoped_release release;
        const auto thread_seconds = [] {
          timespec ts{};
          clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
          return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
        };
        const auto start = std::chrono::steady_clock::now();
        const double cpu_start = thread_seconds();
        for (int r = 0; r < repeats; ++r)
          std::visit([&](const auto& set) { render_tiles(set, job, std::span<const Tile>(tiles), image); },
                     frames.frames);
        const double n = std::max(repeats, 1);
        return std::make_pair(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / n,
                              (thread_seconds() - cpu_start) / n);
      },
      py::arg("frames"), py::arg("view"), py::arg("width"), py::arg("height"), py::arg("interpolation"),
      py::arg("repeats"), py::arg("threads") = 0, py::arg("out") = py::none(),
      "Benchmark aid: (wall, calling thread's CPU) seconds per render of the same job timed inside C++ (8-bit "
      "output into `out` when given, else into an image of its own; no Python in the loop).");
  const auto listed = [](const auto& table) {
    py::list names;
    for (const auto& e : table)
      if (!e.alias) names.append(std::string(e.name));
    return names;
  };
  m.attr("interpolations") = listed(mpr::interpolation_names);
  m.attr("filters") = listed(mpr::filter_names);
}

} // namespace mpr_py
