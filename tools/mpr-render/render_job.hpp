#pragma once
// mpr-render's render path: a Job (job.hpp) -> loaded data -> per frame and per view a camera
// (surface + selector) and a sampler, each a std::variant, combined by ONE std::visit per view
// render into a fully typed mpr::Renderer. No per-pixel dispatch: inside the visit the inner loop
// is the same template instantiation a C++ user writes by hand (benchmarks/cli_dispatch.cpp).

#include "job.hpp"

#include <mpr/glc.hpp>
#include <mpr/lightfield.hpp>
#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>
#include <mpr/scene/rasterized_sampler.hpp>
#ifdef MPR_HAVE_TINYOBJLOADER
#include <mpr/scene/obj_loader.hpp>
#endif

#include <cctype>
#include <cstdio>
#include <functional>
#include <memory>
#include <numbers>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

namespace mpr_cli {

/// A GLC view on an image plane (no rectification).
template <std::floating_point T>
struct PlanarCamera {
  mpr::PlanarSurface<T> surface;
  mpr::GlcSelector<T> selector;
};

/// The surface+selector pair of one view: planar, or rectified through a homography.
template <std::floating_point T>
using CameraVariant = std::variant<PlanarCamera<T>, mpr::glc::Rectified<T>>;

template <std::floating_point T>
using SamplerVariant =
    std::variant<mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>, mpr::CameraFrameSampler<mpr::NearestCamera, T>,
                 mpr::CameraFrameSampler<mpr::SyntheticAperture, T>, mpr::CameraFrameSampler<mpr::CylinderAperture, T>,
                 mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::NearestCamera>>,
                 mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::SyntheticAperture>>,
                 mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::CylinderAperture>>>;

/// Renders one view: the only run-time dispatch of a render (one std::visit).
template <std::floating_point T>
void render_view(const CameraVariant<T>& camera, const SamplerVariant<T>& sampler, mpr::ImageView<mpr::Rgb8> out,
                 const mpr::Region& region, const mpr::RenderOptions& options) {
  std::visit(
      [&](const auto& cam, const auto& smp) {
        const mpr::Renderer renderer(cam.surface, cam.selector, smp);
        renderer.render(out, region, options);
      },
      camera, sampler);
}

/// The data of a job, loaded once for all frames.
template <std::floating_point T>
struct Loaded {
  std::shared_ptr<const mpr::scene::Scene<T>> scene;
  std::optional<mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>> scene_sampler;
  std::shared_ptr<const mpr::CameraFrameSet<T>> frames;
  std::optional<mpr::PinholeCamera<T>> reference; ///< light fields: the camera the views start from
  double default_focal_depth = 1;
  // Scene defaults (world units).
  mpr::Vec3<double> plane_centre{0, 3.1, 3}, look_at{0, 1.6, -8}, scene_centre{0, 1.6, -8};
  double plane_width = 8, scene_scale = 14;
};

namespace detail {

inline mpr::PlanarArrayOptions array_options(const Job& job) {
  mpr::PlanarArrayOptions o;
  o.reference_depth = job.reference_depth;
  o.scale = job.position_scale;
  return o;
}

/// The virtual camera at the centre of a rectified planar array: frame 0's intrinsics with the
/// principal point at the image centre, R = I, centre at the mean camera centre.
template <std::floating_point T>
mpr::PinholeCamera<T> array_centre_camera(const mpr::CameraFrameSet<T>& frames) {
  mpr::Vec3<T> mean = mpr::Vec3<T>::Zero();
  for (std::size_t i = 0; i < frames.size(); ++i) mean += frames.camera(i).centre();
  mean /= static_cast<T>(frames.size());
  return mpr::planar_array_reference_camera(frames.camera(0), mean);
}

} // namespace detail

/// Loads the sampler's data (scene, OBJ or light field) and its default framing.
template <std::floating_point T>
Loaded<T> load(const Job& job) {
  Loaded<T> l;
  switch (job.sampler) {
  case SamplerKind::scene:
    l.scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scene::classroom<T>());
    break;
  case SamplerKind::obj: {
#ifdef MPR_HAVE_TINYOBJLOADER
    mpr::scene::Scene<T> scene;
    mpr::scene::ObjOptions o;
    o.scale = job.obj_scale;
    mpr::scene::add_obj(scene, job.input, o);
    if (scene.empty()) throw mpr::io_error(job.input.string(), "no usable (non-degenerate) faces");
    l.scene = std::make_shared<const mpr::scene::Scene<T>>(std::move(scene));
    mpr::Vec3<double> lo = mpr::Vec3<double>::Constant(1e300), hi = -lo;
    for (const auto& tri : l.scene->triangles())
      for (const mpr::Vec3<T>& p : tri.p) {
        lo = lo.cwiseMin(p.template cast<double>());
        hi = hi.cwiseMax(p.template cast<double>());
      }
    const double diag = std::max((hi - lo).norm(), 1e-6);
    l.scene_centre = l.look_at = 0.5 * (lo + hi);
    l.plane_centre = l.scene_centre + mpr::Vec3<double>(0, 0, 1.2 * diag);
    l.plane_width = diag;
    l.scene_scale = diag;
    break;
#else
    throw mpr::argument_error("--obj", "this mpr-render was built without tinyobjloader");
#endif
  }
  case SamplerKind::par:
    l.frames = std::make_shared<const mpr::CameraFrameSet<T>>(mpr::read_par_file<T>(job.input));
    break;
  case SamplerKind::stanford:
    l.frames = std::make_shared<const mpr::CameraFrameSet<T>>(
        mpr::read_stanford_light_field<T>(job.input, detail::array_options(job)));
    break;
  case SamplerKind::lfca: {
    mpr::LfcaOptions o;
    o.array = detail::array_options(job);
    l.frames = std::make_shared<const mpr::CameraFrameSet<T>>(mpr::read_lfca<T>(job.input, o));
    break;
  }
  }
  if (l.scene) l.scene_sampler.emplace(l.scene);
  if (l.frames) {
    if (job.camera && *job.camera >= static_cast<int>(l.frames->size()))
      throw mpr::argument_error("--camera", std::to_string(*job.camera) + " is not below the camera count " +
                                                std::to_string(l.frames->size()));
    if (job.sampler == SamplerKind::par || job.camera) {
      l.reference = l.frames->camera(job.camera ? static_cast<std::size_t>(*job.camera) : l.frames->size() / 2);
      // Default focus: the depth of the mean camera centre's... projection of the array's middle.
      mpr::Vec3<double> mean = mpr::Vec3<double>::Zero();
      for (std::size_t i = 0; i < l.frames->size(); ++i) mean += l.frames->camera(i).centre().template cast<double>();
      mean /= static_cast<double>(l.frames->size());
      const double z = (l.reference->R().template cast<double>() * mean + l.reference->t().template cast<double>()).z();
      l.default_focal_depth = job.sampler == SamplerKind::par ? z : job.reference_depth;
      if (!(l.default_focal_depth > 0) && !job.focal_depth)
        throw mpr::argument_error("--focal-depth", "no default for this camera set: give --focal-depth");
    } else {
      l.reference = detail::array_centre_camera(*l.frames);
      l.default_focal_depth = job.reference_depth;
    }
  }
  return l;
}

