#pragma once
// The small command line shared by the self-contained examples:
//   PROGRAM [--size N] [--threads N] [--spp N] [OUTPUT_FOLDER]
// (`--width` is accepted as a synonym of `--size`; `--spp` only where the program offers it).
// Bad values throw mpr::argument_error.

#include <mpr/core/error.hpp>

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

namespace mpr_example {

struct Args {
  int size = 0;    ///< output width (and height, for square outputs), pixels
  int threads = 0; ///< 0: all hardware threads
  int spp = 0;     ///< samples per pixel (programs that offer --spp), else 0
  std::filesystem::path out;
};

/// Parses the command line; prints the usage and returns nothing for --help. Creates the output
/// folder. `default_spp` > 0 offers `--spp N` (samples per pixel, 1 to 4096) with that default.
inline std::optional<Args> parse_args(int argc, char** argv, const char* program, int default_size, int min_size,
                                      int max_size, const char* default_out, int default_spp = 0) {
  Args args{default_size, 0, default_spp, default_out};
  const auto integer = [&](const std::string& option, const char* text, int lo, int hi) {
    int value = 0;
    const std::string s = text;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc{} || ptr != s.data() + s.size() || value < lo || value > hi)
      throw mpr::argument_error(option, "'" + s + "' is not an integer in [" + std::to_string(lo) + ", " +
                                            std::to_string(hi) + "]");
    return value;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--size" || arg == "--width") && i + 1 < argc) {
      args.size = integer(arg, argv[++i], min_size, max_size);
    } else if (arg == "--threads" && i + 1 < argc) {
      args.threads = integer(arg, argv[++i], 0, 1024);
    } else if (arg == "--spp" && default_spp > 0 && i + 1 < argc) {
      args.spp = integer(arg, argv[++i], 1, 4096);
    } else if (arg == "--help" || arg == "-h") {
      if (default_spp > 0)
        std::printf("usage: %s [--size N] [--threads N] [--spp N] [OUTPUT_FOLDER]   (defaults: %d, all threads, %d "
                    "samples per pixel, %s)\n",
                    program, default_size, default_spp, default_out);
      else
        std::printf("usage: %s [--size N] [--threads N] [OUTPUT_FOLDER]   (defaults: %d, all threads, %s)\n", program,
                    default_size, default_out);
      return std::nullopt;
    } else if (!arg.empty() && arg[0] == '-') {
      throw mpr::argument_error(arg, "unknown option or missing value (see --help)");
    } else {
      args.out = arg;
    }
  }
  std::filesystem::create_directories(args.out);
  return args;
}

} // namespace mpr_example
