#pragma once
/// \file
/// Writing and reading linear-light RGB OpenEXR files through the OpenEXR library (link
/// `OpenEXR::OpenEXR`, Debian's libopenexr-dev).
///
/// A linear `Color` image is stored as the channels R, G and B of one scan-line part (data window
/// from (0, 0), ZIP compression), as 16-bit half floats (`ExrSample::half`: about three decimal
/// digits, values up to 65504, larger ones become infinity) or as 32-bit floats
/// (`ExrSample::float32`: the values exactly); floats become half by Imath's conversion, rounded
/// to nearest (ties to even). Reading returns the R, G and B channels as 32-bit floats (a missing
/// channel reads as 0).

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/file_write.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/load_limits.hpp>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace mpr {

/// The sample type of an OpenEXR file's channels.
enum class ExrSample {
  half,   ///< 16-bit IEEE half floats (OpenEXR's HALF)
  float32 ///< 32-bit IEEE floats (OpenEXR's FLOAT)
};

namespace detail {

/// An OpenEXR output stream into memory (OpenEXR writes through this interface; one object per
/// file, so its virtual calls are per block of bytes, never per pixel).
class ExrMemoryStream final : public Imf::OStream {
public:
  ExrMemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    const std::size_t end = static_cast<std::size_t>(position_) + static_cast<std::size_t>(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::memcpy(bytes_.data() + position_, c, static_cast<std::size_t>(n));
    position_ = end;
  }
  [[nodiscard]] std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t pos) override { position_ = pos; }
  [[nodiscard]] std::vector<unsigned char>& bytes() noexcept { return bytes_; }

private:
  std::vector<unsigned char> bytes_;
  std::uint64_t position_ = 0;
};

/// The frame-buffer slices of the R, G and B floats of `image` (`Color` packs three floats).
[[nodiscard]] inline Imf::FrameBuffer exr_frame_buffer(ImageView<const Color> image) {
  static_assert(sizeof(Color) == 3 * sizeof(float), "Color must be three packed floats");
  Imf::FrameBuffer fb;
  const std::size_t x_stride = sizeof(Color), y_stride = sizeof(Color) * static_cast<std::size_t>(image.stride());
  char* base = const_cast<char*>(reinterpret_cast<const char*>(image.data())); // OpenEXR only reads it
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), x_stride, y_stride));
  return fb;
}

/// The frame-buffer slices of `halves`, R G B half floats per pixel, `width` pixels a row
/// (OpenEXR writes a frame buffer of the channels' own type only).
[[nodiscard]] inline Imf::FrameBuffer exr_half_frame_buffer(std::vector<Imath::half>& halves, int width) {
  Imf::FrameBuffer fb;
  const std::size_t x_stride = 3 * sizeof(Imath::half), y_stride = x_stride * static_cast<std::size_t>(width);
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c)
    fb.insert(names[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.data() + c), x_stride, y_stride));
  return fb;
}

/// `image` as R G B half floats per pixel, rows packed (Imath::half: rounded to nearest even;
/// above 65504 infinity).
[[nodiscard]] inline std::vector<Imath::half> to_halves(ImageView<const Color> image) {
  std::vector<Imath::half> halves;
  halves.reserve(3 * static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.height()));
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < 3; ++c) halves.emplace_back(image(x, y)[c]);
  return halves;
}

} // namespace detail

/// The bytes of an OpenEXR file of the linear image `image` with channels R, G, B of `sample`
/// type (see the file comment). Throws `io_error` naming `name` (the file it is meant for) when
/// the image is empty or OpenEXR fails.
[[nodiscard]] inline std::vector<unsigned char> encode_exr(ImageView<const Color> image, ExrSample sample,
                                                           const std::string& name = "EXR") {
  if (image.empty()) throw io_error(name, "cannot write an empty image");
  try {
    Imf::Header header(image.width(), image.height());
    const Imf::PixelType type = sample == ExrSample::half ? Imf::HALF : Imf::FLOAT;
    for (const char* channel : {"R", "G", "B"}) header.channels().insert(channel, Imf::Channel(type));
    detail::ExrMemoryStream stream;
    {
      Imf::OutputFile file(stream, header, 1);
      std::vector<Imath::half> halves;
      if (sample == ExrSample::half) {
        halves = detail::to_halves(image);
        file.setFrameBuffer(detail::exr_half_frame_buffer(halves, image.width()));
      } else {
        file.setFrameBuffer(detail::exr_frame_buffer(image));
      }
      file.writePixels(image.height());
    } // the file's destructor writes the line-offset table
    return std::move(stream.bytes());
  } catch (const std::exception& e) {
    throw io_error(name, std::string("cannot encode OpenEXR: ") + e.what());
  }
}

/// Writes the linear image `image` as an OpenEXR file (encode_exr) through
/// `write_file_atomically`: a failed write throws `io_error` naming the file and leaves no
/// partial file.
inline void write_exr(const std::filesystem::path& path, ImageView<const Color> image,
                      ExrSample sample = ExrSample::half) {
  write_file_atomically(path, encode_exr(image, sample, path.string()));
}

/// Reads the R, G and B channels of an OpenEXR file as linear `Color` (32-bit floats, top row
/// first; a missing channel is 0). Refuses non-regular files, files above
/// `limits.max_image_file_bytes` and data windows above `limits.max_image_pixels` (from the
/// header, before the pixels are read). Throws `io_error` naming the file.
[[nodiscard]] inline Image<Color> read_exr(const std::filesystem::path& path, const LoadLimits& limits = {}) {
  (void)detail::require_regular_file(path, limits.max_image_file_bytes, "image");
  try {
    Imf::InputFile file(path.string().c_str(), 1);
    const Imath::Box2i window = file.header().dataWindow();
    const std::int64_t w = std::int64_t(window.max.x) - window.min.x + 1,
                       h = std::int64_t(window.max.y) - window.min.y + 1;
    if (w <= 0 || h <= 0 || w > std::numeric_limits<int>::max() || h > std::numeric_limits<int>::max())
      throw io_error(path.string(), "bad OpenEXR data window");
    detail::check_image_pixels(path, static_cast<int>(w), static_cast<int>(h), limits);
    Image<Color> image(static_cast<int>(w), static_cast<int>(h));
    Imf::FrameBuffer fb;
    const std::size_t x_stride = sizeof(Color), y_stride = sizeof(Color) * static_cast<std::size_t>(w);
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) // Slice::Make: the data window's first pixel at the image's first
      fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, reinterpret_cast<char*>(image.data()) + c * sizeof(float),
                                           window, x_stride, y_stride));
    file.setFrameBuffer(fb);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const io_error&) {
    throw;
  } catch (const std::exception& e) {
    throw io_error(path.string(), std::string("cannot read OpenEXR: ") + e.what());
  }
}

} // namespace mpr
