// Cameras from Python: metric pinhole cameras, views (an image plane plus a General Linear
// Camera): the pinhole refocus view, the GLC gallery, GLCs from corner rays or from two planes;
// `classify` and `project`.

#include "bindings.hpp"

#include <mpr/camera/pinhole_glc.hpp>
#include <mpr/glc/classify.hpp>
#include <mpr/glc/gallery.hpp>
#include <mpr/glc/project.hpp>
#include <mpr/lightfield/array_view.hpp>

#include <pybind11/stl.h>

#include <optional>
#include <string>

namespace mpr_py {

mpr::Vec3<T> to_vec3(const py::handle& value, const char* name) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 1 || a.shape(0) != 3) throw mpr::argument_error(name, "expected 3 numbers");
  const mpr::Vec3<double> v(a.at(0), a.at(1), a.at(2));
  if (!v.allFinite()) throw mpr::argument_error(name, "not finite");
  return v.cast<T>();
}

mpr::Mat3<T> to_mat3(const py::handle& value, const char* name) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 2 || a.shape(0) != 3 || a.shape(1) != 3)
    throw mpr::argument_error(name, "expected a 3x3 array");
  mpr::Mat3<double> m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = a.at(r, c);
  if (!m.allFinite()) throw mpr::argument_error(name, "not finite");
  return m.cast<T>();
}

py::array_t<double> from_vec3(const mpr::Vec3<T>& v) {
  py::array_t<double> a(3);
  for (int k = 0; k < 3; ++k) a.mutable_at(k) = static_cast<double>(v[k]);
  return a;
}

py::array_t<double> from_mat3(const mpr::Mat3<T>& m) {
  py::array_t<double> a({3, 3});
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a.mutable_at(r, c) = static_cast<double>(m(r, c));
  return a;
}

namespace {

using Camera = mpr::PinholeCamera<T>;

mpr::PlanarSurface<T> plane_of(const py::handle& origin, const py::handle& width_vector,
                               const py::handle& height_vector) {
  return mpr::PlanarSurface<T>(to_vec3(origin, "origin"), to_vec3(width_vector, "width_vector"),
                               to_vec3(height_vector, "height_vector"));
}

py::dict classify_view(const View& v) {
  const mpr::glc::Classification<T> c = mpr::glc::classify(v.plane, v.selector);
  py::dict d;
  d["type"] = std::string(mpr::glc::to_string(c.type));
  d["slit_count"] = c.slit_count;
  d["depths"] = py::make_tuple(static_cast<double>(c.depths[0]), static_cast<double>(c.depths[1]));
  d["centre"] = from_vec3(c.centre);
  d["direction"] = from_vec3(c.direction);
  return d;
}

std::optional<py::tuple> project_point(const View& v, const py::handle& point) {
  const std::optional<mpr::Vec2<T>> uv = mpr::glc::project(v.plane, v.selector, to_vec3(point, "point"));
  if (!uv) return std::nullopt;
  return py::make_tuple(static_cast<double>(uv->x()), static_cast<double>(uv->y()));
}

} // namespace

