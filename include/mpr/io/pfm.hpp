#pragma once
/// \file
/// Reading and writing PFM files (Portable Float Map): one-channel ("Pf"), the format of the depth
/// and disparity maps of the HCI 4D light-field benchmark and of Middlebury stereo, and RGB
/// ("PF"), a linear-light colour image (mpr-render --output x.pfm).
///
/// Layout: the ASCII header `Pf` (or `PF`), the width and height, and a scale whose sign gives the byte
/// order (negative: little-endian, positive: big-endian), separated by white space, then exactly
/// one white-space byte and `width * height` 32-bit IEEE floats (times 3, R G B interleaved, for
/// `PF`), rows from the BOTTOM of the image up. `read_pfm` returns rows top-down (row 0 at the top, as every mpr
/// image); the scale's magnitude is ignored. Reading refuses non-regular files, files above
/// `LoadLimits::max_image_file_bytes`, images above `LoadLimits::max_image_pixels` (from the
/// header, before allocating) and any malformed header or size with an `io_error` naming the file.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/file_write.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/load_limits.hpp>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace mpr {

namespace detail {

/// The longest PFM header token read (a longer one is refused, never cut).
inline constexpr std::size_t kPfmTokenBytes = 32;
/// The PFM header must end within the file's first bytes (read before the data).
inline constexpr std::size_t kPfmHeaderBytes = 4096;

/// Reads one white-space separated token of the PFM header starting at `i` (skipping white
/// space first); at most `kPfmTokenBytes` + 1 bytes, so a longer token shows as one above the
/// limit and `i` never passes a byte of it. Empty when the header ends first.
[[nodiscard]] inline std::string pfm_token(const std::vector<unsigned char>& b, std::size_t& i) {
  const auto space = [](unsigned char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (i < b.size() && space(b[i])) ++i;
  std::string token;
  while (i < b.size() && !space(b[i]) && token.size() <= kPfmTokenBytes) token.push_back(static_cast<char>(b[i++]));
  return token;
}

/// The positive integer `token` (a PFM width or height), or -1 when it is not one (digits only,
/// at most 9 of them).
[[nodiscard]] inline long pfm_size(const std::string& token) noexcept {
  if (token.empty() || token.size() > 9) return -1;
  long v = 0;
  for (const char c : token) {
    if (c < '0' || c > '9') return -1;
    v = v * 10 + (c - '0');
  }
  return v;
}

/// A PFM header: the image size, the byte order and where the data starts.
struct PfmHeader {
  long width = 0, height = 0;
  bool little = true;
  std::size_t data_offset = 0;
};

/// Parses the PFM header in `head`, the first bytes of a file of `file_bytes` bytes, and checks
/// the size against `limits` and the file's length; the data is not needed. The header ends with
/// one white-space byte, or with `\r\n` when the data then has exactly the size's length.
/// `channels`: 1 expects a one-channel map (Pf), 3 an RGB image (PF).
[[nodiscard]] inline PfmHeader parse_pfm_header(const std::filesystem::path& path,
                                                const std::vector<unsigned char>& head, std::uint64_t file_bytes,
                                                const LoadLimits& limits, int channels = 1) {
  const auto bad = [&](const std::string& reason) { return io_error(path.string(), "bad PFM: " + reason); };
  std::size_t i = 0;
  const auto token = [&] {
    std::string t = pfm_token(head, i);
    if (i >= head.size() && head.size() < file_bytes)
      throw bad("header longer than " + std::to_string(head.size()) + " bytes");
    if (t.size() > kPfmTokenBytes)
      throw bad("header token '" + t.substr(0, 16) + "...' longer than " + std::to_string(kPfmTokenBytes) + " bytes");
    return t;
  };
  const std::string magic = token();
  if (channels == 1 && magic == "PF") throw bad("a colour map (PF); a one-channel map (Pf) is expected");
  if (channels == 3 && magic == "Pf") throw bad("a one-channel map (Pf); a colour image (PF) is expected");
  if (magic != (channels == 3 ? "PF" : "Pf"))
    throw bad(std::string("the file does not start with ") + (channels == 3 ? "PF" : "Pf"));
  const std::string w_token = token(), h_token = token();
  PfmHeader h;
  h.width = pfm_size(w_token);
  h.height = pfm_size(h_token);
  if (h.width <= 0 || h.height <= 0) throw bad("size '" + w_token + " " + h_token + "' is not two positive integers");
  check_image_pixels(path, static_cast<int>(h.width), static_cast<int>(h.height), limits);
  const std::string scale_token = token();
  char* end = nullptr;
  errno = 0;
  const double scale = scale_token.empty() ? 0.0 : std::strtod(scale_token.c_str(), &end);
  if (scale_token.empty() || end != scale_token.c_str() + scale_token.size() || !std::isfinite(scale) || scale == 0)
    throw bad("scale '" + scale_token + "' is not a non-zero number");
  if (i >= head.size()) throw bad("no data after the header"); // (a longer file was refused above)
  h.little = scale < 0;
  const std::uint64_t count =
      static_cast<std::uint64_t>(h.width) * static_cast<std::uint64_t>(h.height) * static_cast<std::uint64_t>(channels);
  h.data_offset = i + 1; // the single white-space byte that ends the header
  if (head[i] == '\r' && i + 1 < head.size() && head[i + 1] == '\n' && file_bytes - (i + 2) == 4 * count)
    h.data_offset = i + 2; // a header ending in "\r\n"
  const std::uint64_t have = file_bytes - h.data_offset;
  if (have != 4 * count)
    throw bad(std::to_string(h.width) + "x" + std::to_string(h.height) + " needs " + std::to_string(4 * count) +
              " bytes of data, the file has " + std::to_string(have));
  return h;
}

} // namespace detail

namespace detail {

/// Reads a PFM file of `channels` channels (1: Pf, 3: PF) into `Px` pixels (float or Color),
/// top row first; see read_pfm.
template <class Px, int channels>
[[nodiscard]] Image<Px> read_pfm_as(const std::filesystem::path& path, const LoadLimits& limits) {
  static_assert(sizeof(Px) == channels * sizeof(float), "one float per channel, packed");
  const std::uint64_t max_bytes = std::min<std::uint64_t>(limits.max_image_file_bytes, std::numeric_limits<int>::max());
  const std::uint64_t file_bytes = require_regular_file(path, max_bytes, "image");
  if (file_bytes == 0) throw io_error(path.string(), "empty file (not an image)");
  const std::vector<unsigned char> head =
      read_file_bytes(path, 0, static_cast<std::size_t>(std::min<std::uint64_t>(file_bytes, kPfmHeaderBytes)));
  const PfmHeader h = parse_pfm_header(path, head, file_bytes, limits, channels);
  const std::vector<unsigned char> data =
      read_file_bytes(path, h.data_offset, static_cast<std::size_t>(file_bytes - h.data_offset));
  if (data.size() != file_bytes - h.data_offset)
    throw io_error(path.string(), "read error (file shorter than its size)");
  const bool swap = h.little != (std::endian::native == std::endian::little);
  Image<Px> image(static_cast<int>(h.width), static_cast<int>(h.height));
  const unsigned char* p = data.data();
  for (long y = h.height - 1; y >= 0; --y) {
    float* row = reinterpret_cast<float*>(image.view().row(static_cast<int>(y)));
    for (long x = 0; x < h.width * channels; ++x, p += 4) {
      unsigned char v[4] = {p[0], p[1], p[2], p[3]};
      if (swap) {
        std::swap(v[0], v[3]);
        std::swap(v[1], v[2]);
      }
      std::memcpy(&row[x], v, 4);
    }
  }
  return image;
}

/// The bytes of a little-endian PFM file of `channels` channels of `image` (top row first in
/// `image`, bottom row first in the file).
template <class Px, int channels>
[[nodiscard]] std::vector<unsigned char> encode_pfm_as(ImageView<const Px> image) {
  static_assert(sizeof(Px) == channels * sizeof(float), "one float per channel, packed");
  const std::string header = std::string(channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(image.width()) + " " +
                             std::to_string(image.height()) + "\n-1\n";
  std::vector<unsigned char> bytes(header.begin(), header.end());
  bytes.reserve(bytes.size() +
                4 * channels * static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.height()));
  for (int y = image.height() - 1; y >= 0; --y) {
    const float* row = reinterpret_cast<const float*>(image.row(y));
    for (int x = 0; x < image.width() * channels; ++x) {
      unsigned char v[4];
      std::memcpy(v, &row[x], 4);
      if constexpr (std::endian::native != std::endian::little) {
        std::swap(v[0], v[3]);
        std::swap(v[1], v[2]);
      }
      bytes.insert(bytes.end(), v, v + 4);
    }
  }
  return bytes;
}

} // namespace detail

/// Reads a one-channel PFM file (see the file comment) into a float image, top row first.
/// Values are returned as stored (NaN and infinities included; `CameraFrameSet::with_depth`
/// checks depths). The header (within the first `detail::kPfmHeaderBytes` bytes, tokens of at
/// most 32 bytes) is checked, size and length included, before the data is read. Throws
/// `io_error` naming the file for a file that cannot be read or lies outside `limits`, a colour
/// PFM ("PF"), a bad header (magic, size, scale) or data of the wrong length.
[[nodiscard]] inline Image<float> read_pfm(const std::filesystem::path& path, const LoadLimits& limits = {}) {
  return detail::read_pfm_as<float, 1>(path, limits);
}

/// Reads an RGB PFM file ("PF") into linear `Color`, top row first, values as stored; checked and
/// refused as `read_pfm` (a one-channel "Pf" file is refused).
[[nodiscard]] inline Image<Color> read_pfm_rgb(const std::filesystem::path& path, const LoadLimits& limits = {}) {
  return detail::read_pfm_as<Color, 3>(path, limits);
}

/// The bytes of a little-endian one-channel PFM file of `image` (top row first in `image`,
/// bottom row first in the file).
[[nodiscard]] inline std::vector<unsigned char> encode_pfm(ImageView<const float> image) {
  return detail::encode_pfm_as<float, 1>(image);
}

/// The bytes of a little-endian RGB PFM file ("PF") of the linear image `image`: its values
/// exactly, 32-bit floats, R G B per pixel, bottom row first in the file.
[[nodiscard]] inline std::vector<unsigned char> encode_pfm(ImageView<const Color> image) {
  return detail::encode_pfm_as<Color, 3>(image);
}

/// Writes `image` as a little-endian one-channel PFM file through `write_file_atomically`: a
/// failed write throws `io_error` naming the file and leaves no partial file.
inline void write_pfm(const std::filesystem::path& path, ImageView<const float> image) {
  if (image.empty()) throw io_error(path.string(), "cannot write an empty image");
  write_file_atomically(path, encode_pfm(image));
}

inline void write_pfm(const std::filesystem::path& path, const Image<float>& image) { write_pfm(path, image.view()); }

/// Writes the linear image `image` as a little-endian RGB PFM file ("PF"), atomically as
/// `write_pfm` of a one-channel image.
inline void write_pfm(const std::filesystem::path& path, ImageView<const Color> image) {
  if (image.empty()) throw io_error(path.string(), "cannot write an empty image");
  write_file_atomically(path, encode_pfm(image));
}

inline void write_pfm(const std::filesystem::path& path, const Image<Color>& image) { write_pfm(path, image.view()); }

} // namespace mpr
