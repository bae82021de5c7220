#pragma once
// mpr-render's data: the classroom scene, an OBJ mesh or a light field (_par.txt, Stanford,
// LFCA), loaded once for all frames, with the reference camera and default framing.

#include "job.hpp"
#include "publish.hpp"

#include <mpr/camera/planar_camera_array.hpp>
#include <mpr/io/colmap.hpp>
#include <mpr/lightfield.hpp>
#include <mpr/lightfield/array_view.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/scene_depth.hpp>
#include <mpr/scene.hpp>
#ifdef MPR_HAVE_TINYOBJLOADER
#include <mpr/scene/obj_loader.hpp>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>
#include <ostream>
#include <string>
#include <system_error>
#include <vector>

namespace mpr_cli {

/// The data of a job, loaded once for all frames.
template <std::floating_point T>
struct Loaded {
  std::shared_ptr<const mpr::scene::Scene<T>> scene;
  std::optional<mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>> scene_sampler;
  std::shared_ptr<const mpr::CameraFrameSet<T>> frames;
  std::optional<mpr::PinholeCamera<T>> reference;  ///< light fields: the camera the views start from
  std::optional<mpr::ArrayFootprint<T>> footprint; ///< light fields: where the cameras lie, seen from `reference`
  double default_focal_depth = 1;
  // Scene defaults (world units).
  mpr::Vec3<double> plane_centre{0, 3.1, 3}, look_at{0, 1.6, -8}, scene_centre{0, 1.6, -8};
  double plane_width = 8, scene_scale = 14;
  /// Lines for the user about what loading did (e.g. depth estimation and its time).
  std::vector<std::string> notes;
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

/// --colmap's images folder: --colmap-images, else the first of MODEL/images, MODEL/../images and
/// MODEL/../../images (COLMAP's own layout: PROJECT/sparse/0 beside PROJECT/images) that exists.
inline std::filesystem::path colmap_images(const Job& job) {
  if (!job.colmap_images.empty()) return job.colmap_images;
  std::error_code ec;
  for (const std::filesystem::path& p :
       {job.input / "images", job.input / ".." / "images", job.input / ".." / ".." / "images"})
    if (std::filesystem::is_directory(p, ec)) return p.lexically_normal();
  throw mpr::io_error(job.input.string(), "no images folder beside the COLMAP model (images/, ../images/ or "
                                          "../../images/): give --colmap-images FOLDER");
}

/// --depth-maps estimate[:NEAR:FAR[:PLANES]]: the depth maps of `set` (mpr::estimate_scene_depth
/// with the job's sweep, threads and progress), and lines saying what was estimated and found
/// appended to `notes`. Throws argument_error naming --depth-maps when the sweep's working memory
/// exceeds its limit, else as estimate_scene_depth.
template <std::floating_point T>
std::vector<mpr::Image<float>> estimated_depth_maps(const Job& job, const mpr::CameraFrameSet<T>& set,
                                                    std::vector<std::string>& notes) {
  mpr::SceneDepthConfig config;
  config.sweep = *job.depth_estimate;
  config.sweep.threads = job.threads;
  config.sweep.progress = job.depth_progress;
  const auto start = std::chrono::steady_clock::now();
  mpr::SceneDepth found;
  try {
    found = mpr::estimate_scene_depth(set, config);
  } catch (const mpr::argument_error& e) {
    // The sweep's working memory (PlaneSweepConfig::memory_limit, 2 GiB): name the option.
    if (e.parameter() != "memory_limit") throw;
    std::string why = e.what();
    why.erase(0, why.find(": ", why.find("memory_limit")) + 2);
    throw mpr::argument_error("--depth-maps", "estimate: " + why + "; give depth maps as files instead");
  }
  const mpr::PlaneSweepConfig& sweep = config.sweep;
  const char* source = found.range.source == mpr::SweepRangeSource::given ? "as given"
                       : found.range.source == mpr::SweepRangeSource::matches
                           ? "found from sparse matches"
                           : "found from the cameras' common frustum";
  char note[384];
  std::snprintf(note, sizeof note,
                "estimated the depth maps of %zu cameras in %.2f s (%d planes from %g to %g, %s; neighbours %d, "
                "best %d, truncation %g, spatial %g, range %g)",
                set.size(), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                sweep.planes, found.range.near, found.range.far, source, sweep.neighbours, sweep.best, sweep.truncation,
                sweep.spatial, sweep.range);
  notes.emplace_back(note);
  if (found.backdrop) {
    const mpr::Backdrop& b = *found.backdrop;
    std::snprintf(note, sizeof note,
                  "an object on an empty backdrop: rgb(%d, %d, %d) within %d codes on %zu of %zu views' borders "
                  "(%.0f%% of the images); depth kept inside the visual hull of its silhouettes",
                  b.colour.r, b.colour.g, b.colour.b, b.tolerance, b.views, b.total, 100 * b.image_share);
    notes.emplace_back(note);
  }
  return std::move(found.maps);
}

/// A light field as read (before its depth maps), and for --hci the centre view and the depth of
/// the benchmark's zero-disparity plane.
template <std::floating_point T>
struct ReadLightField {
  mpr::CameraFrameSet<T> set;
  std::size_t hci_centre = 0;
  double hci_focus = 0;
};

/// Reads the light field of a job whose sampler is a light field (_par.txt, Stanford, LFCA, HCI,
/// COLMAP) within `limits`. Throws as the readers.
template <std::floating_point T>
ReadLightField<T> read_light_field(const Job& job, const mpr::LoadLimits& limits) {
  ReadLightField<T> out;
  switch (job.sampler) {
  case SamplerKind::par:
    out.set = mpr::read_par_file<T>(job.input, limits);
    break;
  case SamplerKind::stanford:
    out.set = mpr::read_stanford_light_field<T>(job.input, array_options(job), limits);
    break;
  case SamplerKind::lfca: {
    mpr::LfcaOptions o;
    o.array = array_options(job);
    out.set = mpr::read_lfca<T>(job.input, o, limits);
    break;
  }
  case SamplerKind::hci: {
    mpr::HciLightField<T> lf = mpr::read_hci_light_field<T>(job.input, {}, limits);
    out.hci_centre = lf.centre;
    out.hci_focus = lf.disparity.depth(0); // the benchmark's zero-disparity plane
    out.set = std::move(lf.frames);
    break;
  }
  case SamplerKind::colmap:
    out.set = mpr::read_colmap<T>(job.input, colmap_images(job), limits);
    break;
  case SamplerKind::scene:
  case SamplerKind::obj:
    break;
  }
  return out;
}

// Compiled once each, in units of their own (tools/dispatch/light_field_*.cpp, estimate_*.cpp), so
// that no unit instantiates every loader and the plane sweep together.
extern template ReadLightField<float> read_light_field<float>(const Job&, const mpr::LoadLimits&);
extern template ReadLightField<double> read_light_field<double>(const Job&, const mpr::LoadLimits&);
extern template std::vector<mpr::Image<float>>
estimated_depth_maps<float>(const Job&, const mpr::CameraFrameSet<float>&, std::vector<std::string>&);
extern template std::vector<mpr::Image<float>>
estimated_depth_maps<double>(const Job&, const mpr::CameraFrameSet<double>&, std::vector<std::string>&);

} // namespace detail

/// --save-depth-maps FOLDER: writes the estimated depth maps of `l` (after the preflight check, so
/// that a job refused there writes nothing), creating FOLDER only under an existing parent; a
/// line to `info` (when not null).
template <std::floating_point T>
void save_depth_maps(const Job& job, const Loaded<T>& l, std::ostream* info) {
  if (!job.save_depth_maps || !l.frames) return;
  std::filesystem::path folder = *job.save_depth_maps;
  check_output_folder(folder / "x", "--save-depth-maps");
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec) && !std::filesystem::create_directory(folder, ec) && ec)
    throw mpr::io_error(folder.string(), "cannot create the folder: " + ec.message());
  mpr::write_depth_maps(folder, *l.frames);
  if (info != nullptr) *info << "wrote " << l.frames->size() << " depth maps to " << folder.string() << '\n';
}

