// mpr-render's views of camera arrays (tools/mpr-render/light_field_views.hpp): the nine gallery
// letters on a light field and on a rasterized array render nine different images whose rays
// stay inside the array; the defaults (synthetic aperture for refocusing, a cylinder of the
// camera spacing for other views); the warnings for rays off the array, for a focal surface
// outside every camera's frame and for a ray-independent interpolation under non-pinhole views.
#include "io/light_field_test_files.hpp"
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <unistd.h>

namespace {

using Image = mpr::Image<mpr::Rgb8>;

using mpr_tools_test::job_of;

/// Renders a job; --print-camera text and warnings are returned through the streams.
Image render(const mpr_cli::Job& job, std::ostream& info, std::ostream& warnings) {
  std::vector<Image> frames;
  mpr_cli::run(
      job, [&](int, int, const Image& image) { frames.push_back(image); }, &info, &warnings);
  REQUIRE(frames.size() == 1);
  return frames[0];
}

/// Pixels that differ between tiles a and b of a 3 x 3 contact sheet.
int tile_difference(const Image& sheet, int a, int b) {
  const int w = sheet.width() / 3, h = sheet.height() / 3;
  int n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      n += sheet((a % 3) * w + x, (a / 3) * h + y) == sheet((b % 3) * w + x, (b / 3) * h + y) ? 0 : 1;
  return n;
}

/// A 5 x 5 Stanford-style folder of smooth random images (positions 5 units apart).
std::filesystem::path stanford_folder() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mpr_lf_views_test_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::mt19937 rng(5);
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 5; ++c) {
      Image img(40, 30);
      const double fx = 0.2 + 0.05 * static_cast<double>(rng() % 7), fy = 0.25 + 0.04 * static_cast<double>(rng() % 5);
      for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
          const auto v = [&](double phase) {
            return static_cast<std::uint8_t>(127.5 + 120 * std::sin(fx * x + fy * y + phase + 0.7 * (r * 5 + c)));
          };
          img(x, y) = mpr::Rgb8{v(0), v(2), v(4)};
        }
      char name[96];
      std::snprintf(name, sizeof name, "out_%02d_%02d_%.1f_%.1f.png", r, c, -5.0 * r, 5.0 * c);
      mpr::write_png(dir / name, img);
    }
  return dir;
}

/// Eight 40 x 30 cameras on a ring of radius 1 in the plane y = 0, each looking at the origin
/// (focal 40 pixels), camera i's image the flat colour (30 i, 255 - 30 i, 90): ring_par.txt.
std::filesystem::path ring_folder() {
  const std::filesystem::path dir = mpr_tools_test::temp_folder("ring");
  std::ofstream par(dir / "ring_par.txt");
  par << "8\n";
  for (int i = 0; i < 8; ++i) {
    const double a = 2 * 3.141592653589793 * i / 8;
    const double c[3] = {std::cos(a), 0, std::sin(a)};
    const double z[3] = {-c[0], 0, -c[2]}, y[3] = {0, 1, 0};
    const double x[3] = {y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0]};
    const std::string name = "ring" + std::to_string(i) + ".png";
    const auto code = static_cast<std::uint8_t>(30 * i);
    mpr::write_png(dir / name, Image(40, 30, mpr::Rgb8{code, static_cast<std::uint8_t>(255 - code), 90}));
    par << name << " 40 0 19.5 0 40 14.5 0 0 1 ";
    for (const double* row : {x, y, z}) par << row[0] << ' ' << row[1] << ' ' << row[2] << ' ';
    for (const double* row : {x, y, z}) par << -(row[0] * c[0] + row[1] * c[1] + row[2] * c[2]) << ' ';
    par << '\n';
  }
  return dir / "ring_par.txt";
}

const std::string nine = "A,B,C,D,E,F,G,H,I";

} // namespace

