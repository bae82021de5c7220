// mpr-render's framing (tools/mpr-render/framing.hpp): a light field's view keeps its aspect
// ratio under any --size (cropped, not stretched) and --zoom magnifies it about its centre.
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

using mpr_tools_test::job_of;

/// A _par.txt light field of three 8x6 cameras (fx = fy = 8, so square pixels) in a fresh folder;
/// every image is a ramp, red 30 x and green 40 y (pixel codes).
std::filesystem::path tiny_par() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mpr_framing_test_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream par(dir / "tiny_par.txt");
  par << "3\n";
  for (int i = 0; i < 3; ++i) {
    const std::string name = "view" + std::to_string(i) + ".png";
    mpr::Image<mpr::Rgb8> image(8, 6);
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 8; ++x)
        image(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(30 * x), static_cast<std::uint8_t>(40 * y), 0};
    mpr::write_png(dir / name, image);
    par << name << " 8 0 3.5 0 8 2.5 0 0 1  1 0 0 0 1 0 0 0 1  " << -0.1 * (i - 1) << " 0 0\n";
  }
  return dir / "tiny_par.txt";
}

template <class T>
mpr::PlanarSurface<T> plane_of(const mpr_cli::Job& job) {
  const mpr_cli::Loaded<T> l = mpr_cli::load<T>(job);
  const auto [w, h] = mpr_cli::view_size(job, l);
  const mpr_cli::FrameParams p = mpr_cli::frame_params(job, l.default_focal_depth, 0);
  return mpr_cli::base_plane(job, l, p, w, h);
}

} // namespace

TEMPLATE_TEST_CASE("mpr-render: a light field's view keeps its aspect ratio under --size", "[tools][framing]", float,
                   double) {
  using T = TestType;
  const std::filesystem::path par = tiny_par();
  const std::vector<std::string> base{"--par", par.string(), "--focal-depth", "2"};
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    if (std::is_same_v<T, double>) args.push_back("--double");
    return job_of(args);
  };
  const mpr::PlanarSurface<T> full = plane_of<T>(with({}));
  // The reference camera's own size: its view at depth 2 is 8/8*2 = 2 wide and 1.5 high.
  CHECK(full.width_vector().norm() == Approx(2));
  CHECK(full.height_vector().norm() == Approx(1.5));
  for (const auto& [size, w, h] : std::vector<std::tuple<std::string, double, double>>{
           {"20x10", 2.0, 1.0}, {"6x12", 0.75, 1.5}, {"16x12", 2.0, 1.5}, {"3x3", 1.5, 1.5}}) {
    INFO("--size " << size);
    const mpr::PlanarSurface<T> plane = plane_of<T>(with({"--size", size}));
    // Square pixels: the plane's width / height equals the output's (before: always 4/3).
    CHECK(plane.width_vector().norm() == Approx(w));
    CHECK(plane.height_vector().norm() == Approx(h));
    CHECK((plane.centre() - full.centre()).norm() == Approx(0).margin(1e-5));
    CHECK(plane.width_vector().normalized().dot(full.width_vector().normalized()) == Approx(1));
  }
  // --zoom 2: the middle half, about the same centre.
  const mpr::PlanarSurface<T> zoomed = plane_of<T>(with({"--zoom", "2"}));
  CHECK(zoomed.width_vector().norm() == Approx(1));
  CHECK(zoomed.height_vector().norm() == Approx(0.75));
  CHECK((zoomed.centre() - full.centre()).norm() == Approx(0).margin(1e-5));
  std::filesystem::remove_all(par.parent_path());
}

TEST_CASE("mpr-render: the progress of loading a light field reaches Job::load_progress", "[tools][loading]") {
  const std::filesystem::path par = tiny_par();
  mpr_cli::Job job = job_of({"--par", par.string(), "--focal-depth", "2"});
  std::vector<std::size_t> loaded;
  job.load_progress = [&](std::size_t done, std::size_t total) {
    CHECK(total == 3);
    loaded.push_back(done);
  };
  CHECK(mpr_cli::render_frames(job).size() == 1);
  CHECK(loaded == std::vector<std::size_t>{1, 2, 3});
  std::filesystem::remove_all(par.parent_path());
}

TEST_CASE("mpr-render: --rectify on the focal plane itself points to --zoom", "[tools][framing]") {
  // The tiny array's reference camera looks along +z; its focal plane at depth 2 is z = 2.
  const std::filesystem::path par = tiny_par();
  try {
    (void)mpr_cli::render_frames(job_of(
        {"--par", par.string(), "--focal-depth", "2", "--rectify", "-0.5,-0.4,2;0.5,-0.4,2;0.5,0.4,2;-0.5,0.4,2"}));
    FAIL("no error");
  } catch (const mpr::argument_error& e) {
    // Before: "corner 0 lies behind the image plane".
    CHECK_THAT(e.what(), Catch::Contains("invalid --rectify: the quadrilateral lies on the image plane itself") &&
                             Catch::Contains("--zoom"));
  }
  // In front of the plane it is a rectification as before.
  CHECK(mpr_cli::render_frames(job_of({"--par", par.string(), "--focal-depth", "2", "--rectify",
                                       "-0.5,-0.4,3;0.5,-0.4,3;0.5,0.4,3;-0.5,0.4,3"}))
            .size() == 1);
  std::filesystem::remove_all(par.parent_path());
}

TEST_CASE("mpr-render: a square in a light field stays square at another --size", "[tools][framing]") {
  // With --interp nearest the view through camera 1 is camera 1's image (a ramp: red 30 per
  // camera pixel to the right, green 40 per pixel down). At --size 16x6 (wider than 8x6) the view
  // is the middle 8 x 3 camera pixels, so one camera pixel covers 2 x 2 output pixels: red grows
  // by 15 per output column and green by 20 per output row. A view stretched to 16x6 (before)
  // showed all 6 rows, green growing by 40 per row.
  const std::filesystem::path par = tiny_par();
  const std::vector<mpr::Image<mpr::Rgb8>> frames = mpr_cli::render_frames(
      job_of({"--par", par.string(), "--focal-depth", "2", "--interp", "nearest", "--size", "16x6"}));
  REQUIRE(frames.size() == 1);
  const mpr::Image<mpr::Rgb8>& img = frames[0];
  REQUIRE(img.width() == 16);
  REQUIRE(img.height() == 6);
  CHECK(img(12, 3).r - img(4, 3).r == Approx(8 * 15).margin(4));
  CHECK(img(8, 4).g - img(8, 1).g == Approx(3 * 20).margin(4));
  std::filesystem::remove_all(par.parent_path());
}
