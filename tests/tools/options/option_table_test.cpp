#include "options/option_table.hpp"
#include "options/parse.hpp"
#include "options/save_command.hpp"
#include "tools/tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <vector>

TEST_CASE("the option table declares each option once and completely", "[cli]") {
  std::set<std::string_view> names;
  for (const mpr_cli::Option& o : mpr_cli::option_table()) {
    INFO(o.name);
    CHECK(names.insert(o.name).second);
    CHECK(!o.help.empty());
    CHECK(!o.example.empty());
    CHECK(o.value.empty() == (o.kind == mpr_cli::ValueKind::flag));
    if (o.kind == mpr_cli::ValueKind::choice) CHECK(!o.choices.empty());
    if (o.kind == mpr_cli::ValueKind::integer) CHECK((o.lo > -1e9 && o.hi < 1e9 && o.lo <= o.hi));
    if (o.kind == mpr_cli::ValueKind::number || o.kind == mpr_cli::ValueKind::track)
      CHECK((o.bound_text.empty() == (o.lo == -mpr_cli::kUnbounded && o.hi == mpr_cli::kUnbounded)));
  }
  CHECK(names.size() == 62); // mpr-render's 59 and the viewer's 3
}

TEST_CASE("values are read as their option declares", "[cli]") {
  using mpr_tools_test::job_of;
  CHECK_THROWS_WITH(job_of({"--spp", "0"}), Catch::Contains("invalid --spp: 0 is outside [1, 4096]"));
  CHECK_THROWS_WITH(job_of({"--threads", "1025"}), Catch::Contains("invalid --threads: 1025 is outside [0, 1024]"));
  CHECK_THROWS_WITH(job_of({"--tilt-x", "89"}), Catch::Contains("invalid --tilt-x: must lie within (-89, 89)"));
  CHECK(job_of({"--tilt-x", "-88.9"}).tilt_x.at(0) == -88.9);
  CHECK_THROWS_WITH(job_of({"--raster", "2x2", "--radius", "0"}),
                    Catch::Contains("invalid --radius: must be positive"));
  CHECK_THROWS_WITH(job_of({"--tilt-y", "0:5", "--frames", "2", "--fps", "1000.5"}),
                    Catch::Contains("invalid --fps: must lie in (0, 1000]"));
  CHECK(job_of({"--tilt-y", "0:5", "--frames", "2", "--fps", "1000"}).fps == 1000);
  CHECK_THROWS_WITH(job_of({"--raster", "2x2", "--interp", "linear"}),
                    Catch::Contains("invalid --interp: 'linear' is not nearest, synthetic, cylinder or depth"));
  CHECK(job_of({"--raster", "2x2", "--interp", "depth"}).interpolation == mpr_cli::Interpolation::depth);
  CHECK_THROWS_WITH(job_of({"--scene", "office"}), Catch::Contains("'office' is not a built-in scene (classroom)"));
  CHECK_THROWS_WITH(job_of({"--bit-depth", "12"}), Catch::Contains("invalid --bit-depth: '12' is not 8 or 16"));
  CHECK(job_of({"--bit-depth", "16"}).encoding.png_bits == 16);
  CHECK(job_of({}).encoding.png_bits == 8);
}

TEST_CASE("the declared defaults are the Job's", "[cli]") {
  // Each option given its declared default writes the same save command as the option left out.
  const std::vector<std::vector<std::string>> cases = {
      {"--size", "480x360"},    {"--layout", "1x1"}, {"--view", "default"}, {"--threads", "0"},
      {"--spp", "1"},           {"--up", "0,1,0"},   {"--tilt-x", "0"},     {"--tilt-y", "0"},
      {"--scene", "classroom"}, {"--bit-depth", "8"}};
  const auto saved = [](const mpr_cli::Job& j) { return mpr_cli::save_arguments(j, 0, j.width, j.height, j.output); };
  const mpr_cli::Job plain = mpr_tools_test::job_of({});
  for (const std::vector<std::string>& c : cases) {
    INFO(c[0]);
    const mpr_cli::Option* o = mpr_cli::find_option(c[0].substr(2), mpr_cli::Tools::render);
    REQUIRE(o != nullptr);
    CHECK(std::string(o->default_text) == (c[1] == "default" ? "'default'" : c[1]));
    CHECK(saved(mpr_tools_test::job_of(c)) == saved(plain));
  }
  CHECK(saved(mpr_tools_test::job_of({"--raster", "2x2", "--raster-samples", "1"})) ==
        saved(mpr_tools_test::job_of({"--raster", "2x2"})));
  CHECK(mpr_tools_test::job_of({}).output == "mpr-render.png");
  CHECK(mpr_cli::find_option("output", mpr_cli::Tools::render)->default_text == "mpr-render.png");
  CHECK(mpr_cli::Job{}.fps == 12);
  CHECK(mpr_cli::find_option("fps", mpr_cli::Tools::render)->default_text == "12");
}

TEST_CASE("the save command writes each option in the table's order", "[cli]") {
  const mpr_cli::Job job = mpr_tools_test::job_of(
      {"--threads", "3", "--tilt-x", "5", "--view", "G", "--raster", "4x3", "--radius", "2", "--double"});
  CHECK(mpr_cli::save_command(job, 0, 32, 24, "a b.png") ==
        "mpr-render --raster 4x3 --interp cylinder --radius 2 --size 32x24 --view G --tilt-x 5 --threads 3 --double "
        "--output 'a b.png'");
}
