#pragma once
// Shared helpers of the light-field examples: finding the real data, the refocusing camera of a
// planar array, and General Linear Cameras given by where their rays cross two parallel planes.

#include <mpr/lightfield.hpp>
#include <mpr/mpr.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>

namespace lf_example {

using T = float;

/// The data folder: `argument` if given, else $MPR_DATA_DIR, else the folder configured in CMake.
inline std::filesystem::path data_dir(const char* argument) {
  if (argument != nullptr) return argument;
  if (const char* env = std::getenv("MPR_DATA_DIR"); env != nullptr && *env != 0) return env;
  return MPR_EXAMPLE_DATA_DIR;
}

/// Loads Stanford Chess (7x7, 1400x800) with the default planar-array options: camera plane
/// z = 0, positions in file units (about 5 per grid step), reference plane at z = 1000
/// (the board spans about z = 700 to 950).
inline std::shared_ptr<const mpr::CameraFrameSet<T>> load_chess(const std::filesystem::path& data) {
  const auto start = std::chrono::steady_clock::now();
  auto frames =
      std::make_shared<const mpr::CameraFrameSet<T>>(mpr::read_stanford_light_field<T>(data / "stanford" / "chess"));
  std::printf("loaded %zu Chess views in %.2f s\n", frames->size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return frames;
}

/// The GLC whose ray at uv runs from the camera-plane point `s(uv)` (z = 0) to the focal-plane
/// point `plane.point_at(uv)`, with s affine in uv: s(u, v) = s00 + u (s10 - s00) + v (s01 - s00).
/// Both planes parallel (the two-plane parametrisation of Yu & McMillan 2004).
inline mpr::GlcSelector<T> two_plane_glc(const mpr::PlanarSurface<T>& plane, const mpr::Vec3<T>& s00,
                                         const mpr::Vec3<T>& s10, const mpr::Vec3<T>& s01) {
  return mpr::GlcSelector<T>(plane, mpr::Vec3<T>(plane.point_at({0, 0}) - s00),
                             mpr::Vec3<T>(plane.point_at({1, 0}) - s10), mpr::Vec3<T>(plane.point_at({0, 1}) - s01));
}

/// The output folder: the second argument or "lightfield-output", created if missing.
inline std::filesystem::path output_dir(int argc, char** argv) {
  const std::filesystem::path out = argc > 2 ? argv[2] : "lightfield-output";
  std::filesystem::create_directories(out);
  return out;
}

/// What every Chess example starts from: the output folder, the 49 frames and the refocusing
/// camera at the array centre. Arguments: [DATA_DIR] [OUTPUT_FOLDER].
struct ChessExample {
  std::filesystem::path out;
  std::shared_ptr<const mpr::CameraFrameSet<T>> frames;
  mpr::PinholeCamera<T> centre;
};

inline ChessExample open_chess(int argc, char** argv) {
  const std::filesystem::path data = data_dir(argc > 1 ? argv[1] : nullptr);
  std::filesystem::path out = output_dir(argc, argv);
  auto frames = load_chess(data);
  const mpr::PinholeCamera<T> centre =
      mpr::planar_array_reference_camera(frames->camera(0), mpr::Vec3<T>(mpr::Vec3<T>::Zero()));
  return {std::move(out), std::move(frames), centre};
}

inline void report(const std::filesystem::path& path) { std::printf("wrote %s\n", path.string().c_str()); }

template <class Fn>
double seconds(Fn&& fn) {
  const auto start = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace lf_example
