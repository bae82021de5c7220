#pragma once
/// \file
/// `mpr::scene::Texture`: an image of linear colour sampled with nearest-texel lookup and
/// repeat wrapping, plus procedural texture generators (checker, grid).

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>

#include <cmath>
#include <utility>

namespace mpr::scene {

/// A texture: linear `Color` texels. Texture coordinates follow the Wavefront OBJ convention:
/// (0, 0) is the *bottom*-left corner of the image, (1, 1) the top-right, and the texture repeats
/// outside [0, 1). Sampling is nearest-texel (no filtering), so that two renderers which hit the
/// same uv get exactly the same colour. Non-finite uv give texel (0, 0) (never a crash).
class Texture {
public:
  /// Throws `argument_error("texture", ...)` for an empty image.
  explicit Texture(Image<Color> image) : image_(std::move(image)) {
    if (image_.empty()) throw argument_error("texture", "empty image");
    width_ = static_cast<float>(image_.width());
    height_ = static_cast<float>(image_.height());
  }

  [[nodiscard]] const Image<Color>& image() const noexcept { return image_; }

  /// The texel at texture coordinates (u, v), repeat wrapping.
  [[nodiscard]] Color sample(float u, float v) const noexcept {
    return image_(index(u, width_, image_.width()), image_.height() - 1 - index(v, height_, image_.height()));
  }

private:
  static int index(float s, float size, int n) noexcept {
    if (!std::isfinite(s)) return 0;
    const float f = s - std::floor(s); // [0, 1], 1 only by rounding
    const int i = static_cast<int>(f * size);
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
  }

  Image<Color> image_;
  float width_ = 1;
  float height_ = 1;
};

/// A `cells` x `cells` checkerboard of `size` x `size` texels (cells must divide size), colour
/// `a` in the top-left cell. Throws `argument_error` for non-positive sizes.
[[nodiscard]] inline Image<Color> checker_image(int size, int cells, const Color& a, const Color& b) {
  if (size <= 0) throw argument_error("size", "must be positive");
  if (cells <= 0 || size % cells != 0) throw argument_error("cells", "must be positive and divide size");
  Image<Color> image(size, size);
  const int cell = size / cells;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) image(x, y) = ((x / cell + y / cell) & 1) ? b : a;
  return image;
}

/// A `size` x `size` tile of `paper` with a `line`-coloured border `thickness` texels wide on its
/// left and top edges: repeated, it draws a grid of square cells.
[[nodiscard]] inline Image<Color> grid_image(int size, int thickness, const Color& paper, const Color& line) {
  if (size <= 0) throw argument_error("size", "must be positive");
  if (thickness <= 0 || thickness >= size) throw argument_error("thickness", "must be in [1, size)");
  Image<Color> image(size, size, paper);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      if (x < thickness || y < thickness) image(x, y) = line;
  return image;
}

} // namespace mpr::scene
