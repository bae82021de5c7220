#pragma once
/// \file
/// The run-time dispatch a front end (mpr-render, mpr-view, the Python module) renders through:
/// the policy types the names of policy_names.hpp select, as one `std::variant` per choice
/// (light-field interpolation, pixel sampling), the functions that turn a choice into the
/// variant, and `render_chosen`, which resolves the pixel sampling by one `std::visit` and runs a
/// fully typed `Renderer` (the same instantiation a C++ user writes by hand), with or without a
/// finite aperture (Adams and Levoy 2007, glc/finite_aperture.hpp). The caller visits its sampler
/// variant and passes the concrete sampler, so a front end can compile one sampler family per
/// translation unit.

#include <mpr/core/image.hpp>
#include <mpr/core/region.hpp>
#include <mpr/render/renderer.hpp>
#include <mpr/glc/aperture.hpp>
#include <mpr/glc/finite_aperture.hpp>
#include <mpr/lightfield/cylinder_aperture.hpp>
#include <mpr/lightfield/depth_proxy.hpp>
#include <mpr/lightfield/frame_sampler.hpp>
#include <mpr/lightfield/nearest_camera.hpp>
#include <mpr/lightfield/synthetic_aperture.hpp>
#include <mpr/render/policy_names.hpp>
#include <mpr/sampling.hpp>
#include <mpr/surface/planar_surface.hpp>

#include <concepts>
#include <memory>
#include <type_traits>
#include <utility>
#include <variant>

namespace mpr {

/// The light-field samplers of `InterpolationChoice`, in its order: nearest camera, synthetic
/// aperture, cylinder aperture, depth proxy, over frames of pixel type `Px` (Rgb8 or Color).
template <std::floating_point T, class Px = Rgb8>
using FrameSamplerVariant =
    std::variant<CameraFrameSampler<NearestCamera, T, Px>, CameraFrameSampler<SyntheticAperture, T, Px>,
                 CameraFrameSampler<CylinderAperture, T, Px>, CameraFrameSampler<DepthProxy, T, Px>>;

/// The sampler `interpolation` selects over `frames`: `radius` (world units) is the cylinder
/// aperture's radius and the depth proxy's camera radius; `depth` the rest of the depth proxy's
/// configuration (its `radius` is replaced by `radius`). Throws `argument_error` from the
/// policy's checks (e.g. a radius <= 0, depth maps missing for `depth`).
template <std::floating_point T, class Px>
[[nodiscard]] FrameSamplerVariant<T, Px> make_frame_sampler(std::shared_ptr<const CameraFrameSet<T, Px>> frames,
                                                            InterpolationChoice interpolation, double radius,
                                                            DepthProxy depth = {}) {
  switch (interpolation) {
  case InterpolationChoice::nearest:
    return CameraFrameSampler<NearestCamera, T, Px>(std::move(frames));
  case InterpolationChoice::synthetic:
    return CameraFrameSampler<SyntheticAperture, T, Px>(std::move(frames));
  case InterpolationChoice::depth:
    depth.radius = radius;
    return CameraFrameSampler<DepthProxy, T, Px>(std::move(frames), depth);
  case InterpolationChoice::cylinder:
    break;
  }
  return CameraFrameSampler<CylinderAperture, T, Px>(std::move(frames), CylinderAperture{radius});
}

/// The pixel sampling of a render: the pixel centre (one ray per pixel), or Owen-scrambled Sobol
/// samples combined by a filter (`make_filter` of a `FilterChoice`).
using PixelSamplingVariant = std::variant<PixelCentre, Supersample<OwenSobol, AnyFilter>>;

/// `spp` samples per pixel weighted by `filter`: the pixel centre for `spp` <= 1.
[[nodiscard]] inline PixelSamplingVariant make_pixel_sampling(int spp, const AnyFilter& filter) {
  if (spp <= 1) return PixelCentre{};
  return Supersample<OwenSobol, AnyFilter>(OwenSobol(spp), filter);
}

/// A finite aperture chosen at run time: `glc::FiniteAperture`'s arguments but the plane and the
/// selector it wraps.
template <std::floating_point T>
struct LensChoice {
  glc::AnyAperture shape;
  /// Radius (disc, polygon), half side (square) or sigma (gaussian), world units; 0: a pinhole.
  T size = 0;
  /// The lens plane's distance behind the image plane, world units (> 0).
  T distance = 1;
  /// The focus matrix (`glc::focus_at_depth`, `glc::astigmatic_focus`; zero: focused on the image plane).
  glc::Mat2<T> focus = glc::Mat2<T>::Zero();
};

/// The pixels of `region` of `out` (one view; Rgb8 codes or linear Color) rendered from `surface`
/// and `selector` with `sampler` and the pixel sampling `pixels`, through the one `std::visit` of
/// the pixel sampling. With `lens` (not null) and supersampling, `selector` integrates over that
/// finite aperture on `lens_plane` (the view's untilted image plane), each sample at its own
/// aperture point; the pixel centre ignores `lens`. Throws `argument_error` from
/// `glc::FiniteAperture` (e.g. "focus" for rays parallel to the image plane) before any pixel is
/// written; the render itself does not throw.
template <class Surface, class Selector, class Sampler, std::floating_point T, class OutPx>
void render_chosen(const Surface& surface, const Selector& selector, const PlanarSurface<T>& lens_plane,
                   const Sampler& sampler, const PixelSamplingVariant& pixels,
                   const LensChoice<std::type_identity_t<T>>* lens, ImageView<OutPx> out, const Region& region,
                   const RenderOptions& options) {
  std::visit(
      [&](const auto& px) {
        if constexpr (!std::is_same_v<std::remove_cvref_t<decltype(px)>, PixelCentre>) {
          if (lens != nullptr) {
            const glc::FiniteAperture aperture(lens_plane, selector, lens->shape, lens->size, lens->distance,
                                               lens->focus);
            Renderer(surface, aperture, sampler, px).render(out, region, options);
            return;
          }
        }
        const Renderer renderer(surface, selector, sampler, px);
        renderer.render(out, region, options);
      },
      pixels);
}

} // namespace mpr
