// Ray casting: BVH build time, then primary-ray throughput (Mrays/s) of a 1000 x 1000
// perspective view and of a cross-slit view on the same image plane, with 1 and 2 threads.
//
// Part 1, the renderer: the classroom demo scene through `mpr::Renderer` with the ray-cast
// sampler (shaded colour, and depth only), which traces 4 x 4 pixel packets on its own.
//
// Part 2, the same rays side by side: each view's rays are generated once (4 x 4 pixel blocks,
// 16 consecutive rays each) and traced by mpr single rays (`Bvh::closest_hits`), mpr packets
// (`Bvh::closest_hits_coherent`) and, when Embree 3 was found at configure time, Embree's
// `rtcIntersect1` and `rtcIntersect16` (one 16-ray packet per block, coherent flag, build
// quality HIGH), on the classroom (17,770 triangles) and on a generated terrain (524,288
// triangles). Then one line per view and thread count, for scripts:
//   ratio mpr/embree16 <view> <threads>: <mpr packets Mrays/s over Embree rtcIntersect16's>
// (the terrain's views named terrain-perspective and terrain-cross-slit). With 1 thread the table
// also gives Mrays per CPU-second of the tracing thread, steadier than the wall clock when other
// processes share the machine.
//
// Part 3, anti-aliasing (issue 15): gallery view G (cross-slit) at 640 x 480 with 1 (pixel
// centres), 4 and 16 scrambled Sobol samples per pixel, box filter, ms per view (and, with one
// thread, the rendering thread's CPU ms).
//
// Embree runs at the instruction set of mpr's kernels: `isa=avx2` when `MPR_SIMD` lowers mpr to
// avx2 and `isa=sse4.2` at portable (printed on the Embree build line); otherwise its best.
//
// usage: scene_raycast [--quick] [--antialias | --same-rays]   (part 3 only | part 2 only)
#include "bench_common.hpp"

#include <mpr/glc.hpp>
#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#if MPR_BENCH_EMBREE
#include <embree3/rtcore.h>
#endif

