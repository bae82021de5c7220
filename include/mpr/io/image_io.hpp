#pragma once
/// \file
/// Reading images (PNG, JPEG, BMP, TGA, ... through stb_image) and writing PNG and JPEG
/// (stb_image_write).
///
/// This header only declares stb's functions: link Debian's `libstb` (the CMake target `mpr::mpr`
/// does this) or compile `src/stb_implementation.cpp` once into your program.
/// Files are sRGB-encoded: `read_rgb8` returns the stored 8-bit codes, `read_linear` decodes them
/// to linear `Color`, and `write_png` of a linear image encodes with `to_rgb8`. Reading refuses
/// non-regular files and images above `LoadLimits` (load_limits.hpp) before decoding.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/file_write.hpp>
#include <mpr/io/load_limits.hpp>

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace mpr {

namespace detail {
struct StbFree {
  void operator()(unsigned char* p) const noexcept { stbi_image_free(p); }
};

/// Bytes of an image file read before its header is checked: enough for the header of every
/// format stb_image reads (a JPEG's frame header follows its APP segments, 64 KiB each at most).
inline constexpr std::size_t kImageHeaderBytes = std::size_t(1) << 20;

/// Reads at most `count` bytes of `path` from byte `offset` on (fewer only at the end of the
/// file). Throws `io_error` naming the file when it cannot be opened or read.
[[nodiscard]] inline std::vector<unsigned char> read_file_bytes(const std::filesystem::path& path, std::uint64_t offset,
                                                                std::size_t count) {
  std::vector<unsigned char> bytes(count);
  std::FILE* file = std::fopen(path.string().c_str(), "rb");
  if (file == nullptr) throw io_error(path.string(), std::string("cannot open: ") + std::strerror(errno));
  if (offset > 0 && std::fseek(file, static_cast<long>(offset), SEEK_SET) != 0) {
    std::fclose(file);
    throw io_error(path.string(), "read error (cannot seek)");
  }
  const std::size_t got = bytes.empty() ? 0 : std::fread(bytes.data(), 1, bytes.size(), file);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) throw io_error(path.string(), "read error");
  bytes.resize(got);
  return bytes;
}

/// The size of image file `path` (a regular, non-empty file within
/// `limits.max_image_file_bytes`) and its first `kImageHeaderBytes` bytes (all of it when
/// shorter): what the header checks read before the file is read whole.
struct ImageFileHead {
  std::uint64_t size = 0;
  std::vector<unsigned char> head;
};

[[nodiscard]] inline ImageFileHead read_image_head(const std::filesystem::path& path, const LoadLimits& limits) {
  const std::uint64_t max_bytes = std::min<std::uint64_t>(limits.max_image_file_bytes, std::numeric_limits<int>::max());
  ImageFileHead h;
  h.size = require_regular_file(path, max_bytes, "image");
  if (h.size == 0) throw io_error(path.string(), "empty file (not an image)");
  h.head = read_file_bytes(path, 0, static_cast<std::size_t>(std::min<std::uint64_t>(h.size, kImageHeaderBytes)));
  if (h.head.size() != std::min<std::uint64_t>(h.size, kImageHeaderBytes))
    throw io_error(path.string(), "read error (file shorter than its size)");
  return h;
}

/// The whole image file whose head `h` was read (`read_image_head`).
[[nodiscard]] inline std::vector<unsigned char> read_image_rest(const std::filesystem::path& path, ImageFileHead&& h) {
  std::vector<unsigned char> bytes = std::move(h.head);
  if (bytes.size() < h.size) {
    const std::vector<unsigned char> rest =
        read_file_bytes(path, bytes.size(), static_cast<std::size_t>(h.size - bytes.size()));
    bytes.insert(bytes.end(), rest.begin(), rest.end());
  }
  if (bytes.size() != h.size) throw io_error(path.string(), "read error (file shorter than its size)");
  return bytes;
}

/// The bytes of the image file `path` (a regular file within `limits.max_image_file_bytes`).
[[nodiscard]] inline std::vector<unsigned char> read_image_bytes(const std::filesystem::path& path,
                                                                 const LoadLimits& limits) {
  return read_image_rest(path, read_image_head(path, limits));
}

/// The most bytes an image file of `pixels` pixels plausibly has: 8 a pixel (16-bit RGBA stored
/// uncompressed) plus 16 MiB of metadata. A larger file is refused before it is read whole.
[[nodiscard]] constexpr std::uint64_t max_image_file_bytes_for(std::uint64_t pixels) noexcept {
  return 8 * pixels + (std::uint64_t(16) << 20);
}

/// stb's reason for the last failure, never empty.
[[nodiscard]] inline std::string stb_reason() {
  const char* reason = stbi_failure_reason();
  return reason != nullptr && reason[0] != '\0' ? std::string(reason)
                                                : std::string("corrupt or truncated data (stb gave no reason)");
}

/// Refuses a JPEG whose Huffman tables (DHT segments) define more than 256 codes: stb_image
/// (Debian's 2022 version) writes past its tables for those (found by fuzzing, see
/// docs/reliability.md). Walks the JPEG's marker segments, entropy-coded data included.
inline void check_jpeg_tables(const std::filesystem::path& path, std::span<const unsigned char> b) {
  // stb_image takes any number of 0xFF fill bytes before the start-of-image marker D8.
  std::size_t i = 0;
  while (i < b.size() && b[i] == 0xFF) ++i;
  if (i < 1 || i >= b.size() || b[i] != 0xD8) return; // not a JPEG
  ++i;
  const auto refuse = [&](const std::string& reason) { throw io_error(path.string(), "corrupt JPEG: " + reason); };
  const auto at = [&](std::size_t k) -> unsigned { return k < b.size() ? b[k] : 0u; }; // stb reads 0 past the end
  while (i + 1 < b.size()) {
    if (b[i] != 0xFF) { // entropy-coded data: skip to the next marker
      ++i;
      continue;
    }
    const unsigned marker = b[i + 1];
    if (marker == 0x00 || marker == 0xFF || (marker >= 0xD0 && marker <= 0xD8) || marker == 0x01) {
      i += marker == 0xFF ? 1 : 2; // stuffed byte, fill byte, restart marker, SOI, TEM
      continue;
    }
    if (marker == 0xD9) return; // EOI
    if (i + 3 >= b.size()) return;
    const std::size_t length = (std::size_t(b[i + 2]) << 8) | b[i + 3];
    if (length < 2) refuse("segment length below 2");
    const std::size_t end = std::min(b.size(), i + 2 + length);
    if (marker == 0xC4) { // DHT: tables of 1 + 16 counts + the values, read as stb reads them
      for (std::size_t t = i + 4; t < i + 2 + length && t < b.size();) {
        std::size_t codes = 0;
        for (std::size_t k = 1; k <= 16; ++k) codes += at(t + k); // even past the segment's end
        if (codes > 256) refuse("a Huffman table defines " + std::to_string(codes) + " codes (at most 256)");
        t += 17 + codes;
      }
    }
    i = end;
  }
}

/// Refuses a PNG with a chunk that claims more bytes than the file has left: stb_image grows
/// its IDAT buffer to the claimed length before reading it (a 129-byte file asked for 2 GiB;
/// found by fuzzing, see docs/reliability.md). Walks the chunks up to IEND; anything that is not
/// a PNG, or a header cut short, is left to stb_image's own checks. `b` may be the head of a file
/// of `file_bytes` bytes (the chunks within `b` are walked, their lengths checked against the file).
inline void check_png_chunks(const std::filesystem::path& path, std::span<const unsigned char> b,
                             std::uint64_t file_bytes) {
  static constexpr unsigned char signature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (b.size() < 8 || !std::equal(signature, signature + 8, b.begin())) return;
  std::size_t i = 8;
  while (i + 8 <= b.size()) {
    const std::uint64_t length = (std::uint64_t(b[i]) << 24) | (std::uint64_t(b[i + 1]) << 16) |
                                 (std::uint64_t(b[i + 2]) << 8) | std::uint64_t(b[i + 3]);
    const std::string type(reinterpret_cast<const char*>(b.data() + i + 4), 4);
    const std::uint64_t left = file_bytes - (i + 8);
    if (length > left) {
      std::string name;
      for (const char c : type) name += std::isalpha(static_cast<unsigned char>(c)) ? c : '?';
      throw io_error(path.string(), "corrupt PNG: chunk " + name + " at byte " + std::to_string(i) + " claims " +
                                        std::to_string(length) + " bytes, the file has " + std::to_string(left) +
                                        " left");
    }
    if (type == "IEND") return;
    i += 12 + static_cast<std::size_t>(length); // length, type, data, CRC
  }
}

/// Refuses a binary PNM (P5 or P6, the kinds stb_image reads) whose width, height or maximum
/// value has more than 9 digits: stb_image 2.27 accumulates the digits in an `int` without a
/// bound, a signed overflow (found by fuzzing, see docs/reliability.md). Walks the header as
/// stb_image does (white space, `#` comments to the end of the line); anything else is left to
/// stb_image's own checks. `b` may be the head of the file (a token cut by its end is not judged).
inline void check_pnm_header(const std::filesystem::path& path, std::span<const unsigned char> b) {
  if (b.size() < 2 || b[0] != 'P' || (b[1] != '5' && b[1] != '6')) return;
  const auto space = [](unsigned char c) { return c == ' ' || (c >= '\t' && c <= '\r'); };
  std::size_t i = 2;
  for (const char* field : {"width", "height", "maximum value"}) {
    for (;;) { // stb__pnm_skip_whitespace: spaces, then any comments and the spaces after them
      while (i < b.size() && space(b[i])) ++i;
      if (i >= b.size() || b[i] != '#') break;
      while (i < b.size() && b[i] != '\n' && b[i] != '\r') ++i;
    }
    std::size_t digits = 0;
    while (i < b.size() && b[i] >= '0' && b[i] <= '9') ++i, ++digits;
    if (digits > 9)
      throw io_error(path.string(), std::string("corrupt PNM: its ") + field + " has " + std::to_string(digits) +
                                        " digits (at most 9)");
    if (digits == 0 || i >= b.size()) return; // not a number, or the head ends: stb_image decides
  }
}

/// Throws `io_error` naming `path` when the image is empty or `width` x `height` is above
/// `limits.max_image_pixels`.
inline void check_image_pixels(const std::filesystem::path& path, int width, int height, const LoadLimits& limits) {
  if (width <= 0 || height <= 0) // stb_image accepts e.g. a BMP of height 0 (found by fuzzing)
    throw io_error(path.string(), "empty image (" + std::to_string(width) + "x" + std::to_string(height) + ")");
  const std::uint64_t pixels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  if (pixels > limits.max_image_pixels)
    throw io_error(path.string(), "image of " + std::to_string(width) + "x" + std::to_string(height) + " = " +
                                      std::to_string(pixels) + " pixels is above the limit of " +
                                      std::to_string(limits.max_image_pixels) +
                                      " pixels (LoadLimits::max_image_pixels)");
}
/// Throws `io_error` naming `path` unless a file of `file_bytes` bytes is plausible for an image
/// of `width` x `height` pixels (`max_image_file_bytes_for`).
inline void check_image_file_size(const std::filesystem::path& path, std::uint64_t file_bytes, int width, int height) {
  const std::uint64_t most =
      max_image_file_bytes_for(static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height));
  if (file_bytes > most)
    throw io_error(path.string(), "file of " + std::to_string(file_bytes) + " bytes is far larger than an image of " +
                                      std::to_string(width) + "x" + std::to_string(height) + " can be (at most " +
                                      std::to_string(most) + " bytes)");
}

