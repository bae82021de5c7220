#include "mpr-render/cli_args.hpp"

#include <catch2/catch.hpp>

namespace {
const std::vector<mpr_cli::OptionSpec> kSpecs = {
    {"size", "WxH", "output size", "--size 640x480"},
    {"eye", "X,Y,Z", "eye point", "--eye 0,0,-5"},
    {"print-camera", "", "print the camera", "--print-camera"},
};
mpr_cli::ParsedArgs parse(std::vector<const char*> args) {
  args.insert(args.begin(), "mpr-render");
  return mpr_cli::parse_args(static_cast<int>(args.size()), args.data(), kSpecs);
}
} // namespace

TEST_CASE("parse_args accepts both value forms and flags", "[cli]") {
  const mpr_cli::ParsedArgs a = parse({"--size", "64x48", "--eye=1,2,3", "--print-camera"});
  CHECK(a.get("size") == "64x48");
  CHECK(a.get("eye") == "1,2,3");
  CHECK(a.has("print-camera"));
  CHECK_FALSE(a.has("other"));
  CHECK(mpr_cli::parse_size(*a.get("size"), "--size") == std::pair{64, 48});
  CHECK(mpr_cli::parse_vec3(*a.get("eye"), "--eye") == mpr::Vec3<double>(1, 2, 3));
}

TEST_CASE("parse_args rejects bad command lines with the option named", "[cli]") {
  CHECK_THROWS_WITH(parse({"--sise", "1x1"}), Catch::Contains("--sise") && Catch::Contains("unknown"));
  CHECK_THROWS_WITH(parse({"--size"}), Catch::Contains("--size") && Catch::Contains("needs a value"));
  CHECK_THROWS_WITH(parse({"--print-camera=yes"}), Catch::Contains("flag"));
  CHECK_THROWS_WITH(parse({"stray"}), Catch::Contains("unexpected"));
}

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