namespace {

using T = float;
using V = mpr::Vec3<T>;

/// An image plane `width` x 0.75 `width` centred at `centre` looking at `target`, and two-slit
/// views on it.
struct Setup {
  V centre, forward, right, down;
  T width;
  Setup(const V& c, const V& target, T w) : centre(c), width(w) {
    forward = (target - centre).normalized();
    right = forward.cross(V::UnitY()).normalized();
    down = forward.cross(right);
  }
  [[nodiscard]] mpr::PlanarSurface<T> plane() const {
    return mpr::PlanarSurface<T>::centred(centre, width * right, T(0.75) * width * down);
  }
  /// d = forward + (x / fx) right + (y / fy) down: a pinhole for fx == fy, else cross-slit
  /// (fx, fy in units of width / 8: the classroom's in metres).
  [[nodiscard]] mpr::GlcSelector<T> two_slit(T fx, T fy) const {
    const auto p = plane();
    fx *= width / 8;
    fy *= width / 8;
    const auto dir = [&](T u, T v) {
      const V offset = p.point_at({u, v}) - centre;
      return V(forward + offset.dot(right) / fx * right + offset.dot(down) / fy * down);
    };
    return {p, dir(0, 0), dir(1, 0), dir(0, 1)};
  }
};

/// The gallery's plane and frame (examples/gallery.cpp): 8 x 6 m, looking into the room.
Setup classroom_setup() { return Setup(V(0, 3.1f, 3.0f), V(0, 1.6f, -8), 8); }

/// A displaced terrain of 2 n^2 triangles over 200 x 200 m: rolling hills, ridges and a fine
/// bump pattern, so that many small triangles face the rays at all angles.
mpr::scene::Scene<T> terrain(int n) {
  mpr::scene::Mesh<T> m;
  m.positions.reserve(std::size_t(n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const T x = T(200) * T(i) / T(n) - 100, z = T(200) * T(j) / T(n) - 100;
      const T h = 8 * std::sin(0.045f * x) * std::cos(0.037f * z) + 3 * std::sin(0.13f * x + 0.21f * z) +
                  0.6f * std::sin(1.7f * x) * std::sin(1.3f * z) + 4 * std::abs(std::sin(0.02f * (x - z)));
      m.positions.emplace_back(x, h, z);
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  m.triangles.reserve(std::size_t(2) * n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  m.color = mpr::Color(0.45f, 0.6f, 0.3f);
  mpr::scene::Scene<T> s;
  s.add(m, "terrain");
  return s;
}

/// Above the terrain's edge, looking across it and down.
Setup terrain_setup() { return Setup(V(0, 40, 110), V(0, 0, 20), 40); }

template <class Output>
void run(const char* view, const char* output, const std::shared_ptr<const mpr::scene::Scene<T>>& scene,
         const mpr::GlcSelector<T>& glc, int size, int repeats) {
  const Setup setup = classroom_setup();
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast, Output> sampler(scene);
  const mpr::Renderer renderer(setup.plane(), glc, sampler);
  using Px = std::conditional_t<std::is_same_v<Output, mpr::HitDepth>, float, mpr::Rgb8>;
  mpr::Image<Px> image(size, size);
  const double rays = double(size) * size;
  for (int threads : {1, 2}) {
    const mpr_bench::Timing t = mpr_bench::time_repeated(
        repeats, [&] { renderer.render(image.view(), mpr::Region(0, 0, size, size), mpr::RenderOptions{threads}); });
    std::printf("| %-12s | %-12s | %d | %6.2f (%.2f-%.2f) | %7.1f |\n", view, output, threads, rays / t.median * 1e-6,
                rays / t.max * 1e-6, rays / t.min * 1e-6, t.median * 1e3);
  }
}

/// CPU time of the calling thread, in seconds.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

/// A view's rays in 4 x 4 pixel blocks, block rows top to bottom (16 consecutive rays a block).
std::vector<mpr::Ray<T>> block_rays(const Setup& setup, const mpr::GlcSelector<T>& glc, int size) {
  const mpr::PlanarSurface<T> plane = setup.plane();
  const mpr::Region region(0, 0, size, size);
  std::vector<mpr::Ray<T>> rays;
  rays.reserve(std::size_t(size) * size);
  for (int by = 0; by < size; by += 4)
    for (int bx = 0; bx < size; bx += 4)
      for (int y = by; y < by + 4; ++y)
        for (int x = bx; x < bx + 4; ++x) {
          const mpr::Vec2<T> uv = region.pixel_to_uv<T>({x, y});
          rays.push_back(glc.ray_at({x, y}, uv, plane.point_at(uv)));
        }
  return rays;
}

#if MPR_BENCH_EMBREE
/// An Embree scene of the same triangles (one triangle geometry), build quality HIGH.
class EmbreeScene {
public:
  explicit EmbreeScene(const mpr::scene::Scene<T>& s) : device_(rtcNewDevice(device_config())) {
    scene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    const std::size_t n = s.size();
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    for (std::size_t i = 0; i < n; ++i)
      for (int j = 0; j < 3; ++j) {
        for (int a = 0; a < 3; ++a) v[9 * i + 3 * j + a] = s.triangles()[i].p[j][a];
        idx[3 * i + j] = static_cast<unsigned>(3 * i + j);
      }
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene_);
  }
  /// The Embree device configuration matching mpr's SIMD level (nullptr: Embree's best).
  [[nodiscard]] static const char* device_config() noexcept {
    switch (mpr::detail::simd_level()) {
    case mpr::detail::SimdLevel::portable:
      return "isa=sse4.2";
    case mpr::detail::SimdLevel::avx2:
      return "isa=avx2";
    default:
      return nullptr;
    }
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  ~EmbreeScene() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }

  /// t of each ray's closest hit (+inf for a miss), one ray at a time.
  void intersect1(const mpr::Ray<T>* rays, std::size_t n, float* t) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::size_t i = 0; i < n; ++i) {
      RTCRayHit rh{};
      rh.ray.org_x = rays[i].origin.x();
      rh.ray.org_y = rays[i].origin.y();
      rh.ray.org_z = rays[i].origin.z();
      rh.ray.dir_x = rays[i].direction.x();
      rh.ray.dir_y = rays[i].direction.y();
      rh.ray.dir_z = rays[i].direction.z();
      rh.ray.tnear = 0;
      rh.ray.tfar = std::numeric_limits<float>::infinity();
      rh.ray.mask = ~0U;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene_, &context, &rh);
      t[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<float>::infinity() : rh.ray.tfar;
    }
  }

  /// The same through `rtcIntersect16`, 16 consecutive rays per packet (coherent flag).
  void intersect16(const mpr::Ray<T>* rays, std::size_t n, float* t) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (std::size_t i0 = 0; i0 < n; i0 += 16) {
      alignas(64) int valid[16];
      RTCRayHit16 rh;
      const std::size_t k = std::min<std::size_t>(16, n - i0);
      for (std::size_t r = 0; r < 16; ++r) {
        const mpr::Ray<T>& ray = rays[i0 + std::min(r, k - 1)];
        valid[r] = r < k ? -1 : 0;
        rh.ray.org_x[r] = ray.origin.x();
        rh.ray.org_y[r] = ray.origin.y();
        rh.ray.org_z[r] = ray.origin.z();
        rh.ray.dir_x[r] = ray.direction.x();
        rh.ray.dir_y[r] = ray.direction.y();
        rh.ray.dir_z[r] = ray.direction.z();
        rh.ray.tnear[r] = 0;
        rh.ray.tfar[r] = std::numeric_limits<float>::infinity();
        rh.ray.time[r] = 0;
        rh.ray.mask[r] = ~0U;
        rh.ray.id[r] = 0;
        rh.ray.flags[r] = 0;
        rh.hit.geomID[r] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, scene_, &context, &rh);
      for (std::size_t r = 0; r < k; ++r)
        t[i0 + r] =
            rh.hit.geomID[r] == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<float>::infinity() : rh.ray.tfar[r];
    }
  }

private:
  RTCDevice device_;
  RTCScene scene_;
};
#endif

