// mpr-render's depth of a view: --write-depth, --focus-at and --all-in-focus, on a tiny light
// field whose depth maps show a fronto-parallel plane at a known depth and on the classroom
// (whose back wall lies at a known distance), and their command-line errors.
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <mpr/io/depth_maps.hpp>
#include <mpr/io/par_file.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using mpr_tools_test::job_of;
using mpr_tools_test::plane_light_field;
using mpr_tools_test::temp_folder;
using Image = mpr::Image<mpr::Rgb8>;

std::string error_of(const std::vector<std::string>& args) {
  try {
    (void)mpr_cli::render_frames(job_of(args));
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// The classroom seen square-on: the image plane z = 3 (8 x 6 m, centred at y = 1.6) faces the
// back wall z = -14 from a pinhole at z = 10; 10 pixels per metre at --size 80x60.
const std::vector<std::string> square_on{"--plane-centre", "0,1.6,3", "--look-at", "0,1.6,-8",
                                         "--plane-size",   "8,6",     "--view",    "pinhole:0,1.6,10",
                                         "--size",         "80x60"};

std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

} // namespace

TEST_CASE("mpr-render --focus-at on a light field: the depth of the plane its depth maps show", "[tools]") {
  const std::filesystem::path dir = plane_light_field("focus_at", 2.3f);
  const std::vector<std::string> base{"--par",         (dir / "tiny_par.txt").string(),
                                      "--depth-maps",  dir.string(),
                                      "--focal-depth", "1.5"}; // the plane the search starts from
  // The reference view, and the cross-slit gallery view (whose rays move with the focal plane,
  // so the plane is moved until the pixel's ray meets the surface on it).
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--focus-at", "1,4"}, std::vector<std::string>{"--focus-at", "6,2", "--view", "G"},
        std::vector<std::string>{"--focus-at", "3,3", "--interp", "depth"}}) {
    const mpr_cli::Job job = job_of(base + extra);
    const mpr_cli::Loaded<float> l = mpr_cli::load<float>(job);
    std::ostringstream info;
    const mpr_cli::Job focused = mpr_cli::with_focus_at(mpr_cli::with_array_defaults(job, l), l, &info);
    INFO(info.str());
    REQUIRE(focused.focal_depth.has_value());
    CHECK(focused.focal_depth->at(0) == Approx(2.3).epsilon(1e-4));
    CHECK_THAT(info.str(), Catch::StartsWith("focus at pixel (") && Catch::Contains("depth 2.3"));
    // The whole run takes the focus too: the same image as --focal-depth 2.3 for the focal-plane
    // interpolations. (Under --interp depth the focal depth moves only the rays' origins along
    // their lines; the camera blend has a step where a point leaves a camera's 8x6 image, which a
    // rounding of the origin may cross, so its images are not compared.)
    if (extra.back() == "depth") continue;
    std::vector<std::string> plain{"--par", (dir / "tiny_par.txt").string(), "--focal-depth", "2.3"};
    for (std::size_t i = 2; i < extra.size(); ++i) plain.push_back(extra[i]);
    const Image a = mpr_cli::render_frames(job_of(base + extra)).at(0);
    const Image b = mpr_cli::render_frames(job_of(plain)).at(0);
    // The focus found is 2.3 to float rounding: codes may differ by one where a pixel rounds
    // the other way.
    int worst = 0;
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x)
        worst = std::max(
            {worst, std::abs(a(x, y).r - b(x, y).r), std::abs(a(x, y).g - b(x, y).g), std::abs(a(x, y).b - b(x, y).b)});
    CHECK(worst <= 1);
  }
  // Errors, one line each naming --focus-at.
  CHECK_THAT(error_of(base + std::vector<std::string>{"--focus-at", "8,0"}),
             Catch::Contains("--focus-at") && Catch::Contains("outside the 8x6 output"));
  CHECK_THAT(error_of({"--par", (dir / "tiny_par.txt").string(), "--focal-depth", "2", "--focus-at", "1,1"}),
             Catch::Contains("--focus-at") && Catch::Contains("--depth-maps"));
  CHECK_THAT(error_of(base + std::vector<std::string>{"--focus-at", "1"}), Catch::Contains("is not X,Y"));
  CHECK_THAT(error_of(base + std::vector<std::string>{"--focus-at", "1,1", "--focal-depth", "1:2", "--frames", "2"}),
             Catch::Contains("--focus-at") && Catch::Contains("one number"));
  CHECK_THAT(error_of(base + std::vector<std::string>{"--focus-at", "1,1", "--all-in-focus"}),
             Catch::Contains("--focus-at") && Catch::Contains("--all-in-focus"));
  // Nothing seen: every map says +inf.
  const std::filesystem::path empty = plane_light_field("focus_at_empty", std::numeric_limits<float>::infinity());
  CHECK_THAT(error_of({"--par", (empty / "tiny_par.txt").string(), "--depth-maps", empty.string(), "--focal-depth", "2",
                       "--focus-at", "2,2"}),
             Catch::Contains("--focus-at: nothing is seen at pixel (2, 2)"));
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(empty);
}