/// The parameters of one frame.
struct FrameParams {
  double tilt_x = 0, tilt_y = 0, radius = 10, focal_depth = 1, morph = 0;
};

inline FrameParams frame_params(const Job& job, double default_focal_depth, double t) {
  FrameParams p;
  p.tilt_x = job.tilt_x.at(t);
  p.tilt_y = job.tilt_y.at(t);
  p.radius = job.radius.at(t);
  p.focal_depth = job.focal_depth ? job.focal_depth->at(t) : default_focal_depth;
  p.morph = job.morph.at(t);
  return p;
}

/// The output size of one view.
template <std::floating_point T>
std::pair<int, int> view_size(const Job& job, const Loaded<T>& l) {
  if (!job.size_given && l.reference) return {l.reference->width(), l.reference->height()};
  return {job.width, job.height};
}

/// The image plane of a frame, before tilting (see job.hpp for the defaults).
template <std::floating_point T>
mpr::PlanarSurface<T> base_plane(const Job& job, const Loaded<T>& l, const FrameParams& p, int width, int height) {
  if (l.reference) return l.reference->image_plane(static_cast<T>(p.focal_depth));
  using V = mpr::Vec3<T>;
  const V centre = (job.plane_centre ? *job.plane_centre : l.plane_centre).template cast<T>();
  const V look = (job.look_at ? *job.look_at : l.look_at).template cast<T>();
  const V up = job.up.template cast<T>();
  const T w = static_cast<T>(job.plane_size ? job.plane_size->first : l.plane_width);
  const T h =
      job.plane_size ? static_cast<T>(job.plane_size->second) : w * static_cast<T>(height) / static_cast<T>(width);
  if (!((look - centre).norm() > 0)) throw mpr::argument_error("--look-at", "equals the plane centre");
  const V forward = (look - centre).normalized();
  const V side = forward.cross(up);
  if (!(side.norm() > T(1e-6) * up.norm())) throw mpr::argument_error("--up", "parallel to the viewing direction");
  const V right = side.normalized();
  const V down = forward.cross(right);
  return mpr::PlanarSurface<T>::centred(centre, w * right, h * down);
}

