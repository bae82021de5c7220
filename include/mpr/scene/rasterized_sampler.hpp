#pragma once
/// \file
/// `mpr::SceneSampler<Scene, mpr::Rasterized<Interpolation, Px>>`: the *software rasterized
/// synthetic scene* policy. At construction the scene is rasterized ONCE into a virtual camera
/// array (a planar grid of pinhole cameras, `VirtualArrayConfig`); rays are then answered from
/// those frames by `mpr::CameraFrameSampler<Interpolation>` (nearest camera, synthetic aperture,
/// cylinder aperture), exactly as real camera-array data is sampled (light field rendering,
/// Levoy & Hanrahan 1996; the OpenGL-rendered synthetic light fields of Yu & McMillan, ECCV 2004).
///
/// The virtual array can be written to disk in the Middlebury `_par.txt` calibration format plus
/// one PNG per camera (`mpr::write_frame_set`, <mpr/io/par_file.hpp>) and read back with
/// `mpr::read_par_file`, so a synthetic data set with a known ground truth (the ray-cast scene)
/// can be shared.
///
/// Example (16 x 12 cameras of 160 x 120 in the image plane, cylinder aperture of one spacing):
///
///     mpr::scene::VirtualArrayConfig<float> config;
///     config.columns = 16; config.rows = 12; config.width = 160; config.height = 120;
///     const mpr::SceneSampler<mpr::scene::Scene<float>, mpr::Rasterized<mpr::CylinderAperture>>
///         sampler(scene, plane, config, {mpr::CylinderAperture{0.5}});
///     const mpr::Renderer renderer(plane, glc, sampler);   // renders like any other sampler
///     mpr::write_frame_set("classroom-array", "classroom", sampler.frames()); // + cam_RRR_CCC.png
///
/// How close this gets to the ray-cast image depends on the scene's depth range against the
/// array's spacing (one focal plane for all rays): see docs/accuracy.md.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/color.hpp>
#include <mpr/core/concepts.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/frame_sampler.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/nearest_camera.hpp>
#include <mpr/scene/rasterizer.hpp>
#include <mpr/scene/scene.hpp>
#include <mpr/scene/scene_sampler.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mpr {

/// Sampling policy tag: rasterize the scene into a virtual camera array once, then interpolate
/// its frames with `Interpolation` (`NearestCamera`, `SyntheticAperture` or `CylinderAperture`).
/// Frames are stored as `Px`: 8-bit sRGB `Rgb8` (the default; what `mpr::write_frame_set` writes,
/// so a reloaded data set samples identically) or linear `Color` (no quantisation).
template <class Interpolation = NearestCamera, class Px = Rgb8>
struct Rasterized {
  /// The interpolation policy's parameters (e.g. the cylinder radius, world units).
  Interpolation interpolation{};
};

