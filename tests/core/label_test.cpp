// Labels for contact sheets (core/label.hpp): sizes, glyph pixels against the font drawn by hand,
// clipping at every image edge, lower case and unknown characters.
#include <mpr/core/label.hpp>

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace {

/// The image as '#' (ink) and '.' (anything else), one string per row.
std::vector<std::string> picture(const mpr::Image<mpr::Rgb8>& img, mpr::Rgb8 ink) {
  std::vector<std::string> rows;
  for (int y = 0; y < img.height(); ++y) {
    std::string r;
    for (int x = 0; x < img.width(); ++x) r += img(x, y) == ink ? '#' : '.';
    rows.push_back(r);
  }
  return rows;
}

} // namespace

TEST_CASE("label_size: 6 pixels a character less the last gap, one font pixel of margin", "[core][label]") {
  STATIC_REQUIRE(mpr::label_size("") == std::pair{4, 18}); // default scale 2: the margins only
  STATIC_REQUIRE(mpr::label_size("AB", mpr::LabelStyle{1}) == std::pair{13, 9});
  STATIC_REQUIRE(mpr::label_size("G cross-slit") == std::pair{(12 * 6 - 1) * 2 + 4, 18});
  STATIC_REQUIRE(mpr::label_size("x", mpr::LabelStyle{0}) == std::pair{7, 9}); // scale clamped to 1
}

TEST_CASE("draw_label: the glyphs of 'T1' at scale 1, box and margin", "[core][label]") {
  const mpr::Rgb8 ink{255, 255, 255}, bg{0, 0, 0};
  mpr::Image<mpr::Rgb8> img(15, 10, mpr::Rgb8{9, 9, 9});
  mpr::draw_label(img.view(), 1, 0, "T1", mpr::LabelStyle{1, ink, bg, true});
  const std::vector<std::string> want = {
      "...............", // box row: background, not ink
      "..#####...#....", //
      "....#....##....", //
      "....#.....#....", //
      "....#.....#....", //
      "....#.....#....", //
      "....#.....#....", //
      "....#....###...", //
      "...............", //
      "...............", // below the box: untouched
  };
  CHECK(picture(img, ink) == want);
  CHECK(img(1, 0) == bg);                    // box corner
  CHECK(img(13, 8) == bg);                   // box is 13 x 9
  CHECK(img(14, 0) == (mpr::Rgb8{9, 9, 9})); // outside the box
  CHECK(img(0, 9) == (mpr::Rgb8{9, 9, 9}));
}

TEST_CASE("draw_label: scale, lower case, unknown characters, no box", "[core][label]") {
  const mpr::Rgb8 ink{255, 0, 0};
  mpr::Image<mpr::Rgb8> upper(40, 20), lower(40, 20);
  mpr::draw_label(upper.view(), 0, 0, "GLC", mpr::LabelStyle{2, ink});
  mpr::draw_label(lower.view(), 0, 0, "glc", mpr::LabelStyle{2, ink});
  CHECK(picture(upper, ink) == picture(lower, ink));
  // 'L' at scale 2: its vertical stroke is 2 pixels wide from x = 2 + 6*2 = 14, rows 2..15.
  CHECK(upper(14, 2) == ink);
  CHECK(upper(15, 15) == ink);
  CHECK_FALSE(upper(16, 2) == ink);
  // An unknown character is a box outline; without a box nothing but ink is written.
  mpr::Image<mpr::Rgb8> box(7, 9, mpr::Rgb8{1, 2, 3});
  mpr::draw_label(box.view(), 0, 0, "\x01", mpr::LabelStyle{1, ink, {}, false});
  CHECK(box(1, 1) == ink);
  CHECK(box(5, 7) == ink);
  CHECK(box(3, 4) == (mpr::Rgb8{1, 2, 3}));
  CHECK(box(0, 0) == (mpr::Rgb8{1, 2, 3}));
}

TEST_CASE("draw_label: clipped at every edge without writing outside", "[core][label]") {
  mpr::Image<mpr::Rgb8> img(6, 5);
  for (const auto& [x, y] : {std::pair{-20, -20}, std::pair{4, 3}, std::pair{-3, 2}, std::pair{2, -6},
                             std::pair{1000, 0}, std::pair{0, 1000}})
    mpr::draw_label(img.view(), x, y, "WIDE LABEL 100%", mpr::LabelStyle{3});
  // A sub-view: drawing into the top-left 3 x 3 leaves the rest alone.
  mpr::Image<mpr::Rgb8> big(8, 8, mpr::Rgb8{7, 7, 7});
  mpr::draw_label(big.view().subview(0, 0, 3, 3), 0, 0, "MMMM");
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      if (x >= 3 || y >= 3) CHECK(big(x, y) == (mpr::Rgb8{7, 7, 7}));
}

TEST_CASE("label_tiles: one label per tile, row-major, each clipped to its tile", "[core][label]") {
  const mpr::Rgb8 paper{7, 7, 7}, ink{255, 255, 255};
  mpr::Image<mpr::Rgb8> sheet(40, 24, paper); // 2 x 2 tiles of 20 x 12
  const std::vector<std::string> labels = {"WWWWWWWWWW", "", "I", "-", "ignored: no fifth tile"};
  mpr::label_tiles(sheet.view(), 20, 12, labels, mpr::LabelStyle{1, ink});
  // Tile 0's long label stops at its right edge: tile 1 (empty label) keeps its paper past the
  // 2-pixel box of the empty label.
  CHECK(sheet(19, 4) != paper);
  for (int y = 0; y < 12; ++y)
    for (int x = 25; x < 40; ++x) CHECK(sheet(x, y) == paper);
  // Tile 2 ('I' at tile offset (2, 2) + margin 1): its top bar at y = 12 + 3, x = 2 + 1 + 1..3.
  CHECK(sheet(4, 15) == ink);
  CHECK(sheet(4, 21) == ink);
  CHECK(sheet(3, 18) != ink);
  // Tile 3 ('-' in its middle row): x = 20 + 3 .. 20 + 7, y = 12 + 6.
  CHECK(sheet(23, 18) == ink);
  CHECK(sheet(27, 18) == ink);
  CHECK(sheet(23, 17) != ink);
  // Degenerate tiles draw nothing.
  mpr::Image<mpr::Rgb8> blank(8, 8, paper);
  mpr::label_tiles(blank.view(), 0, 4, labels);
  mpr::label_tiles(blank.view(), 16, 16, labels); // no whole tile fits
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) CHECK(blank(x, y) == paper);
}