template <std::floating_point T>
mpr::PlanarSurface<T> frame_plane(const mpr::PlanarSurface<T>& base, const FrameParams& p) {
  if (p.tilt_x == 0 && p.tilt_y == 0) return base;
  constexpr double deg = std::numbers::pi / 180;
  return base.tilted(static_cast<T>(p.tilt_x * deg), static_cast<T>(p.tilt_y * deg));
}

namespace detail {

/// An error's text without the "mpr: invalid " prefix, to nest it in another message.
inline std::string nested(const std::exception& e) {
  std::string what = e.what();
  for (const char* prefix : {"mpr: invalid ", "mpr: "})
    if (what.rfind(prefix, 0) == 0) return what.substr(std::char_traits<char>::length(prefix));
  return what;
}

inline std::string normalized_name(std::string s) {
  for (char& c : s)
    c = (c == ' ' || c == '-' || c == ',') ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string out;
  for (char c : s)
    if (!(c == '_' && !out.empty() && out.back() == '_')) out += c;
  return out;
}

/// The gallery letter of a view name or letter, or 0.
inline char gallery_letter(const std::string& spec) {
  if (spec.size() == 1) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(spec[0])));
    return c >= 'A' && c <= 'I' ? c : 0;
  }
  const std::string n = normalized_name(spec);
  static const std::pair<const char*, char> aliases[] = {{"oblique", 'C'},      {"twisted", 'E'},
                                                         {"twisted_down", 'F'}, {"cross_slit", 'G'},
                                                         {"crossed_slit", 'G'}, {"pinhole", 'A'}};
  for (const auto& a : aliases)
    if (n == a.first) return a.second;
  for (const mpr::glc::GalleryEntry& e : mpr::glc::gallery)
    if (n == normalized_name(std::string(e.name))) return e.id;
  return 0;
}

} // namespace detail

/// The GLC of a view spec (see view_help()) on `plane`. Throws argument_error naming `option`.
template <std::floating_point T>
mpr::GlcSelector<T> make_selector(const std::string& spec, const std::string& option,
                                  const mpr::PlanarSurface<T>& plane, const Job& job, const Loaded<T>& l,
                                  const FrameParams& p) {
  using V = mpr::Vec3<T>;
  try {
    if (spec == "default") {
      if (l.reference) return mpr::pinhole_glc(*l.reference, plane);
      return make_selector<T>("A", option, plane, job, l, p);
    }
    if (const char letter = detail::gallery_letter(spec); letter != 0) {
      V centre;
      T scale;
      if (l.reference) {
        centre = plane.centre() + static_cast<T>(0.1 * p.focal_depth) * plane.normal();
        scale = plane.width_vector().norm();
      } else {
        centre = l.scene_centre.template cast<T>();
        scale = static_cast<T>(l.scene_scale);
      }
      if (job.scene_centre) centre = job.scene_centre->template cast<T>();
      if (job.scene_scale) scale = static_cast<T>(*job.scene_scale);
      return mpr::glc::gallery_view(letter, plane, centre, scale);
    }
    const std::vector<std::string> parts = split(spec, ':');
    const std::string type = detail::normalized_name(parts[0]);
    const auto need = [&](std::size_t n, const char* form) {
      if (parts.size() != n + 1) throw mpr::argument_error(option, "'" + spec + "': expected " + form);
    };
    const auto vec = [&](std::size_t i) { return V(parse_vec3(parts[i], option).template cast<T>()); };
    const auto num = [&](std::size_t i) { return static_cast<T>(parse_number(parts[i], option)); };
    const auto line = [&](std::size_t i) {
      const V d = vec(i + 1);
      if (!(d.norm() > 0)) throw mpr::argument_error(option, "zero slit direction in '" + spec + "'");
      return mpr::glc::Line<T>{vec(i), V(d.normalized())};
    };
    if (type == "pinhole" || type == "perspective") {
      need(1, "pinhole:X,Y,Z");
      return mpr::glc::perspective(plane, vec(1));
    }
    if (type == "orthographic") {
      need(1, "orthographic:DX,DY,DZ");
      return mpr::glc::orthographic(plane, vec(1));
    }
    if (type == "oblique") {
      need(1, "oblique:AU,AV (degrees)");
      const std::vector<std::string> a = split(parts[1], ',');
      if (a.size() != 2) throw mpr::argument_error(option, "'" + spec + "': expected oblique:AU,AV");
      constexpr double deg = std::numbers::pi / 180;
      return mpr::glc::oblique_orthographic(plane, static_cast<T>(parse_number(a[0], option) * deg),
                                            static_cast<T>(parse_number(a[1], option) * deg));
    }
    if (type == "pushbroom") {
      need(2, "pushbroom:P:D");
      return mpr::glc::pushbroom(plane, line(1));
    }
    if (type == "cross_slit") {
      need(4, "cross_slit:P1:D1:P2:D2");
      return mpr::glc::cross_slit(plane, line(1), line(3));
    }
    if (type == "pencil") {
      need(3, "pencil:P:D:TWIST");
      return mpr::glc::pencil(plane, line(1), num(3));
    }
    if (type == "twisted") {
      need(3, "twisted:D:TILT:TWIST");
      return mpr::glc::twisted_orthographic(plane, vec(1), vec(2), num(3));
    }
    if (type == "bilinear") {
      need(3, "bilinear:D:CONVERGENCE:TWIST");
      return mpr::glc::bilinear(plane, vec(1), num(2), num(3));
    }
    if (type == "corners") {
      need(3, "corners:D00:D10:D01");
      return mpr::GlcSelector<T>(plane, vec(1), vec(2), vec(3));
    }
  } catch (const mpr::argument_error& e) {
    if (e.parameter() == option) throw;
    throw mpr::argument_error(option, "'" + spec + "' is an impossible camera here: " + detail::nested(e));
  }
  throw mpr::argument_error(option, "'" + spec + "' is not a view (see VIEW in --help)");
}