TEST_CASE("mpr-render --focus-at on the classroom: --raster and --aperture focus on the back wall", "[tools]") {
  // Pixel (51, 22) shows the back wall at (3.9, 4.2, -14): 17 m in front of the plane z = 3.
  std::ostringstream info;
  const mpr_cli::Job raster = job_of(square_on + std::vector<std::string>{"--raster", "3x2", "--focus-at", "51,22"});
  const mpr_cli::Loaded<float> l = mpr_cli::load<float>(raster);
  const mpr_cli::Job focused = mpr_cli::with_focus_at(mpr_cli::with_array_defaults(raster, l), l, &info);
  REQUIRE(focused.focal_depth.has_value());
  CHECK(focused.focal_depth->at(0) == Approx(17).epsilon(1e-4));
  CHECK_THAT(info.str(), Catch::Contains("depth 17 (--focal-depth 17)"));
  const mpr_cli::Job lens =
      job_of(square_on + std::vector<std::string>{"--spp", "4", "--aperture", "disc:0.1", "--focus-at", "51,22"});
  info.str("");
  const mpr_cli::Job lens_focused = mpr_cli::with_focus_at(lens, mpr_cli::load<float>(lens), &info);
  REQUIRE(lens_focused.aperture->focus.size() == 1);
  CHECK(lens_focused.aperture->focus[0] == Approx(17).epsilon(1e-4));
  CHECK_THAT(info.str(), Catch::Contains("(--focus 17)"));
  // A pinhole view of the ray-cast scene has no focus to set; the sky shows nothing.
  CHECK_THAT(error_of(square_on + std::vector<std::string>{"--focus-at", "51,22"}),
             Catch::Contains("--focus-at: applies to light fields, --raster and --aperture"));
  CHECK_THAT(error_of(square_on + std::vector<std::string>{"--raster", "2x2", "--focus-at", "79,0"}),
             Catch::Contains("nothing is seen at pixel (79, 0)"));
}

