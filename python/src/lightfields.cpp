// Light fields from Python: mpr's loaders (_par.txt, Stanford, LFCA, COLMAP) and frame sets built
// from numpy images with per-camera K, R, t and optional depth maps.

#include "bindings.hpp"

#include <mpr/io/colmap.hpp>
#include <mpr/io/lfca_calibration.hpp>
#include <mpr/io/par_file.hpp>
#include <mpr/io/stanford_light_field.hpp>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mpr_py {
namespace {

template <class Set>
FrameSet shared(Set&& set) {
  return FrameSet{std::make_shared<const std::remove_cvref_t<Set>>(std::forward<Set>(set))};
}

mpr::PlanarArrayOptions array_options(double scale, double reference_depth, double focal_length, bool negate_x,
                                      bool negate_y, bool centre) {
  mpr::PlanarArrayOptions o;
  o.scale = scale;
  o.reference_depth = reference_depth;
  o.focal_length = focal_length;
  o.negate_x = negate_x;
  o.negate_y = negate_y;
  o.centre = centre;
  return o;
}

/// `image` as an (H, W, 3) C-contiguous array of `dtype`, or ValueError naming `name`.
void require_image(const py::array& image, const std::string& name) {
  if (image.ndim() != 3 || image.shape(2) != 3)
    throw mpr::argument_error(name, "expected an H x W x 3 array, got " + std::to_string(image.ndim()) + " dimensions");
  if (!(image.flags() & py::array::c_style))
    throw mpr::argument_error(name, "not C-contiguous (use numpy.ascontiguousarray)");
  if (image.shape(0) < 1 || image.shape(1) < 1) throw mpr::argument_error(name, "empty image");
}

/// A handle that holds a reference to `object` (taken with the GIL) and drops it with the GIL,
/// whichever thread lets the last copy go.
std::shared_ptr<const void> keep_alive(const py::object& object) {
  PyObject* held = object.inc_ref().ptr();
  return std::shared_ptr<const void>(held, [](PyObject* p) {
    py::gil_scoped_acquire gil;
    Py_DECREF(p);
  });
}

/// The arrays as images: uint8 arrays borrowed in place (each holds a reference to its array; an
/// array the samplers cannot read in place, see `CameraFrameSet::can_share`, is copied), float32
/// arrays converted to linear `Color` images.
template <class Px, class Channel>
std::vector<mpr::Image<Px>> frame_images(const std::vector<py::array>& arrays) {
  std::vector<mpr::Image<Px>> images;
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    const py::array& a = arrays[i];
    const std::string name = "images[" + std::to_string(i) + "]";
    require_image(a, name);
    if (!py::isinstance<py::array_t<Channel>>(a) || a.dtype().kind() != py::dtype::of<Channel>().kind())
      throw mpr::argument_error(name, "every image must have the dtype of images[0]");
    const int width = static_cast<int>(a.shape(1)), height = static_cast<int>(a.shape(0));
    const auto* src = static_cast<const Channel*>(a.data());
    if constexpr (std::is_same_v<Px, mpr::Rgb8>) {
      // The set only reads frames: the pointer is const again inside it.
      auto* pixels = const_cast<mpr::Rgb8*>(reinterpret_cast<const mpr::Rgb8*>(src));
      mpr::Image<Px> image = mpr::Image<Px>::borrow(pixels, width, height, keep_alive(a));
      if (!FrameSet8::can_share(image)) { // rare: copied, so that the set is all copy or all view
        mpr::Image<Px> copy(width, height);
        std::memcpy(copy.data(), src, static_cast<std::size_t>(a.size()));
        image = std::move(copy);
      }
      images.push_back(std::move(image));
    } else {
      mpr::Image<Px> image(width, height);
      for (py::ssize_t k = 0; k < a.size(); ++k)
        if (!std::isfinite(src[k])) throw mpr::argument_error(name, "not finite at flat index " + std::to_string(k));
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
          const Channel* p = src + 3 * (static_cast<std::size_t>(y) * image.width() + x);
          image(x, y) = mpr::Color(p[0], p[1], p[2]);
        }
      images.push_back(std::move(image));
    }
  }
  return images;
}

