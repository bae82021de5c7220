#pragma once
// Shared by mpr-render's and mpr-view's tests: a command line as mpr-render parses it, fresh
// temporary folders, and a tiny light field with depth maps.

#include "mpr-render/job.hpp"

#include <mpr/core/image.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/pfm.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

namespace mpr_tools_test {

/// The Job of `mpr-render ARGS...` (argv[0] supplied).
inline mpr_cli::Job job_of(const std::vector<std::string>& args) {
  std::vector<const char*> argv{"mpr-render"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  return mpr_cli::parse_job(static_cast<int>(argv.size()), argv.data());
}

/// A fresh, empty temporary folder named after this process and `name`.
inline std::filesystem::path temp_folder(const std::string& name) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / ("mpr_tools_test_" + std::to_string(getpid()) + "_" + name);
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

// Three 8 x 6 cameras (R = I, looking along +z, centres 0.1 apart on the x axis) of random
// images, each with a depth map of the plane z = `depth`: view<i>.png, view<i>.pfm, tiny_par.txt.
inline std::filesystem::path plane_light_field(const std::string& name, float depth) {
  const std::filesystem::path dir = temp_folder(name);
  std::mt19937 rng(5);
  std::ofstream par(dir / "tiny_par.txt");
  par << "3\n";
  for (int i = 0; i < 3; ++i) {
    mpr::Image<mpr::Rgb8> image(8, 6);
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 8; ++x)
        image(x, y) = mpr::Rgb8{static_cast<std::uint8_t>(rng() & 255), static_cast<std::uint8_t>(rng() & 255),
                                static_cast<std::uint8_t>(rng() & 255)};
    mpr::write_png(dir / ("view" + std::to_string(i) + ".png"), image);
    mpr::write_pfm(dir / ("view" + std::to_string(i) + ".pfm"), mpr::Image<float>(8, 6, depth));
    par << "view" << i << ".png 8 0 3.5 0 8 2.5 0 0 1  1 0 0 0 1 0 0 0 1  " << -0.1 * (i - 1) << " 0 0\n";
  }
  return dir;
}

} // namespace mpr_tools_test
