#pragma once
// Shared helpers of the light-field examples: finding the real data, the refocusing camera of a
// planar array, and General Linear Cameras given by where their rays cross two parallel planes.

#include <mpr/lightfield.hpp>
#include <mpr/mpr.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace lf_example {

using T = float;

/// The default output folder of the light-field examples (in .gitignore).
inline constexpr const char* default_output = "lightfield-output";

/// The command line of a light-field example: PROGRAM [DATA_DIR] [OUTPUT_FOLDER] followed by up
/// to `extra_names.size()` more positional arguments (named in the usage; e.g. "VIEW_A").
/// `--help` or `-h` anywhere prints the usage (with `extra_help`, one line per extra argument)
/// and exits with status 0; any other option, or too many arguments, throws argument_error.
/// Returns the positional arguments.
inline std::vector<std::string> positional_args(int argc, char** argv, const std::vector<std::string>& extra_names = {},
                                                const char* extra_help = "") {
  const std::string program = argc > 0 ? std::filesystem::path(argv[0]).filename().string() : "example";
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::string names;
      for (const std::string& n : extra_names) names += " [" + n + "]";
      const char* env = std::getenv("MPR_DATA_DIR");
      std::printf("usage: %s [DATA_DIR] [OUTPUT_FOLDER]%s\n"
                  "  DATA_DIR       folder holding stanford/ and middlebury/ (default: $MPR_DATA_DIR, now %s;\n"
                  "                 else %s)\n"
                  "  OUTPUT_FOLDER  where the images go (default: %s, created if missing)\n%s",
                  program.c_str(), names.c_str(), env != nullptr && *env != 0 ? env : "unset", MPR_EXAMPLE_DATA_DIR,
                  default_output, extra_help);
      std::fflush(stdout);
      std::exit(0);
    }
    if (arg.size() > 1 && arg[0] == '-')
      throw mpr::argument_error(arg, "unknown option (the arguments are DATA_DIR OUTPUT_FOLDER; see --help)");
    positional.push_back(arg);
  }
  if (positional.size() > 2 + extra_names.size())
    throw mpr::argument_error(positional[2 + extra_names.size()], "unexpected argument (see --help)");
  return positional;
}

/// The data folder: `argument` if given, else $MPR_DATA_DIR, else the folder configured in CMake.
inline std::filesystem::path data_dir(const char* argument) {
  if (argument != nullptr) return argument;
  if (const char* env = std::getenv("MPR_DATA_DIR"); env != nullptr && *env != 0) return env;
  return MPR_EXAMPLE_DATA_DIR;
}

/// Load limits whose progress callback draws "loading images k/n" on stderr when stderr is a
/// terminal (a 49-image Chess load takes a few seconds).
inline mpr::LoadLimits load_limits_with_progress() {
  mpr::LoadLimits limits;
  if (isatty(STDERR_FILENO))
    limits.progress = [](std::size_t loaded, std::size_t total) {
      std::fprintf(stderr, "\rloading images %zu/%zu", loaded, total);
      if (loaded == total) std::fprintf(stderr, "\r%*s\r", 40, "");
      std::fflush(stderr);
    };
  return limits;
}

/// Loads Stanford Chess (7x7, 1400x800) with the default planar-array options: camera plane
/// z = 0, positions in file units (about 5 per grid step), reference plane at z = 1000
/// (the board spans about z = 700 to 950).
inline std::shared_ptr<const mpr::CameraFrameSet<T>> load_chess(const std::filesystem::path& data) {
  const auto start = std::chrono::steady_clock::now();
  auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(
      mpr::read_stanford_light_field<T>(data / "stanford" / "chess", {}, load_limits_with_progress()));
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

/// The output folder: the second argument or `default_output`, created if missing.
inline std::filesystem::path output_dir(int argc, char** argv) {
  const std::filesystem::path out = argc > 2 ? argv[2] : default_output;
  std::filesystem::create_directories(out);
  return out;
}

/// What every Chess example starts from: the output folder, the 49 frames and the refocusing
/// camera at the array centre. Arguments: [DATA_DIR] [OUTPUT_FOLDER] (`--help`: the usage, see
/// positional_args).
struct ChessExample {
  std::filesystem::path out;
  std::shared_ptr<const mpr::CameraFrameSet<T>> frames;
  mpr::PinholeCamera<T> centre;
};

inline ChessExample open_chess(int argc, char** argv) {
  (void)positional_args(argc, argv);
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