std::vector<mpr::PinholeCamera<T>> cameras_of(const py::array_t<double>& K, const py::array_t<double>& R,
                                              const py::array_t<double>& t, const std::vector<py::array>& images) {
  const std::size_t n = images.size();
  const auto shape_is = [](const py::array_t<double>& a, std::vector<py::ssize_t> s) {
    if (static_cast<std::size_t>(a.ndim()) != s.size()) return false;
    for (std::size_t k = 0; k < s.size(); ++k)
      if (a.shape(static_cast<py::ssize_t>(k)) != s[k]) return false;
    return true;
  };
  const auto N = static_cast<py::ssize_t>(n);
  if (!shape_is(K, {N, 3, 3})) throw mpr::argument_error("K", "expected shape (N, 3, 3) with N = len(images)");
  if (!shape_is(R, {N, 3, 3})) throw mpr::argument_error("R", "expected shape (N, 3, 3) with N = len(images)");
  if (!shape_is(t, {N, 3})) throw mpr::argument_error("t", "expected shape (N, 3) with N = len(images)");
  const auto k = K.unchecked<3>();
  const auto r = R.unchecked<3>();
  const auto tt = t.unchecked<2>();
  std::vector<mpr::PinholeCamera<T>> cameras;
  for (py::ssize_t i = 0; i < N; ++i) {
    mpr::Mat3<double> Ki, Ri;
    mpr::Vec3<double> ti;
    for (int a = 0; a < 3; ++a) {
      ti[a] = tt(i, a);
      for (int b = 0; b < 3; ++b) Ki(a, b) = k(i, a, b), Ri(a, b) = r(i, a, b);
    }
    const py::array& image = images[static_cast<std::size_t>(i)];
    try {
      cameras.emplace_back(Ki.cast<T>(), Ri.cast<T>(), ti.cast<T>(), static_cast<int>(image.shape(1)),
                           static_cast<int>(image.shape(0)));
    } catch (const mpr::argument_error& e) {
      throw mpr::argument_error(e.parameter() + "[" + std::to_string(i) + "]", e.reason());
    }
  }
  return cameras;
}

std::vector<mpr::Image<float>> depth_maps(const std::optional<std::vector<py::array_t<float>>>& depths) {
  std::vector<mpr::Image<float>> maps;
  if (!depths) return maps;
  for (std::size_t i = 0; i < depths->size(); ++i) {
    const py::array_t<float>& d = (*depths)[i];
    if (d.ndim() != 2) throw mpr::argument_error("depths[" + std::to_string(i) + "]", "expected an H x W array");
    mpr::Image<float> map(static_cast<int>(d.shape(1)), static_cast<int>(d.shape(0)));
    const auto v = d.unchecked<2>();
    for (int y = 0; y < map.height(); ++y)
      for (int x = 0; x < map.width(); ++x) map(x, y) = v(y, x);
    maps.push_back(std::move(map));
  }
  return maps;
}

FrameSet from_arrays(const std::vector<py::array>& images, const py::array_t<double>& K, const py::array_t<double>& R,
                     const py::array_t<double>& t, std::vector<std::string> names,
                     const std::optional<std::vector<py::array_t<float>>>& depths) {
  if (images.empty()) throw mpr::argument_error("images", "no images");
  std::vector<mpr::PinholeCamera<T>> cameras = cameras_of(K, R, t, images);
  std::vector<mpr::Image<float>> maps = depth_maps(depths);
  const py::dtype dtype = images[0].dtype();
  if (dtype.is(py::dtype::of<std::uint8_t>())) {
    auto frames = frame_images<mpr::Rgb8, std::uint8_t>(images);
    py::gil_scoped_release release;
    FrameSet8 set(std::move(cameras), std::move(frames), std::move(names));
    if (!maps.empty()) set = std::move(set).with_depth(std::move(maps));
    return shared(std::move(set));
  }
  if (dtype.is(py::dtype::of<float>())) {
    auto frames = frame_images<mpr::Color, float>(images);
    py::gil_scoped_release release;
    FrameSetLinear set(std::move(cameras), std::move(frames), std::move(names));
    if (!maps.empty()) set = std::move(set).with_depth(std::move(maps));
    return shared(std::move(set));
  }
  throw mpr::argument_error("images", "dtype must be uint8 (sRGB codes) or float32 (linear RGB)");
}

py::array image_array(const FrameSet& fs, std::size_t i) {
  if (i >= fs.size()) throw py::index_error("frame index out of range");
  return std::visit(
      [&](const auto& f) -> py::array {
        using Px = typename std::remove_cvref_t<decltype(*f)>::pixel_type;
        const auto& image = f->image(i);
        const std::vector<py::ssize_t> shape{image.height(), image.width(), 3};
        if constexpr (std::is_same_v<Px, mpr::Rgb8>) {
          py::array_t<std::uint8_t> out(shape);
          std::memcpy(out.mutable_data(), image.view().row(0), static_cast<std::size_t>(out.size()));
          return out;
        } else {
          py::array_t<float> out(shape);
          float* p = out.mutable_data();
          for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
              for (int c = 0; c < 3; ++c) *p++ = image(x, y)[c];
          return out;
        }
      },
      fs.frames);
}

} // namespace

