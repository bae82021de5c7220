// error_vs_time: every rendering method's error against its run time, so that a user can pick the
// cheapest method that is accurate enough (issue 6).
//
// Synthetic: the built-in classroom scene seen through the nine GLC gallery views
// (mpr::glc::gallery_view on the image plane of examples/gallery.cpp). Ground truth is the converged
// ray-cast image of each view (mpr::SceneSampler<Scene, RayCast>, 256 scrambled Sobol samples per
// pixel and the box filter, i.e. the pixel's area average; 64 with --quick). Methods: the ray cast
// at 1 (pixel centres), 4, 16 and 64 samples per pixel (mpr::Supersample<OwenSobol>, seed 1, so
// its points are not the reference's), and the rasterized virtual camera
// array (mpr::SceneSampler<Scene, Rasterized<...>>, cameras in the gallery's image plane, 100 degree
// field of view, focal depth = median scene depth) at several grid sizes and resolutions, each with
// the nearest camera, the full synthetic aperture and cylinder apertures of 1 and 2 grid spacings.
// Errors are over all pixels of the nine views (8-bit sRGB): RMSE, PSNR and the 99th percentile of
// the per-pixel error (mpr::compare_images). Build time (BVH, or rasterizing the array) and render
// time (per view, median of repeated renders of all nine views) are reported separately.
//
// Real data: leave-one-out on Stanford Chess and the Middlebury temple ring (the set-ups of
// benchmarks/leave_one_out_setup.hpp): each held-out view rendered from the others with every
// policy; errors aggregated over the held-out views (RMSE: root of the mean squared error; p99:
// mean of the views' p99), render time = mean of the views' medians.
//
// Precision: the synthetic workloads and the temple in float and in double, with the difference
// between the float and the double images.
//
// usage: error_vs_time [--quick] [--threads N] [--data DIR] [--png] [OUTPUT_FOLDER]
//   writes OUTPUT_FOLDER/error_vs_time.{md,csv,svg} (default folder: error-vs-time-output)
#include "bench_common.hpp"
#include "leave_one_out_setup.hpp"
#include "report.hpp"

#include <mpr/core/image_metrics.hpp>
#include <mpr/glc.hpp>
#include <mpr/lightfield.hpp>
#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

struct Options {
  bool quick = false;
  bool png = false;
  int threads = 0;
  int repeats = 3;
  std::filesystem::path out = "error-vs-time-output";
  std::filesystem::path data;
};

