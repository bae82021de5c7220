// Light-field rendering speed: the reference workload of the 2004 GLC system (a 500x500 output
// from 90 cameras of 640x480 on a planar grid; 1.44 s with the nearest camera, 2.5 s with the
// full synthetic aperture on a 2.8 GHz Pentium 4) with synthetic images generated in memory,
// and a full synthetic-aperture refocus of the real Stanford Chess light field (49 views of
// 1400x800) when the data is present. Each policy runs through the batch path (the sampler's
// `sample_rays`, cameras in the outer loop) and, for comparison, through the per-pixel
// `sample(ray)` contract only.
//
// usage: lightfield [--quick] [--only=SUBSTRING] [--repeats=N] [--no-per-pixel] [--levels] [DATA_DIR]
//   --only: run only the workloads whose label contains SUBSTRING (e.g. --only=Chess)
//   --no-per-pixel: skip the per-pixel runs and the batch == per-pixel check (for profiling)
//   --levels: add the Chess synthetic-aperture rows (z = 1000 and 820, 1 thread) and the magnified
//     rows (Chess scale 1x/1.5x/2x) at every SIMD
//     level the CPU runs, labelled "@level": each level runs in a child process of this program
//     with MPR_SIMD set (a process chooses its level once), the levels in turn, twice (portable
//     up to the best, then back down), so that a load that changes during the run shows as two
//     figures of a level that differ (--level-rows: what such a child runs)
#include "bench_common.hpp"

#include <mpr/lightfield.hpp>
#include <mpr/mpr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace {

using T = float;

// nx x ny cameras, `spacing` apart on z = 0, looking along +z, images of a textured plane at
// z = depth (a checkerboard modulated by smooth colour ramps).
std::shared_ptr<const mpr::CameraFrameSet<T>> synthetic_array(int nx, int ny, T spacing, int w, int h, T focal,
                                                              T depth) {
  std::vector<mpr::PinholeCamera<T>> cameras;
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const mpr::Vec3<T> c((static_cast<T>(i) - T(0.5) * static_cast<T>(nx - 1)) * spacing,
                           (static_cast<T>(j) - T(0.5) * static_cast<T>(ny - 1)) * spacing, 0);
      mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
      K(0, 0) = K(1, 1) = focal;
      K(0, 2) = T(0.5) * static_cast<T>(w - 1);
      K(1, 2) = T(0.5) * static_cast<T>(h - 1);
      cameras.emplace_back(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>(-c), w, h);
      mpr::Image<mpr::Rgb8> img(w, h);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const T X = c.x() + (static_cast<T>(x) - K(0, 2)) / focal * depth;
          const T Y = c.y() + (static_cast<T>(y) - K(1, 2)) / focal * depth;
          const bool dark = (static_cast<int>(std::floor(X)) + static_cast<int>(std::floor(Y))) & 1;
          img(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(dark ? 40 : 200 + 50 * std::sin(X)),
                                static_cast<std::uint8_t>(dark ? 30 : 150 + 60 * std::cos(Y)),
                                static_cast<std::uint8_t>(x * 255 / w)};
        }
      images.push_back(std::move(img));
    }
  return std::make_shared<const mpr::CameraFrameSet<T>>(std::move(cameras), std::move(images));
}

