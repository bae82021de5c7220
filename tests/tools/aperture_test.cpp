// mpr-render's --aperture and --focus (tools/mpr-render/aperture.hpp).
#include "mpr-render/aperture.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <sstream>
#include <variant>

using mpr_tools_test::job_of;

TEST_CASE("--aperture SHAPE:SIZE[:DISTANCE] and --focus D | DU,DV", "[cli][aperture]") {
  const mpr_cli::Job job = job_of({"--spp", "8", "--aperture", "polygon7:0.4:3", "--focus", "2,5"});
  REQUIRE(job.aperture);
  CHECK(job.aperture->size == 0.4);
  CHECK(job.aperture->distance == 3.0);
  CHECK(job.aperture->focus == std::vector<double>{2, 5});
  const auto* polygon = std::get_if<mpr::glc::PolygonAperture>(&job.aperture->shape.variant());
  REQUIRE(polygon != nullptr);
  CHECK(polygon->blades() == 7);
  CHECK(std::holds_alternative<mpr::glc::DiscAperture>(mpr_cli::parse_aperture("disc:1").shape.variant()));
  CHECK(std::holds_alternative<mpr::glc::GaussianAperture>(mpr_cli::parse_aperture("gaussian:1").shape.variant()));
  CHECK(std::holds_alternative<mpr::glc::SquareAperture>(mpr_cli::parse_aperture("square:0").shape.variant()));
  // The focus matrix: anastigmatic at D, astigmatic at DU, DV, as classify_focus reads it back.
  mpr_cli::ApertureSpec spec = mpr_cli::parse_aperture("disc:0.2:4");
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
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc:0.2:0"}), Catch::Contains("distance 0"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "hexagon:1"}), Catch::Contains("'hexagon' is not disc"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "polygon2:1"}), Catch::Contains("--aperture"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc"}), Catch::Contains("SHAPE:SIZE"));
  CHECK_THROWS_WITH(job_of({"--aperture", "disc:0.2"}), Catch::Contains("needs --spp"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--focus", "3"}), Catch::Contains("needs --aperture"));
  CHECK_THROWS_WITH(job_of({"--spp", "4", "--aperture", "disc:1", "--focus", "1,2,3"}), Catch::Contains("D or DU,DV"));
  mpr_cli::ApertureSpec behind = mpr_cli::parse_aperture("disc:0.2:1");
  behind.focus = {-3};
  CHECK_THROWS_WITH(mpr_cli::focus_matrix<double>(behind, 1.0),
                    Catch::Contains("--focus") && Catch::Contains("in front of the lens plane"));
}
