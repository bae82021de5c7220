#pragma once
/// \file
/// `mpr::CameraFrameSampler<Interpolation>`: a ray sampler answering each ray from a set of
/// calibrated camera images (light field rendering, Levoy & Hanrahan 1996; dynamically
/// reparameterized light fields, Isaksen et al. 2000), as in the General Linear Camera system of
/// Yu & McMillan (ECCV 2004), which rendered from the Stanford camera array. A thin dispatcher:
/// the frames live in a shared `FrameTable`, the choice and weighting of cameras in the
/// interpolation (`NearestCamera`, `SyntheticAperture`, `CylinderAperture`, or any type that
/// models `FrameInterpolation`).

#include <mpr/core/color.hpp>
#include <mpr/core/concepts.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/lightfield/frame_table.hpp>
#include <mpr/lightfield/interpolation.hpp>

#include <cstddef>
#include <memory>
#include <span>
#include <utility>

namespace mpr {

/// Answers a ray with the colour the cameras of a `CameraFrameSet` see at the ray's point.
///
/// The point is where the ray starts (`ray.origin`: the image-surface point, so the image
/// surface is the focal surface), or `ray.at(depth)` when `Config::depth` is set. Cameras are
/// chosen and weighted by `Interpolation` using the distance from their centres to the ray
/// *line*; each chosen camera that sees the point (in front of it, projecting inside its image)
/// contributes its pixel there, reconstructed by `Config::filter`. Colour is linear (8-bit
/// frames are decoded with the exact sRGB table). A point no camera sees gets
/// `Config::background`; the result is never NaN for finite rays.
///
/// The sampler shares its `FrameTable` through a `shared_ptr`, so copies are cheap, threads
/// share one set of images, and samplers of several interpolations can share one table. It
/// models `BatchRaySampler` / `TileRaySampler` / `GridRaySampler` exactly when the interpolation
/// has those paths.
template <class Interpolation, std::floating_point T = float, class Px = Rgb8>
requires FrameInterpolation<Interpolation, T, Px>
class CameraFrameSampler {
public:
  using scalar_type = T;
  using color_type = Color;
  using frame_set_type = CameraFrameSet<T, Px>;
  using table_type = FrameTable<T, Px>;
  using interpolation_type = Interpolation;
  using texel_type = typename table_type::texel_type;
  using Config = FrameSamplerConfig<T>;

  /// Throws `argument_error` naming "frames" (null or empty), "depth" or "background" (not
  /// finite), or what `interpolation.validate()` names (e.g. "radius").
  explicit CameraFrameSampler(std::shared_ptr<const frame_set_type> frames, Interpolation interpolation = {},
                              const Config& config = {})
      : CameraFrameSampler(std::make_shared<const table_type>(std::move(frames), config), std::move(interpolation),
                           Sharing{}) {}

  /// A sampler over an existing table, shared, not copied: samplers of several interpolations
  /// over the same frames then hold one set of texels. Throws `argument_error` naming "table"
  /// (null) or what `interpolation.validate()` or `interpolation.validate(table)` names.
  [[nodiscard]] static CameraFrameSampler sharing(std::shared_ptr<const table_type> table,
                                                  Interpolation interpolation = {}) {
    return CameraFrameSampler(std::move(table), std::move(interpolation), Sharing{});
  }

  [[nodiscard]] const frame_set_type& frames() const noexcept { return table_->frames(); }
  [[nodiscard]] const table_type& table() const noexcept { return *table_; }
  [[nodiscard]] const std::shared_ptr<const table_type>& shared_table() const noexcept { return table_; }
  [[nodiscard]] const Interpolation& interpolation() const noexcept { return interpolation_; }
  [[nodiscard]] const Config& config() const noexcept { return table_->config(); }
  [[nodiscard]] const CameraCentreIndex<T>& index() const noexcept { return table_->index(); }
  /// True when every camera centre lies on one plane (a planar array): then the row paths prove
  /// nearest-camera choices and bound cylinder candidates on that plane.
  [[nodiscard]] bool planar_array() const noexcept { return table_->plane().has_value(); }

  /// The colour along `ray` (see the class comment).
  [[nodiscard]] Color sample(const Ray<T>& ray) const noexcept { return interpolation_.sample(*table_, ray); }

  /// `out[i] = sample(rays[i])` for every i (precondition: equal lengths), by the
  /// interpolation's batch path.
  void sample_rays(std::span<const Ray<T>> rays,
                   std::span<Color> out) const noexcept requires BatchFrameInterpolation<Interpolation, T, Px> {
    interpolation_.sample_rays(*table_, rays, out);
  }

  /// `out[i] = sample(rays[i])` for the rays of consecutive output rows (the renderer's tile
  /// interface, `TileRaySampler`; preconditions there), by the interpolation's tile path.
  void sample_tile(std::span<const Ray<T>> rays, int width,
                   std::span<Color> out) const noexcept requires TileFrameInterpolation<Interpolation, T, Px> {
    interpolation_.sample_tile(*table_, rays, width, out);
  }

  /// The colours of a tile whose rays are affine in the pixel (the renderer's grid interface,
  /// `GridRaySampler`), by the interpolation's grid path; false when it has none for this tile.
  template <class ExactRay>
  [[nodiscard]] bool
  sample_grid(const RayGrid<T, ExactRay>& grid,
              std::span<Color> out) const noexcept requires GridFrameInterpolation<Interpolation, T, Px> {
    return interpolation_.sample_grid(*table_, grid, out);
  }

private:
  struct Sharing {};
  CameraFrameSampler(std::shared_ptr<const table_type> table, Interpolation interpolation, Sharing)
      : table_(std::move(table)), interpolation_(std::move(interpolation)) {
    if (!table_) throw argument_error("table", "null");
    if constexpr (requires { interpolation_.validate(); }) interpolation_.validate();
    if constexpr (requires { interpolation_.validate(*table_); }) interpolation_.validate(*table_);
  }

  std::shared_ptr<const table_type> table_;
  [[no_unique_address]] Interpolation interpolation_;
};

} // namespace mpr