namespace scene {

/// Placement and resolution of a virtual camera array: `columns` x `rows` pinhole cameras on a
/// regular grid in a plane, all looking along the plane's normal.
///
/// Frame: the grid is centred on `plane.centre()`, moved `behind` world units against
/// `plane.normal()` (0: the cameras lie in the plane itself); its columns run along
/// `plane.width_vector()`, its rows along `plane.height_vector()` (Gram-Schmidt orthogonalised
/// to the width vector). Camera (c, r) -- frame index `r * columns + c` -- has image x along the
/// width vector, image y along the (orthogonalised) height vector, square pixels, the principal
/// point at the image centre and a horizontal field of view of `horizontal_fov` radians.
template <std::floating_point T>
struct VirtualArrayConfig {
  int columns = 8;
  int rows = 6;
  /// World units between neighbouring cameras, along both axes; 0 spreads the grid over the
  /// plane's rectangle (cell centres: spacing = plane width / columns and plane height / rows).
  T spacing = 0;
  /// Distance of the camera grid behind the plane (against its normal), world units, >= 0.
  T behind = 0;
  /// Resolution of every camera, pixels.
  int width = 160;
  int height = 120;
  /// Horizontal field of view of every camera, radians, in (0, pi).
  T horizontal_fov = T(1.7453292519943295); // 100 degrees
  /// Where the sampler takes each ray's colour: `ray.at(focal_depth)` (with GLC rays from the
  /// plane, whose directions have unit normal component, that is `focal_depth` world units in
  /// front of the plane). Unset: the median depth of the visible surfaces seen by the array
  /// (camera z over all frames, minus `behind`), i.e. a focal plane through the bulk of the scene.
  std::optional<T> focal_depth;
  /// Samples per pixel side, odd, in [1, 15], with `samples` x `width` and x `height` at most
  /// 16384: each frame pixel is the mean, in linear light, of an n x n grid of rasterized points
  /// spread evenly over the pixel (a box filter, as a real sensor's pixel integrates its area),
  /// which takes out the staircases and moire of point-sampled frames. The middle point lies on
  /// the pixel centre and gives the depth map its value there. 1 (the default): one point at the
  /// centre. Rasterizing costs up to n^2 times as much (the per-point work; the per-triangle
  /// work stays), and the rasterizer's buffers are n^2 times larger (16 bytes a point), for one
  /// camera at a time.
  int samples = 1;
  /// Reconstruction of each camera's pixels.
  PixelFilter filter = PixelFilter::bilinear;
  /// Rasterizer settings (threads, near plane, tile size) for building the array.
  RasterOptions raster{};
  /// Keep each camera's z-buffer as the frame set's depth map (`CameraFrameSet::with_depth`;
  /// exact camera-space depth, +inf on background), for geometry-aware interpolations such as
  /// `DepthProxy`. Off by default: 4 bytes per pixel more.
  bool depth_maps = false;
};

/// The cameras of a virtual array on `plane` (see `VirtualArrayConfig` for the frame). Throws
/// `argument_error` naming "columns", "rows", "width", "height", "samples", "spacing", "behind",
/// "horizontal_fov" or "focal_depth" for a non-positive / non-finite / out-of-range value (or an
/// even `samples`), "plane" for a degenerate plane.
template <std::floating_point T>
[[nodiscard]] std::vector<PinholeCamera<T>> virtual_array_cameras(const PlanarSurface<T>& plane,
                                                                  const VirtualArrayConfig<T>& config) {
  if (config.columns < 1 || config.columns > 4096) throw argument_error("columns", "must be in 1..4096");
  if (config.rows < 1 || config.rows > 4096) throw argument_error("rows", "must be in 1..4096");
  if (config.width < 1 || config.width > 16384) throw argument_error("width", "must be in 1..16384");
  if (config.height < 1 || config.height > 16384) throw argument_error("height", "must be in 1..16384");
  if (config.samples < 1 || config.samples > 15 || config.samples % 2 == 0)
    throw argument_error("samples", "must be odd, in 1..15");
  if (config.samples * config.width > 16384 || config.samples * config.height > 16384)
    throw argument_error("samples", "samples x width and samples x height must be at most 16384");
  if (!(config.spacing >= 0) || !std::isfinite(config.spacing))
    throw argument_error("spacing", "must be finite and >= 0");
  if (!(config.behind >= 0) || !std::isfinite(config.behind)) throw argument_error("behind", "must be finite and >= 0");
  if (!(config.horizontal_fov > 0 && config.horizontal_fov < T(3.14159)))
    throw argument_error("horizontal_fov", "must be in (0, pi) radians");
  if (config.focal_depth && !std::isfinite(*config.focal_depth)) throw argument_error("focal_depth", "not finite");
  const Vec3<T> eu = plane.width_vector(), ev_raw = plane.height_vector();
  const T width_length = eu.norm();
  const Vec3<T> x = eu.normalized();
  const Vec3<T> ev_ortho = ev_raw - x.dot(ev_raw) * x;
  const T height_length = ev_ortho.norm();
  if (!(width_length > 0) || !(height_length > 0) || !x.allFinite() || !ev_ortho.allFinite())
    throw argument_error("plane", "degenerate (zero or parallel edge vectors)");
  const Vec3<T> y = ev_ortho / height_length;
  const Vec3<T> z = x.cross(y); // right-handed: image x, image y, viewing axis
  if (z.dot(plane.normal()) <= 0) throw argument_error("plane", "normal disagrees with width x height");
  Mat3<T> R;
  R.row(0) = x.transpose();
  R.row(1) = y.transpose();
  R.row(2) = z.transpose();
  const T f = T(0.5) * static_cast<T>(config.width) / std::tan(T(0.5) * config.horizontal_fov);
  Mat3<T> K = Mat3<T>::Identity();
  K(0, 0) = f;
  K(1, 1) = f;
  K(0, 2) = T(0.5) * static_cast<T>(config.width) - T(0.5);
  K(1, 2) = T(0.5) * static_cast<T>(config.height) - T(0.5);
  const T du = config.spacing > 0 ? config.spacing : width_length / static_cast<T>(config.columns);
  const T dv = config.spacing > 0 ? config.spacing : height_length / static_cast<T>(config.rows);
  const Vec3<T> centre = plane.centre() - config.behind * z;
  std::vector<PinholeCamera<T>> cameras;
  cameras.reserve(static_cast<std::size_t>(config.columns) * static_cast<std::size_t>(config.rows));
  for (int r = 0; r < config.rows; ++r)
    for (int c = 0; c < config.columns; ++c) {
      const T oc = (static_cast<T>(c) - T(0.5) * static_cast<T>(config.columns - 1)) * du;
      const T orow = (static_cast<T>(r) - T(0.5) * static_cast<T>(config.rows - 1)) * dv;
      const Vec3<T> eye = centre + oc * x + orow * y;
      if (!eye.allFinite()) throw argument_error("plane", "camera position not finite");
      cameras.emplace_back(K, R, Vec3<T>(-(R * eye)), config.width, config.height);
    }
  return cameras;
}

/// The frames of a virtual array and the focal depth chosen for it.
template <std::floating_point T, class Px>
struct VirtualArray {
  CameraFrameSet<T, Px> frames;
  /// See `VirtualArrayConfig::focal_depth`.
  T focal_depth = 0;
};

namespace detail {
/// `camera` with n x n times the pixels over the same image area: its pixel (n x + i, n y + j)
/// looks at `camera`'s point (x + (i - (n - 1) / 2) / n, y + (j - (n - 1) / 2) / n), so for odd n
/// the middle one, i = j = (n - 1) / 2, is `camera`'s pixel centre (x, y). Preconditions (as
/// `virtual_array_cameras` checks them): n >= 1, n x width and n x height at most 16384, no lens
/// distortion (the rasterizer refuses it; this camera would drop it).
template <std::floating_point T>
[[nodiscard]] PinholeCamera<T> subpixel_camera(const PinholeCamera<T>& camera, int n) {
  Mat3<T> scale = Mat3<T>::Identity();
  scale(0, 0) = scale(1, 1) = static_cast<T>(n);
  scale(0, 2) = scale(1, 2) = T(0.5) * static_cast<T>(n - 1);
  const Mat3<T> K = scale * camera.K();
  return PinholeCamera<T>(K, camera.R(), camera.t(), n * camera.width(), n * camera.height());
}
} // namespace detail

/// Rasterizes `scene` into every camera of the array (the expensive step: one rasterized view
/// per camera, of `config.samples`^2 points a pixel). Frames are named "cam_<r>_<c>.png"; with
/// `config.depth_maps` the set carries the depths at the pixel centres as depth maps. Throws as
/// `virtual_array_cameras`.
template <class Px = Rgb8, std::floating_point T>
[[nodiscard]] VirtualArray<T, Px> rasterize_virtual_array(const Scene<T>& scene, const PlanarSurface<T>& plane,
                                                          const VirtualArrayConfig<T>& config) {
  static_assert(std::is_same_v<Px, Rgb8> || std::is_same_v<Px, Color>, "frames are Rgb8 or linear Color");
  std::vector<PinholeCamera<T>> cameras = virtual_array_cameras(plane, config);
  std::vector<Image<Px>> images;
  std::vector<std::string> names;
  images.reserve(cameras.size());
  std::vector<float> depths; // a subsample of visible depths, for the default focal depth
  std::vector<Image<float>> depth_maps;
  Image<Color> color(config.width, config.height);
  Image<float> depth(config.width, config.height);
  const int n = config.samples, half = (n - 1) / 2;
  Image<Color> fine(n > 1 ? n * config.width : 0, n > 1 ? n * config.height : 0);
  Image<float> fine_depth(fine.width(), fine.height());
  const float inv = 1.0f / static_cast<float>(n * n);
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    if (n == 1) {
      rasterize(scene, cameras[i], color.view(), depth.view(), config.raster);
    } else {
      rasterize(scene, detail::subpixel_camera(cameras[i], n), fine.view(), fine_depth.view(), config.raster);
      for (int yy = 0; yy < config.height; ++yy)
        for (int xx = 0; xx < config.width; ++xx) {
          Color sum = Color::Zero();
          for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) sum += fine(n * xx + k, n * yy + j);
          color(xx, yy) = sum * inv;
          depth(xx, yy) = fine_depth(n * xx + half, n * yy + half);
        }
    }
    if constexpr (std::is_same_v<Px, Rgb8>) {
      Image<Rgb8> frame(config.width, config.height);
      for (int yy = 0; yy < config.height; ++yy)
        for (int xx = 0; xx < config.width; ++xx) frame(xx, yy) = to_rgb8(color(xx, yy));
      images.push_back(std::move(frame));
    } else {
      images.push_back(color);
    }
    if (config.depth_maps) depth_maps.push_back(depth);
    if (!config.focal_depth)
      for (int yy = 0; yy < config.height; yy += 4)
        for (int xx = 0; xx < config.width; xx += 4)
          if (std::isfinite(depth(xx, yy))) depths.push_back(depth(xx, yy));
    const int r = static_cast<int>(i) / config.columns, c = static_cast<int>(i) % config.columns;
    char name[48];
    std::snprintf(name, sizeof name, "cam_%03d_%03d.png", r, c);
    names.emplace_back(name);
  }
  T focal = 1;
  if (config.focal_depth) {
    focal = *config.focal_depth;
  } else if (!depths.empty()) {
    const auto mid = depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2);
    std::nth_element(depths.begin(), mid, depths.end());
    focal = std::max(static_cast<T>(*mid) - config.behind, static_cast<T>(config.raster.near));
  }
  return {
      CameraFrameSet<T, Px>(std::move(cameras), std::move(images), std::move(names)).with_depth(std::move(depth_maps)),
      focal};
}

} // namespace scene

