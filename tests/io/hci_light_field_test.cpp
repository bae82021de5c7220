#include "io/light_field_test_files.hpp"

#include <mpr/io/hci_light_field.hpp>

#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

namespace {

std::string view_name(int v) {
  char name[32];
  std::snprintf(name, sizeof name, "input_Cam%03d.png", v);
  return name;
}

/// The 33-view star of a 9x9 array: centre row, column and both diagonals.
bool in_star(int v) {
  const int r = v / 9, c = v % 9;
  return r == 4 || c == 4 || r == c || r + c == 8;
}

void write_star(const mpr_test::TempFolder& dir, int width = 8, int height = 6) {
  for (int v = 0; v < 81; ++v)
    if (in_star(v)) mpr_test::write_test_png(dir / view_name(v), width, height, v);
}

std::string message(const std::filesystem::path& folder) {
  try {
    (void)mpr::read_hci_light_field<double>(folder);
  } catch (const mpr::error& e) {
    return e.what();
  }
  return "no error";
}

const std::string kCfg = "[intrinsics]\nfocal_length_mm = 100\nimage_resolution_x_px = 8\nimage_resolution_y_px = 6\n"
                         "sensor_size_mm = 32\n[extrinsics]\nnum_cams_x = 9\nnum_cams_y = 9\nbaseline_mm = 50\n"
                         "focus_distance_m = 0.5\n[meta]\ndisp_min = -1\ndisp_max = 1.5\n";

/// The point at depth z (along the optical axis) seen at pixel (x, y) of camera `c` (R = I).
template <class T>
mpr::Vec3<T> at_depth(const mpr::PinholeCamera<T>& c, T x, T y, T z) {
  return c.centre() + mpr::Vec3<T>((x - c.K()(0, 2)) / c.K()(0, 0) * z, (y - c.K()(1, 2)) / c.K()(1, 1) * z, z);
}

} // namespace

TEST_CASE("HCI view names", "[hci_light_field]") {
  CHECK(mpr::parse_hci_view_name("input_Cam000.png") == 0);
  CHECK(mpr::parse_hci_view_name("input_Cam040.png") == 40);
  CHECK(mpr::parse_hci_view_name("input_Cam80.png") == 80);
  CHECK(mpr::parse_hci_view_name("input_Cam.png") == -1);
  CHECK(mpr::parse_hci_view_name("input_Cam0400.png") == -1);
  CHECK(mpr::parse_hci_view_name("input_Cam04a.png") == -1);
  CHECK(mpr::parse_hci_view_name("input_Cam040.jpg") == -1);
}

TEST_CASE("HCI star without parameters: an array in disparity units", "[hci_light_field]") {
  const mpr_test::TempFolder dir;
  write_star(dir);
  mpr_test::write_text(dir / "README.txt", "ignored");
  const auto lf = mpr::read_hci_light_field<double>(dir.path());
  REQUIRE(lf.frames.size() == 33);
  CHECK(lf.views.front() == 0);
  CHECK(lf.views.back() == 80);
  CHECK(lf.views[lf.centre] == 40);
  CHECK(lf.frames.name(lf.centre) == "input_Cam040.png");
  CHECK_FALSE(lf.parameters);
  CHECK_FALSE(lf.ground_truth);
  // f = width = 8, B = 1, offset 10: d = 8 / Z - 10.
  CHECK(lf.disparity.focal_baseline == 8);
  CHECK(lf.disparity.offset == 10);
  CHECK(lf.near_depth() == Approx(8.0 / 14));
  CHECK(lf.far_depth() == Approx(8.0 / 6));
  // SOURCE.md's convention: the centre's pixel (x, y) at disparity d is seen in view (r, c) at
  // (x - d (c - 4), y - d (r - 4)). Take d = 1.5 (Z = 8 / 11.5) at the centre's pixel (2, 3).
  const double d = 1.5, z = 8.0 / 11.5;
  const auto& centre = lf.frames.camera(lf.centre);
  const mpr::Vec3<double> X = at_depth(centre, 2.0, 3.0, z);
  for (std::size_t i = 0; i < lf.frames.size(); ++i) {
    const auto p = lf.frames.camera(i).project_unbounded(X);
    REQUIRE(p);
    CHECK(p->x() == Approx(2 - d * (lf.column(i) - 4)).margin(1e-9));
    CHECK(p->y() == Approx(3 - d * (lf.row(i) - 4)).margin(1e-9));
  }
}