/// Loads the sampler's data (scene, OBJ or light field) and its default framing.
template <std::floating_point T>
Loaded<T> load(const Job& job) {
  Loaded<T> l;
  mpr::LoadLimits limits;
  limits.progress = job.load_progress;
  // A light field, with the depth maps of --depth-maps attached.
  const auto frames = [&](mpr::CameraFrameSet<T> set) {
    if (job.depth_maps) {
      std::vector<mpr::Image<float>> maps = mpr::read_depth_maps(*job.depth_maps, set, limits);
      set = std::move(set).with_depth(std::move(maps));
    } else if (job.depth_estimate) {
      std::vector<mpr::Image<float>> maps = detail::estimated_depth_maps(job, set, l.notes);
      set = std::move(set).with_depth(std::move(maps));
    }
    return std::make_shared<const mpr::CameraFrameSet<T>>(std::move(set));
  };
  std::size_t hci_centre = 0; // --hci: the centre view and the zero-disparity depth
  double hci_focus = 0;
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
    // Default framing: the bounding box's centre seen from the +z side, 30 degrees above the
    // horizontal (y up), from 1.2 box diagonals away, so a ground plane shows as a surface rather
    // than a line; the image plane is one diagonal wide (gallery view A frames 1.2 diagonals).
    const double diag = std::max((hi - lo).norm(), 1e-6);
    constexpr double elevation = 30 * std::numbers::pi / 180;
    l.scene_centre = l.look_at = 0.5 * (lo + hi);
    l.plane_centre = l.scene_centre + 1.2 * diag * mpr::Vec3<double>(0, std::sin(elevation), std::cos(elevation));
    l.plane_width = diag;
    l.scene_scale = diag;
    break;
#else
    throw mpr::argument_error("--obj", "this mpr-render was built without tinyobjloader");
#endif
  }
  case SamplerKind::par:
  case SamplerKind::stanford:
  case SamplerKind::lfca:
  case SamplerKind::hci:
  case SamplerKind::colmap: {
    detail::ReadLightField<T> lf = detail::read_light_field<T>(job, limits);
    hci_centre = lf.hci_centre;
    hci_focus = lf.hci_focus;
    l.frames = frames(std::move(lf.set));
    break;
  }
  }
  if (l.scene) l.scene_sampler.emplace(l.scene);
  if (l.frames) {
    if (job.camera && *job.camera >= static_cast<int>(l.frames->size()))
      throw mpr::argument_error("--camera", std::to_string(*job.camera) + " is not below the camera count " +
                                                std::to_string(l.frames->size()));
    if (job.sampler == SamplerKind::hci && !job.camera) {
      l.reference = l.frames->camera(hci_centre);
      l.default_focal_depth = hci_focus;
    } else if (job.sampler == SamplerKind::par || job.sampler == SamplerKind::colmap || job.camera) {
      l.reference = l.frames->camera(job.camera ? static_cast<std::size_t>(*job.camera) : l.frames->size() / 2);
      // Default focus: the depth of the mean camera centre's... projection of the array's middle.
      mpr::Vec3<double> mean = mpr::Vec3<double>::Zero();
      for (std::size_t i = 0; i < l.frames->size(); ++i) mean += l.frames->camera(i).centre().template cast<double>();
      mean /= static_cast<double>(l.frames->size());
      const double z = (l.reference->R().template cast<double>() * mean + l.reference->t().template cast<double>()).z();
      l.default_focal_depth = job.sampler == SamplerKind::par || job.sampler == SamplerKind::colmap ? z
                              : job.sampler == SamplerKind::hci                                     ? hci_focus
                                                                : job.reference_depth;
      if (!(l.default_focal_depth > 0) && !job.focal_depth)
        throw mpr::argument_error("--focal-depth", "no default for this camera set: give --focal-depth");
    } else {
      l.reference = detail::array_centre_camera(*l.frames);
      l.default_focal_depth = job.reference_depth;
    }
    l.footprint = mpr::array_footprint(*l.frames, *l.reference);
  }
  return l;
}

// Compiled once, in mpr_tools (tools/dispatch/load_float.cpp, load_double.cpp).
extern template Loaded<float> load<float>(const Job&);
extern template Loaded<double> load<double>(const Job&);

} // namespace mpr_cli
