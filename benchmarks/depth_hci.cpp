// Depth on the 4D Light Field Benchmark (Honauer et al., ACCV 2016) and on a virtual 9x9 array
// of the classroom: the centre view's depth by mpr::estimate_depth with the library's defaults,
// converted to the benchmark's disparity, scored as the benchmark publishes (BadPix 0.07 / 0.03
// / 0.01, MSE x100, Q25; central pixels, 15-pixel border left out) beside the published rows,
// with the time and the error of the most confident 50 % and 90 % of the pixels.
//
//   build/bench/benchmarks/depth_hci [HCI_DIR] [--quick] [--threads=N] [--views=SET] [--out=DIR]
//                                    [--planes=N] [--neighbours=N] [--best=N] [--spatial=X]
//                                    [--range=X] [--truncation=X] [--selection=nearest] [--no-classroom]
//                                    [--median-radius=N] [--median-range=X] [--median-flat=X]
//                                    [--snap-jump=X]
//
// HCI_DIR (default $MPR_DATA_DIR/hci, else the build's data folder /hci) is one scene folder
// (input_CamNNN.png ...) or a folder of them; every scene is estimated, those with
// gt_disp_lowres.pfm are scored. --views= takes all (default), row, column, cross (row and
// column) or star (row, column, diagonals) of the views found. --out=DIR writes, per scene, the
// benchmark's submission layout (DIR/disp_maps/<scene>.pfm, DIR/runtimes/<scene>.txt) and PNGs:
// <scene>_disparity.png (legend: the map's own range), <scene>_error.png (|error| 0..0.2 px,
// 15-pixel border dimmed). --quick (ctest's smoke run): a small classroom array, and of the HCI
// data only the first scene with ground truth from its centre row.

#include "bench_common.hpp"

#include <mpr/io/depth_maps.hpp>
#include <mpr/io/file_write.hpp>
#include <mpr/io/hci_light_field.hpp>
#include <mpr/io/pfm.hpp>
#include <mpr/lightfield/array_disparity.hpp>
#include <mpr/lightfield/depth_estimation.hpp>
#include <mpr/lightfield/disparity_score.hpp>
#include <mpr/scene/classroom.hpp>
#include <mpr/scene/rasterized_sampler.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace {

struct Settings {
  mpr::PlaneSweepConfig sweep; // near and far are set per scene
  std::string views = "all";
  std::filesystem::path out;
  bool quick = false;
};

// Whether grid cell (r, c) of a cams_y x cams_x array belongs to the view set `set`.
bool in_set(const std::string& set, int r, int c, int rows, int columns) {
  const int r0 = rows / 2, c0 = columns / 2;
  const bool row = r == r0, column = c == c0, diagonal = r - r0 == c - c0 || r - r0 == c0 - c;
  if (set == "row") return row;
  if (set == "column") return column;
  if (set == "cross") return row || column;
  if (set == "star") return row || column || diagonal;
  return true;
}

// The frames of `frames` (grid cell of frame i: cell(i)) in `set`; `centre` becomes the centre's
// index in the result.
template <class Cell>
mpr::CameraFrameSet<float> subset(const mpr::CameraFrameSet<float>& frames, std::size_t& centre, const std::string& set,
                                  int rows, int columns, Cell cell) {
  std::vector<mpr::PinholeCamera<float>> cameras;
  std::vector<mpr::Image<mpr::Rgb8>> images;
  std::vector<std::string> names;
  std::size_t new_centre = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto [r, c] = cell(i);
    if (!in_set(set, r, c, rows, columns)) continue;
    if (i == centre) new_centre = cameras.size();
    cameras.push_back(frames.camera(i));
    images.push_back(frames.image(i));
    names.push_back(frames.name(i));
  }
  centre = new_centre;
  return {std::move(cameras), std::move(images), std::move(names)};
}