TEST_CASE("mpr-render --write-depth: a PFM and its preview for any view", "[tools]") {
  const std::filesystem::path dir = plane_light_field("write_depth", 2.3f);
  const std::filesystem::path out = temp_folder("write_depth_out");
  // A light field: the depth along the reference camera's axis, 2.3 wherever a ray meets the
  // plane inside the cameras' views, in every tile of a layout (reference view and cross-slit).
  const std::filesystem::path pfm = out / "lf.pfm";
  std::ostringstream info;
  (void)mpr_cli::render_frames(
      job_of({"--par", (dir / "tiny_par.txt").string(), "--depth-maps", dir.string(), "--focal-depth", "2", "--layout",
              "2x1", "--views", "default,G", "--write-depth", pfm.string()}),
      &info);
  CHECK_THAT(info.str(), Catch::Contains("wrote " + pfm.string()) && Catch::Contains("lf_preview.png"));
  const mpr::Image<float> depth = mpr::read_pfm(pfm);
  REQUIRE(depth.width() == 16);
  REQUIRE(depth.height() == 6);
  int found = 0;
  double worst = 0;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 16; ++x)
      if (std::isfinite(depth(x, y))) {
        ++found;
        worst = std::max(worst, std::abs(static_cast<double>(depth(x, y)) - 2.3));
      }
  CHECK(found >= 80); // the reference view sees the plane everywhere
  CHECK(worst < 1e-3);
  const Image preview = mpr::read_rgb8(out / "lf_preview.png");
  CHECK(preview.width() == 16);
  CHECK(preview.height() > 6); // the legend below the map

  // The classroom: the ray cast's depth in front of the image plane, 17 on the back wall.
  const std::filesystem::path scene = out / "scene.pfm";
  (void)mpr_cli::render_frames(job_of(square_on + std::vector<std::string>{"--write-depth", scene.string()}));
  const mpr::Image<float> scene_depth = mpr::read_pfm(scene);
  REQUIRE(scene_depth.width() == 80);
  CHECK(scene_depth(51, 22) == Approx(17).epsilon(1e-4));
  CHECK(std::isinf(scene_depth(79, 0))); // the open ceiling

  // Errors: a name that is not .pfm, an animation, a light field without depth maps.
  CHECK_THAT(error_of({"--write-depth", (out / "d.png").string()}),
             Catch::Contains("--write-depth") && Catch::Contains("writes a .pfm file"));
  CHECK_THAT(error_of({"--write-depth", (out / "d.pfm").string(), "--tilt-x", "0:5", "--frames", "2"}),
             Catch::Contains("not of an animation"));
  CHECK_THAT(error_of({"--par", (dir / "tiny_par.txt").string(), "--focal-depth", "2", "--write-depth",
                       (out / "d.pfm").string()}),
             Catch::Contains("--write-depth") && Catch::Contains("--depth-maps"));
  CHECK_FALSE(std::filesystem::exists(out / "d.pfm"));
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(out);
}