TEST_CASE("HCI with parameters.cfg: the metric array", "[hci_light_field]") {
  const mpr_test::TempFolder dir;
  write_star(dir);
  mpr_test::write_text(dir / "parameters.cfg", kCfg);
  const auto lf = mpr::read_hci_light_field<float>(dir.path());
  REQUIRE(lf.parameters);
  // f = 100 / 32 * 8 = 25 px, B = 0.05 m: f B = 1.25, offset 1.25 / 0.5.
  CHECK(lf.disparity.focal_baseline == Approx(1.25));
  CHECK(lf.disparity.offset == Approx(2.5));
  CHECK(lf.disparity_min == -1);
  CHECK(lf.disparity_max == 1.5);
  CHECK(lf.frames.camera(lf.centre + 1).centre().x() == Approx(0.05f)); // view 41, one column right
  // A point on the focus plane (0.5 m) has zero disparity: the same pixel in every view.
  const auto& centre = lf.frames.camera(lf.centre);
  const mpr::Vec3<float> X = at_depth(centre, 5.0f, 1.0f, 0.5f);
  for (std::size_t i = 0; i < lf.frames.size(); ++i) {
    const auto p = lf.frames.camera(i).project_unbounded(X);
    REQUIRE(p);
    CHECK(p->x() == Approx(5).margin(1e-4));
    CHECK(p->y() == Approx(1).margin(1e-4));
  }
}

TEST_CASE("HCI ground truth: read top row first, size checked", "[hci_light_field]") {
  const mpr_test::TempFolder dir;
  write_star(dir);
  mpr::Image<float> gt(8, 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) gt(x, y) = 0.1f * static_cast<float>(x) - 0.2f * static_cast<float>(y);
  mpr::write_pfm(dir / "gt_disp_lowres.pfm", gt);
  const auto lf = mpr::read_hci_light_field<double>(dir.path());
  REQUIRE(lf.ground_truth);
  CHECK(*lf.ground_truth == gt);
  mpr::write_pfm(dir / "gt_disp_lowres.pfm", mpr::Image<float>(8, 5));
  CHECK(message(dir.path()).find("gt_disp_lowres.pfm: ground truth is 8x5, the views are 8x6") != std::string::npos);
}