// |estimate - truth| coloured 0 (light) .. 0.2 px and above (dark), the scoring border dimmed.
mpr::Image<mpr::Rgb8> error_image(const mpr::Image<float>& estimate, const mpr::Image<float>& truth, int border) {
  mpr::Image<float> error(truth.width(), truth.height());
  for (int y = 0; y < truth.height(); ++y)
    for (int x = 0; x < truth.width(); ++x) error(x, y) = std::min(std::abs(estimate(x, y) - truth(x, y)), 0.2f);
  mpr::Image<mpr::Rgb8> image = mpr::depth_preview(error.view(), mpr::DepthRange{0.0f, 0.2f});
  for (int y = 0; y < truth.height(); ++y)
    for (int x = 0; x < truth.width(); ++x)
      if (x < border || y < border || x >= truth.width() - border || y >= truth.height() - border) {
        mpr::Rgb8& p = image(x, y);
        p = mpr::Rgb8{static_cast<std::uint8_t>(p.r / 3), static_cast<std::uint8_t>(p.g / 3),
                      static_cast<std::uint8_t>(p.b / 3)};
      }
  return image;
}

bool header_printed = false;

void print_header() {
  if (header_printed) return;
  header_printed = true;
  std::printf("| scene | views | BadPix0.07 %% | MSE x100 | BadPix0.03 %% | BadPix0.01 %% | Q25 | BadPix0.07 / MSE, "
              "most confident 50 %% | ... 90 %% | time s |\n|---|---|---|---|---|---|---|---|---|---|\n");
}

// Estimates camera `centre` of `frames`, converts to disparity with `disparity`, scores against
// `truth` when given, prints a row and writes the outputs.
void run_scene(const std::string& label, const mpr::CameraFrameSet<float>& frames, std::size_t centre,
               const mpr::ArrayDisparity& disparity, double disparity_min, double disparity_max,
               const mpr::Image<float>* truth, const Settings& settings) {
  mpr::PlaneSweepConfig sweep = settings.sweep;
  sweep.near = disparity.depth(disparity_max);
  sweep.far = disparity.depth(disparity_min);
  mpr::DepthEstimate e;
  const auto start = std::chrono::steady_clock::now();
  e = mpr::estimate_depth(frames, centre, sweep);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const mpr::Image<float> d = mpr::disparity_from_depth(e.depth.view(), disparity);
  print_header();
  if (truth != nullptr) {
    const mpr::DisparityScore s = mpr::score_disparity(d.view(), truth->view());
    const mpr::DisparityScore c50 = mpr::score_most_confident(d.view(), truth->view(), e.confidence.view(), 0.5);
    const mpr::DisparityScore c90 = mpr::score_most_confident(d.view(), truth->view(), e.confidence.view(), 0.9);
    std::printf("| %s | %zu | %.2f | %.3f | %.2f | %.2f | %.3f | %.2f / %.3f | %.2f / %.3f | %.2f |\n", label.c_str(),
                frames.size(), s.badpix_007, s.mse_x100, s.badpix_003, s.badpix_001, s.q25_x100, c50.badpix_007,
                c50.mse_x100, c90.badpix_007, c90.mse_x100, seconds);
  } else {
    std::printf("| %s (no ground truth) | %zu | | | | | | | | %.2f |\n", label.c_str(), frames.size(), seconds);
  }
  std::fflush(stdout);
  if (settings.out.empty()) return;
  std::filesystem::create_directories(settings.out / "disp_maps");
  std::filesystem::create_directories(settings.out / "runtimes");
  mpr::write_pfm(settings.out / "disp_maps" / (label + ".pfm"), d);
  char runtime[32];
  std::snprintf(runtime, sizeof runtime, "%.3f\n", seconds);
  const std::string text = runtime;
  mpr::write_file_atomically(settings.out / "runtimes" / (label + ".txt"),
                             std::vector<unsigned char>(text.begin(), text.end()));
  mpr::write_depth_preview(settings.out / (label + "_disparity.png"), d.view());
  if (truth != nullptr) mpr::write_png(settings.out / (label + "_error.png"), error_image(d, *truth, 15));
  mpr::Image<float> confidence = e.confidence;
  mpr::write_depth_preview(settings.out / (label + "_confidence.png"), confidence.view(), mpr::DepthRange{0.0f, 1.0f});
}

// Every scene folder under `dir` (or `dir` itself), sorted by name.
std::vector<std::filesystem::path> scene_folders(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> scenes;
  if (std::filesystem::exists(dir / "input_Cam040.png")) return {dir};
  if (!std::filesystem::is_directory(dir)) return scenes;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_directory() && std::filesystem::exists(entry.path() / "input_Cam040.png"))
      scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

