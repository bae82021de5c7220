#include "io/light_field_test_files.hpp"

#include <mpr/io/stanford_light_field.hpp>

#include <catch2/catch.hpp>

#include <string>

TEST_CASE("Stanford archive file names parse", "[stanford_light_field]") {
  const auto a = mpr::parse_stanford_view_name("out_08_08_-818.578247_-3313.998047_.png");
  REQUIRE(a);
  CHECK(a->row == 8);
  CHECK(a->column == 8);
  CHECK(a->y == -818.578247);
  CHECK(a->x == -3313.998047);
  const auto b = mpr::parse_stanford_view_name("out_00_16_-381.909271_1103.376221.png"); // no trailing _
  REQUIRE(b);
  CHECK(b->column == 16);
  CHECK(b->x == 1103.376221);
  CHECK_FALSE(mpr::parse_stanford_view_name("out_08_08_-818.5.png"));
  CHECK_FALSE(mpr::parse_stanford_view_name("out_08_xx_1_2_.png"));
  CHECK_FALSE(mpr::parse_stanford_view_name("in_08_08_1_2_.png"));
  CHECK_FALSE(mpr::parse_stanford_view_name("out_08_08_1_2"));
  CHECK_FALSE(mpr::parse_stanford_view_name("out_08_08_1_2_3_.png"));
}

TEST_CASE("Stanford folder: planar array with zero disparity on the reference plane", "[stanford_light_field]") {
  const mpr_test::TempFolder dir;
  // 2 rows x 3 columns; Y falls by 5 per row, X rises by 5 per column (as in the archive).
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c)
      mpr_test::write_test_png(dir / ("out_0" + std::to_string(r) + "_0" + std::to_string(c) + "_" +
                                      std::to_string(-800.0 - 5 * r) + "_" + std::to_string(-3300.0 + 5 * c) + "_.png"),
                               8, 6, 10 * r + c);
  mpr_test::write_text(dir / "README.txt", "ignored");
  mpr::PlanarArrayOptions options;
  options.scale = 2.0;
  options.reference_depth = 500;
  options.focal_length = 10;
  const auto frames = mpr::read_stanford_light_field<double>(dir.path(), options);
  REQUIRE(frames.size() == 6);
  CHECK(frames.name(0).rfind("out_00_00_", 0) == 0);
  CHECK(frames.name(5).rfind("out_01_02_", 0) == 0);
  CHECK(frames.image(4)(0, 0).b == 11);
  // Centres: z = 0, centred on the mean, spacing scale * 5 = 10; x grows with X (the column),
  // y (image down) with Y, which falls as the row grows.
  CHECK(frames.camera(0).centre().isApprox(mpr::Vec3<double>(-10, 5, 0)));
  CHECK(frames.camera(5).centre().isApprox(mpr::Vec3<double>(10, -5, 0)));
  // The loader hands the array plane (z = 0) to the samplers.
  REQUIRE(frames.array_plane().has_value());
  CHECK(frames.array_plane()->normal == mpr::Vec3<double>::UnitZ());
  CHECK(frames.array_plane()->point == mpr::Vec3<double>::Zero());
  CHECK(frames.without(2).array_plane().has_value());
  CHECK(frames.cast<float>().array_plane()->normal == mpr::Vec3<float>::UnitZ());
  // LoadLimits::progress: called once per decoded image, in order, with the total.
  std::vector<std::pair<std::size_t, std::size_t>> calls;
  mpr::LoadLimits limits;
  limits.progress = [&](std::size_t loaded, std::size_t total) { calls.emplace_back(loaded, total); };
  CHECK(mpr::read_stanford_light_field<double>(dir.path(), options, limits).size() == 6);
  REQUIRE(calls.size() == 6);
  for (std::size_t i = 0; i < 6; ++i) CHECK(calls[i] == std::pair<std::size_t, std::size_t>(i + 1, 6));
  options.negate_x = true;
  options.negate_y = true;
  CHECK(mpr::read_stanford_light_field<double>(dir.path(), options)
            .camera(0)
            .centre()
            .isApprox(mpr::Vec3<double>(10, -5, 0)));
  options.negate_x = false;
  options.negate_y = false;
  // A point of the reference plane has the same pixel in every view; a nearer point moves
  // against the camera motion.
  const mpr::Vec3<double> on_plane(13, -7, 500), nearer(13, -7, 250);
  const mpr::Vec2<double> p0 = *frames.camera(0).project_unbounded(on_plane);
  for (std::size_t k = 0; k < 6; ++k) {
    CHECK((*frames.camera(k).project_unbounded(on_plane) - p0).norm() < 1e-9);
    CHECK(frames.camera(k).K()(0, 0) == 10);
  }
  const double d = frames.camera(1).project_unbounded(nearer)->x() - frames.camera(0).project_unbounded(nearer)->x();
  CHECK(d == Approx(-10 * 10 * (1.0 / 250 - 1.0 / 500)));
  // Default options: focal length = image width.
  CHECK(mpr::read_stanford_light_field<float>(dir.path()).camera(0).K()(0, 0) == 8.0f);
  // Bad options.
  options.scale = 0;
  CHECK_THROWS_AS(mpr::read_stanford_light_field<double>(dir.path(), options), mpr::argument_error);
  options.scale = 1;
  options.reference_depth = -1;
  CHECK_THROWS_AS(mpr::read_stanford_light_field<double>(dir.path(), options), mpr::argument_error);
}

