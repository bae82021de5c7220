#pragma once
// The one std::visit of a render from Python: sampler x pixel sampling, then a fully typed
// mpr::Renderer per tile (the same instantiation a C++ user writes by hand; a finite aperture is
// mpr-render's `FiniteAperture<GlcSelector, AnyAperture>`).

#include "policies.hpp"

#include <mpr/render/renderer.hpp>

#include <type_traits>

namespace mpr_py {

template <class FramePx, class OutPx>
void render_tiles(const std::shared_ptr<const mpr::CameraFrameSet<T, FramePx>>& frames, const RenderJob& job,
                  std::span<const Tile> tiles, mpr::ImageView<OutPx> out) {
  const SamplerVariant<FramePx> sampler = make_sampler<FramePx>(frames, job.interpolation, job.radius);
  const PixelSamplingVariant sampling = make_pixel_sampling(job.spp, job.filter, job.filter_radius);
  const mpr::RenderOptions options{job.threads};
  std::visit(
      [&](const auto& smp, const auto& pixels) {
        for (const Tile& tile : tiles) {
          const mpr::PlanarSurface<T>& plane = tile.view->plane;
          if constexpr (!std::is_same_v<std::remove_cvref_t<decltype(pixels)>, mpr::PixelCentre>) {
            if (job.aperture) { // each sample gets its own aperture point
              const T h = static_cast<T>(job.lens_distance > 0 ? job.lens_distance : plane.width_vector().norm());
              const mpr::glc::Mat2<T> focus = job.focus_depth > 0
                                                  ? mpr::glc::focus_at_depth(h, static_cast<T>(job.focus_depth))
                                                  : mpr::glc::Mat2<T>(mpr::glc::Mat2<T>::Zero());
              const mpr::glc::FiniteAperture lens(plane, tile.view->selector, *job.aperture,
                                                  static_cast<T>(job.aperture_size), h, focus);
              mpr::Renderer(plane, lens, smp, pixels).render(out, tile.region, options);
              continue;
            }
          }
          const mpr::Renderer renderer(plane, tile.view->selector, smp, pixels);
          renderer.render(out, tile.region, options);
        }
      },
      sampler, sampling);
}

} // namespace mpr_py