void bind_lightfields(py::module_& m) {
  py::class_<FrameSet>(m, "FrameSet",
                       "Calibrated cameras and the images they took (a light field). Frames are 8-bit sRGB "
                       "(uint8) or linear RGB (float32), shared by every sampler; a set built by `frame_set` from "
                       "uint8 arrays reads them in place (see `shares`).")
      .def("__len__", &FrameSet::size)
      .def_property_readonly(
          "linear", [](const FrameSet& f) { return f.frames.index() == 1; }, "True for float32 linear frames.")
      .def(
          "camera", [](const FrameSet& f, std::size_t i) { return f.camera(i); }, py::arg("index"),
          "Camera `index` (a copy).")
      .def_property_readonly(
          "names", [](const FrameSet& f) { return std::visit([](const auto& s) { return s->names(); }, f.frames); },
          "The frame names (image file names for loaded sets).")
      .def_property_readonly(
          "has_depth",
          [](const FrameSet& f) { return std::visit([](const auto& s) { return s->has_depth(); }, f.frames); })
      .def(
          "shares",
          [](const FrameSet& f, std::size_t i) {
            if (i >= f.size()) throw py::index_error("frame index out of range");
            return std::visit([&](const auto& s) { return s->shares_image(i); }, f.frames);
          },
          py::arg("index"),
          "True when frame `index` is read in place from the array it was built from (no copy): writing to that "
          "array changes later renders. False for loaded, float32 and copied frames.")
      .def("image", &image_array, py::arg("index"),
           "Frame `index` as a new H x W x 3 array (uint8 sRGB codes or float32 linear).");

  m.def(
      "read_par", [](const std::filesystem::path& path) { return shared(mpr::read_par_file<T>(path)); },
      py::arg("path"), py::call_guard<py::gil_scoped_release>(),
      "Reads a Middlebury `<name>_par.txt` calibration and its images (metric pinhole cameras, x ~ K [R|t] X). "
      "Raises OSError naming the file and line.");
  m.def(
      "read_stanford",
      [](const std::filesystem::path& folder, double scale, double reference_depth, double focal_length, bool negate_x,
         bool negate_y, bool centre) {
        return shared(mpr::read_stanford_light_field<T>(
            folder, array_options(scale, reference_depth, focal_length, negate_x, negate_y, centre)));
      },
      py::arg("folder"), py::arg("scale") = 1.0, py::arg("reference_depth") = 1000.0, py::arg("focal_length") = 0.0,
      py::arg("negate_x") = false, py::arg("negate_y") = false, py::arg("centre") = true,
      py::call_guard<py::gil_scoped_release>(),
      "Reads a Stanford light-field folder (out_ROW_COL_Y_X.png) as a rectified planar array on z = 0: positions "
      "times `scale` are world units, the reference plane (zero disparity) lies at z = `reference_depth`, "
      "`focal_length` in pixels (0: the image width).");
  m.def(
      "read_lfca",
      [](const std::filesystem::path& positions, double scale, double reference_depth, double focal_length) {
        mpr::LfcaOptions o;
        o.array = array_options(scale, reference_depth, focal_length, false, false, true);
        return shared(mpr::read_lfca<T>(positions, o));
      },
      py::arg("positions"), py::arg("scale") = 1.0, py::arg("reference_depth") = 1000.0, py::arg("focal_length") = 0.0,
      py::call_guard<py::gil_scoped_release>(),
      "Reads an LFCA calibration (`camera-id X Y` lines, per-camera homographies, images) as a planar array.");
  m.def(
      "read_colmap",
      [](const std::filesystem::path& model, const std::filesystem::path& images) {
        return shared(mpr::read_colmap<T>(model, images));
      },
      py::arg("model_dir"), py::arg("image_dir"), py::call_guard<py::gil_scoped_release>(),
      "Reads a COLMAP text model (cameras.txt: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV without "
      "tangential terms; images.txt) and its images, ordered by image id. Raises OSError naming the file and "
      "line; other camera models are refused by name.");
  m.def("frame_set", &from_arrays, py::arg("images"), py::arg("K"), py::arg("R"), py::arg("t"),
        py::arg("names") = std::vector<std::string>{}, py::arg("depths") = py::none(),
        "A frame set from numpy arrays: `images` a list of H x W x 3 C-contiguous arrays, all uint8 (sRGB codes) "
        "or all float32 (linear RGB); K (N, 3, 3) intrinsics in pixels (pixel centres at integers), R (N, 3, 3) "
        "and t (N, 3) world to camera (x_cam = R X + t); optional `depths`, one H x W float32 map per camera "
        "(camera-space z, world units, inf where nothing). uint8 images are not copied: the set reads each array "
        "in place and keeps a reference to it, so writing to an array changes later renders (do not write while a "
        "render runs; pass copies for a snapshot). An array whose last byte lies within 64 bytes of the end of a "
        "4 KiB memory block (about 1 in 64; the kernels read up to 64 bytes past a frame) is copied instead: "
        "`FrameSet.shares(i)` tells which. float32 images are converted (copied) to the set's linear frames, and "
        "depth maps are copied. Raises ValueError naming the argument.");
}

} // namespace mpr_py
