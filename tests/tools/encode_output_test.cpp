// mpr-render's writer choice (tools/mpr-render/encode_output.hpp) on the renderer's linear
// frames: each format read back against the values run_linear rendered, float and double.
#include "mpr-render/encode_output.hpp"
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <mpr/io/file_write.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/pfm.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

namespace {
using mpr_tools_test::job_of;
using mpr_tools_test::temp_folder;

/// The linear frame mpr-render renders for `args`.
mpr::Image<mpr::Color> linear_frame(const std::vector<std::string>& args) {
  std::vector<mpr::Image<mpr::Color>> frames;
  mpr_cli::run_linear(job_of(args), [&](int, int, const mpr::Image<mpr::Color>& image) { frames.push_back(image); });
  REQUIRE(frames.size() == 1);
  return frames[0];
}

/// Writes `image` to `dir/name` as mpr-render does (encode_output, atomically).
std::filesystem::path written(const std::filesystem::path& dir, const std::string& name,
                              const mpr::Image<mpr::Color>& image, const mpr_cli::OutputEncoding& encoding = {}) {
  const std::filesystem::path path = dir / name;
  mpr::write_file_atomically(path, mpr_cli::encode_output(path, image, encoding));
  return path;
}
} // namespace

TEST_CASE("mpr-render: .pfm and .exr are recognised, --bit-depth and --exr-pixel checked", "[tools][output]") {
  using mpr_cli::ImageFormat;
  CHECK(mpr_cli::image_format("a.pfm") == ImageFormat::pfm);
  CHECK(mpr_cli::image_format("a.PFM") == ImageFormat::pfm);
  CHECK(mpr_cli::frame_path("x/anim.pfm", 2) == std::filesystem::path("x/anim_0003.pfm"));
  if (mpr_cli::exr_available()) {
    CHECK(mpr_cli::image_format("a.exr") == ImageFormat::exr);
    CHECK(job_of({"--output", "a.exr", "--exr-pixel", "float"}).encoding.exr_pixel == mpr_cli::ExrPixel::full);
    CHECK(job_of({"--output", "a.exr"}).encoding.exr_pixel == mpr_cli::ExrPixel::half);
  } else {
    CHECK_THROWS_WITH(mpr_cli::image_format("a.exr"), Catch::Contains("--output") && Catch::Contains("OpenEXR"));
  }
  CHECK(job_of({"--output", "a.png", "--bit-depth", "16"}).encoding.png_bits == 16);
  CHECK(job_of({"--output", "a.png"}).encoding.png_bits == 8);
  CHECK_THROWS_WITH(job_of({"--output", "a.png", "--bit-depth", "12"}),
                    Catch::Contains("--bit-depth: '12' is not 8 or 16"));
  CHECK_THROWS_WITH(job_of({"--output", "a.jpg", "--bit-depth", "16"}), Catch::Contains("--bit-depth: JPEG is 8-bit"));
  CHECK_THROWS_WITH(job_of({"--output", "a.pfm", "--bit-depth", "16"}), Catch::Contains("stores linear floats"));
  CHECK_THROWS_WITH(job_of({"--output", "a.png", "--exr-pixel", "float"}),
                    Catch::Contains("--exr-pixel: applies to .exr"));
}

TEMPLATE_TEST_CASE("mpr-render: each output format holds the render's linear values", "[tools][output]", float,
                   double) {
  std::vector<std::string> args{"--view", "G", "--size", "48x36", "--spp", "4"};
  if constexpr (std::is_same_v<TestType, double>) args.push_back("--double");
  const mpr::Image<mpr::Color> frame = linear_frame(args);
  const std::filesystem::path dir = temp_folder(std::string("encode_output_") + (sizeof(TestType) == 8 ? "d" : "f"));
  const int w = frame.width(), h = frame.height();

  // PFM: every float as rendered.
  const mpr::Image<mpr::Color> pfm = mpr::read_pfm_rgb(written(dir, "a.pfm", frame));
  REQUIRE((pfm.width() == w && pfm.height() == h));
  int same = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) same += (pfm(x, y) == frame(x, y)).all() ? 1 : 0;
  CHECK(same == w * h);

  // 8-bit PNG: the codes of mpr::to_rgb8, as the 8-bit run path (run) gives them.
  const mpr::Image<mpr::Rgb8> png8 = mpr::read_rgb8(written(dir, "a.png", frame));
  const mpr::Image<mpr::Rgb8> expected8 = mpr_cli::encode_rgb8(frame);
  int same8 = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) same8 += png8(x, y) == expected8(x, y) ? 1 : 0;
  CHECK(same8 == w * h);

#if defined(MPR_HAVE_LIBPNG)
  // 16-bit PNG: each code the rounded sRGB encoding of the clamped linear value.
  mpr_cli::OutputEncoding sixteen;
  sixteen.png_bits = 16;
  const mpr::Image<mpr::Rgb16> png16 = mpr::read_png16(written(dir, "b.png", frame, sixteen));
  REQUIRE((png16.width() == w && png16.height() == h));
  double worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::uint16_t codes[3] = {png16(x, y).r, png16(x, y).g, png16(x, y).b};
      for (int c = 0; c < 3; ++c) {
        const double v = std::clamp(static_cast<double>(frame(x, y)[c]), 0.0, 1.0);
        const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
        worst = std::max(worst, std::abs(codes[c] - 65535 * encoded));
      }
    }
  CHECK(worst <= 0.5 + 1e-6);
#endif
#if defined(MPR_HAVE_OPENEXR)
  // OpenEXR float: every float as rendered; half: within half's rounding (2^-11 relative).
  mpr_cli::OutputEncoding full;
  full.exr_pixel = mpr_cli::ExrPixel::full;
  const mpr::Image<mpr::Color> exr32 = mpr::read_exr(written(dir, "f.exr", frame, full));
  const mpr::Image<mpr::Color> exr16 = mpr::read_exr(written(dir, "h.exr", frame));
  int exact = 0, close = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      exact += (exr32(x, y) == frame(x, y)).all() ? 1 : 0;
      bool near = true;
      for (int c = 0; c < 3; ++c)
        near = near &&
               std::abs(exr16(x, y)[c] - frame(x, y)[c]) <= std::max(std::abs(frame(x, y)[c]) * 0x1p-11f, 0x1p-25f);
      close += near ? 1 : 0;
    }
  CHECK(exact == w * h);
  CHECK(close == w * h);
#endif
}
