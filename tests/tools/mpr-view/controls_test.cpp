#include "mpr-view/controls.hpp"

#include <catch2/catch.hpp>

#include <tuple>
#include <utility>

using mpr_view::Action;
using mpr_view::Button;

namespace {
mpr_view::ViewContext scene_context() {
  mpr_view::ViewContext ctx;
  ctx.plane_centre = {0, 3, 3};
  ctx.look_at = {0, 1, -8};
  ctx.plane_width = 8;
  ctx.plane_height = 6;
  return ctx;
}
} // namespace

TEST_CASE("gallery keys choose one view and remember the previous one", "[view]") {
  mpr_view::ViewState s;
  s.job.cols = s.job.rows = 3;
  s.job.views.assign(9, "A");
  const mpr_view::ViewContext ctx = scene_context();
  CHECK(mpr_view::on_key(s, ctx, "G") == Action::changed);
  CHECK((s.job.views == std::vector<std::string>{"G"} && s.job.cols == 1 && s.job.rows == 1));
  CHECK(mpr_view::on_key(s, ctx, "G") == Action::none);
  CHECK(mpr_view::on_key(s, ctx, "B") == Action::changed);
  CHECK(s.last_letter == 'G');
  CHECK(mpr_view::on_key(s, ctx, "M") == Action::changed);
  CHECK(s.job.morph_to == std::optional<std::string>("G"));
  CHECK(s.job.morph.at(0) == Approx(0.125));
  for (int i = 0; i < 7; ++i) (void)mpr_view::on_key(s, ctx, "M");
  CHECK(s.job.morph.at(0) == Approx(1));
  (void)mpr_view::on_key(s, ctx, "M");
  CHECK(s.job.morph.at(0) == 0); // wraps
  CHECK(mpr_view::on_key(s, ctx, "Escape") == Action::quit);
  CHECK(mpr_view::on_key(s, ctx, "S") == Action::save);
  CHECK(mpr_view::on_key(s, ctx, "F1") == Action::redraw);
  CHECK(s.help);
  CHECK(mpr_view::on_key(s, ctx, "K") == Action::none);
}

TEST_CASE("on an array, gallery keys take mpr-render's defaults for a letter unless the user chose", "[view]") {
  mpr_view::ViewContext ctx;
  ctx.light_field = true;
  ctx.letter_interpolation = mpr_cli::Interpolation::cylinder;
  ctx.letter_radius = mpr_cli::Track(4.5);
  mpr_view::ViewState s; // refocusing: the synthetic aperture, as mpr-render starts it
  s.job.interpolation = mpr_cli::Interpolation::synthetic;
  CHECK(mpr_view::on_key(s, ctx, "G") == Action::changed);
  CHECK(s.job.interpolation == mpr_cli::Interpolation::cylinder);
  CHECK(s.job.radius.at(0) == Approx(4.5));
  mpr_view::ViewState chosen;
  chosen.job.interpolation = mpr_cli::Interpolation::nearest;
  chosen.job.interpolation_given = true;
  CHECK(mpr_view::on_key(chosen, ctx, "G") == Action::changed);
  CHECK(chosen.job.interpolation == mpr_cli::Interpolation::nearest);
  mpr_view::ViewState scene; // scenes have no letter defaults
  scene.job.interpolation = mpr_cli::Interpolation::synthetic;
  CHECK(mpr_view::on_key(scene, scene_context(), "G") == Action::changed);
  CHECK(scene.job.interpolation == mpr_cli::Interpolation::synthetic);
}

TEST_CASE("scene drags orbit about the look-at point and pan the plane", "[view]") {
  mpr_view::ViewState s;
  const mpr_view::ViewContext ctx = scene_context();
  const double distance = (ctx.plane_centre - ctx.look_at).norm();
  CHECK(mpr_view::on_drag(s, ctx, Button::left, 30, 10, 320, 240) == Action::changed);
  REQUIRE(s.job.plane_centre);
  CHECK((*s.job.plane_centre - *s.job.look_at).norm() == Approx(distance));
  CHECK(*s.job.look_at == ctx.look_at);
  CHECK((*s.job.plane_centre - ctx.plane_centre).norm() > 0.1);
  const mpr::Vec3<double> before = *s.job.plane_centre, look = *s.job.look_at;
  CHECK(mpr_view::on_drag(s, ctx, Button::right, 32, 0, 320, 240) == Action::changed);
  const mpr::Vec3<double> moved = *s.job.plane_centre - before;
  CHECK(moved.norm() == Approx(0.8)); // 32 of 320 pixels of an 8-unit plane
  CHECK((*s.job.look_at - look - moved).norm() == Approx(0).margin(1e-12));
  CHECK(mpr_view::on_wheel(s, ctx, 2, false) == Action::changed); // dolly: no focus in a plain scene
  CHECK((*s.job.plane_centre - *s.job.look_at).norm() == Approx(distance * 0.81));
}