/// Reads the head of image file `path` and checks its header: stb_image recognises it, its size
/// is within `limits.max_image_pixels` and the file is not far larger than such an image. Sets
/// `width` and `height`; returns the head for `read_image_rest`.
[[nodiscard]] inline ImageFileHead check_image_head(const std::filesystem::path& path, const LoadLimits& limits,
                                                    int& width, int& height) {
  ImageFileHead h = read_image_head(path, limits);
  check_jpeg_tables(path, h.head); // stb_image reads the tables before the frame header
  check_png_chunks(path, h.head, h.size);
  check_pnm_header(path, h.head);
  int channels = 0;
  if (stbi_info_from_memory(h.head.data(), static_cast<int>(h.head.size()), &width, &height, &channels) == 0) {
    if (h.head.size() < h.size)
      throw io_error(path.string(), "cannot decode image: no header stb_image reads in the first " +
                                        std::to_string(kImageHeaderBytes) + " bytes (" + stb_reason() + ")");
    throw io_error(path.string(), "cannot decode image: " + stb_reason());
  }
  check_image_pixels(path, width, height, limits);
  check_image_file_size(path, h.size, width, height);
  return h;
}
} // namespace detail

/// The size of an image, read from its header.
struct ImageInfo {
  int width = 0;
  int height = 0;
};

