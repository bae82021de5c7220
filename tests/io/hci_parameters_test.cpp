#include <mpr/io/hci_parameters.hpp>

#include <catch2/catch.hpp>

#include <string>

namespace {

const std::string kCfg = "[intrinsics]\n"
                         "focal_length_mm = 100\n"
                         "image_resolution_x_px = 512\n"
                         "image_resolution_y_px = 256\n"
                         "sensor_size_mm = 32\n"
                         "fstop = 100\n"
                         "\n"
                         "# a comment\n"
                         "[extrinsics]\n"
                         "num_cams_x = 9\n"
                         "num_cams_y = 7\n"
                         "baseline_mm = 50\n"
                         "focus_distance_m = 4\n"
                         "center_cam_rx_rad = 1.5\n"
                         "\n"
                         "[meta]\n"
                         "disp_min = -1.5\n"
                         "disp_max = 2\n";

std::string message(const std::string& text) {
  try {
    (void)mpr::parse_hci_parameters(text, "scene/parameters.cfg");
  } catch (const mpr::io_error& e) {
    return e.what();
  }
  return "no error";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

} // namespace

TEST_CASE("parameters.cfg: the fields and the benchmark's disparity conversion", "[hci_parameters]") {
  const mpr::HciParameters p = mpr::parse_hci_parameters(kCfg, "parameters.cfg");
  CHECK(p.focal_length_mm == 100);
  CHECK(p.sensor_size_mm == 32);
  CHECK(p.width == 512);
  CHECK(p.height == 256);
  CHECK(p.cams_x == 9);
  CHECK(p.cams_y == 7);
  CHECK(p.baseline_mm == 50);
  CHECK(p.focus_distance_m == 4);
  REQUIRE(p.disparity_min);
  CHECK(*p.disparity_min == -1.5);
  CHECK(*p.disparity_max == 2);
  // f = 100 / 32 * 512 = 1600 px; f B = 1600 * 0.05 = 80 px m; offset 80 / 4 = 20 px.
  CHECK(p.focal_length_px() == Approx(1600));
  const mpr::ArrayDisparity d = p.disparity();
  CHECK(d.focal_baseline == Approx(80));
  CHECK(d.offset == Approx(20));
  CHECK(d.disparity(4.0) == Approx(0).margin(1e-12)); // the focus plane has zero disparity
  CHECK(d.disparity(2.0) == Approx(20));              // 80 / 2 - 20
  CHECK(d.depth(-10.0) == Approx(8.0));               // 80 / (-10 + 20)
}

TEST_CASE("parameters.cfg: meta range is optional", "[hci_parameters]") {
  const std::string text = kCfg.substr(0, kCfg.find("[meta]"));
  const mpr::HciParameters p = mpr::parse_hci_parameters(text, "parameters.cfg");
  CHECK_FALSE(p.disparity_min);
  CHECK(message(replaced(kCfg, "disp_max = 2\n", "")).find("disp_min and disp_max go together") != std::string::npos);
  CHECK(message(replaced(kCfg, "disp_max = 2", "disp_max = -2")).find("below disp_max") != std::string::npos);
}

TEST_CASE("parameters.cfg: malformed files name the file and line", "[hci_parameters]") {
  CHECK(message(replaced(kCfg, "fstop = 100", "fstop 100")) ==
        "mpr: scene/parameters.cfg:6: expected 'key = value', got 'fstop 100'");
  CHECK(message(replaced(kCfg, "baseline_mm = 50", "baseline_mm = 5o")) ==
        "mpr: scene/parameters.cfg:12: baseline_mm = '5o' is not a number");
  CHECK(message(replaced(kCfg, "num_cams_x = 9", "num_cams_x = 9.5")) ==
        "mpr: scene/parameters.cfg:10: num_cams_x = '9.5' is not an integer");
  CHECK(message(replaced(kCfg, "[meta]", "[meta")).find(":16: malformed section header") != std::string::npos);
  CHECK(message(kCfg + "baseline_mm = 50\n").find("baseline_mm given twice") != std::string::npos);
  CHECK(message(replaced(kCfg, "focus_distance_m = 4\n", "")) ==
        "mpr: scene/parameters.cfg: missing key focus_distance_m");
  CHECK(message(replaced(kCfg, "sensor_size_mm = 32", "sensor_size_mm = 0")) ==
        "mpr: scene/parameters.cfg: sensor_size_mm must be positive");
  CHECK(message(replaced(kCfg, "baseline_mm = 50", "baseline_mm = nan")).find("is not a number") != std::string::npos);
  CHECK(message(replaced(kCfg, "baseline_mm = 50", "baseline_mm =")).find("is not a number") != std::string::npos);
}
