// mpr-render's loading (tools/mpr-render/loading.hpp): the default framing of an OBJ scene, the
// camera a _par.txt light field is viewed from, COLMAP models and HCI scenes.
#include "io/light_field_test_files.hpp"
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
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

TEST_CASE("mpr-render: --colmap loads the same array as --par and renders the same image", "[tools][loading][colmap]") {
  // The three cameras of plane_light_field (R = I, f = 8, principal point (3.5, 2.5) in mpr's
  // convention, (4, 3) in COLMAP's) written as PROJECT/sparse/0 beside PROJECT/images.
  const std::filesystem::path dir = mpr_tools_test::plane_light_field("loading_colmap", 2.0f);
  const std::filesystem::path project = mpr_tools_test::temp_folder("loading_colmap_project");
  const std::filesystem::path model = project / "sparse" / "0", images = project / "images";
  std::filesystem::create_directories(model);
  std::filesystem::create_directories(images);
  std::ofstream(model / "cameras.txt") << "# CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]\n1 PINHOLE 8 6 8 8 4 3\n";
  std::ofstream ims(model / "images.txt");
  for (int i = 0; i < 3; ++i) {
    const std::string name = "view" + std::to_string(i) + ".png";
    std::filesystem::copy_file(dir / name, images / name, std::filesystem::copy_options::overwrite_existing);
    ims << i + 1 << " 1 0 0 0 " << -0.1 * (i - 1) << " 0 0 1 " << name << "\n\n";
  }
  ims.close();

  const std::string par = (dir / "tiny_par.txt").string();
  const mpr_cli::Loaded<float> a = mpr_cli::load<float>(job_of({"--par", par, "--focal-depth", "2"}));
  const mpr_cli::Loaded<float> b = mpr_cli::load<float>(job_of({"--colmap", model.string(), "--focal-depth", "2"}));
  REQUIRE(b.frames);
  REQUIRE(b.frames->size() == 3);
  REQUIRE(b.reference);
  CHECK(b.reference->centre().isApprox(a.reference->centre()));
  CHECK(b.reference->K().isApprox(a.reference->K()));
  // The default focus, the depth of the cameras' mean centre, is 0 here: both refuse it alike.
  CHECK_THROWS_WITH(mpr_cli::load<float>(job_of({"--colmap", model.string()})),
                    Catch::Matchers::Contains("--focal-depth"));
  CHECK_THROWS_WITH(mpr_cli::load<float>(job_of({"--par", par})), Catch::Matchers::Contains("--focal-depth"));
  const std::vector<mpr::Image<mpr::Rgb8>> pa = mpr_cli::render_frames(job_of({"--par", par, "--focal-depth", "2"}));
  const std::vector<mpr::Image<mpr::Rgb8>> pb =
      mpr_cli::render_frames(job_of({"--colmap", model.string(), "--focal-depth", "2"}));
  REQUIRE(pa.size() == 1);
  REQUIRE(pb.size() == 1);
  REQUIRE(pa[0].width() == pb[0].width());
  REQUIRE(pa[0].height() == pb[0].height());
  int differ = 0;
  for (int y = 0; y < pa[0].height(); ++y)
    for (int x = 0; x < pa[0].width(); ++x) differ += pa[0](x, y) == pb[0](x, y) ? 0 : 1;
  CHECK(differ == 0);

  // --colmap-images names the folder; without one beside the model the error says how to give it.
  const mpr_cli::Loaded<float> c = mpr_cli::load<float>(
      job_of({"--colmap", model.string(), "--colmap-images", images.string(), "--focal-depth", "2"}));
  CHECK(c.frames->size() == 3);
  std::filesystem::remove_all(images);
  CHECK_THROWS_WITH(mpr_cli::load<float>(job_of({"--colmap", model.string(), "--focal-depth", "2"})),
                    Catch::Matchers::Contains("--colmap-images"));
  CHECK_THROWS_WITH(job_of({"--par", par, "--colmap-images", dir.string()}),
                    Catch::Matchers::Contains("applies to --colmap only"));
}

TEST_CASE("mpr-render: --hci views the centre camera focused on the zero-disparity plane",
          "[tools][loading][real_data]") {
  const std::filesystem::path root = mpr_test::data_dir();
  const std::filesystem::path scene = root / "hci" / "backgammon";
  if (root.empty() || !std::filesystem::is_directory(scene)) {
    WARN("real data not found under '" << root.string() << "' (set MPR_DATA_DIR): skipped");
    return;
  }
  const mpr_cli::Loaded<float> l = mpr_cli::load<float>(job_of({"--hci", scene.string()}));
  const mpr::HciLightField<float> lf = mpr::read_hci_light_field<float>(scene);
  REQUIRE(l.frames);
  CHECK(l.frames->size() == lf.frames.size());
  REQUIRE(l.reference);
  CHECK(l.reference->centre().isApprox(lf.frames.camera(lf.centre).centre()));
  // Disparity units (no parameters.cfg): f = width, B = 1, s = 10, so the zero-disparity plane
  // lies at depth 512 / 10.
  CHECK(l.default_focal_depth == Approx(lf.disparity.depth(0)));
  CHECK(l.default_focal_depth == Approx(51.2));
  // Another camera keeps the focus (the benchmark's plane, not the Stanford reference depth).
  const mpr_cli::Loaded<float> corner = mpr_cli::load<float>(job_of({"--hci", scene.string(), "--camera", "0"}));
  CHECK(corner.reference->centre().isApprox(lf.frames.camera(0).centre()));
  CHECK(corner.default_focal_depth == Approx(51.2));
}
