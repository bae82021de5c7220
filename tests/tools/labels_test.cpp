// mpr-render --labels (tools/mpr-render/labels.hpp): each tile carries its view, GLC type and
// focus, drawn with mpr::draw_label; checked against the unlabelled render with the expected
// text (written out here) drawn on it.
#include "mpr-render/labels.hpp"
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <mpr/core/label.hpp>

#include <array>
#include <string>
#include <vector>

using mpr_tools_test::job_of;

TEST_CASE("--labels: view, GLC type and focus in each tile's corner", "[cli][labels]") {
  using Image = mpr::Image<mpr::Rgb8>;
  std::vector<std::string> args{"--layout", "3x1", "--views",    "A,D,G",    "--size",  "200x150",
                                "--spp",    "4",   "--aperture", "disc:0.3", "--focus", "4,12"};
  const Image plain = mpr_cli::render_frames(job_of(args)).at(0);
  args.push_back("--labels");
  const Image labelled = mpr_cli::render_frames(job_of(args)).at(0);
  REQUIRE(!(labelled == plain));

  Image expected = plain;
  const char* types[] = {"A: pinhole", "D: pushbroom", "G: cross_slit"};
  const mpr::LabelStyle style{1}; // tiles narrower than 400 pixels: the small font
  for (int k = 0; k < 3; ++k) {
    const mpr::ImageView<mpr::Rgb8> tile = expected.view().subview(200 * k, 0, 200, 150);
    mpr::draw_label(tile, 2, 2, types[k], style);
    mpr::draw_label(tile, 2, 2 + 9, "focus: astigmatic at 4 and 12", style);
  }
  CHECK(labelled == expected);
}

TEST_CASE("tile_label without a lens, rectified views; wide tiles get the large font when it fits", "[cli][labels]") {
  const mpr_cli::Job job = job_of({"--view", "B", "--size", "16x12"});
  const mpr::PlanarSurface<double> plane({-4, -3, 0}, {8, 0, 0}, {0, 6, 0});
  const mpr::GlcSelector<double> ortho(plane, {0, 0, -1}, {0, 0, -1}, {0, 0, -1});
  const mpr_cli::CameraVariant<double> camera = mpr_cli::PlanarCamera<double>{plane, ortho};
  CHECK(mpr_cli::tile_label(job.views[0], camera, nullptr) == std::vector<std::string>{"B: orthographic"});
  CHECK(mpr_cli::tile_label("orthographic:0,-0.1,-1", camera, nullptr) == std::vector<std::string>{"orthographic"});
  const mpr_cli::CameraVariant<double> rectified =
      mpr::glc::rectify(plane, ortho,
                        std::array<mpr::Vec2<double>, 4>{mpr::Vec2<double>(0, 0), mpr::Vec2<double>(1, 0),
                                                         mpr::Vec2<double>(1, 1), mpr::Vec2<double>(0, 1)});
  CHECK(mpr_cli::tile_label("B", rectified, nullptr) == std::vector<std::string>{"B: orthographic (rectified)"});

  // 400 pixels wide: "B: orthographic" at twice the size; a line too long for it: all small.
  mpr::Image<mpr::Rgb8> image(400, 60), expected(400, 60);
  mpr_cli::draw_tile_label(image.view(), mpr::Region(0, 0, 400, 60), {"B: orthographic"});
  mpr::draw_label(expected.view(), 2, 2, "B: orthographic", mpr::LabelStyle{2});
  CHECK(image == expected);
  const std::string long_line(40, 'x'); // 40 characters: 480 pixels at twice the size
  image = mpr::Image<mpr::Rgb8>(400, 60);
  expected = mpr::Image<mpr::Rgb8>(400, 60);
  mpr_cli::draw_tile_label(image.view(), mpr::Region(0, 0, 400, 60), {"B: orthographic", long_line});
  mpr::draw_label(expected.view(), 2, 2, "B: orthographic", mpr::LabelStyle{1});
  mpr::draw_label(expected.view(), 2, 11, long_line, mpr::LabelStyle{1});
  CHECK(image == expected);
}
