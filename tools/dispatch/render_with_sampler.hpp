#pragma once
// The definition of render_with_sampler (tools/mpr-render/render_dispatch.hpp): included only by
// the units of tools/dispatch/, each of which instantiates it for one sampler family. The visit
// of the pixel sampling and the finite aperture are the library's (mpr::render_chosen,
// include/mpr/render/policy_dispatch.hpp), which the Python module renders through too.

#include "mpr-render/render_dispatch.hpp"

#include <mpr/mpr.hpp>
#include <mpr/render/policy_dispatch.hpp>

#include <optional>
#include <variant>

namespace mpr_cli {

template <std::floating_point T, class Sampler>
void render_with_sampler(const CameraVariant<T>& camera, const Sampler& sampler, const ViewTarget& target) {
  std::optional<mpr::LensChoice<T>> lens; // a finite aperture needs supersampling; the pixel centre ignores it
  if (target.aperture != nullptr && !std::holds_alternative<mpr::PixelCentre>(*target.sampling))
    lens = lens_choice<T>(*target.aperture, target.aperture_size, plane_of(camera));
  std::visit(
      [&](const auto& cam) {
        try {
          mpr::render_chosen(cam.surface, cam.selector, plane_of(camera), sampler, *target.sampling,
                             lens ? &*lens : nullptr, target.out, target.region, target.options);
        } catch (const mpr::argument_error& e) { // only the lens's construction throws
          if (!lens) throw;
          rethrow_aperture_error(*target.aperture, e);
        }
      },
      camera);
}

} // namespace mpr_cli
