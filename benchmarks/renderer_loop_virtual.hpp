#pragma once
// The 2004-style design for the renderer_loop benchmark: abstract base classes, one virtual call
// per role per pixel. The implementations live in renderer_loop_virtual.cpp, a separate
// translation unit, as plug-in implementations did: the loop cannot see (or devirtualise) them.

#include <mpr/mpr.hpp>

#include <memory>

namespace mpr_bench {

/// A trivial sampler: the colour is the absolute ray direction (cheap, but depends on every ray).
template <class T>
struct DirectionColor {
  using scalar_type = T;
  [[nodiscard]] mpr::Color sample(const mpr::Ray<T>& ray) const noexcept {
    return mpr::Color(static_cast<float>(ray.direction.x()), static_cast<float>(ray.direction.y()),
                      static_cast<float>(ray.direction.z()))
        .abs();
  }
};

template <class T>
struct VirtualRegion {
  virtual ~VirtualRegion() = default;
  virtual mpr::Vec2<T> pixel_to_uv(mpr::Pixel px) const = 0;
};
template <class T>
struct VirtualSurface {
  virtual ~VirtualSurface() = default;
  virtual mpr::Vec3<T> point_at(const mpr::Vec2<T>& uv) const = 0;
};
template <class T>
struct VirtualSelector {
  virtual ~VirtualSelector() = default;
  virtual mpr::Ray<T> ray_at(mpr::Pixel px, const mpr::Vec2<T>& uv, const mpr::Vec3<T>& point) const = 0;
};
template <class T>
struct VirtualSampler {
  virtual ~VirtualSampler() = default;
  virtual mpr::Color sample(const mpr::Ray<T>& ray) const = 0;
};

/// The role objects a 2004-style program holds behind base-class pointers.
template <class T>
struct VirtualPolicies {
  std::unique_ptr<VirtualRegion<T>> region;
  std::unique_ptr<VirtualSurface<T>> surface;
  std::unique_ptr<VirtualSelector<T>> selector;
  std::unique_ptr<VirtualSampler<T>> sampler;
};

template <class T>
VirtualPolicies<T> make_virtual_policies(const mpr::Region& region, const mpr::PlanarSurface<T>& plane,
                                         const mpr::GlcSelector<T>& glc);

} // namespace mpr_bench