/// Reads only the header of an image file (its first `detail::kImageHeaderBytes` bytes at most;
/// nothing is decoded). Throws `io_error` naming the file when it is not a regular file within
/// the limits, not an image stb_image can read from that head, larger than
/// `limits.max_image_pixels`, or a file far larger than an image of that size can be
/// (`detail::max_image_file_bytes_for`).
[[nodiscard]] inline ImageInfo read_image_info(const std::filesystem::path& path, const LoadLimits& limits = {}) {
  ImageInfo info;
  (void)detail::check_image_head(path, limits, info.width, info.height);
  return info;
}

/// Bytes a loaded frame set takes per pixel: 3 for the decoded 8-bit RGB image, 3 for its copy in
/// the set's texel buffer (`CameraFrameSet`, lightfield/frame_set.hpp).
inline constexpr std::uint64_t kSetBytesPerPixel = 6;

/// Bytes a pixel takes in addition where the set also holds its frames as 16-bit linear values
/// (`CameraFrameSet::holds_linear16`: 3 channels of 2 bytes).
inline constexpr std::uint64_t kLinear16BytesPerPixel = 6;

/// Throws `io_error` naming the first of `paths` above the budget when the images (sizes
/// `infos`, in the same order) take more than `limits.max_set_bytes` bytes once loaded into a
/// frame set (`kSetBytesPerPixel` a pixel, and `kLinear16BytesPerPixel` more with `linear16`: the
/// set's `holds_linear16()`).
inline void check_set_budget(std::span<const std::filesystem::path> paths, std::span<const ImageInfo> infos,
                             const LoadLimits& limits, bool linear16 = false) {
  const std::uint64_t per_pixel = kSetBytesPerPixel + (linear16 ? kLinear16BytesPerPixel : 0);
  std::uint64_t bytes = 0;
  for (std::size_t i = 0; i < infos.size() && i < paths.size(); ++i) {
    bytes += per_pixel * static_cast<std::uint64_t>(infos[i].width) * static_cast<std::uint64_t>(infos[i].height);
    if (bytes > limits.max_set_bytes)
      throw io_error(paths[i].string(),
                     "the " + std::to_string(infos.size()) + " images of this set take more than the limit of " +
                         std::to_string(limits.max_set_bytes) +
                         " bytes (LoadLimits::max_set_bytes); reached at this image (" + std::to_string(i + 1) + ")");
  }
}

