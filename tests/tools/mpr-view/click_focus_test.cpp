// mpr-view's click-to-focus (tools/mpr-view/click_focus.hpp): a click on a light field with depth
// maps focuses on the surface the maps show under the cursor, as mpr-render's --focus-at does;
// without depth maps, or where nothing is seen, the focus is left alone.
#include "mpr-view/click_focus.hpp"
#include "mpr-view/view_options.hpp"
#include "tools/tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <vector>

namespace {

// The viewer's Job for `args` (its own parser: --depth-maps needs no other reader).
mpr_cli::Job viewer_job(std::vector<std::string> args) {
  std::vector<const char*> argv{"mpr-view"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  return mpr_view::parse_command_line(static_cast<int>(argv.size()), argv.data()).first;
}

} // namespace

TEST_CASE("mpr-view click-to-focus on a light field with depth maps", "[view]") {
  const std::filesystem::path dir = mpr_tools_test::plane_light_field("click_focus", 2.3f);
  const std::string par = (dir / "tiny_par.txt").string();
  // mpr-render refuses --depth-maps that nothing reads; the viewer's click reads them.
  CHECK_THROWS_WITH(mpr_tools_test::job_of({"--par", par, "--depth-maps", dir.string()}),
                    Catch::Contains("--depth-maps"));
  for (const std::vector<std::string>& view : {std::vector<std::string>{}, std::vector<std::string>{"--view", "G"}}) {
    std::vector<std::string> args{"--par", par, "--depth-maps", dir.string(), "--focal-depth", "1.5"};
    args.insert(args.end(), view.begin(), view.end());
    const mpr_cli::Job given = viewer_job(args);
    const mpr_cli::Loaded<float> l = mpr_cli::load<float>(given);
    const mpr_cli::Job job = mpr_cli::with_array_defaults(given, l);
    REQUIRE(mpr_view::click_focuses(job, l));
    std::ostringstream out;
    const std::optional<double> focus = mpr_view::click_focus(job, l, 3, 2, out);
    INFO(out.str());
    REQUIRE(focus.has_value());
    CHECK(*focus == Approx(2.3).epsilon(1e-4));
    CHECK_THAT(out.str(), Catch::Contains("focus at pixel (3, 2)"));
    // Outside the output: a message, no focus.
    std::ostringstream outside;
    CHECK_FALSE(mpr_view::click_focus(job, l, 500, 2, outside).has_value());
    CHECK_THAT(outside.str(), Catch::StartsWith("no focus: ") && Catch::Contains("--focus-at"));
  }
  // The same light field without depth maps: the click does not focus.
  const mpr_cli::Job plain = viewer_job({"--par", par, "--focal-depth", "1.5"});
  const mpr_cli::Loaded<float> l = mpr_cli::load<float>(plain);
  CHECK_FALSE(mpr_view::click_focuses(plain, l));
  std::ostringstream out;
  CHECK_FALSE(mpr_view::click_focus(plain, l, 3, 2, out).has_value());
  CHECK(out.str().empty());
}