TEST_CASE("light-field views: the nine gallery letters differ and stay inside the array", "[tools][lf_views]") {
  const std::filesystem::path dir = stanford_folder();
  const mpr_cli::Job job =
      job_of({"--stanford", dir.string(), "--layout", "3x3", "--views", nine, "--size", "40x30", "--print-camera"});
  std::ostringstream info, warnings;
  const Image sheet = render(job, info, warnings);
  for (int a = 0; a < 9; ++a)
    for (int b = a + 1; b < 9; ++b) {
      INFO("views " << static_cast<char>('A' + a) << " and " << static_cast<char>('A' + b));
      CHECK(tile_difference(sheet, a, b) > 40);
    }
  // Every view's coverage line says no ray leaves the array, and no warning says otherwise.
  const std::string text = info.str();
  const std::regex coverage("array coverage: 25 cameras over 20 x 20, spacing 5; .* 0\\.0% off it");
  CHECK(std::distance(std::sregex_iterator(text.begin(), text.end(), coverage), std::sregex_iterator()) == 9);
  CHECK(warnings.str().find("off the array") == std::string::npos);
  CHECK(warnings.str().find("ignores the ray") == std::string::npos);
  // The types the array cannot hold are named where they change.
  CHECK(warnings.str().find("view B (orthographic) is a pinhole on this array") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("light-field views: defaults per use and the warnings", "[tools][lf_views]") {
  const std::filesystem::path dir = stanford_folder();
  {
    // Refocusing keeps the synthetic aperture; other views get a cylinder of the camera spacing.
    const mpr_cli::Job refocus = job_of({"--stanford", dir.string(), "--size", "40x30"});
    const mpr_cli::Loaded<float> l = mpr_cli::load<float>(refocus);
    CHECK(mpr_cli::with_array_defaults(refocus, l).interpolation == mpr_cli::Interpolation::synthetic);
    // One default radius: the synthetic aperture's job carries the spacing too (mpr-view's
    // cylinder key starts from it), the nearest camera's too.
    CHECK(mpr_cli::with_array_defaults(refocus, l).radius.at(0) == Approx(5).epsilon(1e-5));
    CHECK(mpr_cli::with_array_defaults(job_of({"--stanford", dir.string(), "--interp", "nearest"}), l).radius.at(0) ==
          Approx(5).epsilon(1e-5));
    const mpr_cli::Job g = job_of({"--stanford", dir.string(), "--view", "G"});
    const mpr_cli::Job resolved = mpr_cli::with_array_defaults(g, l);
    CHECK(resolved.interpolation == mpr_cli::Interpolation::cylinder);
    CHECK(resolved.radius.at(0) == Approx(5).epsilon(1e-5));
    // --radius alone means the cylinder, with that radius; --interp is kept as given.
    const mpr_cli::Job r = mpr_cli::with_array_defaults(job_of({"--stanford", dir.string(), "--radius", "3"}), l);
    CHECK(r.interpolation == mpr_cli::Interpolation::cylinder);
    CHECK(r.radius.at(0) == 3);
    CHECK(mpr_cli::with_array_defaults(job_of({"--stanford", dir.string(), "--view", "G", "--interp", "nearest"}), l)
              .interpolation == mpr_cli::Interpolation::nearest);
  }
  {
    // A ray-independent interpolation: all views alike, and the user is told so.
    std::ostringstream info, warnings;
    const Image sheet = render(job_of({"--stanford", dir.string(), "--layout", "3x3", "--views", nine, "--size",
                                       "40x30", "--interp", "synthetic"}),
                               info, warnings);
    CHECK(tile_difference(sheet, 0, 6) == 0);
    CHECK(warnings.str().find("--interp synthetic averages every camera") != std::string::npos);
    // Cameras 5 apart seen from 1000 away: 0.29 degrees, no warning about their angle.
    CHECK(warnings.str().find("degrees apart") == std::string::npos);
  }
  {
    // Seen from a focal plane 50 away the cameras are 2 atan(2.5 / 50) = 5.7 degrees apart.
    std::ostringstream info, warnings;
    (void)render(job_of({"--stanford", dir.string(), "--view", "G", "--focal-depth", "50", "--size", "40x30"}), info,
                 warnings);
    CHECK(warnings.str().find("neighbouring cameras are 5.7 degrees apart seen from the focal plane") !=
          std::string::npos);
  }
  {
    // An explicit cross-slit far outside the 20 x 20 array: the share of rays off it.
    std::ostringstream info, warnings;
    (void)render(job_of({"--stanford", dir.string(), "--view", "cross_slit:0,0,-500:0,1,0:0,0,-2000:1,0,0", "--size",
                         "40x30", "--interp", "nearest"}),
                 info, warnings);
    const std::regex off("warning: view cross_slit:[^ ]*: ([0-9]+)% of its rays cross the camera plane off the array");
    std::smatch m;
    const std::string w = warnings.str();
    REQUIRE(std::regex_search(w, m, off));
    CHECK(std::atoi(m[1].str().c_str()) > 50);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("light-field views: rasterized classroom array, nine different letters", "[tools][lf_views]") {
  const mpr_cli::Job job = job_of({"--raster", "4x3", "--layout", "3x3", "--views", nine, "--size", "32x24"});
  const mpr_cli::Loaded<float> l = mpr_cli::load<float>(job);
  const mpr_cli::Job resolved = mpr_cli::with_array_defaults(job, l);
  CHECK(resolved.interpolation == mpr_cli::Interpolation::cylinder);
  CHECK(resolved.radius.at(0) == Approx(2).epsilon(1e-5)); // the 8 m plane over 4 columns
  const mpr_cli::Job refocus = job_of({"--raster", "4x3", "--size", "32x24"});
  CHECK(mpr_cli::with_array_defaults(refocus, l).interpolation == mpr_cli::Interpolation::synthetic);
  CHECK(mpr_cli::with_array_defaults(refocus, l).radius.at(0) == Approx(2).epsilon(1e-5));
  std::ostringstream info, warnings;
  const Image sheet = render(job, info, warnings);
  for (int a = 0; a < 9; ++a)
    for (int b = a + 1; b < 9; ++b) {
      INFO("views " << static_cast<char>('A' + a) << " and " << static_cast<char>('A' + b));
      CHECK(tile_difference(sheet, a, b) > 20);
    }
  // The only warning: cameras 2 m apart (the 8 m plane over 4 columns) seen from the array's
  // focal plane, which the cylinder aperture doubles off that plane.
  const std::string w = warnings.str();
  CHECK(std::count(w.begin(), w.end(), '\n') == 1);
  CHECK(w.find("mpr-render: warning: --raster 4x3: neighbouring cameras are ") == 0);
  CHECK(w.find("--interp depth uses the rasterizer's depth instead") != std::string::npos);
}

TEST_CASE("light-field views: Stanford Chess, nine letters inside the array", "[tools][lf_views][real_data]") {
  const std::filesystem::path root = mpr_test::data_dir();
  const std::filesystem::path chess = root / "stanford" / "chess";
  if (root.empty() || !std::filesystem::is_directory(chess)) {
    // ctest's tools_real_data entry reports "skipped" on this message (tests/CMakeLists.txt).
    WARN("real data not found under '" << root.string() << "' (set MPR_DATA_DIR): skipped");
    return;
  }
  std::ostringstream info, warnings;
  const Image sheet = render(
      job_of({"--stanford", chess.string(), "--layout", "3x3", "--views", nine, "--size", "140x80", "--print-camera"}),
      info, warnings);
  for (int a = 0; a < 9; ++a)
    for (int b = a + 1; b < 9; ++b) {
      INFO("views " << static_cast<char>('A' + a) << " and " << static_cast<char>('A' + b));
      CHECK(tile_difference(sheet, a, b) > 140);
    }
  const std::string text = info.str();
  const std::regex coverage("array coverage: 49 cameras .* 0\\.0% off it");
  CHECK(std::distance(std::sregex_iterator(text.begin(), text.end(), coverage), std::sregex_iterator()) == 9);
  CHECK(warnings.str().find("off the array") == std::string::npos);
  CHECK(warnings.str().find("outside every camera's frame") == std::string::npos);

  // A plane tilted 20 degrees about its vertical axis in the untilted framing: its near side
  // leaves every camera's frame (black), and the warning says how much and what keeps it in.
  for (const bool rectify : {false, true}) {
    std::vector<std::string> args = {"--stanford", chess.string(), "--size", "140x80", "--tilt-y", "20"};
    if (rectify) args.insert(args.end(), {"--rectify", "plane"});
    std::ostringstream tilt_info, tilt_warnings;
    const Image tilted = render(job_of(args), tilt_info, tilt_warnings);
    const std::string w = tilt_warnings.str();
    INFO(w);
    const std::regex unseen("view default: ([0-9]+)% of its focal surface lies outside every camera's frame: those "
                            "pixels have nothing to show \\(black\\); --rectify plane keeps");
    std::smatch m;
    int black = 0;
    for (int y = 0; y < tilted.height(); ++y)
      for (int x = 0; x < tilted.width(); ++x) black += tilted(x, y) == mpr::Rgb8{0, 0, 0} ? 1 : 0;
    const double share = static_cast<double>(black) / (tilted.width() * tilted.height());
    if (rectify) {
      CHECK(w.find("outside every camera's frame") == std::string::npos);
      CHECK(share < 0.001);
    } else {
      REQUIRE(std::regex_search(w, m, unseen));
      const int percent = std::stoi(m[1].str());
      CHECK(percent >= 3);
      CHECK(std::abs(100 * share - percent) <= 2); // the black pixels, as announced
    }
  }
}

TEST_CASE("light-field views: a ring's reference view shows a camera; the synthetic aperture there warns of ghosts",
          "[tools][lf_views]") {
  const std::string par = ring_folder().string();
  const auto is_camera_colour = [](mpr::Rgb8 p) {
    for (int i = 0; i < 8; ++i)
      if (p == mpr::Rgb8{static_cast<std::uint8_t>(30 * i), static_cast<std::uint8_t>(255 - 30 * i), 90}) return true;
    return false;
  };
  {
    // No --interp: the nearest camera, so the reference view is one camera's own colour (the
    // synthetic aperture would average all eight into a colour no camera has), no warning.
    const mpr_cli::Job plain = job_of({"--par", par, "--size", "40x30"});
    const mpr_cli::Loaded<float> l = mpr_cli::load<float>(plain);
    CHECK(mpr_cli::with_array_defaults(plain, l).interpolation == mpr_cli::Interpolation::nearest);
    std::ostringstream info, warnings;
    const Image image = render(plain, info, warnings);
    CHECK(is_camera_colour(image(20, 15)));
    CHECK(warnings.str().find("ghosts") == std::string::npos);
  }
  {
    // --interp synthetic asked for: a blend no camera shows, and one line naming the fix.
    std::ostringstream info, warnings;
    const Image image = render(job_of({"--par", par, "--size", "40x30", "--interp", "synthetic"}), info, warnings);
    CHECK_FALSE(is_camera_colour(image(20, 15)));
    const std::string w = warnings.str();
    INFO(w);
    CHECK(w.find("renders ghosts; use --interp nearest, or --interp depth with --depth-maps estimate\n") !=
          std::string::npos);
  }
}
