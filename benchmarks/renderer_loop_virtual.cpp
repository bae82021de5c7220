// Implementations of the 2004-style virtual roles, compiled apart from the loop that calls them.
#include "renderer_loop_virtual.hpp"

namespace mpr_bench {
namespace {

template <class T>
struct RegionImpl : VirtualRegion<T> {
  mpr::Region region;
  explicit RegionImpl(mpr::Region r) : region(r) {}
  mpr::Vec2<T> pixel_to_uv(mpr::Pixel px) const override { return region.pixel_to_uv<T>(px); }
};
template <class T>
struct SurfaceImpl : VirtualSurface<T> {
  mpr::PlanarSurface<T> plane;
  explicit SurfaceImpl(mpr::PlanarSurface<T> p) : plane(p) {}
  mpr::Vec3<T> point_at(const mpr::Vec2<T>& uv) const override { return plane.point_at(uv); }
};
template <class T>
struct SelectorImpl : VirtualSelector<T> {
  mpr::GlcSelector<T> glc;
  explicit SelectorImpl(mpr::GlcSelector<T> g) : glc(g) {}
  mpr::Ray<T> ray_at(mpr::Pixel px, const mpr::Vec2<T>& uv, const mpr::Vec3<T>& point) const override {
    return glc.ray_at(px, uv, point);
  }
};
template <class T>
struct SamplerImpl : VirtualSampler<T> {
  mpr::Color sample(const mpr::Ray<T>& ray) const override { return DirectionColor<T>{}.sample(ray); }
};

} // namespace

template <class T>
VirtualPolicies<T> make_virtual_policies(const mpr::Region& region, const mpr::PlanarSurface<T>& plane,
                                         const mpr::GlcSelector<T>& glc) {
  VirtualPolicies<T> p;
  p.region = std::make_unique<RegionImpl<T>>(region);
  p.surface = std::make_unique<SurfaceImpl<T>>(plane);
  p.selector = std::make_unique<SelectorImpl<T>>(glc);
  p.sampler = std::make_unique<SamplerImpl<T>>();
  return p;
}

template VirtualPolicies<float> make_virtual_policies(const mpr::Region&, const mpr::PlanarSurface<float>&,
                                                      const mpr::GlcSelector<float>&);
template VirtualPolicies<double> make_virtual_policies(const mpr::Region&, const mpr::PlanarSurface<double>&,
                                                       const mpr::GlcSelector<double>&);

} // namespace mpr_bench