double seconds_of(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

constexpr std::array<char, 9> kViews = {'A', 'B', 'C', 'D', 'E', 'F', 'G', 'H', 'I'};

/// The gallery of examples/gallery.cpp: one 8 x 6 m image plane, nine GLC views of the classroom.
template <class T>
struct Gallery {
  mpr::PlanarSurface<T> plane;
  std::vector<mpr::GlcSelector<T>> views;
  int width, height;

  explicit Gallery(int w) : plane(make_plane()), width(w), height(w * 3 / 4) {
    for (const char id : kViews) views.push_back(mpr::glc::gallery_view(id, plane, mpr::Vec3<T>(0, T(1.6), -8), T(14)));
  }
  static mpr::PlanarSurface<T> make_plane() {
    const mpr::Vec3<T> centre(0, T(3.1), T(3.0));
    const mpr::Vec3<T> forward = (mpr::Vec3<T>(0, T(1.6), -8) - centre).normalized();
    const mpr::Vec3<T> right = forward.cross(mpr::Vec3<T>::UnitY()).normalized();
    const mpr::Vec3<T> down = forward.cross(right);
    return mpr::PlanarSurface<T>::centred(centre, mpr::Vec3<T>(T(8) * right), mpr::Vec3<T>(T(6) * down));
  }
  [[nodiscard]] mpr::Region region(std::size_t k) const {
    return mpr::Region(static_cast<int>(k % 3) * width, static_cast<int>(k / 3) * height, width, height);
  }
};

/// The nine views rendered with `sampler` (and pixel sampling `sampling`) into one 3 x 3 sheet;
/// returns the median seconds per view of `repeats` renders (default: the options').
template <class T, class Sampler, class Sampling = mpr::PixelCentre>
double render_gallery(const Gallery<T>& g, const Sampler& sampler, const Options& o, mpr::Image<mpr::Rgb8>& sheet,
                      const Sampling& sampling = {}, int repeats = 0) {
  sheet = mpr::Image<mpr::Rgb8>(3 * g.width, 3 * g.height);
  std::vector<mpr::Renderer<mpr::PlanarSurface<T>, mpr::GlcSelector<T>, Sampler, Sampling>> renderers;
  for (const auto& v : g.views) renderers.emplace_back(g.plane, v, sampler, sampling);
  const mpr_bench::Timing t = mpr_bench::time_repeated(repeats > 0 ? repeats : o.repeats, [&] {
    for (std::size_t k = 0; k < renderers.size(); ++k) renderers[k].render(sheet.view(), g.region(k), {o.threads});
  });
  return t.median / static_cast<double>(kViews.size());
}

/// One method's result on the synthetic gallery, kept for the float/double comparison.
struct Measured {
  mpr_bench::ReportRow row;
  mpr::Image<mpr::Rgb8> sheet;
  std::vector<double> view_psnr;
};

void fill_errors(Measured& m, const mpr::Image<mpr::Rgb8>& truth, const Gallery<float>& g) {
  const mpr::ImageError e = mpr::compare_images(m.sheet.view(), truth.view());
  m.row.rmse = e.rmse;
  m.row.psnr = e.psnr;
  m.row.p99 = e.p99;
  for (std::size_t k = 0; k < kViews.size(); ++k) {
    const mpr::Region r = g.region(k);
    mpr::Image<mpr::Rgb8> a(r.width, r.height), b(r.width, r.height);
    for (int y = 0; y < r.height; ++y)
      for (int x = 0; x < r.width; ++x) {
        a(x, y) = m.sheet(r.x + x, r.y + y);
        b(x, y) = truth(r.x + x, r.y + y);
      }
    m.view_psnr.push_back(mpr::compare_images(a.view(), b.view()).psnr);
  }
}

struct ArraySize {
  int columns, rows, width;
};

/// The synthetic workloads in scalar T: ray cast ground truth, then every array and policy.
/// `arrays` and `all_policies` choose the methods; results keyed by method name.
template <class T>
std::map<std::string, Measured> run_synthetic(const Options& o, const std::vector<ArraySize>& arrays, bool all_policies,
                                              std::vector<std::string>& order) {
  using Scene = mpr::scene::Scene<T>;
  const char* scalar = sizeof(T) == 4 ? "float" : "double";
  const Gallery<T> g(o.quick ? 64 : 240);
  const Gallery<float> gf(g.width);
  std::map<std::string, Measured> out;
  const auto scene = std::make_shared<const Scene>(mpr::scene::classroom<T>());

  auto start = std::chrono::steady_clock::now();
  const mpr::SceneSampler<Scene, mpr::RayCast> caster(scene);
  const double bvh_s = seconds_of(start);
  // The converged reference: kReferenceSpp samples per pixel, box filter, rendered once.
  const int reference_spp = o.quick ? 64 : 256;
  Measured truth;
  char reference_name[64];
  std::snprintf(reference_name, sizeof reference_name, "ray cast %d spp (reference)", reference_spp);
  truth.row = {"classroom gallery (9 views)", "ray cast (reference)", reference_name, bvh_s, 0, 0, 0, 0, scalar};
  truth.row.render_s =
      render_gallery(g, caster, o, truth.sheet, mpr::Supersample(mpr::OwenSobol(reference_spp)), /*repeats=*/1);
  fill_errors(truth, truth.sheet, gf);
  const mpr::Image<mpr::Rgb8> reference = truth.sheet;
  std::printf("  [%s] ray cast: build %.1f ms, reference %d spp %.1f ms per view (%zu triangles)\n", scalar,
              1e3 * bvh_s, reference_spp, 1e3 * truth.row.render_s, scene->size());
  out.emplace(truth.row.method, std::move(truth));
  if (sizeof(T) == 4) order.push_back(reference_name);

  // The ray cast at 1 (pixel centres), 4, 16 and 64 samples per pixel against the reference.
  const auto ray_cast = [&](int spp, const auto& sampling) {
    Measured m;
    const std::string name = spp == 1 ? "ray cast 1 spp (pixel centres)" : "ray cast " + std::to_string(spp) + " spp";
    m.row = {"classroom gallery (9 views)", "ray cast", name, bvh_s, 0, 0, 0, 0, scalar};
    m.row.render_s = render_gallery(g, caster, o, m.sheet, sampling);
    fill_errors(m, reference, gf);
    std::printf("  [%s] %-40s build %8.1f ms  render %8.2f ms/view  PSNR %6.2f dB  p99 %5.1f\n", scalar,
                m.row.method.c_str(), 1e3 * m.row.build_s, 1e3 * m.row.render_s, m.row.psnr, m.row.p99);
    if (sizeof(T) == 4) order.push_back(m.row.method);
    out.emplace(m.row.method, std::move(m));
  };
  ray_cast(1, mpr::PixelCentre{});
  for (const int spp : {4, 16, 64}) ray_cast(spp, mpr::Supersample(mpr::OwenSobol(spp, /*seed=*/1)));

  for (const ArraySize& a : arrays) {
    mpr::scene::VirtualArrayConfig<T> config;
    config.columns = a.columns;
    config.rows = a.rows;
    config.width = a.width;
    config.height = a.width * 3 / 4;
    config.raster.threads = o.threads;
    const double spacing = 8.0 / a.columns; // = 6 / rows for the grids used here
    char label[64];
    std::snprintf(label, sizeof label, "%dx%d cams of %dx%d", a.columns, a.rows, config.width, config.height);
    const auto measure = [&]<class I>(const std::string& series, const std::string& name, I interpolation) {
      const auto t0 = std::chrono::steady_clock::now();
      const mpr::SceneSampler<Scene, mpr::Rasterized<I>> sampler(*scene, g.plane, config,
                                                                 mpr::Rasterized<I>{interpolation});
      Measured m;
      m.row = {"classroom gallery (9 views)", series, name + ", " + label, seconds_of(t0), 0, 0, 0, 0, scalar};
      m.row.render_s = render_gallery(g, sampler, o, m.sheet);
      fill_errors(m, reference, gf);
      if (name == "nearest")
        std::printf("  [%s] %s: focal depth %.2f m\n", scalar, label, double(sampler.focal_depth()));
      std::printf("  [%s] %-40s build %8.1f ms  render %8.2f ms/view  PSNR %6.2f dB  p99 %5.1f\n", scalar,
                  m.row.method.c_str(), 1e3 * m.row.build_s, 1e3 * m.row.render_s, m.row.psnr, m.row.p99);
      if (sizeof(T) == 4) order.push_back(m.row.method);
      out.emplace(m.row.method, std::move(m));
    };
    measure("nearest camera", "nearest", mpr::NearestCamera{});
    measure("cylinder aperture", "cylinder r=1 spacing", mpr::CylinderAperture{spacing});
    if (all_policies) {
      measure("cylinder aperture", "cylinder r=2 spacings", mpr::CylinderAperture{2 * spacing});
      measure("synthetic aperture", "full synthetic aperture", mpr::SyntheticAperture{});
    }
  }
  return out;
}

/// Leave-one-out on one real data set, every policy; returns one aggregated row per policy and,
/// for the precision table, the rendered images.
template <class T, class Px>
std::vector<Measured> run_leave_one_out(const Options& o, const std::string& dataset,
                                        const mpr::CameraFrameSet<T, Px>& all, const mpr_loo::LooSetup<T>& setup,
                                        std::size_t views) {
  const char* scalar = sizeof(T) == 4 ? "float" : "double";
  std::vector<Measured> rows(3);
  const char* names[3] = {"nearest", "cylinder", "full synthetic aperture"};
  const char* series[3] = {"nearest camera", "cylinder aperture", "synthetic aperture"};
  for (int p = 0; p < 3; ++p) {
    char method[96];
    if (p == 1)
      std::snprintf(method, sizeof method, "cylinder r=%g", setup.cylinder_radius);
    else
      std::snprintf(method, sizeof method, "%s", names[p]);
    rows[static_cast<std::size_t>(p)].row = {dataset, series[p], method, 0, 0, 0, 0, 0, scalar};
  }
  std::vector<double> mse(3, 0.0);
  const std::size_t n = std::min(views, setup.held_out.size());
  for (std::size_t v = 0; v < n; ++v) {
    const std::size_t k = setup.held_out[v];
    const auto others = std::make_shared<const mpr::CameraFrameSet<T, Px>>(all.without(k));
    const mpr::PinholeCamera<T>& held = all.camera(k);
    const T depth = setup.depth_of(held);
    const auto evaluate = [&]<class I>(int p, I interpolation) {
      const auto t0 = std::chrono::steady_clock::now();
      const mpr::CameraFrameSampler<I, T, Px> sampler(others, interpolation);
      const double build = seconds_of(t0);
      const auto renderer = mpr_loo::held_out_renderer(sampler, held, depth);
      mpr::Image<mpr::Rgb8> image(held.width(), held.height());
      const mpr_bench::Timing t = mpr_bench::time_repeated(o.repeats, [&] {
        renderer.render(image.view(), mpr::Region(0, 0, held.width(), held.height()), {o.threads});
      });
      const mpr::ImageError e = mpr::compare_images(image.view(), all.image(k).view());
      Measured& m = rows[static_cast<std::size_t>(p)];
      m.row.build_s += build / static_cast<double>(n);
      m.row.render_s += t.median / static_cast<double>(n);
      m.row.p99 += e.p99 / static_cast<double>(n);
      mse[static_cast<std::size_t>(p)] += e.rmse * e.rmse / static_cast<double>(n);
      m.view_psnr.push_back(e.psnr);
      if (v == 0) m.sheet = image; // the first held-out view, for the float/double comparison
      std::printf("  [%s] %s %s %-28s render %8.2f ms  PSNR %6.2f dB\n", scalar, dataset.c_str(),
                  mpr_loo::view_name(all.name(k)).c_str(), m.row.method.c_str(), 1e3 * t.median, e.psnr);
    };
    evaluate(0, mpr::NearestCamera{});
    evaluate(1, mpr::CylinderAperture{setup.cylinder_radius});
    evaluate(2, mpr::SyntheticAperture{});
  }
  for (int p = 0; p < 3; ++p) {
    Measured& m = rows[static_cast<std::size_t>(p)];
    m.row.rmse = std::sqrt(mse[static_cast<std::size_t>(p)]);
    m.row.psnr = m.row.rmse > 0 ? 20 * std::log10(255 / m.row.rmse) : 99.0;
  }
  return rows;
}

/// A row of the precision table: float against double on one workload.
std::string precision_row(const std::string& workload, const Measured& f, const Measured& d) {
  const mpr::ImageError diff = mpr::compare_images(f.sheet.view(), d.sheet.view());
  char line[512];
  std::snprintf(line, sizeof line, "| %s | %.1f | %.1f | %.2f | %.2f | %.3f | %.0f | %.2f | %.2f |\n", workload.c_str(),
                1e3 * f.row.build_s, 1e3 * d.row.build_s, 1e3 * f.row.render_s, 1e3 * d.row.render_s, diff.rmse,
                diff.max, f.row.psnr, d.row.psnr);
  return line;
}

std::filesystem::path data_folder(const std::filesystem::path& given) {
  if (!given.empty()) return given;
  if (const char* env = std::getenv("MPR_DATA_DIR"); env != nullptr && *env != 0) return env;
#ifdef MPR_BENCH_DATA_DIR
  return MPR_BENCH_DATA_DIR;
#else
  return "../shared/data";
#endif
}

} // namespace

