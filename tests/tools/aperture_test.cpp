// mpr-render's --aperture, --lens-distance and --focus (tools/mpr-render/aperture.hpp), and the
// aperture opening over an animation.
#include "mpr-render/aperture.hpp"
#include "mpr-render/render_job.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <sstream>
#include <variant>

using mpr_tools_test::job_of;

TEST_CASE("--aperture SHAPE:SIZE, --lens-distance D and --focus D | DU,DV", "[cli][aperture]") {
  const mpr_cli::Job job =
      job_of({"--spp", "8", "--aperture", "polygon7:0.4", "--lens-distance", "3", "--focus", "2,5"});
  REQUIRE(job.aperture);
  CHECK(job.aperture->size.at(0) == 0.4);
  CHECK(job.aperture->size.at(1) == 0.4);
  CHECK(job.aperture->distance == 3.0);
  CHECK(job.aperture->focus == std::vector<double>{2, 5});
  const auto* polygon = std::get_if<mpr::glc::PolygonAperture>(&job.aperture->shape.variant());
  REQUIRE(polygon != nullptr);
  CHECK(polygon->blades() == 7);
  CHECK(std::holds_alternative<mpr::glc::DiscAperture>(mpr_cli::parse_aperture("disc:1").shape.variant()));
  CHECK(std::holds_alternative<mpr::glc::GaussianAperture>(mpr_cli::parse_aperture("gaussian:1").shape.variant()));
  CHECK(std::holds_alternative<mpr::glc::SquareAperture>(mpr_cli::parse_aperture("square:0").shape.variant()));
  // The focus matrix: anastigmatic at D, astigmatic at DU, DV, as classify_focus reads it back.
  mpr_cli::ApertureSpec spec = mpr_cli::parse_aperture("disc:0.2");
  spec.distance = 4;
  spec.focus = {6};
  auto f = mpr::glc::classify_focus(mpr_cli::focus_matrix<double>(spec, 4.0), 4.0);
  CHECK(f.type == mpr::glc::FocusType::anastigmatic);
  CHECK(f.depths[0] == Approx(6));
  spec.focus = {2, 5};
  f = mpr::glc::classify_focus(mpr_cli::focus_matrix<double>(spec, 4.0), 4.0);
  CHECK(f.type == mpr::glc::FocusType::astigmatic);
  CHECK(f.depths[1] == Approx(5));
  const mpr::PlanarSurface<double> plane({-4, -3, 0}, {8, 0, 0}, {0, 6, 0});
  std::ostringstream out;
  mpr_cli::print_focus(out, spec, plane);
  CHECK(out.str() == "  focus: astigmatic, focal lines at depths 2 and 5 (aperture size 0.2, lens plane 4 behind the "
                     "image plane)\n");
}

