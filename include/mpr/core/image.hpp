#pragma once
/// \file
/// Images (owning or borrowing their pixels) and non-owning strided views of them.

#include <mpr/core/error.hpp>

#include <cassert>
#include <cstddef>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
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

/// A contiguous (stride == width) image of `Px` that owns its pixels, or borrows them
/// (`Image::borrow`): caller-owned memory (a numpy array, a mapped file) used in place, kept
/// alive by an owner handle for as long as the image (and every `CameraFrameSet` holding it)
/// lives. Either way the pixels are reached through one pointer, so reading a borrowed image
/// costs what reading an owned one does. Copying an image copies its pixels into a new owned
/// image; moving it moves the storage (a borrowed image stays borrowed).
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
    data_ = pixels_.data();
  }

  /// An image that uses the `width` x `height` pixels at `data` (row-major, contiguous) in place:
  /// nothing is copied, writes through the image change that memory, and changes made to it
  /// elsewhere show in the image. `owner` is held as long as the image (or a `CameraFrameSet`
  /// holding it) lives: a handle that keeps `data` valid (null: the caller guarantees it).
  /// A copy of the image owns its pixels: move a borrowed image (into a `CameraFrameSet`'s
  /// list) to keep it borrowed. Throws `argument_error` ("image size") for negative sizes or a
  /// null `data` of non-zero size.
  [[nodiscard]] static Image borrow(Px* data, int width, int height, std::shared_ptr<const void> owner = nullptr) {
    if (width < 0 || height < 0) throw argument_error("image size", "negative width or height");
    if (data == nullptr && width > 0 && height > 0) throw argument_error("image size", "null pixels");
    Image out;
    out.width_ = width;
    out.height_ = height;
    out.data_ = data;
    out.owner_ = std::move(owner);
    out.borrowed_ = true;
    return out;
  }

  Image(const Image& other)
      : width_(other.width_), height_(other.height_), pixels_(other.data_, other.data_ + other.pixel_count()),
        data_(pixels_.data()) {}
  Image(Image&& other) noexcept
      : width_(other.width_), height_(other.height_), pixels_(std::move(other.pixels_)), data_(other.data_),
        owner_(std::move(other.owner_)), borrowed_(other.borrowed_) {
    other.width_ = other.height_ = 0;
    other.data_ = nullptr;
    other.borrowed_ = false;
  }
  Image& operator=(Image other) noexcept {
    std::swap(width_, other.width_);
    std::swap(height_, other.height_);
    pixels_.swap(other.pixels_); // the buffers change hands, data_ stays valid
    std::swap(data_, other.data_);
    owner_.swap(other.owner_);
    std::swap(borrowed_, other.borrowed_);
    return *this;
  }
  ~Image() = default;

  [[nodiscard]] int width() const noexcept { return width_; }
  [[nodiscard]] int height() const noexcept { return height_; }
  [[nodiscard]] bool empty() const noexcept { return width_ == 0 || height_ == 0; }
  [[nodiscard]] Px* data() noexcept { return data_; }
  [[nodiscard]] const Px* data() const noexcept { return data_; }
  /// True when the pixels are borrowed (`borrow`), not owned.
  [[nodiscard]] bool borrowed() const noexcept { return borrowed_; }
  /// The handle a borrowed image holds (null for an owned image).
  [[nodiscard]] const std::shared_ptr<const void>& owner() const noexcept { return owner_; }

  [[nodiscard]] Px& operator()(int x, int y) noexcept { return view()(x, y); }
  [[nodiscard]] const Px& operator()(int x, int y) const noexcept { return view()(x, y); }

  [[nodiscard]] ImageView<Px> view() noexcept { return {data_, width_, height_}; }
  [[nodiscard]] ImageView<const Px> view() const noexcept { return {data_, width_, height_}; }

  /// Same size and every pixel equal (Eigen pixels compare all channels).
  friend bool operator==(const Image& a, const Image& b) noexcept {
    if (a.width_ != b.width_ || a.height_ != b.height_) return false;
    for (std::size_t i = 0; i < a.pixel_count(); ++i)
      if (!detail::pixel_equal(a.data_[i], b.data_[i])) return false;
    return true;
  }

private:
  [[nodiscard]] std::size_t pixel_count() const noexcept {
    return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  }

  int width_ = 0;
  int height_ = 0;
  std::vector<Px> pixels_;            // the pixels of an owned image (empty when borrowed)
  Px* data_ = nullptr;                // pixels_.data(), or the borrowed pixels
  std::shared_ptr<const void> owner_; // keeps borrowed pixels alive
  bool borrowed_ = false;
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
