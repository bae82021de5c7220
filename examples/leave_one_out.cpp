// leave_one_out: accuracy of the camera-frame sampler on real data. Each held-out view is
// rendered from the remaining views with every interpolation policy, through the perspective
// GLC of the held-out camera (PinholeCamera::image_plane + mpr::pinhole_glc) focused on one plane, and
// compared with the captured image: PSNR over all pixels of the 8-bit sRGB images, SSIM on
// 8-bit luma (7x7 uniform windows, C1 = (0.01 * 255)^2, C2 = (0.03 * 255)^2), and the render
// time (median of 3, all hardware threads). Prints a Markdown table.
//
// The geometry-aware row ("depth proxy") first estimates the depth maps of the remaining views
// from their images alone (mpr::estimate_depth_maps; the held-out image is never read), then
// renders with mpr::DepthProxy (on the temple, constrained to the visual hull of its silhouettes:
// mpr::visual_hull_depth_maps); the estimation time is printed per held-out view, and the
// estimated depth of the held-out camera's nearest remaining view is written as a colour-mapped
// preview (loo_<set>_<view>_depth_map.png).
//
// A second geometry-aware row ("depth_proxy_defaults") uses no per-set setting at all:
// mpr::estimate_scene_depth with its defaults (the sweep range from the calibration and the
// images, an empty backdrop noticed and its silhouettes' visual hull applied) and a DepthProxy
// whose radius is mpr::depth_proxy_radius (twice the camera spacing), the rest at its defaults;
// what it found is printed per held-out view.
//
// The set-ups (held-out views, focal planes, cylinder radii) are in
// benchmarks/leave_one_out_setup.hpp, shared with benchmarks/error_vs_time.cpp.
//
// usage: leave_one_out [DATA_DIR] [OUTPUT_FOLDER] [SETS]   (writes loo_<set>_<view>_<policy>.png;
//        SETS: a comma-separated choice of chess, temple, dino; default all three)
#include "../benchmarks/leave_one_out_setup.hpp"
#include "lightfield_common.hpp"

#include <mpr/io/depth_maps.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/scene_depth.hpp>
#include <mpr/lightfield/visual_hull.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <utility>
#include <vector>

using namespace lf_example;

namespace {

double psnr(const mpr::Image<mpr::Rgb8>& a, const mpr::Image<mpr::Rgb8>& b) {
  double se = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const mpr::Rgb8 p = a(x, y), q = b(x, y);
      se += (p.r - q.r) * (p.r - q.r) + (p.g - q.g) * (p.g - q.g) + (p.b - q.b) * (p.b - q.b);
    }
  const double mse = se / (3.0 * a.width() * a.height());
  return mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : 99.0;
}

