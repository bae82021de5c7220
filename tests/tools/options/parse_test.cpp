#include "options/parse.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace {
mpr_cli::OptionValues parse(std::vector<const char*> args, mpr_cli::Tools tool = mpr_cli::Tools::render) {
  args.insert(args.begin(), "mpr-render");
  return mpr_cli::parse_options(static_cast<int>(args.size()), args.data(), tool);
}
} // namespace

TEST_CASE("parse_options accepts both value forms and flags", "[cli]") {
  const mpr_cli::OptionValues a = parse({"--size", "64x48", "--up=1,2,3", "--print-camera"});
  CHECK(a.get("size") == "64x48");
  CHECK(a.get("up") == "1,2,3");
  CHECK(a.has("print-camera"));
  CHECK_FALSE(a.has("view"));
  CHECK(a.size("size") == std::pair{64, 48});
  CHECK(a.vec3("up") == mpr::Vec3<double>(1, 2, 3));
  // Repeated: every value is kept, the last one wins.
  const mpr_cli::OptionValues b = parse({"--size", "8x6", "--size", "16x12"});
  CHECK(b.all("size") == std::vector<std::string>{"8x6", "16x12"});
  CHECK(b.size("size") == std::pair{16, 12});
  // Values that start with '-' are values, not options.
  const mpr_cli::OptionValues c =
      parse({"--tilt-y", "-20:20", "--rectify", "-4.4,5.4,-14;4.4,5.4,-14;4.4,-1.2,-14;-4.4,-1.2,-14"});
  CHECK(c.get("tilt-y") == "-20:20");
  CHECK(c.get("rectify") == "-4.4,5.4,-14;4.4,5.4,-14;4.4,-1.2,-14;-4.4,-1.2,-14");
}

TEST_CASE("parse_options rejects bad command lines with the option named", "[cli]") {
  CHECK_THROWS_WITH(parse({"--sise", "1x1"}), Catch::Contains("--sise") && Catch::Contains("unknown"));
  CHECK_THROWS_WITH(parse({"--size"}), Catch::Contains("--size") && Catch::Contains("needs a value"));
  CHECK_THROWS_WITH(parse({"--print-camera=yes"}), Catch::Contains("flag"));
  CHECK_THROWS_WITH(parse({"stray"}), Catch::Contains("unexpected"));
  CHECK(parse({"--output="}).get("output") == ""); // an empty value is the option's to judge
}

TEST_CASE("parse_options suggests the nearest option and blames the one whose value is missing", "[cli]") {
  // Hand-worked distances: sise -> size one substitution, ey -> eye one insertion, zsie -> size
  // one transposition plus one substitution; qqqq is 4 edits from everything.
  CHECK(mpr_cli::edit_distance("sise", "size") == 1);
  CHECK(mpr_cli::edit_distance("ey", "eye") == 1);
  CHECK(mpr_cli::edit_distance("szie", "size") == 1);
  CHECK(mpr_cli::edit_distance("zsie", "size") == 2);
  CHECK(mpr_cli::edit_distance("", "eye") == 3);
  CHECK_THROWS_WITH(parse({"--sise", "1x1"}), Catch::Contains("unknown option; did you mean --size?"));
  CHECK_THROWS_WITH(parse({"--veiw", "G"}), Catch::Contains("did you mean --view?"));
  CHECK_THROWS_WITH(parse({"--print-camrea"}), Catch::Contains("did you mean --print-camera?"));
  CHECK_THROWS_WITH(parse({"--qqqq"}), !Catch::Contains("did you mean"));
  CHECK_THROWS_WITH(parse({"--pu", "1,2,3"}), !Catch::Contains("did you mean")); // 2 edits of 2 letters: too far
  // "--size --up 1,2,3": --size lacks its value; the message names it and what followed.
  CHECK_THROWS_WITH(parse({"--size", "--up", "1,2,3"}),
                    Catch::StartsWith("mpr: invalid --size: needs a value WxH before --up"));
  CHECK(parse({"--up", "-1,2,3"}).get("up") == "-1,2,3"); // a negative number is a value
}

TEST_CASE("each tool takes its own options of the table", "[cli]") {
  CHECK_THROWS_WITH(parse({"--script", "a.txt"}), Catch::Contains("invalid --script: unknown option"));
  CHECK(parse({"--script", "a.txt"}, mpr_cli::Tools::view).get("script") == "a.txt");
  CHECK(parse({"--size", "8x6"}, mpr_cli::Tools::view).get("size") == "8x6");
  CHECK(mpr_cli::did_you_mean("scirpt", mpr_cli::Tools::view) == "; did you mean --script?");
  CHECK(mpr_cli::did_you_mean("scirpt", mpr_cli::Tools::render).empty());
}
