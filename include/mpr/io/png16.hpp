#pragma once
/// \file
/// Writing and reading 16-bit sRGB-encoded PNG files through libpng (link `PNG::PNG`, Debian's
/// libpng-dev; stb_image_write writes 8 bits only).
///
/// A linear `Color` channel x is stored as the code round(65535 * srgb_encode(clamp(x, 0, 1)))
/// (NaN as 0), big-endian as PNG requires, with an sRGB chunk (rendering intent perceptual) and
/// the gAMA/cHRM chunks libpng pairs with it; `from_png16_code` decodes a code back to linear
/// light. The 16-bit codes keep the render's values within half a code step, about 1/131070 in
/// encoded units, where 8 bits keep 1/510.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/file_write.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/load_limits.hpp>

#include <png.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace mpr {

/// One pixel of a 16-bit PNG: sRGB-encoded codes 0..65535 per channel.
struct Rgb16 {
  std::uint16_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb16&, const Rgb16&) = default;
};

/// The 16-bit sRGB code of the linear value `linear`: round(65535 * srgb_encode(x)) of x clamped
/// to [0, 1]; NaN gives 0.
[[nodiscard]] inline std::uint16_t to_png16_code(float linear) noexcept {
  const double x = std::isnan(linear) ? 0.0 : std::clamp(static_cast<double>(linear), 0.0, 1.0);
  return static_cast<std::uint16_t>(std::lround(65535.0 * srgb_encode(x)));
}

/// The linear value of the 16-bit sRGB code `code` (srgb_decode(code / 65535)).
[[nodiscard]] inline float from_png16_code(std::uint16_t code) noexcept {
  return static_cast<float>(srgb_decode(code / 65535.0));
}

/// `to_png16_code` per channel.
[[nodiscard]] inline Rgb16 to_rgb16(const Color& c) noexcept {
  return {to_png16_code(c[0]), to_png16_code(c[1]), to_png16_code(c[2])};
}

namespace detail {

/// What libpng's callbacks share with the function that runs it.
struct Png16Io {
  std::vector<unsigned char>* out = nullptr; ///< writing: the file's bytes
  const unsigned char* in = nullptr;         ///< reading: the file's bytes
  std::size_t in_size = 0, in_at = 0;
  char message[200] = {}; ///< libpng's error message
};

inline void png16_error(png_structp png, png_const_charp message) {
  auto* io = static_cast<Png16Io*>(png_get_error_ptr(png));
  std::snprintf(io->message, sizeof io->message, "%s", message);
  png_longjmp(png, 1);
}
inline void png16_warning(png_structp, png_const_charp) {}

inline void png16_write(png_structp png, png_bytep data, png_size_t size) {
  auto* io = static_cast<Png16Io*>(png_get_io_ptr(png));
  io->out->insert(io->out->end(), data, data + size);
}
inline void png16_flush(png_structp) {}

inline void png16_read(png_structp png, png_bytep data, png_size_t size) {
  auto* io = static_cast<Png16Io*>(png_get_io_ptr(png));
  if (size > io->in_size - io->in_at) png_error(png, "file cut short");
  std::memcpy(data, io->in + io->in_at, size);
  io->in_at += size;
}

/// Runs libpng's writer over `rows` (big-endian 16-bit RGB, `height` rows of 6 * `width` bytes).
/// Only trivially destructible objects live in this frame, so libpng's longjmp on an error
/// skips no destructor. False on failure (`io.message` says why).
[[nodiscard]] inline bool png16_encode(Png16Io& io, png_bytep* rows, int width, int height) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &io, png16_error, png16_warning);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &io, png16_write, png16_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 16, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

/// Reads the header of the PNG in `io`, then (when `accept(width, height)` holds) its rows into
/// `pixels` as 16-bit RGB in native byte order. 8-bit, grey, palette and alpha files are
/// converted to 16-bit RGB (8-bit codes c become 257 c). Only trivially destructible objects in
/// this frame (see png16_encode). 0 on success, 1 on a libpng error, 2 when `accept` refused.
template <class Accept, class Allocate>
[[nodiscard]] int png16_decode(Png16Io& io, Accept accept, Allocate allocate) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &io, png16_error, png16_warning);
  if (png == nullptr) return 1;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return 1;
  }
  png_set_read_fn(png, &io, png16_read);
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info), height = png_get_image_height(png, info);
  if (!accept(width, height)) {
    png_destroy_read_struct(&png, &info, nullptr);
    return 2;
  }
  png_set_expand(png);
  png_set_expand_16(png);
  png_set_gray_to_rgb(png);
  png_set_strip_alpha(png);
  if constexpr (std::endian::native == std::endian::little) png_set_swap(png);
  png_read_update_info(png, info);
  png_bytep* rows = allocate(width, height);
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return 0;
}

} // namespace detail