/// Reads an image file into 8-bit sRGB pixels (grey and alpha are converted to RGB; 16-bit files
/// are reduced to 8 bits). The header is checked against `limits` before decoding. Throws
/// `io_error` with the path and the reason (stb's, or the limit exceeded).
[[nodiscard]] inline Image<Rgb8> read_rgb8(const std::filesystem::path& path, const LoadLimits& limits = {}) {
  int width = 0, height = 0, channels = 0;
  const std::vector<unsigned char> bytes =
      detail::read_image_rest(path, detail::check_image_head(path, limits, width, height));
  detail::check_jpeg_tables(path, bytes);
  detail::check_png_chunks(path, bytes, bytes.size());
  detail::check_pnm_header(path, bytes);
  const int length = static_cast<int>(bytes.size());
  int w = 0, h = 0;
  const std::unique_ptr<unsigned char, detail::StbFree> data(
      stbi_load_from_memory(bytes.data(), length, &w, &h, &channels, 3));
  if (!data) throw io_error(path.string(), "cannot decode image: " + detail::stb_reason());
  if (w != width || h != height)
    throw io_error(path.string(), "cannot decode image: header and data disagree on the size");
  Image<Rgb8> image(width, height);
  std::memcpy(static_cast<void*>(image.data()), data.get(), static_cast<std::size_t>(width) * height * 3);
  return image;
}

