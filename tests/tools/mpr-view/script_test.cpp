#include "mpr-view/script.hpp"

#include <catch2/catch.hpp>

#include <sstream>

namespace {
bool known_key(const std::string& name) { return name == "G" || name == "Escape" || name == "F1"; }

std::vector<mpr_view::ScriptCommand> parse(const std::string& text) {
  std::istringstream in(text);
  return mpr_view::parse_script(in, "s.txt", known_key);
}
} // namespace

TEST_CASE("parse_script reads every command, skipping comments and blank lines", "[view]") {
  using Kind = mpr_view::ScriptCommand::Kind;
  const std::vector<mpr_view::ScriptCommand> c =
      parse("# a comment\n\nwait 250\nkey G  # gallery G\r\ndrag 10,20 30,40 right\nwheel -3\nclick 5,6\n"
            "screenshot out/a.png\ndrag 1,2 3,4\n");
  REQUIRE(c.size() == 7);
  CHECK((c[0].kind == Kind::wait && c[0].milliseconds == 250 && c[0].line == 3));
  CHECK((c[1].kind == Kind::key && c[1].key == "G" && c[1].line == 4));
  CHECK((c[2].kind == Kind::drag && c[2].x0 == 10 && c[2].y0 == 20 && c[2].x1 == 30 && c[2].y1 == 40));
  CHECK(c[2].button == "right");
  CHECK((c[3].kind == Kind::wheel && c[3].notches == -3));
  CHECK((c[4].kind == Kind::click && c[4].x0 == 5 && c[4].y0 == 6));
  CHECK((c[5].kind == Kind::screenshot && c[5].path == "out/a.png"));
  CHECK(c[6].button == "left");
}

TEST_CASE("parse_script names the file and line of the first bad command", "[view]") {
  CHECK_THROWS_WITH(parse("wait 1\nkye G\n"), Catch::Contains("s.txt:2:") && Catch::Contains("unknown command 'kye'"));
  CHECK_THROWS_WITH(parse("key Nope\n"), Catch::Contains("s.txt:1:") && Catch::Contains("'Nope' is not an SDL key"));
  CHECK_THROWS_WITH(parse("\nwait -5\n"), Catch::Contains("s.txt:2:") && Catch::Contains("milliseconds"));
  CHECK_THROWS_WITH(parse("wait\n"), Catch::Contains("expected 'wait MS'"));
  CHECK_THROWS_WITH(parse("drag 1,2\n"), Catch::Contains("expected 'drag"));
  CHECK_THROWS_WITH(parse("drag 1,2 3;4\n"), Catch::Contains("'3;4' is not a window position"));
  CHECK_THROWS_WITH(parse("drag 1,2 3,4 left extra\n"), Catch::Contains("expected 'drag"));
  CHECK_THROWS_WITH(parse("drag 1,2 3,4 thumb\n"), Catch::Contains("not a mouse button"));
  CHECK_THROWS_WITH(parse("click -1,4\n"), Catch::Contains("-1,4"));
  CHECK_THROWS_WITH(parse("wheel 1.5\n"), Catch::Contains("notches"));
  CHECK_THROWS_WITH(parse("screenshot\n"), Catch::Contains("screenshot PATH"));
}

TEST_CASE("read_script refuses a missing file", "[view]") {
  CHECK_THROWS_WITH(mpr_view::read_script("/nonexistent/script.txt", known_key),
                    Catch::Contains("/nonexistent/script.txt") && Catch::Contains("no such file"));
}

TEST_CASE("parse_script reads resize WxH and refuses a size outside 16 .. the window limit", "[view]") {
  using Kind = mpr_view::ScriptCommand::Kind;
  const std::vector<mpr_view::ScriptCommand> c = parse("resize 360x200\n");
  REQUIRE(c.size() == 1);
  CHECK((c[0].kind == Kind::resize && c[0].x1 == 360 && c[0].y1 == 200));
  CHECK_THROWS_WITH(parse("resize 10x200\n"),
                    Catch::Contains("s.txt:1:") && Catch::Contains("'10x200' is not a window size WxH"));
  CHECK_THROWS_WITH(parse("resize 360,200\n"), Catch::Contains("is not a window size WxH"));
  CHECK_THROWS_WITH(parse("resize 360x\n"), Catch::Contains("is not a window size WxH"));
  CHECK_THROWS_WITH(parse("resize 20000x200\n"), Catch::Contains("is not a window size WxH"));
  CHECK_THROWS_WITH(parse("resize\n"), Catch::Contains("expected 'resize WxH'"));
}