double ssim(const mpr::Image<mpr::Rgb8>& a, const mpr::Image<mpr::Rgb8>& b) {
  const int w = a.width(), h = a.height(), r = 3;
  // Integral images of x, y, x^2, y^2, xy (luma, Rec. 601 weights on the 8-bit codes).
  const auto luma = [](mpr::Rgb8 p) { return 0.299 * p.r + 0.587 * p.g + 0.114 * p.b; };
  std::vector<double> I[5];
  for (auto& v : I) v.assign(static_cast<std::size_t>(w + 1) * (h + 1), 0.0);
  const auto at = [&](int k, int x, int y) -> double& { return I[k][static_cast<std::size_t>(y) * (w + 1) + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double p = luma(a(x, y)), q = luma(b(x, y));
      const double v[5] = {p, q, p * p, q * q, p * q};
      for (int k = 0; k < 5; ++k) at(k, x + 1, y + 1) = v[k] + at(k, x, y + 1) + at(k, x + 1, y) - at(k, x, y);
    }
  const double c1 = 6.5025, c2 = 58.5225, n = (2 * r + 1) * (2 * r + 1);
  double sum = 0;
  long count = 0;
  for (int y = r; y < h - r; ++y)
    for (int x = r; x < w - r; ++x) {
      double s[5];
      for (int k = 0; k < 5; ++k)
        s[k] =
            (at(k, x + r + 1, y + r + 1) - at(k, x - r, y + r + 1) - at(k, x + r + 1, y - r) + at(k, x - r, y - r)) / n;
      const double va = s[2] - s[0] * s[0], vb = s[3] - s[1] * s[1], cov = s[4] - s[0] * s[1];
      sum += ((2 * s[0] * s[1] + c1) * (2 * cov + c2)) / ((s[0] * s[0] + s[1] * s[1] + c1) * (va + vb + c2));
      ++count;
    }
  return sum / static_cast<double>(count);
}

struct Row {
  std::string set, view, policy;
  double psnr, ssim, ms;
};

template <class Sampler>
Row evaluate(const std::string& set, const std::string& view, const std::string& policy, const Sampler& sampler,
             const mpr::PinholeCamera<T>& held, T depth, const mpr::Image<mpr::Rgb8>& truth,
             const std::filesystem::path& out) {
  const auto renderer = mpr_loo::held_out_renderer(sampler, held, depth);
  mpr::Image<mpr::Rgb8> image(held.width(), held.height());
  const mpr::Region region(0, 0, held.width(), held.height());
  std::vector<double> times;
  for (int i = 0; i < 3; ++i) times.push_back(seconds([&] { renderer.render(image.view(), region); }));
  std::sort(times.begin(), times.end());
  mpr::write_png(out / ("loo_" + set + "_" + view + "_" + policy + ".png"), image);
  return {set, view, policy, psnr(image, truth), ssim(image, truth), 1e3 * times[1]};
}

template <class Px>
void run_set(const mpr_loo::LooSetup<T>& setup, const mpr::CameraFrameSet<T, Px>& all, const std::filesystem::path& out,
             std::vector<Row>& rows) {
  const std::string& set = setup.name;
  const double radius = setup.cylinder_radius;
  for (const std::size_t k : setup.held_out) {
    const auto others = std::make_shared<const mpr::CameraFrameSet<T, Px>>(all.without(k));
    const mpr::PinholeCamera<T>& held = all.camera(k);
    const T depth = setup.depth_of(held);
    const std::string view = mpr_loo::view_name(all.name(k));
    rows.push_back(evaluate(set, view, "nearest", mpr::CameraFrameSampler<mpr::NearestCamera, T, Px>(others), held,
                            depth, all.image(k), out));
    rows.push_back(
        evaluate(set, view, "cylinder",
                 mpr::CameraFrameSampler<mpr::CylinderAperture, T, Px>(others, mpr::CylinderAperture{radius}), held,
                 depth, all.image(k), out));
    rows.push_back(evaluate(set, view, "synthetic_aperture",
                            mpr::CameraFrameSampler<mpr::SyntheticAperture, T, Px>(others), held, depth, all.image(k),
                            out));
    const mpr::PlaneSweepConfig sweep = mpr_loo::sweep_config(setup, *others);
    std::vector<mpr::Image<float>> maps;
    const double estimate_s = seconds([&] { maps = mpr::estimate_depth_maps(*others, sweep); });
    std::printf("%s %s: depth of the %zu other views estimated in %.2f s (%d planes from %g to %g)\n", set.c_str(),
                view.c_str(), others->size(), estimate_s, sweep.planes, sweep.near, sweep.far);
    if (setup.silhouette) {
      mpr::VisualHullConfig hull_config;
      hull_config.near = sweep.near;
      hull_config.far = sweep.far;
      std::vector<mpr::Image<float>> hull;
      const double hull_s = seconds([&] {
        hull = mpr::visual_hull_depth_maps(*others, mpr::BrightnessSilhouette{*setup.silhouette}, hull_config);
      });
      for (std::size_t i = 0; i < maps.size(); ++i) mpr::constrain_to_visual_hull(maps[i], hull[i]);
      std::printf("%s %s: constrained to the visual hull (silhouettes: brightest channel >= %d) in %.2f s\n",
                  set.c_str(), view.c_str(), *setup.silhouette, hull_s);
    }
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < others->size(); ++i)
      if ((others->camera(i).centre() - held.centre()).norm() <
          (others->camera(nearest).centre() - held.centre()).norm())
        nearest = i;
    mpr::write_depth_preview(out / ("loo_" + set + "_" + view + "_depth_map.png"), maps[nearest].view());
    const auto with_depth = std::make_shared<const mpr::CameraFrameSet<T, Px>>(
        mpr::CameraFrameSet<T, Px>(*others).with_depth(std::move(maps)));
    rows.push_back(evaluate(set, view, "depth_proxy",
                            mpr::CameraFrameSampler<mpr::DepthProxy, T, Px>(with_depth, setup.depth_proxy), held, depth,
                            all.image(k), out));
    // The same with the library's defaults only.
    mpr::SceneDepth found;
    const double auto_s = seconds([&] { found = mpr::estimate_scene_depth(*others); });
    mpr::DepthProxy proxy;
    proxy.radius = mpr::depth_proxy_radius(*others);
    std::printf("%s %s: defaults only: depth in %.2f s, range %g..%g (%s), backdrop %s, proxy radius %g\n", set.c_str(),
                view.c_str(), auto_s, found.range.near, found.range.far,
                found.range.source == mpr::SweepRangeSource::matches ? "sparse matches" : "common frustum",
                found.backdrop
                    ? ("rgb(" + std::to_string(found.backdrop->colour.r) + "," +
                       std::to_string(found.backdrop->colour.g) + "," + std::to_string(found.backdrop->colour.b) +
                       ") within " + std::to_string(found.backdrop->tolerance))
                          .c_str()
                    : "none",
                proxy.radius);
    mpr::write_depth_preview(out / ("loo_" + set + "_" + view + "_depth_map_defaults.png"), found.maps[nearest].view());
    const auto with_found = std::make_shared<const mpr::CameraFrameSet<T, Px>>(
        mpr::CameraFrameSet<T, Px>(*others).with_depth(std::move(found.maps)));
    rows.push_back(evaluate(set, view, "depth_proxy_defaults",
                            mpr::CameraFrameSampler<mpr::DepthProxy, T, Px>(with_found, proxy), held, depth,
                            all.image(k), out));
  }
}

} // namespace

