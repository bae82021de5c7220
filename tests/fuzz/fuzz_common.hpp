#pragma once
// Shared by the fuzz targets: a private scratch folder per process (on tmpfs when available),
// whole-file writes, tiny PNGs, and the small limits the fuzzers load with (so that a header
// promising a huge image is refused, not allocated).

#include <mpr/core/color.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/load_limits.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <unistd.h>
#include <vector>

namespace mpr_fuzz {

/// The scratch folders of this process, removed when it exits normally (libFuzzer's end of
/// -runs or -max_total_time, each -jobs worker); a crashing input leaves its folder for the
/// report.
class ScratchFolders {
public:
  ScratchFolders() = default;
  ScratchFolders(const ScratchFolders&) = delete;
  ScratchFolders& operator=(const ScratchFolders&) = delete;
  ~ScratchFolders() {
    for (const std::filesystem::path& dir : dirs_) {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  }
  void add(const std::filesystem::path& dir) { dirs_.push_back(dir); }

private:
  std::vector<std::filesystem::path> dirs_;
};

/// A folder for this process's files: /dev/shm/mpr-fuzz-<pid>-<tag> (or under the temp folder),
/// removed at exit (`ScratchFolders`).
inline std::filesystem::path scratch(const std::string& tag) {
  static ScratchFolders folders;
  const std::filesystem::path base = std::filesystem::is_directory("/dev/shm") ? std::filesystem::path("/dev/shm")
                                                                               : std::filesystem::temp_directory_path();
  const std::filesystem::path dir = base / ("mpr-fuzz-" + std::to_string(::getpid()) + "-" + tag);
  std::filesystem::create_directories(dir);
  folders.add(dir);
  return dir;
}

inline void write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// A w x h PNG with a gradient, as PNG bytes.
inline std::string tiny_png(int w, int h, int seed = 0) {
  mpr::Image<mpr::Rgb8> image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      image(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(40 * x + seed), static_cast<std::uint8_t>(50 * y),
                              static_cast<std::uint8_t>(seed)};
  const std::vector<unsigned char> bytes = mpr::encode_png(image.view());
  return std::string(bytes.begin(), bytes.end());
}

/// Limits small enough for a fuzzer's speed and memory (64 x 64 pixels per image).
inline mpr::LoadLimits fuzz_limits() {
  mpr::LoadLimits limits;
  limits.max_image_pixels = 1 << 12;
  limits.max_set_bytes = 1 << 22;
  limits.max_text_bytes = 1 << 20;
  limits.max_line_bytes = 1 << 16;
  limits.max_image_file_bytes = 1 << 20;
  return limits;
}

/// Splits `text` at the first occurrence of `separator`: {before, after} (after empty if none).
inline std::pair<std::string_view, std::string_view> split_once(std::string_view text, std::string_view separator) {
  const std::size_t at = text.find(separator);
  if (at == std::string_view::npos) return {text, {}};
  return {text.substr(0, at), text.substr(at + separator.size())};
}

} // namespace mpr_fuzz