void hci(const std::filesystem::path& dir, Settings settings) {
  const std::vector<std::filesystem::path> scenes = scene_folders(dir);
  if (scenes.empty()) {
    std::printf("\nHCI: no scene under '%s' (pass HCI_DIR or set MPR_DATA_DIR)\n", dir.string().c_str());
    return;
  }
  bool published = false;
  for (const std::filesystem::path& folder : scenes) {
    const auto lf = mpr::read_hci_light_field<float>(folder);
    if (settings.quick && !lf.ground_truth) continue;
    const std::string name = folder.filename().string();
    std::size_t centre = lf.centre;
    const auto set = subset(lf.frames, centre, settings.quick ? "row" : settings.views, lf.cams_y, lf.cams_x,
                            [&](std::size_t i) { return std::pair<int, int>(lf.row(i), lf.column(i)); });
    if (!header_printed)
      std::printf(
          "\nHCI 4D benchmark under %s: centre view, disparity range of each scene (default -4..4 px), "
          "%d planes, %s neighbours %d, best %d, spatial %.0f, range %.2f, median radius %d range %.2f, snap jump %g, "
          "%d threads\n\n",
          dir.string().c_str(), settings.sweep.planes,
          settings.sweep.selection == mpr::NeighbourSelection::axes ? "row and column" : "nearest",
          settings.sweep.neighbours, settings.sweep.best, settings.sweep.spatial, settings.sweep.range,
          settings.sweep.median.radius, settings.sweep.median.range, settings.sweep.snap.jump, settings.sweep.threads);
    run_scene(name, set, centre, lf.disparity, lf.disparity_min, lf.disparity_max,
              lf.ground_truth ? &*lf.ground_truth : nullptr, settings);
    if (name == "backgammon" && !published) {
      published = true;
      std::printf("| backgammon, published: SPO (2016, classical, ~2,000 s) | 81 | 3.78 | 4.59 | | | | | | |\n"
                  "| backgammon, published: EPINET (2018, learned) | 81 | 3.50 | 3.71 | | | | | | |\n"
                  "| backgammon, published: LFattNet (2020, learned) | 81 | 3.13 | 3.65 | | | | | | |\n");
    }
    if (settings.quick) return;
  }
}

// The classroom as a 9x9 array of parallel rasterized cameras 3.5 cm apart (disparity = f B / Z
// exactly: no sensor shift), the centre camera scored against its z-buffer's disparity over the
// range 0.05..4 px (pixels that see no surface left out).
void classroom(const Settings& settings) {
  const auto scene = mpr::scene::classroom<float>();
  const mpr::Vec3<float> eye(0, 3.1f, 3.0f), target(0, 1.6f, -8);
  const mpr::Vec3<float> forward = (target - eye).normalized();
  const mpr::Vec3<float> right = forward.cross(mpr::Vec3<float>::UnitY()).normalized();
  const mpr::Vec3<float> down = forward.cross(right);
  const auto room = mpr::PlanarSurface<float>::centred(eye, 8.0f * right, 6.0f * down);
  mpr::scene::VirtualArrayConfig<float> config;
  config.columns = 9;
  config.rows = 9;
  config.spacing = 0.035f;
  config.width = settings.quick ? 96 : 512;
  config.height = settings.quick ? 72 : 384;
  config.samples = settings.quick ? 1 : 3;
  config.depth_maps = true;
  const auto array = mpr::scene::rasterize_virtual_array(scene, room, config);
  std::size_t centre = 40;
  const float f = array.frames.camera(centre).K()(0, 0);
  const mpr::ArrayDisparity disparity{static_cast<double>(f) * config.spacing, 0};
  // Pixels that see no surface (depth +inf) have no true disparity: NaN, left out of the scores.
  const mpr::Image<float>& z = array.frames.depth(centre);
  mpr::Image<float> truth(z.width(), z.height());
  for (int y = 0; y < z.height(); ++y)
    for (int x = 0; x < z.width(); ++x)
      truth(x, y) = std::isfinite(z(x, y)) ? static_cast<float>(disparity.disparity(z(x, y))) : std::nanf("");
  const mpr::DepthRange r = mpr::depth_range(truth.view());
  std::printf("\nclassroom, 9x9 rasterized cameras of %dx%d (%d^2 samples a pixel), %.3f m apart, f %.1f px: true "
              "disparity %.2f..%.2f px, swept 0.05..4\n\n",
              config.width, config.height, config.samples, static_cast<double>(config.spacing), static_cast<double>(f),
              static_cast<double>(r.near), static_cast<double>(r.far));
  header_printed = false;
  const auto set = subset(array.frames, centre, settings.views, 9, 9, [](std::size_t i) {
    return std::pair<int, int>(static_cast<int>(i) / 9, static_cast<int>(i) % 9);
  });
  run_scene("classroom-9x9", set, centre, disparity, 0.05, 4.0, &truth, settings);
}

} // namespace

