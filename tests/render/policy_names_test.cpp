#include <mpr/render/policy_names.hpp>

#include <catch2/catch.hpp>

#include <string>
#include <variant>

TEST_CASE("policy names: each name selects its value, aliases are accepted but not listed", "[policy_names]") {
  CHECK(mpr::choose(mpr::interpolation_names, "nearest", "p") == mpr::InterpolationChoice::nearest);
  CHECK(mpr::choose(mpr::interpolation_names, "synthetic", "p") == mpr::InterpolationChoice::synthetic);
  CHECK(mpr::choose(mpr::interpolation_names, "synthetic_aperture", "p") == mpr::InterpolationChoice::synthetic);
  CHECK(mpr::choose(mpr::interpolation_names, "depth", "p") == mpr::InterpolationChoice::depth);
  CHECK(mpr::choice_name(mpr::interpolation_names, mpr::InterpolationChoice::synthetic) == "synthetic");
  CHECK(mpr::choice_name(mpr::interpolation_names, mpr::InterpolationChoice::cylinder) == "cylinder");
  CHECK(mpr::choose(mpr::filter_names, "triangle", "p") == mpr::FilterChoice::tent);
  CHECK(mpr::choose(mpr::neighbour_selection_names, "nearest", "p") == mpr::NeighbourSelection::nearest);
  CHECK(mpr::choose(mpr::neighbour_selection_names, "axes", "p") == mpr::NeighbourSelection::axes);
  // The messages the front ends print (mpr-render's, kept word for word).
  CHECK_THROWS_WITH(mpr::choose(mpr::interpolation_names, "linear", "--interp"),
                    "mpr: invalid --interp: 'linear' is not nearest, synthetic, cylinder or depth");
  CHECK_THROWS_WITH(mpr::choose(mpr::filter_names, "sinc", "--filter"),
                    "mpr: invalid --filter: 'sinc' is not box, tent, gaussian, mitchell or lanczos");
  CHECK_THROWS_WITH(mpr::choose(mpr::neighbour_selection_names, "all", "selection"),
                    "mpr: invalid selection: 'all' is not axes or nearest");
  CHECK_THROWS_AS(mpr::choose(mpr::filter_names, "", "--filter"), mpr::argument_error);
}

TEST_CASE("policy names: filters take pbrt-v4's default radii unless one is given", "[policy_names]") {
  CHECK(mpr::make_filter(mpr::FilterChoice::box).radius() == 0.5);
  CHECK(mpr::make_filter(mpr::FilterChoice::tent).radius() == 2);
  CHECK(mpr::make_filter(mpr::FilterChoice::gaussian).radius() == 1.5);
  CHECK(mpr::make_filter(mpr::FilterChoice::mitchell).radius() == 2);
  CHECK(mpr::make_filter(mpr::FilterChoice::lanczos).radius() == 4);
  CHECK(mpr::make_filter(mpr::FilterChoice::lanczos, 3).radius() == 3);
  CHECK(std::holds_alternative<mpr::MitchellFilter>(mpr::make_filter(mpr::FilterChoice::mitchell).variant()));
}

TEST_CASE("policy names: aperture shapes, polygons by blade count", "[policy_names]") {
  CHECK(std::holds_alternative<mpr::glc::DiscAperture>(mpr::aperture_by_name("disc", "a").variant()));
  CHECK(std::holds_alternative<mpr::glc::SquareAperture>(mpr::aperture_by_name("square", "a").variant()));
  CHECK(std::holds_alternative<mpr::glc::GaussianAperture>(mpr::aperture_by_name("gaussian", "a").variant()));
  const auto polygon = mpr::aperture_by_name("polygon64", "a");
  REQUIRE(std::holds_alternative<mpr::glc::PolygonAperture>(polygon.variant()));
  CHECK(std::get<mpr::glc::PolygonAperture>(polygon.variant()).blades() == 64);
  CHECK_THROWS_WITH(mpr::aperture_by_name("hexagon", "--aperture"),
                    "mpr: invalid --aperture: 'hexagon' is not disc, square, gaussian or polygonN (N = 3..64)");
  CHECK_THROWS_WITH(mpr::aperture_by_name("polygon2", "--aperture"), "mpr: invalid --aperture: 2 is outside [3, 64]");
  CHECK_THROWS_WITH(mpr::aperture_by_name("polygon6x", "--aperture"),
                    "mpr: invalid --aperture: '6x' is not an integer");
  CHECK_THROWS_AS(mpr::aperture_by_name("polygon", "--aperture"), mpr::argument_error);
}