/// Median CPU time of the calling thread over `repeats` runs (after one warm-up), in ms: on a
/// machine shared with other jobs this is what a single-threaded run costs when it has a core.
template <class Fn>
double thread_cpu_ms(int repeats, Fn&& fn) {
  fn();
  std::vector<double> ms;
  for (int i = 0; i < repeats; ++i) {
    timespec a{}, b{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &a);
    fn();
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &b);
    ms.push_back((static_cast<double>(b.tv_sec - a.tv_sec) + 1e-9 * static_cast<double>(b.tv_nsec - a.tv_nsec)) * 1e3);
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

std::string g_only;        // --only=: label filter
bool g_per_pixel = true;   // --no-per-pixel clears it
bool g_levels = false;     // --levels
bool g_level_rows = false; // --level-rows: the child of --levels (only its rows, labelled with the level)

struct Result {
  double batch_ms, per_pixel_ms, cpu_ms;
};

template <class Sampler>
Result measure(const char* label, const mpr::PlanarSurface<T>& plane, const mpr::GlcSelector<T>& glc,
               const Sampler& sampler, int w, int h, int threads, int repeats, bool per_pixel, double ms_2004 = -1) {
  if (!g_only.empty() && std::string(label).find(g_only) == std::string::npos) return {0, 0, 0};
  const mpr::Region region(0, 0, w, h);
  mpr::Image<mpr::Rgb8> a(w, h), b(w, h);
  const mpr::Renderer batch(plane, glc, sampler);
  const mpr_bench::Timing tb = mpr_bench::time_repeated(repeats, [&] { batch.render(a.view(), region, {threads}); });
  const double cpu = threads == 1 ? thread_cpu_ms(repeats, [&] { batch.render(a.view(), region, {1}); }) : 0.0;
  double pp = 0;
  if (per_pixel && g_per_pixel) {
    const mpr::Renderer slow(plane, glc, mpr_bench::PerRay<Sampler>{sampler});
    const mpr_bench::Timing tp =
        mpr_bench::time_repeated(std::max(1, repeats / 4), [&] { slow.render(b.view(), region, {threads}); });
    pp = tp.median * 1e3;
    int worst = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        worst = std::max(
            {worst, std::abs(a(x, y).r - b(x, y).r), std::abs(a(x, y).g - b(x, y).g), std::abs(a(x, y).b - b(x, y).b)});
    if (worst > 1) {
      std::fprintf(stderr, "lightfield: %s: batch and per-pixel images differ by %d levels\n", label, worst);
      std::exit(1);
    }
  }
  std::printf("| %-34s | %d | %8.2f (%.2f-%.2f) | %8.2f | %8.1f | %6.1f |", label, threads, tb.median * 1e3,
              tb.min * 1e3, tb.max * 1e3, cpu, pp, static_cast<double>(w) * h / tb.median * 1e-6);
  if (ms_2004 > 0)
    std::printf(" %6.0fx |\n", ms_2004 / (tb.median * 1e3));
  else if (ms_2004 == 0)
    std::printf("        |\n");
  else
    std::printf("\n");
  return {tb.median * 1e3, pp, cpu};
}

// The peer: shift-and-add refocusing done as the public refocusers do it, in 8-bit code space
// (no decode to linear light), single-threaded, on the images as loaded: per camera an integer
// shift plus a bilinear sub-pixel blend of two code rows into float sums, then the mean rounded
// to a code. Same cameras and shifts as mpr's parallel-plane refocus; `out` receives the image.
double peer_code_space_refocus(const mpr::CameraFrameSet<T>& lf, const mpr::PinholeCamera<T>& centre, T z,
                               mpr::Image<mpr::Rgb8>& out, int repeats) {
  const int w = centre.width(), h = centre.height();
  struct Shift {
    int ix, iy;
    float ax, ay;
  };
  std::vector<Shift> shifts;
  const mpr::PlanarSurface<T> plane = centre.image_plane(z);
  const mpr::Vec3<T> origin = plane.point_at({T(0.5) / static_cast<T>(w), T(0.5) / static_cast<T>(h)});
  for (std::size_t c = 0; c < lf.size(); ++c) {
    const std::optional<mpr::Vec2<T>> p = lf.camera(c).project(origin);
    if (!p) continue;
    const T fx = std::floor(p->x()), fy = std::floor(p->y());
    shifts.push_back(
        {static_cast<int>(fx), static_cast<int>(fy), static_cast<float>(p->x() - fx), static_cast<float>(p->y() - fy)});
  }
  std::vector<float> sum(3 * static_cast<std::size_t>(w)), count(static_cast<std::size_t>(w));
  const auto run = [&] {
    for (int y = 0; y < h; ++y) {
      std::fill(sum.begin(), sum.end(), 0.0f);
      std::fill(count.begin(), count.end(), 0.0f);
      for (std::size_t c = 0; c < shifts.size(); ++c) {
        const Shift& s = shifts[c];
        const mpr::Image<mpr::Rgb8>& img = lf.image(c);
        const int cy = y + s.iy;
        if (cy < 0 || cy + 1 >= img.height()) continue;
        const int x0 = std::max(0, -s.ix), x1 = std::min(w, img.width() - 1 - s.ix);
        if (x0 >= x1) continue;
        const std::uint8_t* a = &img(x0 + s.ix, cy).r;
        const std::uint8_t* b = &img(x0 + s.ix, cy + 1).r;
        const float w00 = (1 - s.ax) * (1 - s.ay), w10 = s.ax * (1 - s.ay), w01 = (1 - s.ax) * s.ay, w11 = s.ax * s.ay;
        float* acc = sum.data() + 3 * x0;
        const int m = 3 * (x1 - x0);
        for (int j = 0; j < m; ++j)
          acc[j] += w00 * static_cast<float>(a[j]) + w10 * static_cast<float>(a[j + 3]) +
                    w01 * static_cast<float>(b[j]) + w11 * static_cast<float>(b[j + 3]);
        for (int x = x0; x < x1; ++x) count[static_cast<std::size_t>(x)] += 1.0f;
      }
      for (int x = 0; x < w; ++x) {
        const float n = count[static_cast<std::size_t>(x)];
        const float inv = n > 0 ? 1.0f / n : 0.0f;
        const float* v = sum.data() + 3 * x;
        out(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(std::lround(std::min(255.0f, v[0] * inv))),
                              static_cast<std::uint8_t>(std::lround(std::min(255.0f, v[1] * inv))),
                              static_cast<std::uint8_t>(std::lround(std::min(255.0f, v[2] * inv)))};
      }
    }
  };
  return mpr_bench::time_repeated(repeats, run).median * 1e3;
}

// Output magnified from the cameras' scale: the centre camera's field of view at 1x, 1.5x and 2x
// its pixel count per axis (1400x800, 2100x1200, 2800x1600; each output pixel steps 1/scale camera
// pixel), 1 thread, z = 1000 and 820. The ratio row is each scale's thread CPU time over the 1x
// view's (pixel counts 2.25x and 4x). `suffix` labels the level in a --levels child.
template <class Sampler>
void print_scale_rows(const mpr::PinholeCamera<T>& centre, const Sampler& sampler, int repeats,
                      const std::string& suffix) {
  for (const T z : {T(1000), T(820)}) {
    const std::string at = " z=" + std::to_string(static_cast<int>(z)) + suffix;
    double cpu[3] = {0, 0, 0};
    const T scales[3] = {T(1), T(1.5), T(2)};
    const char* names[3] = {"1x", "1.5x", "2x"};
    for (int i = 0; i < 3; ++i) {
      mpr::Mat3<T> K = centre.K();
      const int w = static_cast<int>(static_cast<T>(centre.width()) * scales[i]);
      const int h = static_cast<int>(static_cast<T>(centre.height()) * scales[i]);
      K(0, 0) *= scales[i];
      K(1, 1) *= scales[i];
      K(0, 2) = T(0.5) * static_cast<T>(w - 1);
      K(1, 2) = T(0.5) * static_cast<T>(h - 1);
      const mpr::PinholeCamera<T> view(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>::Zero(), w, h);
      const mpr::PlanarSurface<T> p = view.image_plane(z);
      const std::string label = std::string("Chess scale ") + names[i] + at;
      cpu[i] = measure(label.c_str(), p, mpr::pinhole_glc(view, p), sampler, w, h, 1, repeats, true).cpu_ms;
    }
    if (cpu[0] > 0 && cpu[1] > 0 && cpu[2] > 0) // all three run (not narrowed by --only)
      std::printf("| %-34s | 1 | 1.5x: %.2f, 2x: %.2f (thread CPU over 1x; pixels 2.25x, 4x) |\n",
                  ("Chess scale ratio" + at).c_str(), cpu[1] / cpu[0], cpu[2] / cpu[0]);
  }
}

// --levels: the Chess synthetic-aperture rows at each SIMD level the CPU runs, each level in a
// child process (`program` with MPR_SIMD set and --level-rows), portable up to the best level
// and back down; the children's table rows are printed as they come.
void print_level_rows(const char* program, const std::string& data, int repeats) {
  if (std::string(program).find('\'') != std::string::npos || data.find('\'') != std::string::npos) {
    std::printf("\n(--levels: skipped, a path holds a quote)\n");
    return;
  }
  std::vector<mpr::detail::SimdLevel> levels;
  for (const mpr::detail::SimdLevel level : mpr::detail::kSimdLevels)
    if (level <= mpr::detail::cpu_simd_level()) levels.push_back(level);
  std::vector<mpr::detail::SimdLevel> order = levels;
  order.insert(order.end(), levels.rbegin(), levels.rend());
  std::printf(
      "\nChess synthetic aperture at each SIMD level (1 thread; child processes with MPR_SIMD, in the order "
      "run; load average %s)\n\n| workload | threads | batch ms (wall) | batch ms (thread CPU) | per-pixel ms | "
      "Mrays/s |\n|---|---|---|---|---|---|\n",
      mpr_bench::load_average().c_str());
  std::fflush(stdout);
  for (const mpr::detail::SimdLevel level : order) {
    const std::string command = std::string("MPR_SIMD=") + mpr::detail::simd_level_name(level) + " '" + program +
                                "' --level-rows --only='Chess ' --no-per-pixel --repeats=" + std::to_string(repeats) +
                                " '" + data + "'";
    FILE* child = popen(command.c_str(), "r");
    if (child == nullptr) {
      std::printf("(--levels: could not run %s)\n", command.c_str());
      return;
    }
    char line[512];
    while (std::fgets(line, sizeof line, child) != nullptr)
      if (std::string(line).rfind("| Chess synthetic aperture z=", 0) == 0 ||
          std::string(line).rfind("| Chess scale ", 0) == 0)
        std::fputs(line, stdout);
    pclose(child);
    std::fflush(stdout);
  }
}

} // namespace

