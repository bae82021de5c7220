#pragma once
// mpr-render's sampler factories: ray-cast scene, rasterized virtual array (--raster) or light
// field, with the chosen interpolation, as one std::variant of fully typed samplers. The
// light-field alternatives are the library's mpr::FrameSamplerVariant (policy_dispatch.hpp).

#include "job.hpp"
#include "loading.hpp"

#include <mpr/lightfield.hpp>
#include <mpr/render/policy_dispatch.hpp>
#include <mpr/scene.hpp>
#include <mpr/scene/rasterized_sampler.hpp>

#include <utility>
#include <variant>

namespace mpr_cli {

template <std::floating_point T>
using SamplerVariant =
    std::variant<mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>, mpr::CameraFrameSampler<mpr::NearestCamera, T>,
                 mpr::CameraFrameSampler<mpr::SyntheticAperture, T>, mpr::CameraFrameSampler<mpr::CylinderAperture, T>,
                 mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::NearestCamera>>,
                 mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::SyntheticAperture>>,
                 mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::CylinderAperture>>,
                 mpr::CameraFrameSampler<mpr::DepthProxy, T>,
                 mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::DepthProxy>>>;

/// The virtual array of --raster and --raster-samples (the library's defaults otherwise), as the
/// sampler builds it and preflight checks it.
template <std::floating_point T>
[[nodiscard]] mpr::scene::VirtualArrayConfig<T> raster_config(const Job& job) {
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = job.raster->first;
  config.rows = job.raster->second;
  config.samples = job.raster_samples;
  config.raster.threads = job.threads;
  return config;
}

/// The rasterized virtual-array sampler (--raster) on the frame's untilted image plane.
template <std::floating_point T>
SamplerVariant<T> make_raster_sampler(const Job& job, const Loaded<T>& l, const FrameParams& p,
                                      const mpr::PlanarSurface<T>& plane) {
  mpr::scene::VirtualArrayConfig<T> config = raster_config<T>(job);
  if (job.focal_depth) config.focal_depth = static_cast<T>(p.focal_depth);
  using S = mpr::scene::Scene<T>;
  switch (job.interpolation) {
  case Interpolation::nearest:
    return mpr::SceneSampler<S, mpr::Rasterized<mpr::NearestCamera>>(*l.scene, plane, config);
  case Interpolation::synthetic:
    return mpr::SceneSampler<S, mpr::Rasterized<mpr::SyntheticAperture>>(*l.scene, plane, config);
  case Interpolation::depth:
    return mpr::SceneSampler<S, mpr::Rasterized<mpr::DepthProxy>>(
        *l.scene, plane, config, mpr::Rasterized<mpr::DepthProxy>{job.depth_proxy(p.radius)});
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
  // The light-field samplers: the library's choice (the Python module's too), widened to this variant.
  return std::visit([](auto&& s) -> SamplerVariant<T> { return std::move(s); },
                    mpr::make_frame_sampler(l.frames, job.interpolation, p.radius, job.depth_proxy(p.radius)));
}

// Compiled once, in mpr_tools (tools/dispatch/run_float.cpp, run_double.cpp).
extern template SamplerVariant<float> make_sampler<float>(const Job&, const Loaded<float>&, const FrameParams&, int,
                                                          int);
extern template SamplerVariant<double> make_sampler<double>(const Job&, const Loaded<double>&, const FrameParams&, int,
                                                            int);

} // namespace mpr_cli
