#include "mpr-render/cli_args.hpp"

#include <catch2/catch.hpp>

TEST_CASE("value parsers are strict", "[cli]") {
  CHECK_THROWS_WITH(mpr_cli::parse_number("1.5x", "--radius"), Catch::Contains("--radius"));
  CHECK_THROWS_WITH(mpr_cli::parse_number("nan", "--radius"), Catch::Contains("not finite"));
  CHECK_THROWS_WITH(mpr_cli::parse_number("", "--radius"), Catch::Contains("not a number"));
  CHECK(mpr_cli::parse_number("-2.5e3", "--x") == -2500);
  CHECK_THROWS_WITH(mpr_cli::parse_vec3("1,2", "--eye"), Catch::Contains("x,y,z"));
  CHECK_THROWS_WITH(mpr_cli::parse_vec3("1,,2", "--eye"), Catch::Contains("--eye"));
  CHECK_THROWS_WITH(mpr_cli::parse_size("0x5", "--size"), Catch::Contains("outside"));
  CHECK_THROWS_WITH(mpr_cli::parse_int("12a", "--frames", 1, 10), Catch::Contains("not an integer"));
}
