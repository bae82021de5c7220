#pragma once
/// \file
/// Reading images (PNG, JPEG, BMP, TGA, ... through stb_image) and writing PNG (stb_image_write).
///
/// This header only declares stb's functions: link Debian's `libstb` (the CMake target `mpr::mpr`
/// does this) or compile `src/stb_implementation.cpp` once into your program.
/// Files are sRGB-encoded: `read_rgb8` returns the stored 8-bit codes, `read_linear` decodes them
/// to linear `Color`, and `write_png` of a linear image encodes with `to_rgb8`.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>

#include <stb_image.h>
#include <stb_image_write.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace mpr {

namespace detail {
struct StbFree {
  void operator()(unsigned char* p) const noexcept { stbi_image_free(p); }
};

inline void require_readable(const std::filesystem::path& path) {
  std::FILE* file = std::fopen(path.string().c_str(), "rb");
  if (file == nullptr) throw io_error(path.string(), std::string("cannot open: ") + std::strerror(errno));
  std::fclose(file);
}
} // namespace detail

/// Reads an image file into 8-bit sRGB pixels (grey and alpha are converted to RGB; 16-bit files
/// are reduced to 8 bits). Throws `io_error` with the path and stb's reason.
[[nodiscard]] inline Image<Rgb8> read_rgb8(const std::filesystem::path& path) {
  detail::require_readable(path);
  int width = 0, height = 0, channels = 0;
  const std::unique_ptr<unsigned char, detail::StbFree> data(
      stbi_load(path.string().c_str(), &width, &height, &channels, 3));
  if (!data) {
    const char* reason = stbi_failure_reason();
    throw io_error(path.string(), std::string("cannot decode image: ") + (reason ? reason : "unknown reason"));
  }
  Image<Rgb8> image(width, height);
  std::memcpy(static_cast<void*>(image.data()), data.get(), static_cast<std::size_t>(width) * height * 3);
  return image;
}

/// Reads an image file and decodes it to linear `Color` (see `read_rgb8`).
[[nodiscard]] inline Image<Color> read_linear(const std::filesystem::path& path) {
  const Image<Rgb8> encoded = read_rgb8(path);
  return convert_image<Color>(encoded.view(), [](const Rgb8& p) { return to_color(p); });
}

/// Writes 8-bit sRGB pixels as a PNG file. Throws `io_error` if the file cannot be written.
inline void write_png(const std::filesystem::path& path, ImageView<const Rgb8> image) {
  static_assert(sizeof(Rgb8) == 3, "Rgb8 must be tightly packed for stb");
  if (image.empty()) throw io_error(path.string(), "cannot write an empty image");
  const int ok = stbi_write_png(path.string().c_str(), image.width(), image.height(), 3, image.data(),
                                static_cast<int>(image.stride() * 3));
  if (ok == 0) throw io_error(path.string(), "cannot write PNG (missing folder or no permission?)");
}

/// Writes a linear image as an 8-bit sRGB PNG (`to_rgb8` per pixel).
inline void write_png(const std::filesystem::path& path, ImageView<const Color> image) {
  const Image<Rgb8> encoded = convert_image<Rgb8>(image, [](const Color& c) { return to_rgb8(c); });
  write_png(path, encoded.view());
}

inline void write_png(const std::filesystem::path& path, const Image<Rgb8>& image) { write_png(path, image.view()); }
inline void write_png(const std::filesystem::path& path, const Image<Color>& image) { write_png(path, image.view()); }

} // namespace mpr
