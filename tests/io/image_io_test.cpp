#include <mpr/io/image_io.hpp>

#include <catch2/catch.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace {
std::filesystem::path temp_path(const char* name) {
  return std::filesystem::temp_directory_path() / (std::string("mpr_image_io_") + name);
}
} // namespace

TEST_CASE("PNG round trip preserves 8-bit pixels, strided views included", "[io]") {
  mpr::Image<mpr::Rgb8> image(37, 11);
  for (int y = 0; y < 11; ++y)
    for (int x = 0; x < 37; ++x)
      image(x, y) = {static_cast<std::uint8_t>(7 * x), static_cast<std::uint8_t>(23 * y),
                     static_cast<std::uint8_t>(x ^ y)};
  const auto path = temp_path("roundtrip.png");
  mpr::write_png(path, image);
  CHECK(mpr::read_rgb8(path) == image);

  const auto sub_path = temp_path("sub.png");
  mpr::write_png(sub_path, mpr::ImageView<const mpr::Rgb8>(image.view().subview(5, 2, 10, 6)));
  const mpr::Image<mpr::Rgb8> sub = mpr::read_rgb8(sub_path);
  REQUIRE(sub.width() == 10);
  REQUIRE(sub.height() == 6);
  CHECK(sub(3, 4) == image(8, 6));

  // Linear round trip: decoding then encoding gives back the same codes.
  const mpr::Image<mpr::Color> linear = mpr::read_linear(path);
  const auto linear_path = temp_path("linear.png");
  mpr::write_png(linear_path, linear);
  CHECK(mpr::read_rgb8(linear_path) == image);
}

TEST_CASE("image I/O errors name the file and the reason", "[io]") {
  const auto missing = temp_path("does_not_exist.png");
  std::filesystem::remove(missing);
  try {
    (void)mpr::read_rgb8(missing);
    FAIL("no exception");
  } catch (const mpr::io_error& e) {
    CHECK(e.path() == missing.string());
    CHECK_THAT(e.what(), Catch::Contains("does_not_exist.png") && Catch::Contains("cannot open"));
  }
  const auto garbage = temp_path("garbage.png");
  std::ofstream(garbage) << "this is not an image";
  CHECK_THROWS_WITH(mpr::read_rgb8(garbage), Catch::Contains("garbage.png") && Catch::Contains("cannot decode"));
  const mpr::Image<mpr::Rgb8> tiny(2, 2);
  CHECK_THROWS_WITH(mpr::write_png(temp_path("no_such_folder/x.png"), tiny), Catch::Contains("cannot write"));
  CHECK_THROWS_AS(mpr::write_png(temp_path("empty.png"), mpr::Image<mpr::Rgb8>()), mpr::io_error);
}

TEST_CASE("inputs that fuzzing found crashing stb_image are refused (tests/fuzz/regressions/png)", "[io][fuzz]") {
  const std::filesystem::path dir = std::filesystem::path(MPR_TEST_SOURCE_DIR) / "tests/fuzz/regressions/png";
  int jpegs = 0, chunks = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::filesystem::path path = entry.path();
    INFO(path.string());
    if (path.filename().string().rfind("stb-jpeg-dht", 0) == 0) {
      // Huffman tables of more than 256 codes: stb_image would write past its tables.
      ++jpegs;
      CHECK_THROWS_WITH(mpr::read_rgb8(path), Catch::Contains("corrupt JPEG: a Huffman table defines"));
      CHECK_THROWS_WITH(mpr::read_image_info(path), Catch::Contains("corrupt JPEG"));
    } else if (path.filename().string().rfind("stb-png-idat-length", 0) == 0) {
      // A chunk longer than the file: stb_image would first grow its buffer to that length (2 GiB).
      ++chunks;
      CHECK_THROWS_WITH(mpr::read_rgb8(path), Catch::Contains("corrupt PNG: chunk") && Catch::Contains("claims"));
      CHECK_THROWS_WITH(mpr::read_image_info(path), Catch::Contains("corrupt PNG: chunk"));
    } else if (path.filename().string().rfind("stb-pnm-integer", 0) == 0) {
      // A header integer of 10 or more digits: stb_image 2.27 would overflow an int reading it.
      CHECK_THROWS_WITH(mpr::read_rgb8(path), Catch::Contains("corrupt PNM: its"));
      CHECK_THROWS_WITH(mpr::read_image_info(path), Catch::Contains("digits (at most 9)"));
    } else if (path.filename() == "bmp-zero-height.bmp") {
      CHECK_THROWS_WITH(mpr::read_rgb8(path), Catch::Contains("empty image ("));
    } else {
      try {
        (void)mpr::read_rgb8(path);
      } catch (const mpr::io_error& e) {
        CHECK_THAT(e.what(), Catch::Contains(path.filename().string()));
      }
    }
  }
  CHECK(jpegs >= 2);
  CHECK(chunks == 2);
}

