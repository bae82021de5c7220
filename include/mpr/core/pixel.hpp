#pragma once
/// \file
/// Integer pixel coordinates of an output image.

namespace mpr {

/// A pixel of an output image: `x` grows to the right, `y` grows *down*; (0, 0) is the top-left
/// pixel. The pixel's centre is at (x + 0.5, y + 0.5) in continuous image coordinates.
struct Pixel {
  int x = 0;
  int y = 0;
  friend constexpr bool operator==(const Pixel&, const Pixel&) = default;
};

} // namespace mpr