int main(int argc, char** argv) try {
  std::setvbuf(stdout, nullptr, _IOLBF, 0); // progress lines appear as they are measured
  Options o;
  std::string command = "error_vs_time";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    command += " " + arg;
    if (arg == "--quick") {
      o.quick = true;
    } else if (arg == "--png") {
      o.png = true;
    } else if (arg == "--threads" && i + 1 < argc) {
      o.threads = std::atoi(argv[++i]);
      command += std::string(" ") + argv[i];
    } else if (arg == "--data" && i + 1 < argc) {
      o.data = argv[++i];
      command += std::string(" ") + argv[i];
    } else if (arg == "--help" || arg == "-h") {
      std::puts("usage: error_vs_time [--quick] [--threads N] [--data DIR] [--png] [OUTPUT_FOLDER]\n"
                "  --png: also write each synthetic method's 3x3 sheet of the nine views");
      return 0;
    } else if (!arg.empty() && arg[0] == '-') {
      throw mpr::argument_error(arg, "unknown option (see --help)");
    } else {
      o.out = arg;
    }
  }
  if (o.quick) o.repeats = 1;
  std::filesystem::create_directories(o.out);
  const std::filesystem::path data = data_folder(o.data);
  const std::string machine = mpr_bench::machine_description();
  std::printf("%s\n", machine.c_str());
  const auto total_start = std::chrono::steady_clock::now();

  // Synthetic gallery, float: every method; double: a subset for the precision table.
  const std::vector<ArraySize> arrays =
      o.quick ? std::vector<ArraySize>{{4, 3, 64}} : std::vector<ArraySize>{{4, 3, 160},   {8, 6, 160},   {8, 6, 320},
                                                                            {16, 12, 160}, {16, 12, 320}, {32, 24, 80}};
  const ArraySize precision_array = o.quick ? ArraySize{4, 3, 64} : ArraySize{8, 6, 320};
  std::printf("synthetic gallery (float):\n");
  std::vector<std::string> order, unused;
  std::map<std::string, Measured> fl = run_synthetic<float>(o, arrays, true, order);
  std::printf("synthetic gallery (double):\n");
  std::map<std::string, Measured> db = run_synthetic<double>(o, {precision_array}, false, unused);

  std::vector<mpr_bench::ReportRow> rows;
  for (const std::string& name : order) rows.push_back(fl.at(name).row);
  if (o.png)
    for (std::size_t i = 0; i < order.size(); ++i)
      mpr::write_png(o.out / ("sheet_" + std::to_string(i) + ".png"), fl.at(order[i]).sheet);

  std::string precision = "| workload | build float (ms) | build double (ms) | render float (ms/view) | render double "
                          "(ms/view) | RMSE float vs double | max float vs double | PSNR float (dB) | PSNR double "
                          "(dB) |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& [name, d] : db) precision += precision_row("classroom gallery, " + name, fl.at(name), d);

  // Per-view PSNR of the synthetic methods.
  std::string per_view = "| method |";
  for (const char id : kViews) per_view += std::string(" ") + id + " |";
  per_view += "\n|---|";
  for (std::size_t k = 0; k < kViews.size(); ++k) per_view += "---:|";
  per_view += "\n";
  for (const std::string& name : order) {
    if (name.find("(reference)") != std::string::npos) continue;
    per_view += "| " + name + " |";
    for (const double p : fl.at(name).view_psnr) per_view += " " + mpr_bench::format_number(p, "%.1f") + " |";
    per_view += "\n";
  }

  // Real data.
  std::string real_note;
  const std::filesystem::path temple_par = mpr_loo::temple_par_file<float>(data);
  if (std::filesystem::exists(temple_par)) {
    std::printf("temple leave-one-out:\n");
    const mpr::CameraFrameSet<float> temple = mpr::read_par_file<float>(temple_par);
    const std::size_t views = o.quick ? 1 : 3;
    const std::string name = "temple ring, leave-one-out (" + std::to_string(views) + " views)";
    const std::vector<Measured> tf = run_leave_one_out(o, name, temple, mpr_loo::temple_setup<float>(), views);
    const std::vector<Measured> td =
        run_leave_one_out(o, name, temple.cast<double>(), mpr_loo::temple_setup<double>(), views);
    for (std::size_t p = 0; p < tf.size(); ++p) {
      rows.push_back(tf[p].row);
      precision +=
          precision_row("temple (times: mean of the views; difference: first view), " + tf[p].row.method, tf[p], td[p]);
    }
  } else {
    real_note += "temple data not found under " + data.string() + ": skipped\n";
  }
  const std::filesystem::path chess_dir = data / "stanford" / "chess";
  if (o.quick) {
    real_note += "--quick: Stanford Chess skipped\n";
  } else if (std::filesystem::exists(chess_dir)) {
    std::printf("chess leave-one-out:\n");
    const auto t0 = std::chrono::steady_clock::now();
    const mpr::CameraFrameSet<float> chess = mpr::read_stanford_light_field<float>(chess_dir);
    std::printf("  loaded %zu views in %.1f s\n", chess.size(), seconds_of(t0));
    const std::vector<Measured> cf =
        run_leave_one_out(o, "Stanford Chess, leave-one-out (3 views)", chess, mpr_loo::chess_setup<float>(), 3);
    for (const Measured& m : cf) rows.push_back(m.row);
  } else {
    real_note += "Stanford Chess not found under " + data.string() + ": skipped\n";
  }
  if (!real_note.empty()) std::printf("%s", real_note.c_str());

  const std::string table = mpr_bench::markdown_table(rows);
  std::ofstream md(o.out / "error_vs_time.md");
  md << "Command: `" << command << "`\n\n```\n"
     << machine << "\n```\n\n"
     << table << "\nPSNR per gallery view (dB):\n\n"
     << per_view << "\nFloat against double:\n\n"
     << precision;
  if (!real_note.empty()) md << "\n" << real_note;
  mpr_bench::write_csv((o.out / "error_vs_time.csv").string(), rows);
  mpr_bench::write_svg((o.out / "error_vs_time.svg").string(), rows,
                       "mpr: PSNR against render time per view (Pareto front ringed)");
  std::printf("\n%s\nPSNR per gallery view (dB):\n\n%s\nFloat against double:\n\n%s\ntotal %.1f s; wrote "
              "%s/error_vs_time.{md,csv,svg}\n",
              table.c_str(), per_view.c_str(), precision.c_str(), seconds_of(total_start), o.out.string().c_str());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "error_vs_time: %s\n", e.what());
  return 1;
}