/// The same-rays table for one scene: every view, method and thread count; then the ratio lines.
void same_rays(const char* scene_name, const mpr::scene::Scene<T>& scene, const Setup& setup, int size, int repeats) {
  const mpr_bench::Timing build = mpr_bench::time_repeated(repeats, [&] { mpr::scene::Bvh<T> bvh(scene); });
  const mpr::scene::Bvh<T> bvh(scene);
  std::printf("\n%s: %zu triangles; mpr BVH build %.1f ms", scene_name, scene.size(), build.median * 1e3);
#if MPR_BENCH_EMBREE
  const mpr_bench::Timing ebuild = mpr_bench::time_repeated(repeats, [&] { EmbreeScene e(scene); });
  const EmbreeScene embree(scene);
  const char* isa = EmbreeScene::device_config();
  std::printf(", Embree %s (%s) build (HIGH) %.1f ms", RTC_VERSION_STRING, isa ? isa : "best isa", ebuild.median * 1e3);
  std::printf("; mpr SIMD level %s", mpr::detail::simd_level_name());
#endif
  std::printf("\nsame rays, %dx%d in 4x4 blocks, median of %d runs (min-max), Mrays/s\n\n", size, size, repeats);
  std::printf("| scene | view | method | threads | Mrays/s | Mrays per CPU-second |\n|---|---|---|---|---|---|\n");
  const std::size_t n = std::size_t(size) * size, per_row = std::size_t(size) * 4;
  const int block_rows = size / 4;
  struct ViewDef {
    const char* name;
    mpr::GlcSelector<T> glc;
  };
  const ViewDef views[] = {{"perspective", setup.two_slit(5, 5)}, {"cross-slit", setup.two_slit(3, 14)}};
  std::vector<std::string> ratios;
  for (const ViewDef& view : views) {
    const std::vector<mpr::Ray<T>> rays = block_rays(setup, view.glc, size);
    std::vector<mpr::scene::Hit<T>> hits(n);
    std::vector<float> t1(n), t16(n);
    // Each method traces block rows [y, y + 1) of the view.
    const auto mpr_single = [&](int y) noexcept {
      bvh.closest_hits(std::span(rays.data() + y * per_row, per_row), std::span(hits.data() + y * per_row, per_row));
    };
    const auto mpr_packets = [&](int y) noexcept {
      bvh.closest_hits_coherent(std::span(rays.data() + y * per_row, per_row),
                                std::span(hits.data() + y * per_row, per_row));
    };
    double mrays[2][4] = {};
    for (int threads : {1, 2}) {
      const auto one = [&](int column, const char* method, const auto& trace) {
        // With 1 thread the work runs on this thread: its CPU time (best run) is also given, a
        // figure other processes on a loaded machine disturb far less than the wall clock.
        double cpu_best = 1e30;
        const mpr_bench::Timing t = mpr_bench::time_repeated(repeats, [&] {
          const double c0 = thread_cpu_seconds();
          mpr::detail::parallel_rows(0, block_rows, threads, trace);
          cpu_best = std::min(cpu_best, thread_cpu_seconds() - c0);
        });
        mrays[threads - 1][column] = double(n) / t.median * 1e-6;
        char cpu[32] = "-";
        if (threads == 1) std::snprintf(cpu, sizeof cpu, "%.2f", double(n) / cpu_best * 1e-6);
        std::printf("| %-9s | %-11s | %-18s | %d | %6.2f (%.2f-%.2f) | %s |\n", scene_name, view.name, method, threads,
                    double(n) / t.median * 1e-6, double(n) / t.max * 1e-6, double(n) / t.min * 1e-6, cpu);
      };
      one(0, "mpr single", mpr_single);
      one(1, "mpr packets", mpr_packets);
#if MPR_BENCH_EMBREE
      one(2, "embree intersect1",
          [&](int y) noexcept { embree.intersect1(&rays[y * per_row], per_row, &t1[y * per_row]); });
      one(3, "embree intersect16",
          [&](int y) noexcept { embree.intersect16(&rays[y * per_row], per_row, &t16[y * per_row]); });
      char line[128];
      // The classroom's views by their own names, the terrain's prefixed with "terrain-".
      const std::string name =
          std::string(scene_name) == "classroom" ? view.name : scene_name + std::string("-") + view.name;
      std::snprintf(line, sizeof line, "ratio mpr/embree16 %s %d: %.2f", name.c_str(), threads,
                    mrays[threads - 1][1] / mrays[threads - 1][3]);
      ratios.emplace_back(line);
#endif
    }
#if MPR_BENCH_EMBREE
    // Agreement of mpr's packets with Embree's packets on the same rays (the last runs' hits).
    std::size_t disagree = 0, both = 0;
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const bool a = hits[i].valid(), b = std::isfinite(t16[i]);
      if (a != b) ++disagree;
      if (a && b) {
        ++both;
        worst = std::max(worst, std::abs(double(hits[i].t) - t16[i]) / std::max(1e-30, std::abs(double(t16[i]))));
      }
    }
    std::printf(
        "| %-9s | %-11s | agreement: %zu hits, %zu hit/miss disagreements, worst relative t difference %.1e |\n",
        scene_name, view.name, both, disagree, worst);
#endif
  }
  for (const std::string& line : ratios) std::printf("%s\n", line.c_str());
}

