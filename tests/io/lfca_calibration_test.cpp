#include "io/light_field_test_files.hpp"

#include <mpr/io/lfca_calibration.hpp>

#include <catch2/catch.hpp>

#include <random>
#include <sstream>
#include <string>

namespace {

std::string matrix_text(const mpr::Mat3<double>& H) {
  std::ostringstream s;
  s.precision(17);
  for (int r = 0; r < 3; ++r) s << H(r, 0) << ' ' << H(r, 1) << ' ' << H(r, 2) << '\n';
  return s.str();
}

} // namespace

TEST_CASE("rq_decompose splits M into K R", "[lfca_calibration]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 50; ++i) {
    mpr::Mat3<double> M;
    for (int k = 0; k < 9; ++k) M(k / 3, k % 3) = u(rng);
    if (std::abs(M.determinant()) < 1e-3) continue;
    mpr::Mat3<double> K, R;
    mpr::rq_decompose(M, K, R);
    CHECK((R.transpose() * R - mpr::Mat3<double>::Identity()).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(R.determinant() == Approx(1));
    CHECK(K(1, 0) == 0);
    CHECK(K(2, 0) == 0);
    CHECK(K(2, 1) == 0);
    CHECK(K(0, 0) > 0);
    CHECK(K(1, 1) > 0);
    CHECK(K(2, 2) == 1);
    // Equal up to scale.
    const mpr::Mat3<double> KR = K * R;
    const double s = M.norm() / KR.norm() * (M(0, 0) * KR(0, 0) + M(1, 1) * KR(1, 1) + M(2, 2) * KR(2, 2) > 0 ? 1 : -1);
    CHECK((s * KR - M).norm() < 1e-9 * M.norm());
  }
}

TEST_CASE("LFCA positions + homographies give cameras that see the reference plane through H", "[lfca_calibration]") {
  const mpr_test::TempFolder dir;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::string positions = "# camera-id X Y\n";
  std::vector<mpr::Mat3<double>> Hs;
  for (int i = 0; i < 4; ++i) {
    const std::string id = "cam" + std::to_string(i);
    positions += id + " " + std::to_string(10.0 * (i % 2)) + " " + std::to_string(10.0 * (i / 2)) + "\n";
    mpr::Mat3<double> H = mpr::Mat3<double>::Identity();
    H(0, 1) = 0.05 * u(rng);
    H(0, 2) = 3 * u(rng);
    H(1, 0) = 0.05 * u(rng);
    H(1, 2) = 3 * u(rng);
    H(2, 0) = 1e-3 * u(rng);
    H(2, 1) = 1e-3 * u(rng);
    H *= 2.5; // any scale
    Hs.push_back(H);
    mpr_test::write_text(dir / (id + ".homography.txt"), matrix_text(H));
    mpr_test::write_test_png(dir / (id + ".png"), 12, 8, i);
  }
  mpr_test::write_text(dir / "positions.txt", positions);
  mpr::LfcaOptions options;
  options.array.reference_depth = 100;
  options.array.focal_length = 20;
  const auto frames = mpr::read_lfca<double>(dir / "positions.txt", options);
  REQUIRE(frames.size() == 4);
  CHECK(frames.name(3) == "cam3");
  CHECK(frames.image(2)(0, 0).b == 2);
  const mpr::Vec3<double> X(1.5, -2, 100); // on the reference plane
  for (std::size_t i = 0; i < 4; ++i) {
    const auto rectified = mpr::planar_array_camera<double>(frames.camera(i).centre(), 12, 8, options.array);
    const mpr::Vec2<double> r = *rectified.project_unbounded(X);
    const mpr::Vec3<double> raw = Hs[i].inverse() * mpr::Vec3<double>(r.x(), r.y(), 1);
    const mpr::Vec2<double> p = *frames.camera(i).project_unbounded(X);
    CHECK((p - raw.hnormalized()).norm() < 1e-9);
    // Rectified pixels agree between cameras for reference-plane points.
    CHECK((r - *mpr::planar_array_camera<double>(frames.camera(0).centre(), 12, 8, options.array).project_unbounded(X))
              .norm() < 1e-9);
  }
  // Centres: mean-centred, X right, Y down (not negated for LFCA).
  CHECK(frames.camera(3).centre().isApprox(mpr::Vec3<double>(5, 5, 0)));
  // LoadLimits::progress: called once per decoded image with (loaded, total).
  std::size_t calls = 0, last = 0;
  mpr::LoadLimits limits;
  limits.progress = [&](std::size_t loaded, std::size_t total) {
    ++calls;
    CHECK(loaded == calls);
    CHECK(total == 4);
    last = loaded;
  };
  (void)mpr::read_lfca<double>(dir / "positions.txt", options, limits);
  CHECK(calls == 4);
  CHECK(last == 4);
}

TEST_CASE("LFCA errors name the file and line", "[lfca_calibration]") {
  const mpr_test::TempFolder dir;
  mpr_test::write_test_png(dir / "a.png", 6, 4, 0);
  mpr_test::write_test_png(dir / "b.png", 7, 4, 0);
  mpr_test::write_text(dir / "a.homography.txt", "1 0 0\n0 1 0\n0 0 1\n");
  const auto error = [&](const std::string& positions, const std::string& b_h) -> std::pair<std::string, std::size_t> {
    mpr_test::write_text(dir / "p.txt", positions);
    mpr_test::write_text(dir / "b.homography.txt", b_h);
    try {
      (void)mpr::read_lfca<double>(dir / "p.txt");
    } catch (const mpr::io_error& e) {
      return {e.what(), e.line()};
    }
    return {"no error", 0};
  };
  const std::string identity = "1 0 0 0 1 0 0 0 1";
  CHECK(error("a 0 0\n", identity).first == "no error");
  auto e = error("a 0 0\nb 1\n", identity);
  CHECK(e.second == 2);
  CHECK(e.first.find("expected 3 fields") != std::string::npos);
  e = error("a 0 0\n\nb 1 y\n", identity);
  CHECK(e.second == 3);
  CHECK(e.first.find("'y'") != std::string::npos);
  e = error("a 0 0\na 1 0\n", identity);
  CHECK(e.first.find("duplicate camera id a") != std::string::npos);
  e = error("a 0 0\nb 1 0\n", "1 0 0 0 1 0 0 0");
  CHECK(e.first.find("b.homography.txt") != std::string::npos);
  CHECK(e.first.find("found 8") != std::string::npos);
  e = error("a 0 0\nb 1 0\n", "1 0 0\n0 1 0\n0 0 1\n5\n");
  CHECK(e.second == 4);
  e = error("a 0 0\nb 1 0\n", "1 2 3 2 4 6 0 0 1");
  CHECK(e.first.find("singular homography") != std::string::npos);
  e = error("a 0 0\nb 1 0\n", identity);
  CHECK(e.first.find("b.png: image is 7x4") != std::string::npos);
  e = error("a 0 0\nc 1 0\n", identity);
  CHECK(e.first.find("c.homography.txt") != std::string::npos);
  mpr_test::write_text(dir / "c.homography.txt", identity);
  e = error("a 0 0\nc 1 0\n", identity);
  CHECK(e.second == 2);
  CHECK(e.first.find("c.png") != std::string::npos);
  CHECK(error("", identity).first.find("no `camera-id X Y` lines") != std::string::npos);
}