int main(int argc, char** argv) {
  const bool quick = mpr_bench::quick_mode(argc, argv);
  std::string data;
  int repeats_option = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--only=", 0) == 0)
      g_only = a.substr(7);
    else if (a == "--no-per-pixel")
      g_per_pixel = false;
    else if (a.rfind("--repeats=", 0) == 0)
      repeats_option = std::atoi(a.c_str() + 10);
    else if (a == "--levels")
      g_levels = true;
    else if (a == "--level-rows")
      g_level_rows = true;
    else if (a != "--quick")
      data = a;
  }
  if (data.empty()) {
    const char* env = std::getenv("MPR_DATA_DIR");
    data = env != nullptr ? env : "";
  }
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  std::printf("shift-and-add kernels: %s; 8-bit frames sampled from their 3-byte sRGB codes, decoded to linear in "
              "registers%s; tiles of %d rows\n",
              mpr::detail::simd_level_name(),
              mpr::CameraFrameSet<T>::holds_linear16()
                  ? " (the shift tiles read the frames' 16-bit linear copy, decoded once at load)"
                  : "",
              mpr::kTileRows);
  const int repeats = repeats_option > 0 ? repeats_option : quick ? 1 : 15;
  const int nx = quick ? 4 : 10, ny = quick ? 3 : 9, cw = quick ? 160 : 640, ch = quick ? 120 : 480;
  const int size = quick ? 100 : 500;
  const T spacing = 1, focal = quick ? 150 : 600, depth = 20;
  const auto frames = synthetic_array(nx, ny, spacing, cw, ch, focal, depth);

  // The virtual camera at the array centre, same focal length, focused on the textured plane.
  mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
  K(0, 0) = K(1, 1) = focal;
  K(0, 2) = K(1, 2) = T(0.5) * static_cast<T>(size - 1);
  const mpr::PinholeCamera<T> view(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>::Zero(), size, size);
  // The image surface: the plane z = depth seen at the cameras' own scale (one output pixel
  // per camera pixel). The rays: a cross-slit GLC whose rays cross the camera plane at
  // s(u, v) = (-3 + 6u, -2 + 4v, 0), sweeping a 6 x 4 area of the array, so the nearest camera
  // and the cylinder's cameras change across the image.
  const mpr::PlanarSurface<T> plane = view.image_plane(depth);
  const auto crossing_glc = [&](const mpr::PlanarSurface<T>& p) {
    const auto d = [&](T u, T v) { return mpr::Vec3<T>(p.point_at({u, v}) - mpr::Vec3<T>(-3 + 6 * u, -2 + 4 * v, 0)); };
    return mpr::GlcSelector<T>(p, d(0, 0), d(1, 0), d(0, 1));
  };
  const mpr::GlcSelector<T> glc = crossing_glc(plane);
  const mpr::PlanarSurface<T> tilted = plane.tilted(T(0.25), T(0.15));
  const mpr::GlcSelector<T> tilted_glc = crossing_glc(tilted);
  // The parallel plane half a unit deeper: every camera's shift is a fraction of a pixel (29.27
  // pixels per grid step against 30), so each sample is a bilinear blend of four texels, as on
  // the tilted plane, but with one set of weights per camera instead of one per pixel.
  const mpr::PlanarSurface<T> between = view.image_plane(depth + T(0.5));
  const mpr::GlcSelector<T> between_glc = crossing_glc(between);

  const T radius = 2.0f;
  const mpr::CameraFrameSampler<mpr::NearestCamera, T> nearest(frames);
  const mpr::CameraFrameSampler<mpr::SyntheticAperture, T> full(frames);
  const mpr::CameraFrameSampler<mpr::CylinderAperture, T> cylinder(frames, mpr::CylinderAperture{radius});
  // Cameras per ray of the cylinder aperture, averaged over the output.
  double in_cylinder = 0;
  for (int y = 0; y < size; y += 7)
    for (int x = 0; x < size; x += 7) {
      const mpr::Vec2<T> uv((static_cast<T>(x) + T(0.5)) / static_cast<T>(size),
                            (static_cast<T>(y) + T(0.5)) / static_cast<T>(size));
      const mpr::Ray<T> r = glc.ray_at({x, y}, uv, plane.point_at(uv));
      int count = 0;
      nearest.index().within(r.origin, r.direction, radius, [&](int, T) { ++count; });
      in_cylinder += count;
    }
  in_cylinder /= std::pow(std::ceil(size / 7.0), 2);

  std::printf(
      "\nreference workload: %dx%d output, %d cameras of %dx%d on a planar grid (8-bit frames), cross-slit GLC, "
      "focal plane parallel to the camera plane at the cameras' pixel scale unless 'tilted' ('between texels': half a "
      "unit deeper, every camera's shift a fraction of a pixel); cylinder radius %.1f grid "
      "steps = %.1f cameras per ray; "
      "median of %d runs (min-max); thread CPU time for 1 thread; load average at start: %s\n\n",
      size, size, nx * ny, cw, ch, static_cast<double>(radius), in_cylinder, repeats,
      mpr_bench::load_average().c_str());
  std::printf("| workload | threads | batch ms (wall) | batch ms (thread CPU) | per-pixel ms | Mrays/s | vs 2004 "
              "(wall) |\n|---|---|---|---|---|---|---|\n");
  for (int threads : {1, 2}) {
    measure("nearest camera", plane, glc, nearest, size, size, threads, repeats, true, 1440.0);
    measure("synthetic aperture (all cameras)", plane, glc, full, size, size, threads, repeats, true, 2500.0);
    measure("synthetic aperture, tilted plane", tilted, tilted_glc, full, size, size, threads, repeats, true, 2500.0);
    measure("synthetic aperture, between texels", between, between_glc, full, size, size, threads, repeats, true, 0.0);
    measure("cylinder aperture", plane, glc, cylinder, size, size, threads, repeats, true, 0.0);
    measure("cylinder aperture, tilted plane", tilted, tilted_glc, cylinder, size, size, threads, repeats, true, 0.0);
    measure("nearest camera, tilted plane", tilted, tilted_glc, nearest, size, size, threads, repeats, true, 0.0);
  }

  const std::filesystem::path chess = std::filesystem::path(data) / "stanford" / "chess";
  if (quick || data.empty() || !std::filesystem::is_directory(chess)) {
    std::printf("\nChess: skipped (%s)\n", quick ? "--quick" : "no data; pass DATA_DIR or set MPR_DATA_DIR");
    return 0;
  }
  const auto lf = std::make_shared<const mpr::CameraFrameSet<T>>(mpr::read_stanford_light_field<T>(chess));
  mpr::Mat3<T> Kc = lf->camera(0).K();
  Kc(0, 2) = T(0.5) * static_cast<T>(lf->camera(0).width() - 1);
  Kc(1, 2) = T(0.5) * static_cast<T>(lf->camera(0).height() - 1);
  const mpr::PinholeCamera<T> centre(Kc, mpr::Mat3<T>::Identity(), mpr::Vec3<T>::Zero(), lf->camera(0).width(),
                                     lf->camera(0).height());
  std::printf(
      "\nStanford Chess: %zu views of %dx%d, refocus at the reference plane (z = 1000) and at z = 820 (mid-board)\n\n",
      lf->size(), centre.width(), centre.height());
  std::printf("| workload | threads | batch ms (wall) | batch ms (thread CPU) | per-pixel ms | Mrays/s |\n"
              "|---|---|---|---|---|---|\n");
  const mpr::CameraFrameSampler<mpr::SyntheticAperture, T> chess_full(lf);
  if (g_level_rows) { // the child of --levels: its level's rows only
    for (const T z : {T(1000), T(820)}) {
      const mpr::PlanarSurface<T> p = centre.image_plane(z);
      const std::string label =
          "Chess synthetic aperture z=" + std::to_string(static_cast<int>(z)) + " @" + mpr::detail::simd_level_name();
      measure(label.c_str(), p, mpr::pinhole_glc(centre, p), chess_full, centre.width(), centre.height(), 1, repeats,
              false);
    }
    print_scale_rows(centre, chess_full, repeats, std::string(" @") + mpr::detail::simd_level_name());
    return 0;
  }
  const mpr::CameraFrameSampler<mpr::NearestCamera, T> chess_nearest(lf);
  const mpr::CameraFrameSampler<mpr::CylinderAperture, T> chess_cylinder(lf, mpr::CylinderAperture{10.0});
  // The peer, side by side: the same refocus in 8-bit code space, one thread.
  if (g_only.empty() || std::string("peer: 8-bit code-space shift-add").find(g_only) != std::string::npos) {
    mpr::Image<mpr::Rgb8> peer(centre.width(), centre.height()), ours(centre.width(), centre.height());
    const double peer_ms = peer_code_space_refocus(*lf, centre, T(1000), peer, repeats);
    const mpr::PlanarSurface<T> p = centre.image_plane(T(1000));
    const mpr::Renderer r(p, mpr::pinhole_glc(centre, p), mpr::CameraFrameSampler<mpr::SyntheticAperture, T>(lf));
    r.render(ours.view(), mpr::Region(0, 0, centre.width(), centre.height()), {1});
    double diff = 0;
    for (int y = 0; y < centre.height(); ++y)
      for (int x = 0; x < centre.width(); ++x)
        diff += std::abs(peer(x, y).r - ours(x, y).r) + std::abs(peer(x, y).g - ours(x, y).g) +
                std::abs(peer(x, y).b - ours(x, y).b);
    diff /= 3.0 * centre.width() * centre.height();
    std::printf("| %-34s | 1 | %8.2f | | | %6.1f |\n", "peer: 8-bit code-space shift-add", peer_ms,
                static_cast<double>(centre.width()) * centre.height() / peer_ms * 1e-3);
    std::printf("\n(peer: the public refocusers' arithmetic, averaging sRGB codes instead of linear light; mean "
                "difference from mpr's linear-light image at z=1000: %.2f levels, mostly where the views disagree "
                "-- averaging codes darkens mixed colours)\n\n",
                diff);
    std::printf("| workload | threads | batch ms (wall) | batch ms (thread CPU) | per-pixel ms | Mrays/s |\n"
                "|---|---|---|---|---|---|\n");
  }
  for (int threads : {1, 2})
    for (const T z : {T(1000), T(820)}) {
      const mpr::PlanarSurface<T> p = centre.image_plane(z);
      const mpr::GlcSelector<T> g = mpr::pinhole_glc(centre, p);
      const std::string at = " z=" + std::to_string(static_cast<int>(z));
      measure(("Chess synthetic aperture" + at).c_str(), p, g, chess_full, centre.width(), centre.height(), threads,
              repeats, z == 1000 && threads == 2);
      measure(("Chess nearest" + at).c_str(), p, g, chess_nearest, centre.width(), centre.height(), threads, repeats,
              false);
      measure(("Chess cylinder r=10" + at).c_str(), p, g, chess_cylinder, centre.width(), centre.height(), threads,
              repeats, false);
    }
  // A plane tilted 20 degrees about the vertical axis (the cameras' rows cross it: projective
  // rows, the synthetic aperture's decoded boxes), at the cameras' scale.
  for (int threads : {1, 2}) {
    const mpr::PlanarSurface<T> p = centre.image_plane(T(825)).tilted(T(0), T(20) * T(3.14159265358979) / 180);
    measure("Chess synthetic tilt-y 20 deg z=825", p, mpr::pinhole_glc(centre, p), chess_full, centre.width(),
            centre.height(), threads, repeats, threads == 2);
  }

  std::printf("\nOutput magnified from the cameras' scale (same field of view; 1 thread)\n\n| workload | threads | "
              "batch ms (wall) | batch ms (thread CPU) | per-pixel ms | Mrays/s |\n|---|---|---|---|---|---|\n");
  print_scale_rows(centre, chess_full, repeats, "");

  // Half the cameras' scale (700x400 from 1400x800: the projective rows) and the README's Chess
  // animations at their middle frame (`mpr-render --stanford chess --size 700x400 ...`).
  mpr::Mat3<T> Kh = Kc;
  Kh(0, 0) *= T(0.5);
  Kh(1, 1) *= T(0.5);
  Kh(0, 2) = T(349.5);
  Kh(1, 2) = T(199.5);
  const mpr::PinholeCamera<T> half(Kh, mpr::Mat3<T>::Identity(), mpr::Vec3<T>::Zero(), 700, 400);
  std::printf("\nOutput at other scales (700x400: half the cameras'; 960x540: mpr-view's window) and the README's "
              "Chess animations, per frame (middle "
              "frame of each)\n\n| workload | threads | batch ms (wall) | batch ms (thread CPU) | per-pixel ms | "
              "Mrays/s |\n|---|---|---|---|---|---|\n");
  const mpr::CameraFrameSampler<mpr::CylinderAperture, T> chess_cylinder16(lf, mpr::CylinderAperture{16.0});
  // The same at half scale from frames prefiltered to it (lightfield/frame_prefilter.hpp: 2x2
  // boxes in linear light, done once; mpr-render's --prefilter auto).
  const auto prefilter_start = std::chrono::steady_clock::now();
  const auto lh = std::make_shared<const mpr::CameraFrameSet<T>>(mpr::downsampled(*lf, 2));
  const double prefilter_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - prefilter_start).count();
  const mpr::CameraFrameSampler<mpr::SyntheticAperture, T> half_full(lh);
  const mpr::CameraFrameSampler<mpr::CylinderAperture, T> half_cylinder16(lh, mpr::CylinderAperture{16.0});
  for (int threads : {1, 2}) {
    const mpr::PlanarSurface<T> p = half.image_plane(T(1000));
    measure("Chess 700x400 synthetic z=1000", p, mpr::pinhole_glc(half, p), chess_full, 700, 400, threads, repeats,
            threads == 2);
    // mpr-view's default window on Chess: 960x540, 1.458 camera pixels per output pixel.
    mpr::Mat3<T> Kv = Kc;
    Kv(0, 0) *= T(960) / T(1400);
    Kv(1, 1) *= T(960) / T(1400);
    Kv(0, 2) = T(479.5);
    Kv(1, 2) = T(269.5);
    const mpr::PinholeCamera<T> window(Kv, mpr::Mat3<T>::Identity(), mpr::Vec3<T>::Zero(), 960, 540);
    const mpr::PlanarSurface<T> pw = window.image_plane(T(1000));
    measure("Chess 960x540 synthetic z=1000", pw, mpr::pinhole_glc(window, pw), chess_full, 960, 540, threads, repeats,
            threads == 2);
    const mpr::PlanarSurface<T> tilt = half.image_plane(T(825)).tilted(T(-14) * T(3.14159265358979) / 180, T(0));
    measure("README chess_tilt (-14 deg, z=825)", tilt, mpr::pinhole_glc(half, tilt), chess_full, 700, 400, threads,
            repeats, threads == 2);
    const mpr::PlanarSurface<T> p760 = half.image_plane(T(760));
    measure("README chess_aperture (r=16)", p760, mpr::pinhole_glc(half, p760), chess_cylinder16, 700, 400, threads,
            repeats, threads == 2);
    const mpr::PlanarSurface<T> p825 = half.image_plane(T(825));
    measure("README chess_focus (z=825)", p825, mpr::pinhole_glc(half, p825), chess_full, 700, 400, threads, repeats,
            false);
    measure("Chess 700x400 z=1000, prefiltered", p, mpr::pinhole_glc(half, p), half_full, 700, 400, threads, repeats,
            threads == 2);
    measure("chess_tilt, prefiltered", tilt, mpr::pinhole_glc(half, tilt), half_full, 700, 400, threads, repeats,
            threads == 2);
    measure("chess_aperture, prefiltered", p760, mpr::pinhole_glc(half, p760), half_cylinder16, 700, 400, threads,
            repeats, threads == 2);
    measure("chess_focus, prefiltered", p825, mpr::pinhole_glc(half, p825), half_full, 700, 400, threads, repeats,
            threads == 2);
  }
  std::printf(
      "\n(prefiltered: the frames box-filtered to half their scale once, in %.0f ms on all threads; the rows sample "
      "them, a different filter from bilinear sampling of the full frames)\n",
      prefilter_ms);
  if (g_levels) print_level_rows(argv[0], data, repeats);
  return 0;
}