/// The camera of view `k` at frame parameters `p`.
template <std::floating_point T>
CameraVariant<T> make_camera(const Job& job, const Loaded<T>& l, const FrameParams& p, std::size_t k, int width,
                             int height) {
  const mpr::PlanarSurface<T> base = base_plane(job, l, p, width, height);
  const mpr::PlanarSurface<T> plane = frame_plane(base, p);
  mpr::GlcSelector<T> glc = make_selector<T>(job.views[k], "--view", plane, job, l, p);
  if (job.morph_to) {
    const mpr::GlcSelector<T> to = make_selector<T>(*job.morph_to, "--morph-to", plane, job, l, p);
    const T w = static_cast<T>(p.morph);
    const auto mix = [w](const mpr::Vec3<T>& a, const mpr::Vec3<T>& b) { return mpr::Vec3<T>((1 - w) * a + w * b); };
    try {
      glc = mpr::GlcSelector<T>(plane, mix(glc.d00(), to.d00()), mix(glc.d10(), to.d10()), mix(glc.d01(), to.d01()));
    } catch (const mpr::argument_error& e) {
      throw mpr::argument_error("--morph-to", "the two views look to opposite sides of the image plane (" +
                                                  e.parameter() + " of the morph)");
    }
  }
  if (job.rectify_to_plane) {
    // Where the view's rays through the untilted plane's corners cross the tilted plane.
    const mpr::GlcSelector<T> base_glc = make_selector<T>(job.views[k], "--view", base, job, l, p);
    std::array<mpr::Vec2<T>, 4> target;
    const std::array<mpr::Vec2<T>, 4> corners = {mpr::Vec2<T>(0, 0), mpr::Vec2<T>(1, 0), mpr::Vec2<T>(1, 1),
                                                 mpr::Vec2<T>(0, 1)};
    for (std::size_t i = 0; i < 4; ++i) {
      const mpr::Vec3<T> o = base.point_at(corners[i]);
      const mpr::Vec3<T> d = base_glc.direction_at(corners[i]);
      if (!(std::abs(d.dot(plane.normal())) > T(1e-6) * d.norm()))
        throw mpr::argument_error("--rectify", "a corner ray runs parallel to the tilted plane");
      target[i] = plane.uv_of(plane.plane().crossing(mpr::Ray<T>{o, d}));
    }
    try {
      return mpr::glc::rectify(plane, glc, target);
    } catch (const mpr::argument_error& e) {
      throw mpr::argument_error("--rectify", "view " + job.views[k] + ": " + detail::nested(e));
    }
  }
  if (job.rectify) {
    std::array<mpr::Vec3<T>, 4> quad;
    for (std::size_t i = 0; i < 4; ++i) quad[i] = (*job.rectify)[i].template cast<T>();
    try {
      return mpr::glc::rectify(plane, glc, mpr::glc::target_region(plane, glc, quad));
    } catch (const mpr::argument_error& e) {
      throw mpr::argument_error("--rectify", "view " + job.views[k] + ": " + detail::nested(e));
    }
  }
  return PlanarCamera<T>{plane, glc};
}

