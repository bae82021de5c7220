// The all-or-nothing output of a run (tools/mpr-render/publish.hpp): the preflight probe of a
// folder written after long work.
#include "mpr-render/publish.hpp"
#include "tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

TEST_CASE("mpr-render: probe_output_folder fails at once where files cannot go, and leaves nothing", "[tools]") {
  const std::filesystem::path dir = mpr_tools_test::temp_folder("probe");
  // A missing last folder under an existing one: made, probed and removed again.
  CHECK_NOTHROW(mpr_cli::probe_output_folder(dir / "maps", "--save-depth-maps"));
  CHECK_FALSE(std::filesystem::exists(dir / "maps"));
  // An existing folder: probed, its contents as they were (only the user's file in it).
  std::filesystem::create_directory(dir / "kept");
  std::ofstream(dir / "kept" / "mine.txt") << "x";
  CHECK_NOTHROW(mpr_cli::probe_output_folder(dir / "kept", "--save-depth-maps"));
  CHECK(std::distance(std::filesystem::directory_iterator(dir / "kept"), std::filesystem::directory_iterator{}) == 1);
  // A file where the folder should be, or a missing folder above: the option named.
  CHECK_THROWS_WITH(mpr_cli::probe_output_folder(dir / "kept" / "mine.txt", "--save-depth-maps"),
                    Catch::Contains("--save-depth-maps") && Catch::Contains("not a folder"));
  CHECK_THROWS_WITH(mpr_cli::probe_output_folder(dir / "no" / "such", "--save-depth-maps"),
                    Catch::Contains("--save-depth-maps") && Catch::Contains("no such folder"));
  // A folder the system refuses to make (procfs takes no folders, even from root): the folder named.
  CHECK_THROWS_WITH(mpr_cli::probe_output_folder("/proc/mpr-probe-maps", "--save-depth-maps"),
                    Catch::Contains("/proc/mpr-probe-maps") && Catch::Contains("cannot create the folder"));
  // An existing folder that takes no files (procfs again).
  CHECK_THROWS_WITH(mpr_cli::probe_output_folder("/proc", "--save-depth-maps"),
                    Catch::Contains("/proc") && Catch::Contains("cannot write into the folder"));
}
