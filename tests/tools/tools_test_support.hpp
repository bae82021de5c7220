#pragma once
// Shared by mpr-render's and mpr-view's tests: a command line as mpr-render parses it, fresh
// temporary folders, and a tiny light field with depth maps.

#include "mpr-render/job.hpp"
#include "options/make_job.hpp"

#include <mpr/core/image.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/pfm.hpp>

#include <algorithm>
#include <cmath>
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

// Three 48 x 36 cameras (R = I, focal 40, centres 0.1 apart on the x axis) looking at a plane
// z = `depth` with a smooth colour texture (periods 0.4 to 0.9 units, 7 to 16 pixels at z = 2.3),
// images only (no depth maps): tiny_par.txt, view<i>.png. For depth estimation.
inline std::filesystem::path textured_plane_light_field(const std::string& name, double depth) {
  const std::filesystem::path dir = temp_folder(name);
  std::ofstream par(dir / "tiny_par.txt");
  par << "3\n";
  for (int i = 0; i < 3; ++i) {
    const double cx = 0.1 * (i - 1);
    mpr::Image<mpr::Rgb8> image(48, 36);
    for (int y = 0; y < 36; ++y)
      for (int x = 0; x < 48; ++x) {
        const double X = cx + depth * (x - 23.5) / 40, Y = depth * (y - 17.5) / 40;
        const auto channel = [&](double a, double b, double c, double d) {
          const double v = 0.5 + 0.25 * std::sin(a * X + b * Y) + 0.2 * std::sin(c * X - d * Y + 1.0);
          return static_cast<std::uint8_t>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
        };
        image(x, y) =
            mpr::Rgb8{channel(9.1, 3.3, 5.7, 11.7), channel(7.3, -10.7, 12.1, 4.9), channel(-6.9, 8.9, 9.3, -7.2)};
      }
    mpr::write_png(dir / ("view" + std::to_string(i) + ".png"), image);
    par << "view" << i << ".png 40 0 23.5 0 40 17.5 0 0 1  1 0 0 0 1 0 0 0 1  " << -cx << " 0 0\n";
  }
  return dir;
}

} // namespace mpr_tools_test