/// The rasterized-scene sampler: `Rasterized<Interpolation, Px>` over a `scene::Scene<T>`.
///
/// Construction rasterizes the scene into the virtual array (`scene::VirtualArrayConfig`) once;
/// `sample` (and the batch `sample_rays`) forward to the `CameraFrameSampler<Interpolation, T,
/// Px>` built on those frames with `Config::depth = focal_depth`, background = the scene's
/// background. Copies share the frames (`shared_ptr`), so the sampler is cheap to copy into a
/// `Renderer`. A ray is answered from the frames only: with a dense enough array and a focal
/// depth near the surface a ray hits, the result approaches the ray-cast colour
/// (`SceneSampler<Scene, RayCast>`), which is what `benchmarks/error_vs_time` measures.
template <std::floating_point T, class Interpolation, class Px>
class SceneSampler<scene::Scene<T>, Rasterized<Interpolation, Px>, ShadedColor> {
public:
  using scalar_type = T;
  using color_type = Color;
  using scene_type = scene::Scene<T>;
  using frame_set_type = CameraFrameSet<T, Px>;
  using frame_sampler_type = CameraFrameSampler<Interpolation, T, Px>;

  /// Rasterizes `scene` into the array on `plane` described by `config` (keeping the depth maps
  /// when `Interpolation::uses_depth_maps`, as for `DepthProxy`). Throws
  /// `argument_error` as `scene::virtual_array_cameras`, and "radius" for a bad cylinder radius.
  SceneSampler(const scene::Scene<T>& scene, const PlanarSurface<T>& plane,
               const scene::VirtualArrayConfig<T>& config = {}, Rasterized<Interpolation, Px> policy = {})
      : SceneSampler(scene::rasterize_virtual_array<Px>(scene, plane, with_depth_maps(config)), scene.background(),
                     config.filter, policy) {}