/// Gallery view G at `w` x `h`, shaded colour, `spp` samples per pixel (1: pixel centres).
void antialiased(const std::shared_ptr<const mpr::scene::Scene<T>>& scene, int w, int h, int repeats) {
  const Setup setup = classroom_setup();
  const mpr::PlanarSurface<T> plane = setup.plane();
  const mpr::GlcSelector<T> g = mpr::glc::gallery_view('G', plane, V(0, 1.6f, -8), T(14));
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast> sampler(scene);
  mpr::Image<mpr::Rgb8> image(w, h);
  const auto row = [&](int spp, const auto& sampling) {
    const mpr::Renderer renderer(plane, g, sampler, sampling);
    for (int threads : {1, 2}) {
      // With one thread, also the rendering thread's CPU time (steadier on a shared machine).
      std::vector<double> cpu;
      const mpr_bench::Timing t = mpr_bench::time_repeated(repeats, [&] {
        const double c0 = thread_cpu_seconds();
        renderer.render(image.view(), mpr::Region(0, 0, w, h), mpr::RenderOptions{threads});
        cpu.push_back(thread_cpu_seconds() - c0);
      });
      std::sort(cpu.begin(), cpu.end());
      const double rays = double(w) * h * spp;
      char cpu_ms[32] = "-";
      if (threads == 1) std::snprintf(cpu_ms, sizeof cpu_ms, "%.1f", cpu[cpu.size() / 2] * 1e3);
      std::printf("| G cross-slit %dx%d | %3d | %d | %6.2f (%.2f-%.2f) | %7.1f (%.1f-%.1f) | %s |\n", w, h, spp,
                  threads, rays / t.median * 1e-6, rays / t.max * 1e-6, rays / t.min * 1e-6, t.median * 1e3,
                  t.min * 1e3, t.max * 1e3, cpu_ms);
    }
  };
  row(1, mpr::PixelCentre{});
  row(4, mpr::Supersample(mpr::OwenSobol(4)));
  row(16, mpr::Supersample(mpr::OwenSobol(16)));
}

} // namespace

