#pragma once
/// \file
/// Owning images and non-owning strided views of them.

#include <mpr/core/error.hpp>

#include <cassert>
#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

namespace mpr {

namespace detail {
template <class Px>
[[nodiscard]] bool pixel_equal(const Px& a, const Px& b) noexcept {
  if constexpr (requires { (a == b).all(); })
    return (a == b).all();
  else
    return a == b;
}
template <class Px>
[[nodiscard]] Px zero_pixel() noexcept {
  if constexpr (requires { Px::Zero(); })
    return Px::Zero();
  else
    return Px{};
}
} // namespace detail

/// A non-owning view of a 2D grid of pixels, rows `stride` elements apart (stride >= width).
/// Pixel (x, y) is at `data[y * stride + x]`, y down. `ImageView<const Px>` is a read-only view.
/// A view never allocates and is cheap to copy; it must not outlive the storage it points to.
template <class Px>
class ImageView {
public:
  using pixel_type = Px;

  constexpr ImageView() noexcept = default;
  constexpr ImageView(Px* data, int width, int height, std::ptrdiff_t stride) noexcept
      : data_(data), width_(width), height_(height), stride_(stride) {
    assert(width >= 0 && height >= 0 && stride >= width);
  }
  constexpr ImageView(Px* data, int width, int height) noexcept : ImageView(data, width, height, width) {}

  /// A read-only view of a mutable view.
  constexpr operator ImageView<const Px>() const noexcept requires(!std::is_const_v<Px>) {
    return {data_, width_, height_, stride_};
  }

  [[nodiscard]] constexpr int width() const noexcept { return width_; }
  [[nodiscard]] constexpr int height() const noexcept { return height_; }
  /// Distance between the starts of two consecutive rows, in pixels.
  [[nodiscard]] constexpr std::ptrdiff_t stride() const noexcept { return stride_; }
  [[nodiscard]] constexpr bool empty() const noexcept { return width_ == 0 || height_ == 0; }
  [[nodiscard]] constexpr Px* data() const noexcept { return data_; }
  /// Pointer to the first pixel of row `y`; precondition 0 <= y < height().
  [[nodiscard]] constexpr Px* row(int y) const noexcept { return data_ + static_cast<std::ptrdiff_t>(y) * stride_; }

  /// Pixel (x, y); precondition 0 <= x < width(), 0 <= y < height() (checked by assert only).
  [[nodiscard]] constexpr Px& operator()(int x, int y) const noexcept {
    assert(x >= 0 && x < width_ && y >= 0 && y < height_);
    return row(y)[x];
  }

  /// The sub-rectangle (x, y, width, height), clipped to this view.
  [[nodiscard]] constexpr ImageView subview(int x, int y, int width, int height) const noexcept {
    const int x0 = x < 0 ? 0 : (x > width_ ? width_ : x);
    const int y0 = y < 0 ? 0 : (y > height_ ? height_ : y);
    const long x1l = static_cast<long>(x) + width, y1l = static_cast<long>(y) + height;
    const int x1 = x1l < x0 ? x0 : (x1l > width_ ? width_ : static_cast<int>(x1l));
    const int y1 = y1l < y0 ? y0 : (y1l > height_ ? height_ : static_cast<int>(y1l));
    return {data_ + static_cast<std::ptrdiff_t>(y0) * stride_ + x0, x1 - x0, y1 - y0, stride_};
  }

private:
  Px* data_ = nullptr;
  int width_ = 0;
  int height_ = 0;
  std::ptrdiff_t stride_ = 0;
};

/// An owning, contiguous (stride == width) image of `Px`.
template <class Px>
class Image {
public:
  using pixel_type = Px;

  Image() = default;
  /// A `width` x `height` image of zero pixels (Eigen pixels are zeroed, not left uninitialised).
  Image(int width, int height) : Image(width, height, detail::zero_pixel<Px>()) {}
  /// A `width` x `height` image filled with `fill`. Throws `argument_error` for negative sizes.
  Image(int width, int height, const Px& fill) : width_(width), height_(height) {
    if (width < 0 || height < 0) throw argument_error("image size", "negative width or height");
    pixels_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill);
  }

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] bool empty() const noexcept { return pixels_.empty(); }
  [[nodiscard]] Px* data() noexcept { return pixels_.data(); }
  [[nodiscard]] const Px* data() const noexcept { return pixels_.data(); }

  [[nodiscard]] Px& operator()(int x, int y) noexcept { return view()(x, y); }
  [[nodiscard]] const Px& operator()(int x, int y) const noexcept { return view()(x, y); }

  [[nodiscard]] ImageView<Px> view() noexcept { return {pixels_.data(), width_, height_}; }
  [[nodiscard]] ImageView<const Px> view() const noexcept { return {pixels_.data(), width_, height_}; }

  /// Same size and every pixel equal (Eigen pixels compare all channels).
  friend bool operator==(const Image& a, const Image& b) noexcept {
    if (a.width_ != b.width_ || a.height_ != b.height_) return false;
    for (std::size_t i = 0; i < a.pixels_.size(); ++i)
      if (!detail::pixel_equal(a.pixels_[i], b.pixels_[i])) return false;
    return true;
  }

private:
  int width_ = 0;
  int height_ = 0;
  std::vector<Px> pixels_;
};

/// Copies `src` into a new image, converting each pixel with `convert(const Src&) -> Dst`.
template <class Dst, class Src, class Convert>
[[nodiscard]] Image<Dst> convert_image(ImageView<const Src> src, Convert convert) {
  Image<Dst> out(src.width(), src.height());
  for (int y = 0; y < src.height(); ++y)
    for (int x = 0; x < src.width(); ++x) out(x, y) = convert(src(x, y));
  return out;
}

} // namespace mpr