int main(int argc, char** argv) try {
  const std::vector<std::string> args = positional_args(
      argc, argv, {"SETS"}, "  SETS           chess, temple and/or dino, comma-separated (default: all)\n");
  const std::filesystem::path data = data_dir(argc > 1 ? argv[1] : nullptr);
  const std::filesystem::path out = output_dir(argc, argv);
  const std::string sets = args.size() > 2 ? "," + args[2] + "," : ",chess,temple,dino,";
  const auto runs = [&](const char* name) { return sets.find("," + std::string(name) + ",") != std::string::npos; };
  std::vector<Row> rows;
  if (runs("chess")) {
    const auto chess = load_chess(data);
    run_set<mpr::Rgb8>(mpr_loo::chess_setup<T>(), *chess, out, rows);
  }
  if (runs("temple")) {
    const auto temple = mpr::read_par_file<T>(mpr_loo::temple_par_file<T>(data));
    run_set<mpr::Rgb8>(mpr_loo::temple_setup<T>(), temple, out, rows);
  }
  if (runs("dino")) {
    const auto dino = mpr::read_par_file<T>(mpr_loo::dino_par_file<T>(data));
    run_set<mpr::Rgb8>(mpr_loo::dino_setup<T>(), dino, out, rows);
  }
  std::printf("\n| data set | held-out view | policy | PSNR (dB) | SSIM | render (ms) |\n|---|---|---|---|---|---|\n");
  for (const Row& r : rows)
    std::printf("| %s | %s | %s | %.2f | %.3f | %.1f |\n", r.set.c_str(), r.view.c_str(), r.policy.c_str(), r.psnr,
                r.ssim, r.ms);
  // The mean over each set's held-out views, per policy (PSNR: of the per-view values).
  std::vector<std::pair<std::string, std::string>> seen;
  for (const Row& r : rows) {
    if (std::find(seen.begin(), seen.end(), std::pair(r.set, r.policy)) != seen.end()) continue;
    seen.emplace_back(r.set, r.policy);
    double p = 0, q = 0, ms = 0;
    int n = 0;
    for (const Row& o : rows)
      if (o.set == r.set && o.policy == r.policy) {
        p += o.psnr;
        q += o.ssim;
        ms += o.ms;
        ++n;
      }
    std::printf("| %s | mean of %d | %s | %.2f | %.3f | %.1f |\n", r.set.c_str(), n, r.policy.c_str(), p / n, q / n,
                ms / n);
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "leave_one_out: %s\n", e.what());
  return 1;
}
