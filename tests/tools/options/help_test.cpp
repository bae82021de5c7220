#include "options/help.hpp"

#include <catch2/catch.hpp>

#include <string>

TEST_CASE("--help lists every option of the table with its default and an example", "[cli]") {
  const std::string help = mpr_cli::render_help();
  CHECK(help.rfind("usage: mpr-render [OPTIONS]", 0) == 0);
  for (const mpr_cli::Option& o : mpr_cli::option_table()) {
    INFO(o.name);
    std::string head = "\n  --"; // append, not operator+: GCC 12's false -Wrestrict
    head.append(o.name);
    if (!o.value.empty()) head.append(" ").append(o.value);
    head.append("\n");
    CHECK((help.find(head) != std::string::npos) == mpr_cli::takes(o.tools, mpr_cli::Tools::render));
  }
  CHECK(help.find("--threads N\n      Worker threads, 0 = all. Images are identical for any N. Default: 0.\n"
                  "      e.g. --threads 2\n") != std::string::npos);
  CHECK(help.find("\nExamples:\n  mpr-render ") != std::string::npos);
  // The viewer's list: its own options with examples, mpr-render's without, and not the ones it
  // has no use for.
  const std::string viewer = mpr_cli::option_help(mpr_cli::Group::viewer, mpr_cli::Tools::view, true);
  CHECK(viewer.find("--script FILE") != std::string::npos);
  CHECK(mpr_cli::option_help(mpr_cli::Group::image, mpr_cli::Tools::view, false).find("\n  --print-camera\n") ==
        std::string::npos);
  CHECK(mpr_cli::option_help(mpr_cli::Group::image, mpr_cli::Tools::view, false).find("e.g.") == std::string::npos);
}