TEST_CASE("mpr-render --all-in-focus is the depth interpolation", "[tools]") {
  const std::filesystem::path dir = plane_light_field("all_in_focus", 2.3f);
  const std::vector<std::string> base{
      "--par", (dir / "tiny_par.txt").string(), "--depth-maps", dir.string(), "--focal-depth", "1.5"};
  const mpr_cli::Job job = job_of(base + std::vector<std::string>{"--all-in-focus"});
  CHECK(job.interpolation == mpr_cli::Interpolation::depth);
  const Image a = mpr_cli::render_frames(job).at(0);
  const Image b = mpr_cli::render_frames(job_of(base + std::vector<std::string>{"--interp", "depth"})).at(0);
  CHECK(std::memcmp(a.data(), b.data(), sizeof(mpr::Rgb8) * 48) == 0);
  CHECK(job_of({"--raster", "2x2", "--all-in-focus"}).interpolation == mpr_cli::Interpolation::depth);
  CHECK_THAT(error_of({"--all-in-focus"}), Catch::Contains("--all-in-focus: applies to light fields and --raster"));
  CHECK_THAT(error_of({"--raster", "2x2", "--all-in-focus", "--interp", "cylinder"}),
             Catch::Contains("drop --interp cylinder"));
  CHECK_THAT(error_of({"--par", (dir / "tiny_par.txt").string(), "--focal-depth", "2", "--all-in-focus"}),
             Catch::Contains("--all-in-focus: needs --depth-maps"));
  // Depth maps that nothing reads are refused rather than ignored.
  CHECK_THAT(error_of({"--par", (dir / "tiny_par.txt").string(), "--focal-depth", "2", "--depth-maps", dir.string()}),
             Catch::Contains("--depth-maps") && Catch::Contains("give one of them"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("mpr-render --depth-maps estimate: the depth of a textured plane estimated from the images", "[tools]") {
  const std::filesystem::path dir = mpr_tools_test::textured_plane_light_field("estimate", 2.3);
  const std::filesystem::path saved = temp_folder("estimate_saved");
  const std::vector<std::string> args{"--par",
                                      (dir / "tiny_par.txt").string(),
                                      "--depth-maps",
                                      "estimate:1:4:96",
                                      "--save-depth-maps",
                                      saved.string(),
                                      "--focal-depth",
                                      "1.5",
                                      "--focus-at",
                                      "24,18"};
  const mpr_cli::Job job = job_of(args);
  REQUIRE(job.depth_estimate.has_value());
  CHECK(job.depth_estimate->near == 1);
  CHECK(job.depth_estimate->far == 4);
  CHECK(job.depth_estimate->planes == 96);
  CHECK_FALSE(job.depth_maps.has_value());
  std::ostringstream info;
  (void)mpr_cli::render_frames(job, &info);
  INFO(info.str());
  CHECK_THAT(info.str(), Catch::Contains("estimated the depth maps of 3 cameras in") &&
                             Catch::Contains("96 planes from 1 to 4") && Catch::Contains("wrote 3 depth maps to"));
  // The focus found from the estimated maps lies on the plane (within 3%), and the saved maps
  // read back as --depth-maps FOLDER give the same focus.
  const auto focus_of = [](const std::string& text) {
    const std::size_t at = text.find("depth ");
    REQUIRE(at != std::string::npos);
    return std::stod(text.substr(at + 6));
  };
  const double estimated = focus_of(info.str().substr(info.str().find("focus at pixel")));
  CHECK(estimated == Approx(2.3).epsilon(0.03));
  std::vector<std::string> again = args;
  again[3] = saved.string();
  again.erase(again.begin() + 4, again.begin() + 6); // no --save-depth-maps
  std::ostringstream info2;
  (void)mpr_cli::render_frames(job_of(again), &info2);
  CHECK(focus_of(info2.str().substr(info2.str().find("focus at pixel"))) == Approx(estimated).epsilon(1e-6));

  // Bad forms name --depth-maps (or --save-depth-maps) and say what is expected.
  const std::string par = (dir / "tiny_par.txt").string();
  // `estimate` alone takes the range from the calibration (mpr::sweep_range): near = far = 0.
  const mpr_cli::Job plain = job_of({"--par", par, "--depth-maps", "estimate", "--all-in-focus"});
  REQUIRE(plain.depth_estimate.has_value());
  CHECK(plain.depth_estimate->near == 0);
  CHECK(plain.depth_estimate->far == 0);
  for (const char* bad : {"estimate:", "estimate:1", "estimate:3:1", "estimate:0:2", "estimate:1:2:1", "estimate:1:x",
                          "estimate:1:2:64:9"}) {
    INFO(bad);
    CHECK_THROWS_WITH(job_of({"--par", par, "--depth-maps", bad, "--all-in-focus"}), Catch::Contains("--depth-maps"));
  }
  CHECK_THROWS_WITH(job_of({"--par", par, "--depth-maps", dir.string(), "--all-in-focus", "--save-depth-maps", "x"}),
                    Catch::Contains("--save-depth-maps") && Catch::Contains("estimate"));
}

TEST_CASE("mpr-render --sweep sets the plane sweep of estimated depth maps, naming a bad key", "[tools]") {
  const std::filesystem::path dir = mpr_tools_test::textured_plane_light_field("sweep", 2.3);
  const std::filesystem::path saved = temp_folder("sweep_saved");
  const std::string par = (dir / "tiny_par.txt").string();
  const std::vector<std::string> base{"--par",         par,   "--depth-maps", "estimate:1:4:48",
                                      "--focal-depth", "1.5", "--focus-at",   "24,18"};
  std::vector<std::string> args = base;
  args.insert(args.end(), {"--sweep", "neighbours=2,best=1,truncation=0.2,spatial=0,range=0.5", "--save-depth-maps",
                           saved.string()});
  const mpr_cli::Job job = job_of(args);
  REQUIRE(job.depth_estimate.has_value());
  CHECK(job.depth_estimate->planes == 48);
  CHECK(job.depth_estimate->neighbours == 2);
  CHECK(job.depth_estimate->best == 1);
  CHECK(job.depth_estimate->truncation == 0.2);
  CHECK(job.depth_estimate->spatial == 0);
  CHECK(job.depth_estimate->range == 0.5);
  std::ostringstream info;
  (void)mpr_cli::render_frames(job, &info);
  INFO(info.str());
  CHECK_THAT(info.str(),
             Catch::Contains("48 planes from 1 to 4, as given; neighbours 2, best 1, truncation 0.2, spatial 0, "
                             "range 0.5"));
  // The settings reach the sweep: the saved maps are the library's estimate with them (a pixel
  // may differ where the two runs shared a camera's rows among threads differently), and
  // differ from the defaults' (no aggregation, one cost kept).
  const mpr::CameraFrameSet<float> frames = mpr::read_par_file<float>(par);
  const std::vector<mpr::Image<float>> maps = mpr::read_depth_maps(saved, frames);
  const auto share_equal = [&](const mpr::PlaneSweepConfig& c) {
    const std::vector<mpr::Image<float>> expected = mpr::estimate_depth_maps(frames, c);
    long equal = 0, count = 0;
    for (std::size_t i = 0; i < maps.size(); ++i)
      for (int y = 0; y < maps[i].height(); ++y)
        for (int x = 0; x < maps[i].width(); ++x, ++count) equal += maps[i](x, y) == expected[i](x, y);
    return static_cast<double>(equal) / static_cast<double>(count);
  };
  CHECK(share_equal(*job.depth_estimate) >= 0.99);
  mpr::PlaneSweepConfig defaults = *job_of(base).depth_estimate;
  CHECK(defaults.neighbours == mpr::PlaneSweepConfig{}.neighbours);
  CHECK(defaults.best == mpr::PlaneSweepConfig{}.best);
  CHECK(defaults.spatial == mpr::PlaneSweepConfig{}.spatial);
  CHECK(share_equal(defaults) < 0.5);

  // Bad items: one line naming --sweep and the key (or what is expected).
  const std::pair<const char*, const char*> bad[] = {{"best", "KEY=VALUE"},
                                                     {"best=", "KEY=VALUE"},
                                                     {"depth=3", "unknown key 'depth'"},
                                                     {"best=17", "--sweep best"},
                                                     {"neighbours=1", "8 (the default) exceeds neighbours (1)"},
                                                     {"best=0", "--sweep best"},
                                                     {"best=2,best=1", "--sweep best: given twice"},
                                                     {"neighbours=33", "--sweep neighbours"},
                                                     {"best=x", "--sweep best"},
                                                     {"truncation=0", "--sweep truncation"},
                                                     {"spatial=-1", "--sweep spatial"},
                                                     {"range=nan", "--sweep range"},
                                                     {"range=0", "--sweep range"},
                                                     {"best=2,,spatial=3", "KEY=VALUE"},
                                                     {"selection=diagonal", "'diagonal' is not axes or nearest"}};
  for (const auto& [item, expected] : bad) {
    INFO(item);
    std::vector<std::string> b = base;
    b.insert(b.end(), {"--sweep", item});
    CHECK_THROWS_WITH(job_of(b), Catch::Contains("--sweep") && Catch::Contains(expected));
  }
  // Extreme but meaningful values are accepted (the sweep keeps them finite: tested with it).
  std::vector<std::string> extreme = base;
  extreme.insert(extreme.end(), {"--sweep", "truncation=1e39,range=1e-320,spatial=1e300"});
  CHECK_NOTHROW(job_of(extreme));
  // The neighbour selection: the image axes by default, the nearest cameras on request.
  CHECK(defaults.selection == mpr::NeighbourSelection::axes);
  std::vector<std::string> nearest = base;
  nearest.insert(nearest.end(), {"--sweep", "selection=nearest,neighbours=4,best=2"});
  CHECK(job_of(nearest).depth_estimate->selection == mpr::NeighbourSelection::nearest);
  // Only with an estimate.
  CHECK_THROWS_WITH(job_of({"--par", par, "--depth-maps", dir.string(), "--all-in-focus", "--sweep", "best=1"}),
                    Catch::Contains("--sweep") && Catch::Contains("estimate"));
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(saved);
}

TEST_CASE("mpr-render --proxy sets the depth proxy but its radius, naming a bad key", "[tools]") {
  const std::vector<std::string> base = square_on + std::vector<std::string>{"--raster", "4x3", "--interp", "depth"};
  const mpr_cli::Job job =
      job_of(base + std::vector<std::string>{"--proxy", "k=1,tolerance=0.02,visibility_tolerance=0.05,"
                                                        "march_cameras=3,whole_line=0"});
  const mpr::DepthProxy p = job.depth_proxy(1.5);
  CHECK(p.radius == 1.5);
  CHECK(p.k == 1);
  CHECK(p.tolerance == 0.02);
  CHECK(p.visibility_tolerance == 0.05);
  CHECK(p.march_cameras == 3);
  CHECK_FALSE(p.whole_line);
  const mpr::DepthProxy d = job_of(base).depth_proxy(1.5), library{1.5};
  CHECK((d.k == library.k && d.tolerance == library.tolerance &&
         d.visibility_tolerance == library.visibility_tolerance && d.march_cameras == library.march_cameras &&
         d.whole_line == library.whole_line));
  // The settings reach the render: one camera blended instead of four changes the picture.
  const Image one = mpr_cli::render_frames(job_of(base + std::vector<std::string>{"--proxy", "k=1"})).at(0);
  const Image four = mpr_cli::render_frames(job_of(base)).at(0);
  REQUIRE(one.width() == four.width());
  int differ = 0;
  for (int y = 0; y < one.height(); ++y)
    for (int x = 0; x < one.width(); ++x) differ += std::memcmp(&one(x, y), &four(x, y), sizeof(mpr::Rgb8)) != 0;
  CHECK(differ > one.width() * one.height() / 10);
  // Bad items: one line naming --proxy and the key (or what is expected).
  const std::pair<const char*, const char*> bad[] = {{"k", "KEY=VALUE"},
                                                     {"radius=2", "unknown key 'radius'"},
                                                     {"k=0", "--proxy k"},
                                                     {"k=64", "--proxy k"},
                                                     {"k=2,k=3", "--proxy k: given twice"},
                                                     {"tolerance=1", "--proxy tolerance"},
                                                     {"tolerance=nan", "--proxy tolerance"},
                                                     {"visibility_tolerance=0", "--proxy visibility_tolerance"},
                                                     {"march_cameras=0", "--proxy march_cameras"},
                                                     {"whole_line=2", "--proxy whole_line"},
                                                     {"k=2,,tolerance=0.02", "KEY=VALUE"}};
  for (const auto& [item, expected] : bad) {
    INFO(item);
    CHECK_THROWS_WITH(job_of(base + std::vector<std::string>{"--proxy", item}),
                      Catch::Contains("--proxy") && Catch::Contains(expected));
  }
  // Only where a depth proxy runs.
  CHECK_THAT(
      error_of(square_on + std::vector<std::string>{"--raster", "4x3", "--interp", "cylinder", "--proxy", "k=2"}),
      Catch::Contains("--proxy") && Catch::Contains("--interp depth"));
}

TEST_CASE("mpr-render --depth-maps estimate refuses cameras whose sweep exceeds its working memory", "[tools]") {
  // Two flat 6000 x 4000 views (24 Mpixels each, under the loader's limits): the sweep of either
  // needs about 2.3 GiB (`mpr::plane_sweep_bytes`), above PlaneSweepConfig::memory_limit's
  // 2 GiB. Refused before any sweep, in one line naming the option, the camera and the MiB.
  const std::filesystem::path dir = temp_folder("estimate_memory");
  std::ofstream par(dir / "big_par.txt");
  par << "2\n";
  const Image flat(6000, 4000, mpr::Rgb8{90, 120, 150});
  for (int i = 0; i < 2; ++i) {
    mpr::write_png(dir / ("big" + std::to_string(i) + ".png"), flat);
    par << "big" << i << ".png 4000 0 2999.5 0 4000 1999.5 0 0 1  1 0 0 0 1 0 0 0 1  " << -0.1 * i << " 0 0\n";
  }
  par.close();
  const std::string error =
      error_of({"--par", (dir / "big_par.txt").string(), "--depth-maps", "estimate:1:4", "--all-in-focus"});
  CHECK_THAT(error, Catch::Contains("invalid --depth-maps: estimate: the plane sweep of camera big0.png (6000x4000)") &&
                        Catch::Contains("MiB of working memory, more than the 2048 MiB limit"));
  CHECK(error.find('\n') == std::string::npos);
}
