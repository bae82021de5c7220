#pragma once
// The definition of render_with_sampler (tools/mpr-render/render_dispatch.hpp): included only by
// the units of tools/dispatch/, each of which instantiates it for one sampler family.

#include "mpr-render/render_dispatch.hpp"

#include <mpr/mpr.hpp>

#include <type_traits>
#include <variant>

namespace mpr_cli {

template <std::floating_point T, class Sampler>
void render_with_sampler(const CameraVariant<T>& camera, const Sampler& sampler, const ViewTarget& target) {
  std::visit(
      [&](const auto& cam, const auto& pixels) {
        if constexpr (!std::is_same_v<std::remove_cvref_t<decltype(pixels)>, mpr::PixelCentre>) {
          if (target.aperture != nullptr) {
            const auto lens = with_aperture(*target.aperture, target.aperture_size, plane_of(camera), cam.selector);
            mpr::Renderer(cam.surface, lens, sampler, pixels).render(target.out, target.region, target.options);
            return;
          }
        }
        const mpr::Renderer renderer(cam.surface, cam.selector, sampler, pixels);
        renderer.render(target.out, target.region, target.options);
      },
      camera, *target.sampling);
}

} // namespace mpr_cli
