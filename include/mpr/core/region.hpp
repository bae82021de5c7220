#pragma once
/// \file
/// Regions: which output pixels a view covers, and the pixel-to-uv map.

#include <mpr/core/error.hpp>
#include <mpr/core/pixel.hpp>
#include <mpr/core/vec.hpp>

namespace mpr {

/// A rectangle of output pixels, `[x, x + width) x [y, y + height)`, that one view fills.
///
/// Convention: the centre of pixel (px.x, px.y) maps to
///   u = (px.x - x + 0.5) / width,   v = (px.y - y + 0.5) / height,
/// so uv (0, 0) is the top-left *corner* of the region and (1, 1) its bottom-right corner; pixel
/// centres never reach 0 or 1. The image surface spans the whole region, u to the right, v down.
/// A region may extend past the output image; only the overlap is rendered, and uv still refers
/// to the full region (so a tile of a larger view renders exactly the pixels of that view).
struct Region {
  int x = 0;
  int y = 0;
  int width = 1;
  int height = 1;

  constexpr Region() = default;
  /// Throws `argument_error` unless width > 0 and height > 0.
  constexpr Region(int x_, int y_, int width_, int height_) : x(x_), y(y_), width(width_), height(height_) {
    if (width_ <= 0) throw argument_error("region width", "must be positive");
    if (height_ <= 0) throw argument_error("region height", "must be positive");
  }

  /// Normalized coordinates of the centre of `px` within the region (see the struct comment).
  template <std::floating_point T>
  [[nodiscard]] Vec2<T> pixel_to_uv(Pixel px) const noexcept {
    return {column_to_u<T>(px.x), row_to_v<T>(px.y)};
  }

  /// The u of every pixel in image column `column` (the first coordinate of `pixel_to_uv`).
  template <std::floating_point T>
  [[nodiscard]] T column_to_u(int column) const noexcept {
    // Division rather than multiplication by a reciprocal: uv is then the correctly rounded
    // value of the exact fraction, identical for every view and thread.
    return (static_cast<T>(column - x) + T(0.5)) / static_cast<T>(width);
  }

  /// The v of every pixel in image row `row` (the second coordinate of `pixel_to_uv`).
  template <std::floating_point T>
  [[nodiscard]] T row_to_v(int row) const noexcept {
    return (static_cast<T>(row - y) + T(0.5)) / static_cast<T>(height);
  }

  [[nodiscard]] constexpr bool contains(Pixel px) const noexcept {
    return px.x >= x && px.x - x < width && px.y >= y && px.y - y < height;
  }
  friend constexpr bool operator==(const Region&, const Region&) = default;
};

} // namespace mpr