  /// Samples an already rasterized (or reloaded) array.
  SceneSampler(scene::VirtualArray<T, Px> array, const Color& background, PixelFilter filter = PixelFilter::bilinear,
               Rasterized<Interpolation, Px> policy = {})
      : focal_depth_(array.focal_depth), frames_(std::make_shared<const frame_set_type>(std::move(array.frames))),
        sampler_(frames_, policy.interpolation, make_config(array.focal_depth, background, filter)) {}

  [[nodiscard]] const frame_set_type& frames() const noexcept { return *frames_; }
  [[nodiscard]] std::shared_ptr<const frame_set_type> shared_frames() const noexcept { return frames_; }
  [[nodiscard]] const frame_sampler_type& frame_sampler() const noexcept { return sampler_; }
  /// The focal depth in use (`VirtualArrayConfig::focal_depth`, or the median chosen).
  [[nodiscard]] T focal_depth() const noexcept { return focal_depth_; }

  [[nodiscard]] Color sample(const Ray<T>& ray) const noexcept { return sampler_.sample(ray); }
  /// The batch and tile forms of the frame sampler, where its interpolation has them (see
  /// `CameraFrameSampler`).
  void sample_rays(std::span<const Ray<T>> rays,
                   std::span<Color> out) const noexcept requires BatchRaySampler<frame_sampler_type> {
    sampler_.sample_rays(rays, out);
  }
  void sample_tile(std::span<const Ray<T>> rays, int width,
                   std::span<Color> out) const noexcept requires TileRaySampler<frame_sampler_type> {
    sampler_.sample_tile(rays, width, out);
  }

private:
  // The config, keeping the z-buffers when the interpolation reads depth maps (`DepthProxy`).
  static scene::VirtualArrayConfig<T> with_depth_maps(scene::VirtualArrayConfig<T> config) {
    if constexpr (requires { Interpolation::uses_depth_maps; })
      config.depth_maps = config.depth_maps || Interpolation::uses_depth_maps;
    return config;
  }

  static typename frame_sampler_type::Config make_config(T depth, const Color& background, PixelFilter filter) {
    typename frame_sampler_type::Config c;
    c.filter = filter;
    c.depth = depth;
    c.background = background;
    return c;
  }

  T focal_depth_;
  std::shared_ptr<const frame_set_type> frames_;
  frame_sampler_type sampler_;
};

} // namespace mpr
