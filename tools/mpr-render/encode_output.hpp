#pragma once
// mpr-render's image writer choice: a linear render encoded in the format of its file name
// (output.hpp's image_format) with the settings of OutputEncoding: 8-bit sRGB PNG or JPEG
// (stb_image_write), 16-bit sRGB PNG (libpng, mpr/io/png16.hpp), RGB PFM (mpr/io/pfm.hpp) or
// OpenEXR half or float (mpr/io/exr.hpp). Independent of the option parser: a Job's output and
// encoding, or any caller's, pick the writer.

#include "output.hpp"

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/pfm.hpp>
#if defined(MPR_HAVE_LIBPNG)
#include <mpr/io/png16.hpp>
#endif
#if defined(MPR_HAVE_OPENEXR)
#include <mpr/io/exr.hpp>
#endif

#include <cstddef>
#include <filesystem>
#include <vector>

namespace mpr_cli {

/// Whether this build writes 16-bit PNG (libpng found at configure time: MPR_HAVE_LIBPNG).
[[nodiscard]] constexpr bool png16_available() noexcept {
#if defined(MPR_HAVE_LIBPNG)
  return true;
#else
  return false;
#endif
}

/// The bytes of the file `path` (an 8-bit PNG or a JPEG) for the 8-bit sRGB image `image` (the
/// codes of a linear render, render_job.hpp's FrameSinks::encoded). Throws argument_error("--output")
/// for a format that is not 8-bit sRGB, io_error naming `path` when encoding fails.
[[nodiscard]] inline std::vector<unsigned char> encode_output(const std::filesystem::path& path,
                                                              const mpr::Image<mpr::Rgb8>& image,
                                                              const OutputEncoding& encoding = {}) {
  const ImageFormat format = image_format(path);
  if (is_linear(format) || (format == ImageFormat::png && encoding.png_bits != 8))
    throw mpr::argument_error("--output", "'" + path.string() + "' stores more than 8-bit sRGB codes");
  std::vector<unsigned char> bytes = encode_image(path, image);
  if (bytes.empty()) throw mpr::io_error(path.string(), "cannot encode the image");
  return bytes;
}

/// The bytes of the file `path` for the linear image `image`: the format from the extension of
/// `path` (image_format), 16-bit PNG when `encoding.png_bits` is 16, half or float OpenEXR by
/// `encoding.exr_pixel`. Throws argument_error("--output") for an extension mpr-render does not
/// write (or a format this build lacks), io_error naming `path` when encoding fails.
[[nodiscard]] inline std::vector<unsigned char> encode_output(const std::filesystem::path& path,
                                                              const mpr::Image<mpr::Color>& image,
                                                              const OutputEncoding& encoding = {}) {
  const ImageFormat format = image_format(path);
  if (format == ImageFormat::pfm) return mpr::encode_pfm(image.view());
  if (format == ImageFormat::exr) {
#if defined(MPR_HAVE_OPENEXR)
    const mpr::ExrSample sample = encoding.exr_pixel == ExrPixel::full ? mpr::ExrSample::float32 : mpr::ExrSample::half;
    return mpr::encode_exr(image.view(), sample, path.string());
#endif
  }
  if (format == ImageFormat::png && encoding.png_bits == 16) {
#if defined(MPR_HAVE_LIBPNG)
    return mpr::encode_png16(image.view(), path.string());
#else
    throw mpr::argument_error("--bit-depth", "this mpr-render was built without libpng (install libpng-dev and "
                                             "rebuild); 16 bits are unavailable");
#endif
  }
  mpr::Image<mpr::Rgb8> encoded(image.width(), image.height());
  for (int y = 0; y < image.height(); ++y)
    mpr::PixelTraits<mpr::Rgb8>::from_colors(&image(0, y), &encoded(0, y), static_cast<std::size_t>(image.width()));
  return encode_output(path, encoded, encoding);
}

} // namespace mpr_cli
