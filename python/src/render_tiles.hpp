#pragma once
// The one std::visit of a render from Python: sampler x pixel sampling, then a fully typed
// mpr::Renderer per tile (the same instantiation a C++ user writes by hand).

#include "policies.hpp"

#include <mpr/core/renderer.hpp>

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
          const mpr::Renderer renderer(tile.view->plane, tile.view->selector, smp, pixels);
          renderer.render(out, tile.region, options);
        }
      },
      sampler, sampling);
}

} // namespace mpr_py
