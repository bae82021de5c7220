#include "io/light_field_test_files.hpp"

#include <mpr/io/par_file.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace {

// Two cameras looking at the origin from a ring, 6x4 images.
std::vector<mpr::PinholeCamera<double>> ring_cameras() {
  std::vector<mpr::PinholeCamera<double>> cams;
  for (int k = 0; k < 2; ++k) {
    const double a = 0.7 * k + 0.1;
    cams.push_back(
        mpr::PinholeCamera<double>::look_at({std::cos(a), 0.2, std::sin(a)}, {0, 0, 0}, {0, -1, 0}, 0.8, 6, 4));
  }
  return cams;
}

// A valid line for image `name` (K, R = I, t).
std::string par_line(const std::string& name, const std::string& k = "10 0 2.5 0 10 1.5 0 0 1",
                     const std::string& r = "1 0 0 0 1 0 0 0 1", const std::string& t = "0 0 2") {
  return name + " " + k + " " + r + " " + t + "\n";
}

} // namespace

TEST_CASE("_par.txt writer and reader round-trip cameras and images", "[par_file]") {
  const mpr_test::TempFolder dir;
  const auto cams = ring_cameras();
  const std::vector<std::string> names{"a0001.png", "a0002.png"};
  std::vector<mpr::Image<mpr::Rgb8>> imgs;
  for (int k = 0; k < 2; ++k)
    imgs.push_back(mpr_test::write_test_png(dir / names[static_cast<std::size_t>(k)], 6, 4, k));
  mpr::write_par_file<double>(dir / "a_par.txt", names, cams);
  const auto frames = mpr::read_par_file<double>(dir / "a_par.txt");
  REQUIRE(frames.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(frames.name(k) == names[k]);
    CHECK(frames.camera(k).K() == cams[k].K()); // 17 digits: exact
    CHECK(frames.camera(k).R() == cams[k].R());
    CHECK(frames.camera(k).t() == cams[k].t());
    CHECK(frames.camera(k).width() == 6);
    CHECK(frames.image(k) == imgs[k]);
  }
  // The frame-set overload writes the same file.
  mpr::write_par_file(dir / "b_par.txt", frames);
  const auto again = mpr::read_par_entries<double>(dir / "b_par.txt");
  REQUIRE(again.size() == 2);
  CHECK(again[1].R == cams[1].R());
  CHECK(again[1].line == 3);
  // LoadLimits::progress: called once per decoded image with (loaded, total).
  std::vector<std::pair<std::size_t, std::size_t>> calls;
  mpr::LoadLimits limits;
  limits.progress = [&](std::size_t loaded, std::size_t total) { calls.emplace_back(loaded, total); };
  (void)mpr::read_par_file<double>(dir / "a_par.txt", limits);
  CHECK(calls == std::vector<std::pair<std::size_t, std::size_t>>{{1, 2}, {2, 2}});
  // float cameras read the same file.
  const auto f = mpr::read_par_file<float>(dir / "a_par.txt");
  CHECK(f.camera(1).centre().isApprox(cams[1].centre().cast<float>(), 1e-5f));
}

TEST_CASE("_par.txt writer rejects what the format cannot hold", "[par_file]") {
  const mpr_test::TempFolder dir;
  const auto cams = ring_cameras();
  const std::vector<std::string> one{"x.png"};
  CHECK_THROWS_AS(mpr::write_par_file<double>(dir / "p.txt", one, cams), mpr::argument_error);
  const std::vector<std::string> spaced{"a b.png", "c.png"};
  CHECK_THROWS_AS(mpr::write_par_file<double>(dir / "p.txt", spaced, cams), mpr::argument_error);
  std::vector<mpr::PinholeCamera<double>> distorted{mpr::PinholeCamera<double>(
      cams[0].K(), cams[0].R(), cams[0].t(), 6, 4, mpr::PinholeCamera<double>::Distortion{0.1, 0})};
  CHECK_THROWS_AS(mpr::write_par_file<double>(dir / "p.txt", one, distorted), mpr::argument_error);
  CHECK_THROWS_AS(
      mpr::write_par_file<double>(dir / "no-such-folder" / "p.txt", std::vector<std::string>{"a.png", "b.png"}, cams),
      mpr::io_error);
}