int main(int argc, char** argv) {
  Settings settings;
  settings.quick = mpr_bench::quick_mode(argc, argv);
  settings.sweep.threads = 2;
  std::filesystem::path dir;
  bool with_classroom = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&](const char* key) { return a.substr(std::string(key).size()); };
    if (a.rfind("--planes=", 0) == 0)
      settings.sweep.planes = std::atoi(value("--planes=").c_str());
    else if (a.rfind("--neighbours=", 0) == 0)
      settings.sweep.neighbours = std::atoi(value("--neighbours=").c_str());
    else if (a.rfind("--best=", 0) == 0)
      settings.sweep.best = std::atoi(value("--best=").c_str());
    else if (a.rfind("--truncation=", 0) == 0)
      settings.sweep.truncation = std::atof(value("--truncation=").c_str());
    else if (a.rfind("--spatial=", 0) == 0)
      settings.sweep.spatial = std::atof(value("--spatial=").c_str());
    else if (a.rfind("--range=", 0) == 0)
      settings.sweep.range = std::atof(value("--range=").c_str());
    else if (a.rfind("--median-radius=", 0) == 0)
      settings.sweep.median.radius = std::atoi(value("--median-radius=").c_str());
    else if (a.rfind("--median-range=", 0) == 0)
      settings.sweep.median.range = std::atof(value("--median-range=").c_str());
    else if (a.rfind("--snap-jump=", 0) == 0)
      settings.sweep.snap.jump = std::atof(value("--snap-jump=").c_str());
    else if (a.rfind("--median-flat=", 0) == 0)
      settings.sweep.median.flat = std::atof(value("--median-flat=").c_str());
    else if (a == "--selection=nearest")
      settings.sweep.selection = mpr::NeighbourSelection::nearest;
    else if (a.rfind("--threads=", 0) == 0)
      settings.sweep.threads = std::atoi(value("--threads=").c_str());
    else if (a.rfind("--views=", 0) == 0)
      settings.views = value("--views=");
    else if (a.rfind("--out=", 0) == 0)
      settings.out = value("--out=");
    else if (a == "--no-classroom")
      with_classroom = false;
    else if (a == "--help" || a == "-h") {
      std::printf("usage: depth_hci [HCI_DIR] [--quick] [--threads=N] [--views=all|row|column|cross|star] [--out=DIR]\n"
                  "                 [--planes=N] [--neighbours=N] [--best=N] [--spatial=X] [--range=X] "
                  "[--truncation=X]\n                 [--selection=nearest] [--no-classroom] [--median-radius=N] "
                  "[--median-range=X]\n                 [--median-flat=X] [--snap-jump=X]\n");
      return 0;
    } else if (a.rfind("--", 0) == 0 && a != "--quick") {
      std::fprintf(stderr, "depth_hci: unknown option '%s' (--help lists them)\n", a.c_str());
      return 1;
    } else if (a != "--quick")
      dir = a;
  }
  if (dir.empty()) {
    const char* env = std::getenv("MPR_DATA_DIR");
    dir =
        env != nullptr && *env != 0 ? std::filesystem::path(env) / "hci" : std::filesystem::path("../shared/data/hci");
  }
  std::printf("%s\n", mpr_bench::machine_description().c_str());
  std::printf("plane-sweep kernels: %s; load average at start: %s\n", mpr::detail::simd_level_name(),
              mpr_bench::load_average().c_str());
  try {
    hci(dir, settings);
    if (with_classroom) classroom(settings);
  } catch (const mpr::error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  std::printf("\nload average at the end: %s\n", mpr_bench::load_average().c_str());
  return 0;
}
