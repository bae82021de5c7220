#pragma once
// mpr-view's text: a built-in 5x7 bitmap font (capitals, digits and common punctuation; lower
// case is drawn as capitals, anything else as '?') and drawing into an RGB image, so the HUD and
// the help overlay need no font library.

#include <mpr/core/color.hpp>
#include <mpr/core/image.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <string_view>

namespace mpr_view {

/// Glyph size in font pixels, and the advance per character and per line (one pixel of gap
/// across, two down).
inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kAdvance = 6, kLineHeight = 9;

namespace detail {

struct Glyph {
  char c;
  std::array<std::string_view, kGlyphHeight> rows; ///< top to bottom, '#' = ink, 5 columns each
};

// clang-format off
inline constexpr std::array<Glyph, 62> kGlyphs{{
    {' ', {".....", ".....", ".....", ".....", ".....", ".....", "....."}},
    {'A', {".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'B', {"####.", "#...#", "#...#", "####.", "#...#", "#...#", "####."}},
    {'C', {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."}},
    {'D', {"####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####."}},
    {'E', {"#####", "#....", "#....", "####.", "#....", "#....", "#####"}},
    {'F', {"#####", "#....", "#....", "####.", "#....", "#....", "#...."}},
    {'G', {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####"}},
    {'H', {"#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'I', {".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'J', {"..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."}},
    {'K', {"#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"}},
    {'L', {"#....", "#....", "#....", "#....", "#....", "#....", "#####"}},
    {'M', {"#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"}},
    {'N', {"#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#"}},
    {'O', {".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'P', {"####.", "#...#", "#...#", "####.", "#....", "#....", "#...."}},
    {'Q', {".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#"}},
    {'R', {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"}},
    {'S', {".####", "#....", "#....", ".###.", "....#", "....#", "####."}},
    {'T', {"#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."}},
    {'U', {"#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'V', {"#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
    {'W', {"#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."}},
    {'X', {"#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"}},
    {'Y', {"#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."}},
    {'Z', {"#####", "....#", "...#.", "..#..", ".#...", "#....", "#####"}},
    {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
    {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
    {'3', {"####.", "....#", "....#", ".###.", "....#", "....#", "####."}},
    {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
    {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
    {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
    {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
    {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
    {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
    {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
    {',', {".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."}},
    {':', {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."}},
    {';', {".....", ".##..", ".##..", ".....", ".##..", "..#..", ".#..."}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
    {'+', {".....", "..#..", "..#..", "#####", "..#..", "..#..", "....."}},
    {'=', {".....", ".....", "#####", ".....", "#####", ".....", "....."}},
    {'/', {"....#", "....#", "...#.", "..#..", ".#...", "#....", "#...."}},
    {'(', {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."}},
    {')', {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."}},
    {'[', {".###.", ".#...", ".#...", ".#...", ".#...", ".#...", ".###."}},
    {']', {".###.", "...#.", "...#.", "...#.", "...#.", "...#.", ".###."}},
    {'<', {"...#.", "..#..", ".#...", "#....", ".#...", "..#..", "...#."}},
    {'>', {".#...", "..#..", "...#.", "....#", "...#.", "..#..", ".#..."}},
    {'_', {".....", ".....", ".....", ".....", ".....", ".....", "#####"}},
    {'\'', {"..#..", "..#..", ".#...", ".....", ".....", ".....", "....."}},
    {'"', {".#.#.", ".#.#.", ".....", ".....", ".....", ".....", "....."}},
    {'!', {"..#..", "..#..", "..#..", "..#..", "..#..", ".....", "..#.."}},
    {'?', {".###.", "#...#", "....#", "...#.", "..#..", ".....", "..#.."}},
    {'%', {"##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##"}},
    {'|', {"..#..", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."}},
    {'*', {".....", "#.#.#", ".###.", "#####", ".###.", "#.#.#", "....."}},
    {'#', {".#.#.", ".#.#.", "#####", ".#.#.", "#####", ".#.#.", ".#.#."}},
    {'^', {"..#..", ".#.#.", "#...#", ".....", ".....", ".....", "....."}},
    {'~', {".....", ".....", ".#...", "#.#.#", "...#.", ".....", "....."}},
}};
// clang-format on

consteval bool glyphs_well_formed() {
  for (const Glyph& g : kGlyphs)
    for (const std::string_view row : g.rows)
      if (row.size() != static_cast<std::size_t>(kGlyphWidth)) return false;
  return true;
}
static_assert(glyphs_well_formed(), "every glyph row has kGlyphWidth columns");

/// The glyph of `c`: lower case as upper case, unknown characters as '?'.
[[nodiscard]] inline const Glyph& glyph(char c) noexcept {
  c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  const Glyph* unknown = &kGlyphs[0];
  for (const Glyph& g : kGlyphs) {
    if (g.c == c) return g;
    if (g.c == '?') unknown = &g;
  }
  return *unknown;
}

} // namespace detail

/// Width in image pixels of `text` drawn at `scale`.
[[nodiscard]] inline int text_width(std::string_view text, int scale) noexcept {
  return static_cast<int>(text.size()) * kAdvance * scale;
}

/// Font scale for a window: 2 from 640 pixels wide, else 1.
[[nodiscard]] inline int font_scale(int window_width) noexcept { return window_width >= 640 ? 2 : 1; }

/// Height of the HUD bar in pixels.
[[nodiscard]] inline int hud_height(int window_width) noexcept { return (kLineHeight + 2) * font_scale(window_width); }

/// Draws `text` with its top-left corner at (x, y), each font pixel a scale x scale square of
/// `ink`. Parts outside `out` are clipped.
inline void draw_text(mpr::ImageView<mpr::Rgb8> out, int x, int y, std::string_view text, mpr::Rgb8 ink,
                      int scale = 1) noexcept {
  for (const char c : text) {
    const detail::Glyph& g = detail::glyph(c);
    for (int gy = 0; gy < kGlyphHeight; ++gy)
      for (int gx = 0; gx < kGlyphWidth; ++gx) {
        if (g.rows[static_cast<std::size_t>(gy)][static_cast<std::size_t>(gx)] != '#') continue;
        for (int sy = 0; sy < scale; ++sy)
          for (int sx = 0; sx < scale; ++sx) {
            const int px = x + gx * scale + sx, py = y + gy * scale + sy;
            if (px >= 0 && py >= 0 && px < out.width() && py < out.height()) out(px, py) = ink;
          }
      }
    x += kAdvance * scale;
  }
}

/// Darkens the rectangle (x, y, w, h) of `out` to keep/256 of its brightness (clipped).
inline void darken(mpr::ImageView<mpr::Rgb8> out, int x, int y, int w, int h, int keep = 64) noexcept {
  const int x0 = std::max(x, 0), y0 = std::max(y, 0);
  const int x1 = std::min(x + w, out.width()), y1 = std::min(y + h, out.height());
  for (int py = y0; py < y1; ++py)
    for (int px = x0; px < x1; ++px) {
      mpr::Rgb8& p = out(px, py);
      p.r = static_cast<std::uint8_t>(p.r * keep / 256);
      p.g = static_cast<std::uint8_t>(p.g * keep / 256);
      p.b = static_cast<std::uint8_t>(p.b * keep / 256);
    }
}

} // namespace mpr_view
