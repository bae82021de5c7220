#include <catch2/catch.hpp>

#include <mpr/core/error.hpp>

#include <string>
#include <type_traits>

TEST_CASE("argument_error names the parameter and keeps the reason apart from the message", "[error]") {
  STATIC_REQUIRE(std::is_base_of_v<mpr::error, mpr::argument_error>);
  STATIC_REQUIRE(std::is_base_of_v<mpr::error, mpr::io_error>);
  STATIC_REQUIRE(std::is_base_of_v<std::runtime_error, mpr::error>);
  STATIC_REQUIRE_FALSE(std::is_base_of_v<mpr::io_error, mpr::argument_error>);
  const mpr::argument_error e("spatial", "must be finite and >= 0");
  CHECK(e.parameter() == "spatial");
  CHECK(e.reason() == "must be finite and >= 0");
  CHECK(std::string(e.what()) == "mpr: invalid spatial: must be finite and >= 0");
  // Rethrown under another name (a command-line option), the reason carries over unchanged.
  const mpr::argument_error renamed("--sweep " + e.parameter(), e.reason());
  CHECK(std::string(renamed.what()) == "mpr: invalid --sweep spatial: must be finite and >= 0");
}

TEST_CASE("io_error names the file and, when one applies, the line", "[error]") {
  const mpr::io_error at_line("frames/par.txt", "expected 21 numbers", 7);
  CHECK(at_line.path() == "frames/par.txt");
  CHECK(at_line.line() == 7);
  CHECK(std::string(at_line.what()) == "mpr: frames/par.txt:7: expected 21 numbers");
  const mpr::io_error whole("out.png", "cannot write");
  CHECK(whole.line() == 0);
  CHECK(std::string(whole.what()) == "mpr: out.png: cannot write");
}