TEST_CASE("PNM headers: integers of more than 9 digits are refused before stb_image parses them", "[io]") {
  const auto write = [](const char* name, const std::string& text) {
    const std::filesystem::path path = temp_path(name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
  };
  // Hand-made P6 files of 2x1 pixels, maximum 255: the header's three integers, then 6 bytes.
  const std::string pixels(6, '\x80');
  const mpr::Image<mpr::Rgb8> ok = mpr::read_rgb8(write("ok.ppm", "P6\n# a comment\n2 1\n255\n" + pixels));
  CHECK(ok.width() == 2);
  CHECK(ok.height() == 1);
  CHECK(ok(1, 0).g == 0x80);
  // 9 digits (with leading zeros) are read as stb_image reads them; 10 are refused, naming the field.
  CHECK(mpr::read_image_info(write("nine.ppm", "P6 000000002 1 255\n" + pixels)).width == 2);
  CHECK_THROWS_WITH(mpr::read_rgb8(write("width.ppm", "P6 2147483648 1 255\n" + pixels)),
                    Catch::Contains("width.ppm") && Catch::Contains("corrupt PNM: its width has 10 digits"));
  CHECK_THROWS_WITH(mpr::read_image_info(write("height.pgm", "P5\n#\n2\n#x\r0000000001\n255\n" + pixels)),
                    Catch::Contains("corrupt PNM: its height has 10 digits"));
  CHECK_THROWS_WITH(mpr::read_rgb8(write("max.ppm", "P6 2 1 99999999999\n" + pixels)),
                    Catch::Contains("corrupt PNM: its maximum value has 11 digits"));
  // Text PNMs (P3) are not stb_image's: refused by its own check, not by this one.
  CHECK_THROWS_WITH(mpr::read_rgb8(write("text.ppm", "P3 9999999999 1 255\n")), !Catch::Contains("corrupt PNM"));
}

TEST_CASE("JPEG writing: magic bytes, close round trip, strided views, errors", "[io]") {
  // A smooth image (JPEG's quantization is gentle on gradients).
  mpr::Image<mpr::Rgb8> image(40, 24);
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 40; ++x)
      image(x, y) = {static_cast<std::uint8_t>(40 + 4 * x), static_cast<std::uint8_t>(30 + 5 * y),
                     static_cast<std::uint8_t>(120)};
  const auto path = temp_path("roundtrip.jpg");
  mpr::write_jpeg(path, image);
  {
    std::ifstream in(path, std::ios::binary);
    unsigned char magic[3] = {};
    in.read(reinterpret_cast<char*>(magic), 3);
    CHECK(magic[0] == 0xFF); // SOI marker, then the first segment's marker
    CHECK(magic[1] == 0xD8);
    CHECK(magic[2] == 0xFF);
  }
  const mpr::Image<mpr::Rgb8> back = mpr::read_rgb8(path);
  REQUIRE(back.width() == 40);
  REQUIRE(back.height() == 24);
  int worst = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 40; ++x)
      worst = std::max({worst, std::abs(back(x, y).r - image(x, y).r), std::abs(back(x, y).g - image(x, y).g),
                        std::abs(back(x, y).b - image(x, y).b)});
  CHECK(worst <= 8);

  // A strided view is packed first: the same pixels as writing a copy.
  const mpr::ImageView<const mpr::Rgb8> sub(image.view().subview(5, 2, 10, 6));
  mpr::Image<mpr::Rgb8> copy(10, 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 10; ++x) copy(x, y) = sub(x, y);
  CHECK(mpr::encode_jpeg(sub) == mpr::encode_jpeg(copy.view()));
  CHECK(mpr::encode_jpeg(image.view(), 50).size() < mpr::encode_jpeg(image.view(), 100).size());

  CHECK_THROWS_WITH(mpr::write_jpeg(temp_path("q.jpg"), image, 0), Catch::Contains("quality"));
  CHECK_THROWS_WITH(mpr::write_jpeg(temp_path("no_such_folder/x.jpg"), image), Catch::Contains("cannot write"));
  CHECK_THROWS_AS(mpr::write_jpeg(temp_path("empty.jpg"), mpr::Image<mpr::Rgb8>()), mpr::io_error);
  CHECK(mpr::encode_jpeg(image.view(), 101).empty());
}

TEST_CASE("image files: the header is checked before the file is read whole", "[io][limits]") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "mpr_image_head";
  std::filesystem::create_directories(dir);
  const auto peak_kib = [] {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;
  };
  const auto refused = [](const std::filesystem::path& p) -> std::string {
    try {
      (void)mpr::read_rgb8(p);
    } catch (const mpr::io_error& e) {
      return e.what();
    }
    return "not refused";
  };
  const long before = peak_kib();
  // A sparse 1,000 MB file: a valid 4x3 PNG, then zeros (stb_image would decode it).
  mpr::Image<mpr::Rgb8> image(4, 3);
  mpr::write_png(dir / "sparse.png", image.view());
  std::filesystem::resize_file(dir / "sparse.png", 1000ull << 20);
  CHECK_THAT(refused(dir / "sparse.png"), Catch::Contains("far larger than an image of 4x3"));
  CHECK_THROWS_WITH(mpr::read_image_info(dir / "sparse.png"), Catch::Contains("far larger"));
  // A sparse 1,000 MB file of zeros: no header in its first MiB.
  std::ofstream(dir / "zeros.png", std::ios::binary).close();
  std::filesystem::resize_file(dir / "zeros.png", 1000ull << 20);
  CHECK_THAT(refused(dir / "zeros.png"), Catch::Contains("cannot decode image") && Catch::Contains("zeros.png"));
  // Neither file was read whole (reading one takes 1,000 MB).
  CHECK(peak_kib() - before < 200 * 1024);
  // A file just within the bound for its size is read.
  std::filesystem::resize_file(dir / "sparse.png", 0);
  mpr::write_png(dir / "sparse.png", image.view());
  CHECK(mpr::read_rgb8(dir / "sparse.png").width() == 4);
  std::filesystem::remove_all(dir);
}
