#include "mpr-view/command_line.hpp"
#include "mpr-view/controls.hpp"
#include "tools/tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace {
mpr_cli::Job job_of(std::vector<std::string> args) {
  std::vector<const char*> argv{"mpr-render"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  return mpr_cli::parse_job(static_cast<int>(argv.size()), argv.data());
}

/// The command line of `job` parsed back by mpr-render's parser.
mpr_cli::Job round_trip(const mpr_cli::Job& job, double time = 0) {
  return job_of(mpr_view::render_arguments(job, time, 64, 48, "out.png"));
}
} // namespace

TEST_CASE("render_arguments reads back as the same view", "[view]") {
  mpr_view::ViewContext ctx;
  ctx.plane_centre = {0, 3.1, 3};
  ctx.look_at = {0, 1.6, -8};
  ctx.plane_width = 8;
  ctx.plane_height = 6;
  mpr_view::ViewState s;
  s.job = job_of({"--view", "A", "--size", "64x48", "--threads", "2"});
  // A view found by hand: gallery G, orbited and panned, tilted, rectified, morphed.
  CHECK(mpr_view::on_key(s, ctx, "G") == mpr_view::Action::changed);
  CHECK(mpr_view::on_drag(s, ctx, mpr_view::Button::left, 13, -7, 64, 48) == mpr_view::Action::changed);
  CHECK(mpr_view::on_drag(s, ctx, mpr_view::Button::right, 5, 3, 64, 48) == mpr_view::Action::changed);
  CHECK(mpr_view::on_key(s, ctx, "Up") == mpr_view::Action::changed);
  CHECK(mpr_view::on_key(s, ctx, "R") == mpr_view::Action::changed);
  CHECK(mpr_view::on_key(s, ctx, "M") == mpr_view::Action::changed);
  const mpr_cli::Job back = round_trip(s.job);
  CHECK(back.views == std::vector<std::string>{"G"});
  CHECK(*back.plane_centre == *s.job.plane_centre); // exact: shortest round-trip numbers
  CHECK(*back.look_at == *s.job.look_at);
  CHECK(back.plane_size == s.job.plane_size);
  CHECK(back.tilt_x.at(0) == s.job.tilt_x.at(0));
  CHECK(back.rectify_to_plane);
  CHECK(back.morph_to == std::optional<std::string>("A"));
  CHECK(back.morph.at(0) == s.job.morph.at(0));
  CHECK(back.threads == 2);
  CHECK((back.width == 64 && back.height == 48));
  CHECK(back.output == "out.png");
  CHECK(mpr_view::render_arguments(back, 0, 64, 48, "out.png") ==
        mpr_view::render_arguments(s.job, 0, 64, 48, "out.png"));
}

TEST_CASE("render_arguments writes animated values at the frame's time and keeps light-field options", "[view]") {
  const mpr_cli::Job job = job_of({"--raster", "4x3", "--raster-samples", "3", "--interp", "cylinder", "--radius",
                                   "2:4", "--focal-depth", "5", "--tilt-y", "0:10", "--layout", "2x1", "--views",
                                   "A,pinhole:0;1.6;10", "--frames", "3", "--double"});
  const mpr_cli::Job back = round_trip(job, 0.5);
  CHECK(back.frames == 0); // one image
  CHECK(back.radius.at(0) == 3);
  CHECK(back.tilt_y.at(0) == 5);
  CHECK(back.focal_depth->at(0) == 5);
  CHECK(back.interpolation == mpr_cli::Interpolation::cylinder);
  CHECK(back.raster == std::optional<std::pair<int, int>>({4, 3}));
  CHECK(back.raster_samples == 3);
  CHECK((back.cols == 2 && back.rows == 1));
  CHECK(back.views == std::vector<std::string>{"A", "pinhole:0,1.6,10"});
  CHECK(back.use_double);
}