/// The rasterized virtual-array sampler (--raster) on the frame's untilted image plane.
template <std::floating_point T>
SamplerVariant<T> make_raster_sampler(const Job& job, const Loaded<T>& l, const FrameParams& p,
                                      const mpr::PlanarSurface<T>& plane) {
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = job.raster->first;
  config.rows = job.raster->second;
  if (job.focal_depth) config.focal_depth = static_cast<T>(p.focal_depth);
  config.raster.threads = job.threads;
  using S = mpr::scene::Scene<T>;
  switch (job.interpolation) {
  case Interpolation::nearest:
    return mpr::SceneSampler<S, mpr::Rasterized<mpr::NearestCamera>>(*l.scene, plane, config);
  case Interpolation::synthetic:
    return mpr::SceneSampler<S, mpr::Rasterized<mpr::SyntheticAperture>>(*l.scene, plane, config);
  case Interpolation::cylinder:
    break;
  }
  return mpr::SceneSampler<S, mpr::Rasterized<mpr::CylinderAperture>>(
      *l.scene, plane, config, mpr::Rasterized<mpr::CylinderAperture>{mpr::CylinderAperture{p.radius}});
}

template <std::floating_point T>
SamplerVariant<T> make_sampler(const Job& job, const Loaded<T>& l, const FrameParams& p, int width = 1,
                               int height = 1) {
  if (job.raster) return make_raster_sampler(job, l, p, base_plane(job, l, p, width, height));
  if (l.scene_sampler) return *l.scene_sampler;
  switch (job.interpolation) {
  case Interpolation::nearest:
    return mpr::CameraFrameSampler<mpr::NearestCamera, T>(l.frames);
  case Interpolation::synthetic:
    return mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(l.frames);
  case Interpolation::cylinder:
    break;
  }
  return mpr::CameraFrameSampler<mpr::CylinderAperture, T>(l.frames, mpr::CylinderAperture{p.radius});
}

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

/// Called with each finished frame (index from 0, and the frame count).
using FrameSink = std::function<void(int index, int count, const mpr::Image<mpr::Rgb8>& image)>;

template <std::floating_point T>
void run_typed(const Job& job, const FrameSink& sink, std::ostream* info) {
  const Loaded<T> l = load<T>(job);
  const auto [w, h] = view_size(job, l);
  const int count = std::max(job.frames, 1);
  const mpr::RenderOptions options{job.threads};
  for (int f = 0; f < count; ++f) {
    const FrameParams p = frame_params(job, l.default_focal_depth, frame_time(f, count));
    const SamplerVariant<T> sampler = make_sampler(job, l, p, w, h);
    mpr::Image<mpr::Rgb8> image(job.cols * w, job.rows * h);
    for (std::size_t k = 0; k < job.views.size(); ++k) {
      const CameraVariant<T> camera = make_camera(job, l, p, k, w, h);
      if (info != nullptr && job.print_camera && f == 0) print_camera(*info, job.views[k], camera);
      const int col = static_cast<int>(k) % job.cols, row = static_cast<int>(k) / job.cols;
      render_view(camera, sampler, image.view(), mpr::Region(col * w, row * h, w, h), options);
    }
    sink(f, count, image);
  }
}

/// Runs the job: every frame goes to `sink`; --print-camera text to `info` (when not null).
inline void run(const Job& job, const FrameSink& sink, std::ostream* info = nullptr) {
  if (job.use_double)
    run_typed<double>(job, sink, info);
  else
    run_typed<float>(job, sink, info);
}

/// All frames in memory (tests).
inline std::vector<mpr::Image<mpr::Rgb8>> render_frames(const Job& job, std::ostream* info = nullptr) {
  std::vector<mpr::Image<mpr::Rgb8>> frames;
  run(
      job, [&](int, int, const mpr::Image<mpr::Rgb8>& image) { frames.push_back(image); }, info);
  return frames;
}

/// Parses a command line (argv[0] is skipped) into a Job.
inline Job parse_job(int argc, const char* const* argv) { return make_job(parse_args(argc, argv, options())); }

/// The numbered PNG path of frame `index` (0-based) of an animation: out.png -> out_0001.png.
inline std::filesystem::path frame_path(const std::filesystem::path& output, int index) {
  char number[16];
  std::snprintf(number, sizeof number, "_%04d", index + 1);
  std::filesystem::path p = output;
  p.replace_filename(output.stem().string() + number + ".png");
  return p;
}

} // namespace mpr_cli