int main(int argc, char** argv) {
  const bool quick = mpr_bench::quick_mode(argc, argv);
  bool antialias_only = false, same_rays_only = false;
  for (int i = 1; i < argc; ++i) {
    antialias_only = antialias_only || std::string(argv[i]) == "--antialias";
    same_rays_only = same_rays_only || std::string(argv[i]) == "--same-rays";
  }
  const int size = quick ? 64 : 1000;
  const int repeats = quick ? 1 : 9;
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scene::classroom<T>());
  if (antialias_only) {
    std::printf("\nanti-aliased view, shaded colour, box filter, median of %d runs (min-max in brackets)\n\n", repeats);
    std::printf("| view | spp | threads | Mrays/s | ms/view | thread CPU ms |\n|---|---|---|---|---|---|\n");
    antialiased(scene, quick ? 64 : 640, quick ? 48 : 480, repeats);
    return 0;
  }
  if (same_rays_only) {
    same_rays("classroom", *scene, classroom_setup(), size, quick ? 1 : 5);
    same_rays("terrain", terrain(quick ? 64 : 512), terrain_setup(), size, quick ? 1 : 5);
    return 0;
  }
  const mpr_bench::Timing build = mpr_bench::time_repeated(quick ? 1 : 9, [&] { mpr::scene::Bvh<T> bvh(*scene); });
  const mpr::scene::Bvh<T> bvh(*scene);
  std::printf("classroom: %zu triangles (%zu textured), BVH %zu nodes, depth %d, build %.1f ms (%.1f-%.1f), float\n\n",
              scene->size(), scene->textured_triangles(), bvh.nodes().size(), bvh.depth(), build.median * 1e3,
              build.min * 1e3, build.max * 1e3);
  std::printf("primary rays through the renderer, %dx%d, median of %d runs (min-max in brackets)\n\n", size, size,
              repeats);
  std::printf("| view | output | threads | Mrays/s | ms/view |\n|---|---|---|---|---|\n");
  const Setup setup = classroom_setup();
  const mpr::GlcSelector<T> perspective = setup.two_slit(5, 5);
  const mpr::GlcSelector<T> cross_slit = setup.two_slit(3, 14);
  {
    // Untimed warm-up of the whole process (threads, caches, clock) before the first table row.
    const mpr::Renderer warm(setup.plane(), perspective, mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>(scene));
    mpr::Image<mpr::Rgb8> image(size, size);
    for (int i = 0; i < (quick ? 1 : 3); ++i) warm.render(image.view(), mpr::Region(0, 0, size, size));
  }
  run<mpr::ShadedColor>("perspective", "colour", scene, perspective, size, repeats);
  run<mpr::HitDepth>("perspective", "depth only", scene, perspective, size, repeats);
  run<mpr::ShadedColor>("cross-slit", "colour", scene, cross_slit, size, repeats);
  run<mpr::HitDepth>("cross-slit", "depth only", scene, cross_slit, size, repeats);

  same_rays("classroom", *scene, setup, size, quick ? 1 : 5);
  same_rays("terrain", terrain(quick ? 64 : 512), terrain_setup(), size, quick ? 1 : 5);
  std::printf("\nanti-aliased view, shaded colour, box filter, median of %d runs (min-max in brackets)\n\n", repeats);
  std::printf("| view | spp | threads | Mrays/s | ms/view | thread CPU ms |\n|---|---|---|---|---|---|\n");
  antialiased(scene, quick ? 64 : 640, quick ? 48 : 480, repeats);
  return 0;
}