TEST_CASE("light fields: drags tilt, the wheel focuses, keys set the aperture", "[view]") {
  mpr_view::ViewState s;
  mpr_view::ViewContext ctx;
  ctx.light_field = true;
  ctx.focal_depth = 1000;
  CHECK(mpr_view::on_drag(s, ctx, Button::left, 50, 0, 320, 240) == Action::changed);
  CHECK(s.job.tilt_y.at(0) == Approx(10));
  CHECK_FALSE(s.job.plane_centre);
  CHECK(mpr_view::on_drag(s, ctx, Button::right, 50, 0, 320, 240) == Action::none);
  CHECK(mpr_view::on_drag(s, ctx, Button::left, 5000, 0, 320, 240) == Action::changed);
  CHECK(s.job.tilt_y.at(0) == 80); // clamped
  CHECK(mpr_view::on_wheel(s, ctx, 1, false) == Action::changed);
  CHECK(s.job.focal_depth->at(0) == Approx(1030));
  CHECK(mpr_view::on_wheel(s, ctx, 1, true) == Action::none); // no dolly: the plane is the camera's
  CHECK(mpr_view::on_key(s, ctx, "1") == Action::changed);
  CHECK(s.job.interpolation == mpr_cli::Interpolation::nearest);
  CHECK(mpr_view::on_key(s, ctx, "]") == Action::changed);
  CHECK(s.job.interpolation == mpr_cli::Interpolation::cylinder);
  CHECK(s.job.radius.at(0) == Approx(12.5));
  CHECK(mpr_view::on_key(s, ctx, "R") == Action::changed);
  CHECK(s.job.rectify_to_plane);
  CHECK(mpr_view::on_key(s, ctx, "R") == Action::changed);
  CHECK_FALSE(s.job.rectify_to_plane);
  CHECK(mpr_view::on_key(s, ctx, "T") == Action::changed);
  CHECK(s.job.tilt_y.at(0) == 0);
}

TEST_CASE("animation frames step within the job's frames", "[view]") {
  mpr_view::ViewState s;
  const mpr_view::ViewContext ctx = scene_context();
  CHECK(mpr_view::on_key(s, ctx, ".") == Action::none); // not an animation
  s.job.frames = 3;
  CHECK(mpr_view::on_key(s, ctx, ".") == Action::changed);
  CHECK(mpr_view::on_key(s, ctx, ".") == Action::changed);
  CHECK(mpr_view::on_key(s, ctx, ".") == Action::none);
  CHECK(s.time() == 1);
  CHECK(mpr_view::on_key(s, ctx, ",") == Action::changed);
  CHECK(s.time() == 0.5);
}

TEST_CASE("orbit_degrees: azimuth about up and elevation from the command line's plane, worked by hand", "[view]") {
  mpr_view::ViewContext ctx;
  ctx.plane_centre = {0, 0, 10};
  ctx.look_at = {0, 0, 0};
  mpr_view::ViewState s;                                                     // up (0, 1, 0)
  CHECK(mpr_view::orbit_degrees(s, ctx) == std::pair<double, double>{0, 0}); // no explicit plane yet
  s.job.look_at = mpr::Vec3<double>(0, 0, 0);
  // +z to +x: a quarter turn about +y, counter-clockwise seen from above (z x x = +y).
  s.job.plane_centre = mpr::Vec3<double>(10, 0, 0);
  auto [azimuth, elevation] = mpr_view::orbit_degrees(s, ctx);
  CHECK(azimuth == Approx(90));
  CHECK(elevation == Approx(0).margin(1e-12));
  s.job.plane_centre = mpr::Vec3<double>(0, 10, 10); // raised to 45 degrees, same azimuth
  std::tie(azimuth, elevation) = mpr_view::orbit_degrees(s, ctx);
  CHECK(azimuth == Approx(0).margin(1e-12));
  CHECK(elevation == Approx(45));
  // A pan moves both points: no orbit. A left drag of 40 pixels to the right: 40 x 0.3 degrees.
  s.job.plane_centre = mpr::Vec3<double>(3, 1, 10);
  s.job.look_at = mpr::Vec3<double>(3, 1, 0);
  std::tie(azimuth, elevation) = mpr_view::orbit_degrees(s, ctx);
  CHECK(azimuth == Approx(0).margin(1e-12));
  CHECK(elevation == Approx(0).margin(1e-12));
  mpr_view::ViewState d;
  CHECK(mpr_view::on_drag(d, ctx, Button::left, 40, 0, 320, 240) == Action::changed);
  std::tie(azimuth, elevation) = mpr_view::orbit_degrees(d, ctx);
  CHECK(azimuth == Approx(-12));
  CHECK(elevation == Approx(0).margin(1e-9));
  ctx.light_field = true; // light fields tilt; they never orbit
  CHECK(mpr_view::orbit_degrees(d, ctx) == std::pair<double, double>{0, 0});
}