TEST_CASE("Stanford folder errors name the folder or file", "[stanford_light_field]") {
  const mpr_test::TempFolder dir;
  const auto message = [&](const std::filesystem::path& folder) -> std::string {
    try {
      (void)mpr::read_stanford_light_field<double>(folder);
    } catch (const mpr::io_error& e) {
      return e.what();
    }
    return "no error";
  };
  CHECK(message(dir / "absent").find("not a folder") != std::string::npos);
  CHECK(message(dir.path()).find("no out_") != std::string::npos);
  mpr_test::write_test_png(dir / "out_00_00_1.0_2.0_.png", 4, 3, 0);
  mpr_test::write_test_png(dir / "out_00_01_1.0_7.0_.png", 5, 3, 0);
  CHECK(message(dir.path()).find("out_00_01_1.0_7.0_.png: image is 5x3") != std::string::npos);
  std::filesystem::remove(dir / "out_00_01_1.0_7.0_.png");
  mpr_test::write_test_png(dir / "out_00_00_1.5_2.5.png", 4, 3, 0);
  CHECK(message(dir.path()).find("same grid cell") != std::string::npos);
  std::filesystem::remove(dir / "out_00_00_1.5_2.5.png");
  mpr_test::write_test_png(dir / "out_00_0x_1.5_2.5.png", 4, 3, 0);
  CHECK(message(dir.path()).find("out_00_0x_1.5_2.5.png: not a name") != std::string::npos);
  std::filesystem::remove(dir / "out_00_0x_1.5_2.5.png");
  mpr_test::write_text(dir / "out_00_01_1.0_7.0_.png", "truncated");
  CHECK(message(dir.path()).find("out_00_01_1.0_7.0_.png") != std::string::npos);
}

TEST_CASE("real data: Stanford Chess loads as a 7x7 planar array", "[stanford_light_field][real_data]") {
  const std::filesystem::path root = mpr_test::data_dir();
  const auto chess = root / "stanford" / "chess";
  if (root.empty() || !std::filesystem::is_directory(chess)) {
    // ctest's io_real_data entry reports "skipped" on this message (tests/CMakeLists.txt).
    WARN("real data not found under '" << root.string() << "' (set MPR_DATA_DIR): skipped");
    return;
  }
  const auto frames = mpr::read_stanford_light_field<float>(chess);
  REQUIRE(frames.size() == 49);
  CHECK(frames.name(0).rfind("out_05_05_", 0) == 0);
  CHECK(frames.name(48).rfind("out_11_11_", 0) == 0);
  CHECK(frames.image(0).width() == 1400);
  CHECK(frames.image(0).height() == 800);
  // Grid spacing about 5 units; columns run right (+x), rows up (-y: Y falls with the row).
  CHECK(frames.camera(1).centre().x() - frames.camera(0).centre().x() == Approx(5.16).margin(1.0));
  CHECK(frames.camera(7).centre().y() - frames.camera(0).centre().y() == Approx(-4.92).margin(1.0));
  CHECK(std::abs(frames.camera(24).centre().x()) < 1.0f);
}
