// The renderer loop with a trivial sampler: mpr's static policies against the same loop written
// with one virtual call per role per pixel (region, surface, selector, sampler), the design of
// the original 2004 system (pure virtual base classes). 500 x 500 rays, float and double.
//
// usage: renderer_loop [--quick]
#include "bench_common.hpp"

#include <mpr/mpr.hpp>

#include <cstdio>
#include <memory>

namespace {

/// A trivial sampler: the colour is the absolute ray direction (cheap, but depends on every ray).
template <class T> struct DirectionColor {
  using scalar_type = T;
  [[nodiscard]] mpr::Color sample(const mpr::Ray<T>& ray) const noexcept {
    return mpr::Color(static_cast<float>(ray.direction.x()), static_cast<float>(ray.direction.y()),
                      static_cast<float>(ray.direction.z()))
        .abs();
  }
};

// The 2004-style design: abstract base classes, one virtual call per role per pixel.
template <class T> struct VirtualRegion {
  virtual ~VirtualRegion() = default;
  virtual mpr::Vec2<T> pixel_to_uv(mpr::Pixel px) const = 0;
};
template <class T> struct VirtualSurface {
  virtual ~VirtualSurface() = default;
  virtual mpr::Vec3<T> point_at(const mpr::Vec2<T>& uv) const = 0;
};
template <class T> struct VirtualSelector {
  virtual ~VirtualSelector() = default;
  virtual mpr::Ray<T> ray_at(mpr::Pixel px, const mpr::Vec2<T>& uv, const mpr::Vec3<T>& point) const = 0;
};
template <class T> struct VirtualSampler {
  virtual ~VirtualSampler() = default;
  virtual mpr::Color sample(const mpr::Ray<T>& ray) const = 0;
};

template <class T> struct RegionImpl final : VirtualRegion<T> {
  mpr::Region region;
  explicit RegionImpl(mpr::Region r) : region(r) {}
  mpr::Vec2<T> pixel_to_uv(mpr::Pixel px) const override { return region.pixel_to_uv<T>(px); }
};
template <class T> struct SurfaceImpl final : VirtualSurface<T> {
  mpr::PlanarSurface<T> plane;
  explicit SurfaceImpl(mpr::PlanarSurface<T> p) : plane(p) {}
  mpr::Vec3<T> point_at(const mpr::Vec2<T>& uv) const override { return plane.point_at(uv); }
};
template <class T> struct SelectorImpl final : VirtualSelector<T> {
  mpr::GlcSelector<T> glc;
  explicit SelectorImpl(mpr::GlcSelector<T> g) : glc(g) {}
  mpr::Ray<T> ray_at(mpr::Pixel px, const mpr::Vec2<T>& uv, const mpr::Vec3<T>& point) const override {
    return glc.ray_at(px, uv, point);
  }
};
template <class T> struct SamplerImpl final : VirtualSampler<T> {
  mpr::Color sample(const mpr::Ray<T>& ray) const override { return DirectionColor<T>{}.sample(ray); }
};

template <class T>
void virtual_render(mpr::ImageView<mpr::Color> out, const VirtualRegion<T>& region, const VirtualSurface<T>& surface,
                    const VirtualSelector<T>& selector, const VirtualSampler<T>& sampler, int threads) {
  mpr::detail::parallel_rows(0, out.height(), threads, [&](int y) noexcept {
    for (int x = 0; x < out.width(); ++x) {
      const mpr::Pixel px{x, y};
      const mpr::Vec2<T> uv = region.pixel_to_uv(px);
      const mpr::Vec3<T> point = surface.point_at(uv);
      const mpr::Ray<T> ray = selector.ray_at(px, uv, point);
      out(x, y) = sampler.sample(ray);
    }
  });
}

template <class T> void run(const char* scalar, int size, int repeats) {
  const mpr::PlanarSurface<T> plane({-1, -1, 1}, {2, 0, 0}, {0, 2, 0});
  const mpr::Vec3<T> eye(0, 0, 0);
  const mpr::GlcSelector<T> glc(plane, plane.point_at({0, 0}) - eye, plane.point_at({1, 0}) - eye,
                                plane.point_at({0, 1}) - eye);
  const mpr::Region region(0, 0, size, size);
  const mpr::Renderer renderer(plane, glc, DirectionColor<T>{});

  // Heap objects behind base pointers, as a 2004-style program would hold them.
  const std::unique_ptr<VirtualRegion<T>> v_region = std::make_unique<RegionImpl<T>>(region);
  const std::unique_ptr<VirtualSurface<T>> v_surface = std::make_unique<SurfaceImpl<T>>(plane);
  const std::unique_ptr<VirtualSelector<T>> v_selector = std::make_unique<SelectorImpl<T>>(glc);
  const std::unique_ptr<VirtualSampler<T>> v_sampler = std::make_unique<SamplerImpl<T>>();

  mpr::Image<mpr::Color> a(size, size), b(size, size);
  const double rays = double(size) * size;
  for (int threads : {1, 2}) {
    const mpr_bench::Timing s = mpr_bench::time_repeated(repeats, [&] {
      renderer.render(a.view(), region, mpr::RenderOptions{threads});
    });
    const mpr_bench::Timing v = mpr_bench::time_repeated(repeats, [&] {
      virtual_render<T>(b.view(), *v_region, *v_surface, *v_selector, *v_sampler, threads);
    });
    if (!(a == b)) {
      std::fprintf(stderr, "renderer_loop: static and virtual images differ\n");
      std::exit(1);
    }
    std::printf("| %-6s | %d | %8.1f (%.1f-%.1f) | %8.1f (%.1f-%.1f) | %5.2f |\n", scalar, threads,
                rays / s.median * 1e-6, rays / s.max * 1e-6, rays / s.min * 1e-6, rays / v.median * 1e-6,
                rays / v.max * 1e-6, rays / v.min * 1e-6, v.median / s.median);
  }
}

} // namespace

int main(int argc, char** argv) {
  const bool quick = mpr_bench::quick_mode(argc, argv);
  const int size = quick ? 64 : 500;
  const int repeats = quick ? 2 : 31;
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  std::printf("renderer loop, %dx%d rays, trivial sampler, median of %d runs (min-max in brackets)\n\n", size,
              size, repeats);
  std::printf("| scalar | threads | static Mrays/s | virtual Mrays/s | static speed-up |\n");
  std::printf("|---|---|---|---|---|\n");
  run<float>("float", size, repeats);
  run<double>("double", size, repeats);
  return 0;
}