/// Reads an image file and decodes it to linear `Color` (see `read_rgb8`).
[[nodiscard]] inline Image<Color> read_linear(const std::filesystem::path& path, const LoadLimits& limits = {}) {
  const Image<Rgb8> encoded = read_rgb8(path, limits);
  return convert_image<Color>(encoded.view(), [](const Rgb8& p) { return to_color(p); });
}

/// Encodes 8-bit sRGB pixels as PNG bytes (in memory).
[[nodiscard]] inline std::vector<unsigned char> encode_png(ImageView<const Rgb8> image) {
  static_assert(sizeof(Rgb8) == 3, "Rgb8 must be tightly packed for stb");
  std::vector<unsigned char> bytes;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* first = static_cast<const unsigned char*>(data);
    out->insert(out->end(), first, first + size);
  };
  if (stbi_write_png_to_func(append, &bytes, image.width(), image.height(), 3, image.data(),
                             static_cast<int>(image.stride() * 3)) == 0)
    bytes.clear();
  return bytes;
}

/// Writes 8-bit sRGB pixels as a PNG file, through `write_file_atomically` (file_write.hpp): a
/// failed write (missing folder, no permission, full disk) throws `io_error` naming the file and
/// the reason and never leaves a partial file under `path`.
inline void write_png(const std::filesystem::path& path, ImageView<const Rgb8> image) {
  if (image.empty()) throw io_error(path.string(), "cannot write an empty image");
  const std::vector<unsigned char> bytes = encode_png(image);
  if (bytes.empty()) throw io_error(path.string(), "cannot encode PNG");
  write_file_atomically(path, bytes);
}

/// Writes a linear image as an 8-bit sRGB PNG (`to_rgb8` per pixel).
inline void write_png(const std::filesystem::path& path, ImageView<const Color> image) {
  const Image<Rgb8> encoded = convert_image<Rgb8>(image, [](const Color& c) { return to_rgb8(c); });
  write_png(path, encoded.view());
}

inline void write_png(const std::filesystem::path& path, const Image<Rgb8>& image) { write_png(path, image.view()); }
inline void write_png(const std::filesystem::path& path, const Image<Color>& image) { write_png(path, image.view()); }

/// Encodes 8-bit sRGB pixels as baseline JPEG bytes (in memory) at `quality` in [1, 100]
/// (stb_image_write; 4:2:0 chroma subsampling below 90, none from 90). Empty on failure.
[[nodiscard]] inline std::vector<unsigned char> encode_jpeg(ImageView<const Rgb8> image, int quality = 95) {
  static_assert(sizeof(Rgb8) == 3, "Rgb8 must be tightly packed for stb");
  std::vector<unsigned char> bytes;
  if (image.empty() || quality < 1 || quality > 100) return bytes;
  // stb's JPEG writer takes no row stride: copy a strided view into contiguous rows.
  Image<Rgb8> packed;
  const Rgb8* pixels = image.data();
  if (image.stride() != image.width()) {
    packed = Image<Rgb8>(image.width(), image.height());
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) packed(x, y) = image(x, y);
    pixels = packed.data();
  }
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* first = static_cast<const unsigned char*>(data);
    out->insert(out->end(), first, first + size);
  };
  if (stbi_write_jpg_to_func(append, &bytes, image.width(), image.height(), 3, pixels, quality) == 0) bytes.clear();
  return bytes;
}

/// Writes 8-bit sRGB pixels as a JPEG file at `quality` in [1, 100] (default 95), through
/// `write_file_atomically` like `write_png`: a failed write throws `io_error` naming the file and
/// never leaves a partial file under `path`. Throws `argument_error` ("quality") outside [1, 100].
inline void write_jpeg(const std::filesystem::path& path, ImageView<const Rgb8> image, int quality = 95) {
  if (quality < 1 || quality > 100) throw argument_error("quality", "must lie in [1, 100]");
  if (image.empty()) throw io_error(path.string(), "cannot write an empty image");
  const std::vector<unsigned char> bytes = encode_jpeg(image, quality);
  if (bytes.empty()) throw io_error(path.string(), "cannot encode JPEG");
  write_file_atomically(path, bytes);
}

inline void write_jpeg(const std::filesystem::path& path, const Image<Rgb8>& image, int quality = 95) {
  write_jpeg(path, image.view(), quality);
}

} // namespace mpr
