#pragma once
// mpr-render --labels: each tile of the output labelled, in its top-left corner, with its view,
// the GLC type of its camera (mpr::glc::classify) and, with --aperture, the focus of its lens
// (mpr::glc::classify_focus), drawn with mpr::draw_label (include/mpr/core/label.hpp).

#include "aperture.hpp"
#include "framing.hpp"

#include <mpr/core/label.hpp>
#include <mpr/core/region.hpp>
#include <mpr/glc.hpp>

#include <string>
#include <variant>
#include <vector>

namespace mpr_cli {

/// The label lines of a tile: "G: cross_slit" (the view as given when it has at most 16
/// characters, then the type; "(rectified)" after a --rectify view) and, with `aperture`,
/// "focus: anastigmatic at 9" or "focus: astigmatic at 4 and 12" (focal depths in front of the
/// image plane, world units).
template <std::floating_point T>
std::vector<std::string> tile_label(const std::string& spec, const CameraVariant<T>& camera,
                                    const ApertureSpec* aperture) {
  const mpr::glc::Classification<T> c = mpr::glc::classify(plane_of(camera), glc_of(camera));
  std::string first = spec.size() <= 16 ? spec + ": " : std::string();
  first += mpr::glc::to_string(c.type);
  if (std::holds_alternative<mpr::glc::Rectified<T>>(camera)) first += " (rectified)";
  std::vector<std::string> lines{first};
  if (aperture != nullptr) lines.push_back("focus: " + focus_text(*aperture, plane_of(camera), true));
  return lines;
}

/// Draws `lines` into the tile `tile` of `image` (one line under the other, 2 pixels in from its
/// top-left corner, clipped to the tile); glyphs twice as large on tiles at least 400 pixels wide
/// when every line fits so.
inline void draw_tile_label(mpr::ImageView<mpr::Rgb8> image, const mpr::Region& tile,
                            const std::vector<std::string>& lines) noexcept {
  mpr::LabelStyle style{tile.width >= 400 ? 2 : 1};
  for (const std::string& line : lines)
    if (2 + mpr::label_size(line, style).first > tile.width) style.scale = 1;
  const mpr::ImageView<mpr::Rgb8> view = image.subview(tile.x, tile.y, tile.width, tile.height);
  int y = 2;
  for (const std::string& line : lines) {
    mpr::draw_label(view, 2, y, line, style);
    y += mpr::label_size(line, style).second;
  }
}

/// draw_tile_label on a linear image: the tile is encoded to 8-bit sRGB, labelled, and every
/// pixel the label changed is decoded back (`mpr::to_color`), so an 8-bit output of the image
/// shows the label exactly as draw_tile_label on the encoded image would (`to_rgb8(to_color(p))
/// == p`) and a linear output carries the label's own colours.
inline void draw_tile_label(mpr::ImageView<mpr::Color> image, const mpr::Region& tile,
                            const std::vector<std::string>& lines) {
  const mpr::ImageView<mpr::Color> view = image.subview(tile.x, tile.y, tile.width, tile.height);
  const mpr::Image<mpr::Rgb8> before = mpr::convert_image<mpr::Rgb8>(
      mpr::ImageView<const mpr::Color>(view), [](const mpr::Color& c) { return mpr::to_rgb8(c); });
  mpr::Image<mpr::Rgb8> after = before;
  draw_tile_label(after.view(), mpr::Region(0, 0, tile.width, tile.height), lines);
  for (int y = 0; y < view.height(); ++y)
    for (int x = 0; x < view.width(); ++x) {
      const mpr::Rgb8 a = before(x, y), b = after(x, y);
      if (a.r != b.r || a.g != b.g || a.b != b.b) view(x, y) = mpr::to_color(b);
    }
}

} // namespace mpr_cli