TEST_CASE("render_arguments keeps the depth interpolation's depth maps and settings", "[view]") {
  const std::filesystem::path dir = mpr_tools_test::textured_plane_light_field("view_depth_arguments", 2.3);
  const std::string par = (dir / "tiny_par.txt").string();
  const mpr_cli::Job job =
      job_of({"--par", par, "--interp", "depth", "--depth-maps", "estimate:1:4:16", "--sweep", "best=1,spatial=3",
              "--proxy", "k=2,visibility_tolerance=0.05", "--focal-depth", "1.5"});
  const mpr_cli::Job back = round_trip(job);
  REQUIRE(back.depth_estimate.has_value());
  CHECK(back.depth_estimate->planes == 16);
  CHECK(back.depth_estimate->best == 1);
  CHECK(back.depth_estimate->spatial == 3);
  CHECK(back.proxy.k == 2);
  CHECK(back.proxy.visibility_tolerance == 0.05);
  // Under another interpolation (the viewer keeps depth maps for click-to-focus) none of them is
  // written: mpr-render would refuse depth maps that nothing reads.
  mpr_cli::Job cylinder = job;
  cylinder.interpolation = mpr_cli::Interpolation::cylinder;
  const std::vector<std::string> a = mpr_view::render_arguments(cylinder, 0, 64, 48, "out.png");
  for (const char* option : {"--depth-maps", "--sweep", "--proxy"}) {
    INFO(option);
    CHECK(std::find(a.begin(), a.end(), option) == a.end());
  }
  CHECK_NOTHROW(job_of(a));
  // A --prefilter factor is kept; auto (the default) is not written, mpr-render's default too.
  CHECK(round_trip(job_of({"--par", par, "--prefilter", "1"})).prefilter == 1);
  const std::vector<std::string> plain = mpr_view::render_arguments(job_of({"--par", par}), 0, 64, 48, "out.png");
  CHECK(std::find(plain.begin(), plain.end(), "--prefilter") == plain.end());
  std::filesystem::remove_all(dir);
}

TEST_CASE("render_command quotes what a shell would split", "[view]") {
  const mpr_cli::Job job = job_of({"--view", "A"});
  const std::string line = mpr_view::render_command(job, 0, 8, 6, "my views/it's.png");
  CHECK(line == "mpr-render --size 8x6 --view A --output 'my views/it'\\''s.png'");
}

TEST_CASE("render_arguments keeps --spp, --filter, --aperture, --lens-distance and --focus", "[view]") {
  const mpr_cli::Job job = job_of({"--view", "G", "--size", "64x48", "--spp", "8", "--filter", "mitchell:1.5",
                                   "--aperture", "polygon6:0.4", "--lens-distance", "12", "--focus", "4,12"});
  const std::vector<std::string> args = mpr_view::render_arguments(job, 0, 64, 48, "out.png");
  const auto value_of = [&](const std::string& option) {
    const auto it = std::find(args.begin(), args.end(), option);
    return it == args.end() || it + 1 == args.end() ? std::string("(absent)") : *(it + 1);
  };
  CHECK(value_of("--spp") == "8");
  CHECK(value_of("--filter") == "mitchell:1.5");
  CHECK(value_of("--aperture") == "polygon6:0.4");
  CHECK(value_of("--lens-distance") == "12");
  CHECK(value_of("--focus") == "4,12");
  const mpr_cli::Job back = round_trip(job);
  CHECK(back.spp == 8);
  CHECK(back.filter.radius() == 1.5);
  REQUIRE(back.aperture);
  CHECK(back.aperture->size.at(0) == 0.4);
  CHECK(back.aperture->focus == std::vector<double>{4, 12});
  // One sample a pixel and no aperture: none of them.
  const std::vector<std::string> plain = mpr_view::render_arguments(job_of({"--view", "G"}), 0, 64, 48, "out.png");
  for (const char* option : {"--spp", "--filter", "--aperture", "--focus"})
    CHECK(std::find(plain.begin(), plain.end(), std::string(option)) == plain.end());
}