void bind_cameras(py::module_& m) {
  py::class_<Camera>(m, "Camera",
                     "A metric pinhole camera: x ~ K [R | t] X (world to camera x_cam = R X + t, camera looks along "
                     "+z, image x right, y down), pixel centres at integer coordinates, optional radial distortion "
                     "(1 + k1 r^2 + k2 r^4 on normalised coordinates).")
      .def(py::init([](const py::handle& K, const py::handle& R, const py::handle& t, int width, int height, double k1,
                       double k2) {
             return Camera(to_mat3(K, "K"), to_mat3(R, "R"), to_vec3(t, "t"), width, height,
                           Camera::Distortion{static_cast<T>(k1), static_cast<T>(k2)});
           }),
           py::arg("K"), py::arg("R"), py::arg("t"), py::arg("width"), py::arg("height"), py::arg("k1") = 0.0,
           py::arg("k2") = 0.0)
      .def_static(
          "look_at",
          [](const py::handle& eye, const py::handle& target, const py::handle& up, double vertical_fov, int width,
             int height) {
            return Camera::look_at(to_vec3(eye, "eye"), to_vec3(target, "target"), to_vec3(up, "up"),
                                   static_cast<T>(vertical_fov), width, height);
          },
          py::arg("eye"), py::arg("target"), py::arg("up"), py::arg("vertical_fov"), py::arg("width"),
          py::arg("height"), "A camera at `eye` looking at `target`; `vertical_fov` in radians.")
      .def_property_readonly(
          "K", [](const Camera& c) { return from_mat3(c.K()); }, "Intrinsics (pixels), K[2,2] = 1.")
      .def_property_readonly(
          "R", [](const Camera& c) { return from_mat3(c.R()); }, "World-to-camera rotation.")
      .def_property_readonly(
          "t", [](const Camera& c) { return from_vec3(c.t()); }, "World-to-camera translation.")
      .def_property_readonly(
          "centre", [](const Camera& c) { return from_vec3(c.centre()); }, "-R^T t, world units.")
      .def_property_readonly("width", &Camera::width)
      .def_property_readonly("height", &Camera::height)
      .def(
          "project",
          [](const Camera& c, const py::handle& X) -> std::optional<py::tuple> {
            const auto p = c.project(to_vec3(X, "point"));
            if (!p) return std::nullopt;
            return py::make_tuple(static_cast<double>(p->x()), static_cast<double>(p->y()));
          },
          py::arg("point"), "Pixel coordinates (x, y) of a world point, or None when behind or outside the image.");

  py::class_<View>(m, "View",
                   "A view: an image plane (origin, width_vector and height_vector, world units; its uv square "
                   "[0,1]^2 is the output image, u right, v down) and a General Linear Camera giving each pixel's "
                   "ray (Yu and McMillan, ECCV 2004).")
      .def(py::init([](const py::handle& origin, const py::handle& wv, const py::handle& hv, const py::handle& d00,
                       const py::handle& d10, const py::handle& d01) {
             const mpr::PlanarSurface<T> plane = plane_of(origin, wv, hv);
             return View{plane,
                         mpr::GlcSelector<T>(plane, to_vec3(d00, "d00"), to_vec3(d10, "d10"), to_vec3(d01, "d01"))};
           }),
           py::arg("origin"), py::arg("width_vector"), py::arg("height_vector"), py::arg("d00"), py::arg("d10"),
           py::arg("d01"),
           "A GLC from its three generator rays' directions at the plane corners uv (0,0), (1,0), (0,1).")
      .def_static(
          "two_plane",
          [](const py::handle& origin, const py::handle& wv, const py::handle& hv, const py::handle& q00,
             const py::handle& q10, const py::handle& q01) {
            const mpr::PlanarSurface<T> plane = plane_of(origin, wv, hv);
            const mpr::Vec3<T> p00 = plane.origin(), p10 = p00 + plane.width_vector(),
                               p01 = p00 + plane.height_vector();
            return View{plane, mpr::GlcSelector<T>(plane, mpr::Vec3<T>(to_vec3(q00, "q00") - p00),
                                                   mpr::Vec3<T>(to_vec3(q10, "q10") - p10),
                                                   mpr::Vec3<T>(to_vec3(q01, "q01") - p01))};
          },
          py::arg("origin"), py::arg("width_vector"), py::arg("height_vector"), py::arg("q00"), py::arg("q10"),
          py::arg("q01"),
          "The two-plane GLC: the generator ray of corner (0,0) (of (1,0), (0,1)) goes from the image plane's "
          "corner through the world point q00 (q10, q01) on a second plane.")
      .def_static(
          "pinhole",
          [](const Camera& camera, double depth) {
            const mpr::PlanarSurface<T> plane = camera.image_plane(static_cast<T>(depth));
            return View{plane, mpr::pinhole_glc(camera, plane)};
          },
          py::arg("camera"), py::arg("depth"),
          "The refocus view of `camera`: its image plane at `depth` (world units along its axis) and rays "
          "through its centre; an output of camera.width x camera.height puts each pixel on the camera's pixel.")
      .def_static(
          "gallery",
          [](const std::string& id, const py::handle& origin, const py::handle& wv, const py::handle& hv,
             const py::handle& scene_centre, double scale) {
            if (id.size() != 1) throw mpr::argument_error("id", "one letter A..I");
            const mpr::PlanarSurface<T> plane = plane_of(origin, wv, hv);
            return View{plane, mpr::glc::gallery_view(id[0], plane, to_vec3(scene_centre, "scene_centre"),
                                                      static_cast<T>(scale))};
          },
          py::arg("id"), py::arg("origin"), py::arg("width_vector"), py::arg("height_vector"), py::arg("scene_centre"),
          py::arg("scale"),
          "GLC gallery view 'A'..'I' (perspective, orthographic, oblique, pushbroom, twisted orthographic x2, "
          "cross-slit, pencil, bilinear) on the plane, looking at a scene of size `scale` around `scene_centre`.")
      .def(
          "fit_to_array",
          [](const View& v, const FrameSet& frames, const Camera& reference) {
            return std::visit(
                [&](const auto& f) {
                  return View{v.plane, mpr::fit_to_array(v.plane, v.selector, mpr::array_footprint(*f, reference))};
                },
                frames.frames);
          },
          py::arg("frames"), py::arg("reference"),
          "The light-field view this GLC stands for: the same focal-plane points, with the rays' crossings of the "
          "camera plane rescaled to span the array of `frames` as seen from `reference` (so nearest-camera and "
          "cylinder renders see the whole view).")
      .def_property_readonly("origin", [](const View& v) { return from_vec3(v.plane.origin()); })
      .def_property_readonly("width_vector", [](const View& v) { return from_vec3(v.plane.width_vector()); })
      .def_property_readonly("height_vector", [](const View& v) { return from_vec3(v.plane.height_vector()); })
      .def(
          "direction_at",
          [](const View& v, double u, double w) {
            return from_vec3(v.selector.direction_at(mpr::Vec2<T>(static_cast<T>(u), static_cast<T>(w))));
          },
          py::arg("u"), py::arg("v"), "The ray direction at uv (unit component along the plane normal).");

  m.def("classify", &classify_view, py::arg("view"),
        "The GLC type of a view ('pinhole', 'orthographic', 'pushbroom', 'cross_slit', 'pencil', "
        "'twisted_orthographic', 'bilinear', 'epi') with slit count, slit depths (world units from the plane), "
        "pinhole centre and orthographic direction.");
  m.def("project", &project_point, py::arg("view"), py::arg("point"),
        "The uv (plane units, [0,1]^2 is the image) of the view's ray through a world point, or None.");
  m.def(
      "gallery_ids",
      [] {
        py::list ids;
        for (const auto& e : mpr::glc::gallery) ids.append(py::make_tuple(std::string(1, e.id), std::string(e.name)));
        return ids;
      },
      "The gallery's (id, name) pairs.");
}

} // namespace mpr_py