TEST_CASE("bad --aperture and --focus: one error naming the option", "[cli][aperture]") {
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc:-0.2"}),
                    Catch::Contains("--aperture") && Catch::Contains("negative"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc:0=0,1=-1", "--frames", "2"}),
                    Catch::Contains("--aperture") && Catch::Contains("size -1 is negative"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc:0.2", "--lens-distance", "0"}),
                    Catch::Contains("--lens-distance") && Catch::Contains("must be positive"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc:0.2", "--lens-distance", "-2"}),
                    Catch::Contains("--lens-distance"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--lens-distance", "2"}),
                    Catch::Contains("--lens-distance") && Catch::Contains("needs --aperture"));
  // SHAPE:A:B is a size animated from A to B: without --frames it is refused, naming --aperture.
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc:0.2:4"}),
                    Catch::Contains("--aperture") && Catch::Contains("--frames N"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc:0.2:4:5", "--frames", "2"}),
                    Catch::Contains("--aperture"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "hexagon:1"}), Catch::Contains("'hexagon' is not disc"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "polygon2:1"}), Catch::Contains("--aperture"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc"}), Catch::Contains("SHAPE:SIZE"));
  CHECK_THROWS_WITH(job_of({"--aperture", "disc:0.2"}), Catch::Contains("needs --spp"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--focus", "3"}), Catch::Contains("needs --aperture"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc:1", "--focus", "1,2,3"}), Catch::Contains("D or DU,DV"));
  mpr_cli::ApertureSpec behind = mpr_cli::parse_aperture("disc:0.2");
  behind.distance = 1;
  behind.focus = {-3};
  CHECK_THROWS_WITH(mpr_cli::focus_matrix<double>(behind, 1.0),
                    Catch::Contains("--focus") && Catch::Contains("in front of the lens plane"));
}

TEST_CASE("--aperture SHAPE:A:B and keyframes open the aperture over an animation", "[cli][aperture]") {
  mpr_cli::Job job = job_of({"--spp", "4", "--aperture", "disc:0:0.5", "--frames", "3"});
  CHECK(mpr_cli::animated_option(job) == "--aperture");
  const double sizes[] = {0, 0.25, 0.5};
  for (int f = 0; f < 3; ++f)
    CHECK(mpr_cli::frame_params(job, 1, mpr_cli::frame_time(f, 3)).aperture_size == Approx(sizes[f]));
  job = job_of({"--spp", "4", "--aperture", "square:0=0,0.5=1,1=0", "--frames", "5"});
  CHECK(mpr_cli::frame_params(job, 1, 0.25).aperture_size == Approx(0.5));
  CHECK(mpr_cli::frame_params(job, 1, 0.5).aperture_size == Approx(1));
  CHECK(mpr_cli::frame_params(job, 1, 1).aperture_size == 0);
  // A constant size is no animation.
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc:0.3:0.3", "--frames", "2"}),
                    Catch::Contains("--frames") && Catch::Contains("nothing is animated"));
}

TEST_CASE("the aperture-opening animation: each frame is the still render at that frame's size", "[cli][aperture]") {
  using Image = mpr::Image<mpr::Rgb8>;
  const std::vector<std::string> base{"--view", "G", "--size", "24x18", "--spp", "4", "--focus", "9"};
  const auto render = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.begin() + 6, extra.begin(), extra.end()); // before --focus
    return mpr_cli::render_frames(job_of(args));
  };
  const std::vector<Image> frames = render({"--aperture", "disc:0:0.5", "--frames", "3"});
  REQUIRE(frames.size() == 3);
  CHECK(frames[1] == render({"--aperture", "disc:0.25"}).at(0));
  CHECK(frames[2] == render({"--aperture", "disc:0.5"}).at(0));
  // Size 0 is the pinhole: the same image as the same samples without a lens.
  const std::vector<Image> pinhole = mpr_cli::render_frames(job_of({"--view", "G", "--size", "24x18", "--spp", "4"}));
  CHECK(frames[0] == pinhole.at(0));
  CHECK(!(frames[2] == frames[0])); // the open aperture blurs what lies off the focal plane
}

TEST_CASE("rays parallel to the image plane cross no focal plane: refused naming the option", "[cli][aperture]") {
  // Double precision accepts this corner direction (1e-8 along the normal), the lens does not.
  const std::vector<std::string> view{"--double", "--view",     "corners:1,0,-1e-8:0.3,-0.1,-1:-0.3,-0.5,-1",
                                      "--size",   "8x6",        "--spp",
                                      "4",        "--aperture", "disc:0.1"};
  const auto message = [](std::vector<std::string> args) -> std::string {
    try {
      (void)mpr_cli::render_frames(job_of(args));
    } catch (const mpr::argument_error& e) {
      return e.what();
    }
    return "no error";
  };
  CHECK_THAT(message(view), Catch::StartsWith("mpr: invalid --aperture: ") && Catch::Contains("parallel"));
  std::vector<std::string> focused = view;
  focused.insert(focused.end(), {"--focus", "3"});
  CHECK_THAT(message(focused), Catch::StartsWith("mpr: invalid --focus: ") && Catch::Contains("cross no focal plane"));
  // In an animation, the frame that fails is named before any is rendered (preflight).
  CHECK_THAT(message({"--double", "--view", "A", "--morph-to", "corners:1,0,-1e-8:0.3,-0.1,-1:-0.3,-0.5,-1", "--frames",
                      "3", "--size", "8x6", "--spp", "4", "--aperture", "disc:0.1"}),
             Catch::Contains("--aperture") && Catch::Contains("frame 2 of 3") &&
                 Catch::Contains("nothing was written"));
}
