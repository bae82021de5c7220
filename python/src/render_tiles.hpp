#pragma once
// The render of a Python job through the library's dispatch (include/mpr/render/policy_dispatch.hpp),
// the same code mpr-render and mpr-view render through: the choices become the sampler and pixel
// sampling variants, one std::visit picks the sampler, and mpr::render_chosen visits the pixel
// sampling into a fully typed mpr::Renderer per tile (a finite aperture is
// `glc::FiniteAperture<GlcSelector, AnyAperture>`, as mpr-render's).

#include "policies.hpp"

#include <mpr/render/policy_dispatch.hpp>
#include <mpr/render/renderer.hpp>

#include <optional>
#include <variant>

namespace mpr_py {

template <class FramePx, class OutPx>
void render_tiles(const std::shared_ptr<const mpr::CameraFrameSet<T, FramePx>>& frames, const RenderJob& job,
                  std::span<const Tile> tiles, mpr::ImageView<OutPx> out) {
  const mpr::FrameSamplerVariant<T, FramePx> sampler = mpr::make_frame_sampler(frames, job.interpolation, job.radius);
  const mpr::PixelSamplingVariant sampling =
      mpr::make_pixel_sampling(job.spp, mpr::make_filter(job.filter, job.filter_radius));
  const mpr::RenderOptions options{job.threads};
  std::visit(
      [&](const auto& smp) {
        for (const Tile& tile : tiles) {
          const mpr::PlanarSurface<T>& plane = tile.view->plane;
          std::optional<mpr::LensChoice<T>> lens;
          if (job.aperture) {
            const T h = static_cast<T>(job.lens_distance > 0 ? job.lens_distance : plane.width_vector().norm());
            lens = mpr::LensChoice<T>{*job.aperture, static_cast<T>(job.aperture_size), h,
                                      job.focus_depth > 0 ? mpr::glc::focus_at_depth(h, static_cast<T>(job.focus_depth))
                                                          : mpr::glc::Mat2<T>(mpr::glc::Mat2<T>::Zero())};
          }
          mpr::render_chosen(plane, tile.view->selector, plane, smp, sampling, lens ? &*lens : nullptr, out,
                             tile.region, options);
        }
      },
      sampler);
}

} // namespace mpr_py