TEST_CASE("HCI bad folders: one error naming the file", "[hci_light_field]") {
  CHECK(message("/nonexistent/hci").find("not a folder") != std::string::npos);
  {
    const mpr_test::TempFolder dir; // no centre view
    for (int v : {0, 1, 2}) mpr_test::write_test_png(dir / view_name(v), 8, 6, v);
    CHECK(message(dir.path()).find("no centre view (view 40, input_Cam040.png)") != std::string::npos);
  }
  {
    const mpr_test::TempFolder dir; // an extra view outside the 9x9 grid
    write_star(dir);
    mpr_test::write_test_png(dir / view_name(81), 8, 6, 0);
    CHECK(message(dir.path()).find("input_Cam081.png: view 81 is outside the 9x9 array") != std::string::npos);
  }
  {
    const mpr_test::TempFolder dir; // the same view twice
    write_star(dir);
    mpr_test::write_test_png(dir / "input_Cam40.png", 8, 6, 0);
    CHECK(message(dir.path()).find("same view as") != std::string::npos);
  }
  {
    const mpr_test::TempFolder dir; // a view of another size
    write_star(dir);
    mpr_test::write_test_png(dir / view_name(44), 8, 5, 0);
    CHECK(message(dir.path()).find("input_Cam044.png: image is 8x5") != std::string::npos);
  }
  {
    const mpr_test::TempFolder dir; // a badly named view
    write_star(dir);
    mpr_test::write_text(dir / "input_Cam4x.png", "x");
    CHECK(message(dir.path()).find("input_Cam4x.png: not a view name") != std::string::npos);
  }
  {
    const mpr_test::TempFolder dir; // parameters that disagree with the images
    write_star(dir);
    std::string cfg = kCfg;
    cfg.replace(cfg.find("image_resolution_x_px = 8"), 25, "image_resolution_x_px = 9");
    mpr_test::write_text(dir / "parameters.cfg", cfg);
    CHECK(message(dir.path()).find("parameters.cfg: image resolution 9x6 disagrees with the views (8x6)") !=
          std::string::npos);
  }
  {
    const mpr_test::TempFolder dir; // a grid too small for the views
    write_star(dir);
    std::string cfg = kCfg;
    cfg.replace(cfg.find("num_cams_y = 9"), 14, "num_cams_y = 5");
    mpr_test::write_text(dir / "parameters.cfg", cfg);
    CHECK(message(dir.path()).find("is outside the 9x5 array") != std::string::npos);
  }
  {
    const mpr_test::TempFolder dir; // a disparity range beyond the array's infinity
    write_star(dir);
    std::string cfg = kCfg;
    cfg.replace(cfg.find("focus_distance_m = 0.5"), 22, "focus_distance_m = 4.0");
    mpr_test::write_text(dir / "parameters.cfg", cfg);
    CHECK(message(dir.path()).find("parameters.cfg: disp_min lies at or beyond the array's infinity") !=
          std::string::npos);
  }
  {
    const mpr_test::TempFolder dir; // malformed parameters
    write_star(dir);
    mpr_test::write_text(dir / "parameters.cfg", "[intrinsics]\nfocal_length_mm 100\n");
    CHECK(message(dir.path()).find("parameters.cfg:2: expected 'key = value'") != std::string::npos);
  }
  {
    const mpr_test::TempFolder dir; // an unreadable view
    write_star(dir);
    mpr_test::write_text(dir / view_name(41), "not a png");
    CHECK(message(dir.path()).find("input_Cam041.png") != std::string::npos);
  }
}

TEST_CASE("real data: HCI backgammon, 81 views and its ground truth", "[hci_light_field][real_data]") {
  const std::filesystem::path root = mpr_test::data_dir();
  const auto folder = root / "hci" / "backgammon";
  if (root.empty() || !std::filesystem::is_directory(folder)) {
    WARN("real data not found under '" << root.string() << "' (set MPR_DATA_DIR): skipped");
    return;
  }
  const auto lf = mpr::read_hci_light_field<float>(folder);
  REQUIRE(lf.frames.size() == 81);
  CHECK(lf.centre == 40);
  CHECK(lf.frames.image(0).width() == 512);
  CHECK(lf.frames.image(0).height() == 512);
  REQUIRE(lf.ground_truth);
  float lo = 1e9f, hi = -1e9f;
  for (int y = 0; y < 512; ++y)
    for (int x = 0; x < 512; ++x) {
      lo = std::min(lo, (*lf.ground_truth)(x, y));
      hi = std::max(hi, (*lf.ground_truth)(x, y));
    }
  // SOURCE.md: backgammon's disparities span about -1.55 to 0.53.
  CHECK(lo == Approx(-1.55).margin(0.05));
  CHECK(hi == Approx(0.53).margin(0.05));
  const auto star = mpr::read_hci_light_field<float>(root / "hci" / "dino");
  CHECK(star.frames.size() == 33);
  CHECK_FALSE(star.ground_truth);
}
