#pragma once
// Helpers for the loader tests: a fresh temporary folder, tiny PNGs and text files, and the
// real-data folder (skipped when absent).

#include <mpr/io/image_io.hpp>

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace mpr_test {

/// A new empty folder under the system temp folder, removed when the object goes away.
class TempFolder {
public:
  TempFolder() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() / ("mpr-io-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
  std::filesystem::path path_;
};

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// A small PNG whose pixels encode (x, y, seed).
inline mpr::Image<mpr::Rgb8> write_test_png(const std::filesystem::path& path, int width, int height, int seed) {
  mpr::Image<mpr::Rgb8> img(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      img(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(x * 20), static_cast<std::uint8_t>(y * 30),
                            static_cast<std::uint8_t>(seed)};
  mpr::write_png(path, img);
  return img;
}

/// The real-data folder from MPR_DATA_DIR or the build's MPR_TEST_DATA_DIR; empty if unset.
inline std::filesystem::path data_dir() {
  if (const char* env = std::getenv("MPR_DATA_DIR"); env != nullptr && *env != 0) return env;
#ifdef MPR_TEST_DATA_DIR
  return MPR_TEST_DATA_DIR;
#else
  return {};
#endif
}

} // namespace mpr_test
