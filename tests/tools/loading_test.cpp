// mpr-render's loading (tools/mpr-render/loading.hpp): the default framing of an OBJ scene, and
// the camera a _par.txt light field is viewed from.
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

namespace {
using mpr_tools_test::job_of;
} // namespace

TEST_CASE("mpr-render: a _par.txt light field is viewed from its middle camera, or from --camera", "[tools][loading]") {
  // Three cameras on the x axis, centres at x = -0.1, 0, 0.1 (file order).
  const std::filesystem::path dir = mpr_tools_test::plane_light_field("loading_reference", 2.0f);
  const std::string par = (dir / "tiny_par.txt").string();
  const mpr_cli::Loaded<float> middle = mpr_cli::load<float>(job_of({"--par", par, "--focal-depth", "2"}));
  REQUIRE(middle.frames);
  REQUIRE(middle.reference);
  CHECK(middle.reference->centre().isApprox(middle.frames->camera(1).centre()));
  CHECK(middle.reference->centre().x() == Approx(0).margin(1e-6));
  const mpr_cli::Loaded<float> last =
      mpr_cli::load<float>(job_of({"--par", par, "--focal-depth", "2", "--camera", "2"}));
  REQUIRE(last.reference);
  CHECK(last.reference->centre().x() == Approx(0.1).margin(1e-6));
}

#ifdef MPR_HAVE_TINYOBJLOADER

TEST_CASE("mpr-render: an OBJ is framed from above at an angle by default", "[tools][loading]") {
  // examples/boxes.obj: an 8 x 8 ground square at y = 0 and three boxes up to 2 high.
  const std::string obj = std::string(MPR_TEST_SOURCE_DIR) + "/examples/boxes.obj";
  const mpr_cli::Job job = job_of({"--obj", obj, "--size", "64x48"});
  const mpr_cli::Loaded<float> l = mpr_cli::load<float>(job);
  // Looking at the bounding box's centre from 30 degrees above the horizontal.
  CHECK(l.look_at.isApprox(mpr::Vec3<double>(0, 1, 0)));
  const mpr::Vec3<double> from = (l.plane_centre - l.look_at).normalized();
  CHECK(std::asin(from.y()) * 180 / std::numbers::pi == Approx(30));
  CHECK(from.x() == Approx(0).margin(1e-12));

  // The ground shows as a surface: before (a level side view) it was a one-pixel line, under
  // 3% of the image; now it covers about a fifth. Ground pixels are the greenish ones (the
  // background is pale blue, the boxes red, blue and yellow).
  const std::vector<mpr::Image<mpr::Rgb8>> frames = mpr_cli::render_frames(job);
  REQUIRE(frames.size() == 1);
  int ground = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const mpr::Rgb8 p = frames[0](x, y);
      ground += (p.g > p.r + 8 && p.g > p.b + 8) ? 1 : 0;
    }
  INFO(ground << " ground pixels of " << 64 * 48);
  CHECK(ground > 64 * 48 / 8);
}

#endif
