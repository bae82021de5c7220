#include <mpr/io/calibration_text.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/lfca_calibration.hpp>
#include <mpr/io/load_limits.hpp>
#include <mpr/io/par_file.hpp>
#include <mpr/io/stanford_light_field.hpp>

#include "io/light_field_test_files.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

/// The bytes of a file.
std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A small PNG whose IHDR claims `width` x `height` (stb_image checks no CRC): its header
/// promises a huge image that must be refused before anything is decoded.
/// Grey (colour type 0), as stb_image refuses RGB headers above 2^30 bytes itself.
void write_huge_header_png(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height) {
  mpr_test::write_test_png(path, 2, 2, 0);
  std::string bytes = read_bytes(path);
  REQUIRE(bytes.substr(12, 4) == "IHDR");
  bytes[25] = 0; // colour type: grey
  for (int k = 0; k < 4; ++k) {
    bytes[static_cast<std::size_t>(16 + k)] = static_cast<char>((width >> (24 - 8 * k)) & 0xff);
    bytes[static_cast<std::size_t>(20 + k)] = static_cast<char>((height >> (24 - 8 * k)) & 0xff);
  }
  mpr_test::write_text(path, bytes);
}

std::string error_of(const auto& load) {
  try {
    load();
  } catch (const mpr::io_error& e) {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST_CASE("text files: only regular files, bounded lines, any line end", "[io][limits]") {
  const mpr_test::TempFolder dir;
  CHECK_THAT(error_of([] { (void)mpr::detail::read_text_lines("/dev/zero"); }),
             Catch::Contains("/dev/zero") && Catch::Contains("not a regular file"));
  CHECK_THAT(error_of([&] { (void)mpr::detail::read_text_lines(dir.path()); }), Catch::Contains("not a regular file"));
  CHECK_THAT(error_of([&] { (void)mpr::detail::read_text_lines(dir / "absent.txt"); }),
             Catch::Contains("absent.txt") && Catch::Contains("cannot open"));
  const auto loop = dir / "loop.txt";
  std::filesystem::create_symlink(loop, loop);
  CHECK_THAT(error_of([&] { (void)mpr::detail::read_text_lines(loop); }), Catch::Contains("loop.txt"));

  mpr_test::write_text(dir / "lines.txt", "a 1\r\nb 2\rc 3\n\n# comment\nd " + std::string(100, '4') + "\n");
  const std::vector<mpr::detail::TextLine> lines = mpr::detail::read_text_lines(dir / "lines.txt");
  REQUIRE(lines.size() == 4);
  CHECK(lines[1].number == 2);
  CHECK(lines[2].fields[0] == "c");
  CHECK(lines[2].number == 3);
  CHECK(lines[3].number == 6);
  mpr::LoadLimits limits;
  limits.max_line_bytes = 50;
  try {
    (void)mpr::detail::read_text_lines(dir / "lines.txt", limits);
    FAIL("no error for a line over the limit");
  } catch (const mpr::io_error& e) {
    CHECK(e.line() == 6);
    CHECK_THAT(e.what(), Catch::Contains("line longer than 50 bytes"));
  }
  limits = {};
  limits.max_text_bytes = 10;
  CHECK_THAT(error_of([&] { (void)mpr::detail::read_text_lines(dir / "lines.txt", limits); }),
             Catch::Contains("above the limit of 10 bytes"));
}

TEST_CASE("images: size limit checked from the header, before decoding", "[io][limits]") {
  const mpr_test::TempFolder dir;
  // The case: a small file whose header says 20000 x 20000 (2.35 GB decoded before).
  write_huge_header_png(dir / "huge.png", 20000, 20000);
  const std::string message = error_of([&] { (void)mpr::read_rgb8(dir / "huge.png"); });
  CHECK_THAT(message,
             Catch::Contains("huge.png") && Catch::Contains("20000x20000") && Catch::Contains("max_image_pixels"));
  CHECK_THAT(error_of([&] { (void)mpr::read_image_info(dir / "huge.png"); }), Catch::Contains("20000x20000"));
  // The limit is configurable.
  mpr_test::write_test_png(dir / "small.png", 2, 2, 0);
  mpr::LoadLimits limits;
  limits.max_image_pixels = 3;
  CHECK_THAT(error_of([&] { (void)mpr::read_rgb8(dir / "small.png", limits); }), Catch::Contains("2x2 = 4 pixels"));
  limits.max_image_pixels = 4;
  CHECK(mpr::read_rgb8(dir / "small.png", limits).width() == 2);
  const mpr::ImageInfo info = mpr::read_image_info(dir / "small.png");
  CHECK(info.width == 2);
  CHECK(info.height == 2);
  // Not a regular file, a link loop: io_error naming the path.
  CHECK_THAT(error_of([] { (void)mpr::read_rgb8("/dev/zero"); }), Catch::Contains("not a regular file"));
  const auto loop = dir / "loop.png";
  std::filesystem::create_symlink(loop, loop);
  CHECK_THAT(error_of([&] { (void)mpr::read_rgb8(loop); }), Catch::Contains("loop.png"));
  // A truncated PNG gives a reason, never an empty one.
  const std::string bytes = read_bytes(dir / "small.png");
  for (std::size_t keep : {std::size_t(0), std::size_t(8), std::size_t(30), bytes.size() - 12}) {
    mpr_test::write_text(dir / "cut.png", bytes.substr(0, keep));
    const std::string cut = error_of([&] { (void)mpr::read_rgb8(dir / "cut.png"); });
    INFO(keep << " bytes: " << cut);
    CHECK_THAT(cut, Catch::Contains("cut.png: "));
    CHECK(cut.substr(cut.rfind(": ") + 2).size() >= 5); // a reason follows the last ": "
  }
}

TEST_CASE("frame sets: decoded size budget and per-image limit before decoding", "[io][limits]") {
  const mpr_test::TempFolder dir;
  mpr_test::write_test_png(dir / "out_00_00_1.0_2.0_.png", 4, 3, 0);
  mpr_test::write_test_png(dir / "out_00_01_1.0_7.0_.png", 4, 3, 1);
  mpr::LoadLimits limits;
  // A loaded 4x3 image takes 6 bytes a pixel (decoded image + the set's texels): 72 bytes, two
  // take 144; at 3 bytes a pixel (the budget's old count) both would fit in 100. Where the set
  // also holds 16-bit linear values (below the VBMI level), 12 bytes a pixel: 144 and 288.
  const std::uint64_t one = mpr::CameraFrameSet<float>::holds_linear16() ? 144 : 72;
  limits.max_set_bytes = one + 28;
  CHECK_THAT(error_of([&] { (void)mpr::read_stanford_light_field<float>(dir.path(), {}, limits); }),
             Catch::Contains("out_00_01_1.0_7.0_.png") && Catch::Contains("max_set_bytes"));
  limits.max_set_bytes = 2 * one;
  CHECK(mpr::read_stanford_light_field<float>(dir.path(), {}, limits).size() == 2);
  limits.max_set_bytes = 2 * one - 1;
  CHECK_THAT(error_of([&] { (void)mpr::read_stanford_light_field<float>(dir.path(), {}, limits); }),
             Catch::Contains("max_set_bytes"));
  // A huge header in the set fails before the others are decoded.
  write_huge_header_png(dir / "out_01_00_1.0_2.0_.png", 30000, 20000);
  CHECK_THAT(error_of([&] { (void)mpr::read_stanford_light_field<float>(dir.path()); }),
             Catch::Contains("out_01_00_1.0_2.0_.png") && Catch::Contains("30000x20000"));
  std::filesystem::remove(dir / "out_01_00_1.0_2.0_.png");

  // _par.txt and LFCA check the same budget.
  const std::string row = " 4 0 1.5 0 4 1 0 0 1 1 0 0 0 1 0 0 0 1 0 0 5\n";
  mpr_test::write_text(dir / "s_par.txt", "2\nout_00_00_1.0_2.0_.png" + row + "out_00_01_1.0_7.0_.png" + row);
  limits.max_set_bytes = one + 28;
  CHECK_THAT(error_of([&] { (void)mpr::read_par_file<double>(dir / "s_par.txt", limits); }),
             Catch::Contains("max_set_bytes"));
  CHECK(mpr::read_par_file<double>(dir / "s_par.txt").size() == 2);
  mpr_test::write_text(dir / "a.homography.txt", "1 0 0 0 1 0 0 0 1");
  mpr_test::write_text(dir / "b.homography.txt", "1 0 0 0 1 0 0 0 1");
  std::filesystem::copy_file(dir / "out_00_00_1.0_2.0_.png", dir / "a.png");
  std::filesystem::copy_file(dir / "out_00_01_1.0_7.0_.png", dir / "b.png");
  mpr_test::write_text(dir / "p.txt", "a 0 0\nb 1 0\n");
  CHECK_THAT(error_of([&] { (void)mpr::read_lfca<double>(dir / "p.txt", {}, limits); }),
             Catch::Contains("b.png") && Catch::Contains("max_set_bytes"));
  CHECK(mpr::read_lfca<double>(dir / "p.txt").size() == 2);
}

TEST_CASE("loaders: hostile inputs are io_errors naming the file", "[io][limits]") {
  const mpr_test::TempFolder dir;
  mpr_test::write_test_png(dir / "out_00_00_1.0_2.0_.png", 4, 3, 0);
  mpr_test::write_test_png(dir / "out_00_01_1.0_7.0_.png", 4, 3, 1);
  // A link loop named like an archive image: io_error, not std::filesystem::filesystem_error.
  std::filesystem::create_symlink(dir / "out_01_00_1.0_2.0.png", dir / "out_01_00_1.0_2.0.png");
  CHECK_THAT(error_of([&] { (void)mpr::read_stanford_light_field<double>(dir.path()); }),
             Catch::Contains("out_01_00_1.0_2.0.png"));
  std::filesystem::remove(dir / "out_01_00_1.0_2.0.png");
  // A position scale that overflows names the image and the scale, not "invalid K".
  mpr::PlanarArrayOptions huge;
  huge.scale = 1e308;
  CHECK_THAT(error_of([&] { (void)mpr::read_stanford_light_field<double>(dir.path(), huge); }),
             Catch::Contains(".png: camera position") && Catch::Contains("not finite in double"));
  huge.scale = 1e39; // finite in double, not in float
  CHECK_THAT(error_of([&] { (void)mpr::read_stanford_light_field<float>(dir.path(), huge); }),
             Catch::Contains("not finite in float"));
  CHECK_THAT(error_of([] { (void)mpr::read_par_file<double>("/dev/zero"); }), Catch::Contains("not a regular file"));
  CHECK_THAT(error_of([] { (void)mpr::read_lfca<double>("/dev/zero"); }), Catch::Contains("not a regular file"));

  // LFCA: a duplicate id names both lines; 100,000 ids are checked in linear time (the first
  // missing image is reported, after every id has been checked).
  std::filesystem::copy_file(dir / "out_00_00_1.0_2.0_.png", dir / "a.png");
  std::filesystem::copy_file(dir / "out_00_01_1.0_7.0_.png", dir / "b.png");
  mpr_test::write_text(dir / "a.homography.txt", "1 0 0 0 1 0 0 0 1");
  mpr_test::write_text(dir / "dup.txt", "a 0 0\nb 1 0\n\na 2 0\n");
  try {
    (void)mpr::read_lfca<double>(dir / "dup.txt");
    FAIL("no error for a duplicate id");
  } catch (const mpr::io_error& e) {
    CHECK(e.line() == 4);
    CHECK_THAT(e.what(), Catch::Contains("duplicate camera id a (first on line 1)"));
  }
  std::string many;
  for (int i = 0; i < 100000; ++i) many.append("c").append(std::to_string(i)).append(" 1 0\n");
  many.append("c17 5 5\n");
  mpr_test::write_text(dir / "many.txt", many);
  CHECK_THAT(error_of([&] { (void)mpr::read_lfca<double>(dir / "many.txt"); }),
             Catch::Contains("many.txt:100001: duplicate camera id c17 (first on line 18)"));

  // The scale of a homography does not matter: 1e-300 * H gives the cameras of H.
  const std::string h = "1.01 0.02 -0.5 0.01 0.99 0.3 0.0001 0 1";
  std::string tiny;
  for (const double v : {1.01, 0.02, -0.5, 0.01, 0.99, 0.3, 0.0001, 0.0, 1.0}) tiny += std::to_string(v) + "e-300 ";
  mpr_test::write_text(dir / "p.txt", "a 0 0\nb 1 0\n");
  mpr_test::write_text(dir / "b.homography.txt", h);
  const auto plain = mpr::read_lfca<double>(dir / "p.txt");
  mpr_test::write_text(dir / "b.homography.txt", tiny);
  const auto scaled = mpr::read_lfca<double>(dir / "p.txt");
  CHECK((plain.camera(1).K() - scaled.camera(1).K()).cwiseAbs().maxCoeff() < 1e-9);
  CHECK((plain.camera(1).R() - scaled.camera(1).R()).cwiseAbs().maxCoeff() < 1e-12);
}