TEST_CASE("_par.txt reader names the file and line of every error", "[par_file]") {
  const mpr_test::TempFolder dir;
  mpr_test::write_test_png(dir / "a.png", 6, 4, 0);
  mpr_test::write_test_png(dir / "b.png", 6, 4, 1);
  mpr_test::write_test_png(dir / "small.png", 5, 4, 2);
  mpr_test::write_text(dir / "broken.png", "not a png");
  const auto expect_error = [&](const std::string& text, std::size_t line, const std::string& words) {
    const auto path = dir / "t_par.txt";
    mpr_test::write_text(path, text);
    try {
      (void)mpr::read_par_file<double>(path);
      FAIL("no error for: " << text);
    } catch (const mpr::io_error& e) {
      INFO(e.what());
      CHECK(e.line() == line);
      CHECK(std::string(e.what()).find(words) != std::string::npos);
      CHECK(std::string(e.what()).find("t_par.txt") != std::string::npos);
    }
  };
  SECTION("valid file loads") {
    mpr_test::write_text(dir / "ok_par.txt", "2\n" + par_line("a.png") + par_line("b.png"));
    CHECK(mpr::read_par_file<double>(dir / "ok_par.txt").size() == 2);
  }
  SECTION("count") {
    expect_error("", 0, "empty");
    expect_error("two\n" + par_line("a.png"), 1, "not a count");
    expect_error("3\n" + par_line("a.png") + par_line("b.png"), 1, "3 images");
    expect_error("1 2\n" + par_line("a.png"), 1, "expected the image count alone on the first line, found 2 fields");
    // A file of another format (here: a calibration line without the count) says what a
    // _par.txt file looks like, in correct grammar (before: "expected 1 fields, found 22").
    expect_error(par_line("a.png") + par_line("b.png"), 1, "found 22 fields: is this a _par.txt file?");
    expect_error("0 0 0 0 0 0 0 0 0 0\n", 1, "found 10 fields: is this a _par.txt file? (the image count, then");
    const mpr::detail::TextLine two{7, {"a", "b"}};
    CHECK_THROWS_WITH(mpr::detail::require_fields("x.txt", two, 1), Catch::Contains("expected 1 field, found 2"));
    CHECK_THROWS_WITH(mpr::detail::require_fields("x.txt", two, 3, "id X Y"),
                      Catch::Contains("expected 3 fields (id X Y), found 2"));
  }
  SECTION("fields and numbers") {
    expect_error("2\n" + par_line("a.png") + "b.png 10 0 2.5 0 10 1.5 0 0 1 1 0 0 0 1 0 0 0 1 0 0\n", 3,
                 "expected 22 fields (image name, K (9 numbers), R (9), t (3)), found 21");
    expect_error("1\n" + par_line("a.png", "10 0 2.5 0 1O 1.5 0 0 1"), 2, "field 6 ('1O')");
    expect_error("1\n" + par_line("a.png", "10 0 2.5 0 10 1.5 0 0 1", "1 0 0 0 1 0 0 0 1", "0 0 nan"), 2, "field 22");
    expect_error("1\n" + par_line("a.png", "10 0 2.5 0 10 1.5 0 0 1", "1 0 0 0 1 0 0 0 1", "0 0 2x"), 2,
                 "not a finite number");
  }
  SECTION("geometry") {
    expect_error("1\n" + par_line("a.png", "10 0 2.5 0 10 1.5 0 0 1", "1 0 0 0 1 0 0 0 2"), 2, "not a rotation");
    expect_error("1\n" + par_line("a.png", "10 0 2.5 0 10 1.5 0 0 1", "1 0 0 0 -1 0 0 0 1"), 2, "R");
    expect_error("2\n" + par_line("a.png") + par_line("b.png", "10 0 2.5 0 0 1.5 0 0 1"), 3, "singular K");
  }
  SECTION("images") {
    expect_error("2\n" + par_line("a.png") + par_line("missing.png"), 3, "missing.png");
    expect_error("1\n" + par_line("broken.png"), 1 + 1, "broken.png");
    try {
      mpr_test::write_text(dir / "s_par.txt", "2\n" + par_line("a.png") + par_line("small.png"));
      (void)mpr::read_par_file<double>(dir / "s_par.txt");
      FAIL("different sizes accepted");
    } catch (const mpr::io_error& e) {
      CHECK(std::string(e.what()).find("small.png") != std::string::npos);
      CHECK(std::string(e.what()).find("5x4") != std::string::npos);
    }
  }
  CHECK_THROWS_AS(mpr::read_par_file<double>(dir / "absent_par.txt"), mpr::io_error);
}

TEST_CASE("real data: Middlebury temple and dino rings load", "[par_file][real_data]") {
  const std::filesystem::path root = mpr_test::data_dir();
  const auto temple = root / "middlebury" / "templeSparseRing" / "templeSR_par.txt";
  const auto dino = root / "middlebury" / "dinoSparseRing" / "dinoSR_par.txt";
  if (root.empty() || !std::filesystem::exists(temple) || !std::filesystem::exists(dino)) {
    // ctest's io_real_data entry reports "skipped" on this message (tests/CMakeLists.txt).
    WARN("real data not found under '" << root.string() << "' (set MPR_DATA_DIR): skipped");
    return;
  }
  const auto frames = mpr::read_par_file<double>(temple);
  REQUIRE(frames.size() == 16);
  // The bounding-box centre of the temple (README.txt) projects near the image centre of every view.
  const mpr::Vec3<double> centre(0.5 * (-0.073568 + 0.028855), 0.5 * (0.021728 + 0.181892),
                                 0.5 * (-0.012445 + 0.062736));
  for (std::size_t k = 0; k < frames.size(); ++k) {
    CHECK(frames.image(k).width() == 640);
    CHECK(frames.image(k).height() == 480);
    const auto p = frames.camera(k).project(centre);
    REQUIRE(p);
    CHECK(p->x() > 200);
    CHECK(p->x() < 440);
    CHECK((frames.camera(k).centre() - centre).norm() == Approx(0.566).margin(0.01));
  }
  const auto d = mpr::read_par_entries<double>(dino);
  CHECK(d.size() == 16);
  CHECK(d[0].K(0, 0) == Approx(3310.40));
}