/// The bytes of a 16-bit RGB PNG of the linear image `image` (codes `to_rgb16`, see the file
/// comment). Throws `io_error` naming `name` (the file it is meant for) when libpng fails.
[[nodiscard]] inline std::vector<unsigned char> encode_png16(ImageView<const Color> image,
                                                             const std::string& name = "PNG") {
  if (image.empty()) throw io_error(name, "cannot write an empty image");
  const std::size_t row_bytes = 6 * static_cast<std::size_t>(image.width());
  std::vector<unsigned char> data(row_bytes * static_cast<std::size_t>(image.height()));
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height()));
  for (int y = 0; y < image.height(); ++y) {
    unsigned char* row = data.data() + row_bytes * static_cast<std::size_t>(y);
    rows[static_cast<std::size_t>(y)] = row;
    for (int x = 0; x < image.width(); ++x) {
      const Rgb16 p = to_rgb16(image(x, y));
      for (const std::uint16_t code : {p.r, p.g, p.b}) {
        *row++ = static_cast<unsigned char>(code >> 8); // PNG is big-endian
        *row++ = static_cast<unsigned char>(code & 0xFF);
      }
    }
  }
  std::vector<unsigned char> bytes;
  detail::Png16Io io;
  io.out = &bytes;
  if (!detail::png16_encode(io, rows.data(), image.width(), image.height()))
    throw io_error(name, std::string("cannot encode 16-bit PNG: ") + io.message);
  return bytes;
}

/// Writes the linear image `image` as a 16-bit sRGB-encoded PNG (encode_png16) through
/// `write_file_atomically`: a failed write throws `io_error` naming the file and leaves no
/// partial file.
inline void write_png16(const std::filesystem::path& path, ImageView<const Color> image) {
  write_file_atomically(path, encode_png16(image, path.string()));
}

/// Reads a PNG file as 16-bit sRGB codes (an 8-bit file's code c as 257 c; grey, palette and
/// alpha converted to RGB). The file is checked as `read_rgb8` checks it (a regular file within
/// `limits`, the size from the header before decoding). Throws `io_error` naming the file.
[[nodiscard]] inline Image<Rgb16> read_png16(const std::filesystem::path& path, const LoadLimits& limits = {}) {
  static_assert(sizeof(Rgb16) == 6, "Rgb16 must be tightly packed for libpng");
  const std::uint64_t max_bytes = std::min<std::uint64_t>(limits.max_image_file_bytes, std::numeric_limits<int>::max());
  const std::uint64_t file_bytes = detail::require_regular_file(path, max_bytes, "image");
  const std::vector<unsigned char> bytes = detail::read_file_bytes(path, 0, static_cast<std::size_t>(file_bytes));
  detail::check_png_chunks(path, bytes, bytes.size());
  detail::Png16Io io;
  io.in = bytes.data();
  io.in_size = bytes.size();
  Image<Rgb16> image;
  std::vector<png_bytep> rows;
  const int result = detail::png16_decode(
      io,
      [&](png_uint_32 w, png_uint_32 h) {
        if (w > static_cast<png_uint_32>(std::numeric_limits<int>::max()) ||
            h > static_cast<png_uint_32>(std::numeric_limits<int>::max()))
          return false;
        const std::uint64_t pixels = std::uint64_t(w) * h;
        return w > 0 && h > 0 && pixels <= limits.max_image_pixels;
      },
      [&](png_uint_32 w, png_uint_32 h) {
        image = Image<Rgb16>(static_cast<int>(w), static_cast<int>(h));
        rows.resize(h);
        for (png_uint_32 y = 0; y < h; ++y)
          rows[y] = reinterpret_cast<png_bytep>(image.view().row(static_cast<int>(y)));
        return rows.data();
      });
  if (result == 2)
    throw io_error(path.string(), "image size outside [1, LoadLimits::max_image_pixels = " +
                                      std::to_string(limits.max_image_pixels) + "]");
  if (result != 0) throw io_error(path.string(), std::string("cannot decode PNG: ") + io.message);
  return image;
}

} // namespace mpr
