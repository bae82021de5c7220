// mpr-render's output files (tools/mpr-render/output.hpp): format by extension, stale frames of
// an earlier run, the ffmpeg command.
#include "mpr-render/output.hpp"
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <unistd.h>

namespace {
using mpr_tools_test::temp_folder;
} // namespace

TEST_CASE("mpr-render: the output format follows the extension", "[tools][output]") {
  using mpr_cli::ImageFormat;
  CHECK(mpr_cli::image_format("a/b.png") == ImageFormat::png);
  CHECK(mpr_cli::image_format("b.PNG") == ImageFormat::png);
  CHECK(mpr_cli::image_format("/dev/full") == ImageFormat::png);
  CHECK(mpr_cli::image_format("b.jpg") == ImageFormat::jpeg);
  CHECK(mpr_cli::image_format("b.JPEG") == ImageFormat::jpeg);
  CHECK_THROWS_WITH(mpr_cli::image_format("b.bmp"), Catch::Contains("--output") && Catch::Contains("'.bmp'"));
  CHECK_THROWS_WITH(mpr_cli::image_format("b.png.tif"), Catch::Contains("--output"));
  CHECK(mpr_cli::frame_path("x/anim.jpg", 0) == std::filesystem::path("x/anim_0001.jpg"));
  CHECK(mpr_cli::frame_path("x/anim.png", 11) == std::filesystem::path("x/anim_0012.png"));
  CHECK(mpr_cli::frame_path("x/anim", 0) == std::filesystem::path("x/anim_0001.png"));
}

TEST_CASE("mpr-render: stale frames of a longer run are found and removed", "[tools][output]") {
  const std::filesystem::path dir = temp_folder("stale");
  for (const char* name : {"a_0001.png", "a_0002.png", "a_0003.png", "a_0004.png", "a_12345.png", "a_0005.jpg",
                           "b_0009.png", "a_0009x.png", "a_009.png", "notes.txt"})
    std::ofstream(dir / name) << "x";
  const std::vector<std::filesystem::path> stale = mpr_cli::stale_frames(dir / "a.png", 2);
  REQUIRE(stale.size() == 2); // 3 and 4 continue this run's numbers; 12345 was not written by a run of 4
  CHECK(stale[0].filename() == "a_0003.png");
  CHECK(stale[1].filename() == "a_0004.png");
  CHECK(mpr_cli::remove_stale_frames(dir / "a.png", 2) == 2);
  CHECK(std::filesystem::exists(dir / "a_0002.png"));
  CHECK_FALSE(std::filesystem::exists(dir / "a_0003.png"));
  CHECK(std::filesystem::exists(dir / "a_12345.png"));
  CHECK(std::filesystem::exists(dir / "a_0005.jpg")); // another format, another animation
  CHECK(std::filesystem::exists(dir / "b_0009.png"));
  CHECK(std::filesystem::exists(dir / "a_0009x.png"));
  CHECK(mpr_cli::stale_frames(dir / "a.jpg", 4).size() == 1);
  CHECK(mpr_cli::stale_frames(dir / "missing" / "a.png", 1).empty());
  std::filesystem::remove_all(dir);
}

TEST_CASE("mpr-render: the ffmpeg command bounds the frames and sets the rate", "[tools][output]") {
  const std::string cmd = mpr_cli::ffmpeg_command("out/it's.png", 7, 24);
  CHECK_THAT(cmd, Catch::Contains("-framerate 24 ") && Catch::Contains("-frames:v 7 ") &&
                      Catch::Contains("-start_number 1 ") && Catch::Contains("'out/it'\\''s_%04d.png'") &&
                      Catch::EndsWith("'out/it'\\''s.mp4'"));
  CHECK_THAT(mpr_cli::ffmpeg_command("a.jpg", 2, 12.5),
             Catch::Contains("-framerate 12.5 ") && Catch::Contains("'a_%04d.jpg'"));
}

TEST_CASE("mpr-render: --fps is validated", "[tools][output]") {
  const auto job_of = [](std::vector<std::string> args) {
    std::vector<const char*> argv{"mpr-render"};
    for (const std::string& a : args) argv.push_back(a.c_str());
    return mpr_cli::parse_job(static_cast<int>(argv.size()), argv.data());
  };
  CHECK(job_of({"--tilt-x", "0:1", "--frames", "2"}).fps == 12);
  CHECK(job_of({"--tilt-x", "0:1", "--frames", "2", "--fps", "30"}).fps == 30);
  CHECK_THROWS_WITH(job_of({"--tilt-x", "0:1", "--frames", "2", "--fps", "0"}), Catch::Contains("--fps"));
  CHECK_THROWS_WITH(job_of({"--tilt-x", "0:1", "--frames", "2", "--fps", "x"}), Catch::Contains("--fps"));
  CHECK_THROWS_WITH(job_of({"--fps", "24"}), Catch::Contains("--fps") && Catch::Contains("--frames"));
  CHECK_THROWS_WITH(job_of({"--output", "x.gif"}), Catch::Contains("--output"));
}

TEST_CASE("mpr-render: a file that only looks like a frame is never removed as stale", "[tools][output]") {
  // Issue 48: IMG_0042.png of a camera beside --output IMG.png --frames 2 was deleted.
  const std::filesystem::path dir = temp_folder("stale_camera");
  for (const char* name : {"IMG_0001.png", "IMG_0002.png", "IMG_0042.png", "IMG_0043.png"})
    std::ofstream(dir / name) << "x";
  CHECK(mpr_cli::stale_frames(dir / "IMG.png", 2).empty());
  CHECK(mpr_cli::remove_stale_frames(dir / "IMG.png", 2) == 0);
  CHECK(std::filesystem::exists(dir / "IMG_0042.png"));
  CHECK(std::filesystem::exists(dir / "IMG_0043.png"));
  std::filesystem::remove_all(dir);
}
