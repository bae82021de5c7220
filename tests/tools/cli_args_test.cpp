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

TEST_CASE("parse_args suggests the nearest option and blames the one whose value is missing", "[cli]") {
  // Hand-worked distances: sise -> size one substitution, ey -> eye one insertion, zsie -> size
  // one transposition plus one substitution; qqqq is 4 edits from everything.
  CHECK(mpr_cli::edit_distance("sise", "size") == 1);
  CHECK(mpr_cli::edit_distance("ey", "eye") == 1);
  CHECK(mpr_cli::edit_distance("szie", "size") == 1);
  CHECK(mpr_cli::edit_distance("zsie", "size") == 2);
  CHECK(mpr_cli::edit_distance("", "eye") == 3);
  CHECK_THROWS_WITH(parse({"--sise", "1x1"}), Catch::Contains("unknown option; did you mean --size?"));
  CHECK_THROWS_WITH(parse({"--print-camrea"}), Catch::Contains("did you mean --print-camera?"));
  CHECK_THROWS_WITH(parse({"--qqqq"}), !Catch::Contains("did you mean"));
  CHECK_THROWS_WITH(parse({"--ey", "1,2,3"}), !Catch::Contains("did you mean")); // 1 edit of 2 letters: too far
  // "--size --eye 1,2,3": --size lacks its value; the message names it and what followed.
  CHECK_THROWS_WITH(parse({"--size", "--eye", "1,2,3"}),
                    Catch::StartsWith("mpr: invalid --size: needs a value WxH before --eye"));
  CHECK(parse({"--eye", "-1,2,3"}).get("eye") == "-1,2,3"); // a negative number is a value
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
