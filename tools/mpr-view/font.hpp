#pragma once
// mpr-view's text: the library's 5x7 label font (core/label.hpp: capitals, digits and common
// punctuation; lower case drawn as capitals) placed for the HUD and the help overlay.

#include <mpr/core/color.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/label.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <string_view>

namespace mpr_view {

/// Glyph size in font pixels, and the advance per character and per line (one pixel of gap
/// across, two down).
inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kAdvance = 6, kLineHeight = 9;

/// Width in image pixels of `text` drawn at `scale`.
[[nodiscard]] inline int text_width(std::string_view text, int scale) noexcept {
  return static_cast<int>(text.size()) * kAdvance * scale;
}

/// Font scale for a window: 2 from 640 pixels wide, else 1.
[[nodiscard]] inline int font_scale(int window_width) noexcept { return window_width >= 640 ? 2 : 1; }

/// Height of the HUD bar in pixels.
[[nodiscard]] inline int hud_height(int window_width) noexcept { return (kLineHeight + 2) * font_scale(window_width); }

/// Draws `text` with its top-left corner at (x, y), each font pixel a scale x scale square of
/// `ink` (mpr::draw_label's font, without its box). Parts outside `out` are clipped.
inline void draw_text(mpr::ImageView<mpr::Rgb8> out, int x, int y, std::string_view text, mpr::Rgb8 ink,
                      int scale = 1) noexcept {
  mpr::draw_label(out, x - scale, y - scale, text, mpr::LabelStyle{scale, ink, mpr::Rgb8{}, false});
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
