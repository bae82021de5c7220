#pragma once
/// \file
/// The `parameters.cfg` file of a scene of the 4D Light Field Benchmark (Honauer et al., ACCV
/// 2016): an INI file (`[section]`, `key = value`, comments starting with `#` or `;`) giving
/// the virtual camera array the scene was rendered with. Read here: `focal_length_mm`,
/// `sensor_size_mm`, `image_resolution_x_px`, `image_resolution_y_px` ([intrinsics]),
/// `baseline_mm`, `focus_distance_m`, `num_cams_x`, `num_cams_y` ([extrinsics]) and, when
/// present, `disp_min`, `disp_max` ([meta]); other keys are ignored. The benchmark's conversion
/// between depth Z (metres here) and the centre view's disparity d (pixels per view step) is
/// d = f B / Z - f B / focus_distance, with the focal length in pixels
/// f = focal_length_mm / sensor_size_mm x max(resolution x, resolution y) and B the baseline.

#include <mpr/core/error.hpp>
#include <mpr/io/load_limits.hpp>
#include <mpr/lightfield/array_disparity.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace mpr {

/// What mpr reads of a `parameters.cfg` (see the file comment).
struct HciParameters {
  double focal_length_mm = 0;
  double sensor_size_mm = 0;
  int width = 0;  ///< image_resolution_x_px
  int height = 0; ///< image_resolution_y_px
  double baseline_mm = 0;
  double focus_distance_m = 0;
  int cams_x = 0;                      ///< num_cams_x
  int cams_y = 0;                      ///< num_cams_y
  std::optional<double> disparity_min; ///< [meta] disp_min, pixels
  std::optional<double> disparity_max; ///< [meta] disp_max, pixels

  /// Focal length in pixels.
  [[nodiscard]] double focal_length_px() const noexcept {
    return focal_length_mm / sensor_size_mm * static_cast<double>(std::max(width, height));
  }
  /// Depth in metres <-> disparity: f B with B in metres, offset f B / focus distance.
  [[nodiscard]] ArrayDisparity disparity() const noexcept {
    const double fb = focal_length_px() * baseline_mm / 1000.0;
    return {fb, fb / focus_distance_m};
  }
};

namespace detail {

[[nodiscard]] inline std::string_view hci_trim(std::string_view s) noexcept {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

} // namespace detail

/// Parses the text of a `parameters.cfg`; `path` names the file in errors. Throws `io_error`
/// naming the file and line for a line that is neither blank, a comment, a `[section]` nor
/// `key = value`, a key read here given twice or with a value that is not a number (an integer
/// for the counts and sizes), and naming the file for a missing key or a value out of range
/// (lengths, distance and counts must be positive, disp_min < disp_max).
[[nodiscard]] inline HciParameters parse_hci_parameters(const std::string& text, const std::string& path) {
  HciParameters p;
  struct Field {
    const char* key;
    double* real;
    int* whole;
    bool optional;
    bool seen = false;
  };
  double dmin = 0, dmax = 0;
  Field fields[] = {{"focal_length_mm", &p.focal_length_mm, nullptr, false},
                    {"sensor_size_mm", &p.sensor_size_mm, nullptr, false},
                    {"image_resolution_x_px", nullptr, &p.width, false},
                    {"image_resolution_y_px", nullptr, &p.height, false},
                    {"baseline_mm", &p.baseline_mm, nullptr, false},
                    {"focus_distance_m", &p.focus_distance_m, nullptr, false},
                    {"num_cams_x", nullptr, &p.cams_x, false},
                    {"num_cams_y", nullptr, &p.cams_y, false},
                    {"disp_min", &dmin, nullptr, true},
                    {"disp_max", &dmax, nullptr, true}};
  std::size_t line_number = 0;
  for (std::size_t start = 0; start <= text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    ++line_number;
    const std::string_view line = detail::hci_trim(std::string_view(text).substr(start, end - start));
    start = end + 1;
    if (line.empty() || line.front() == '#' || line.front() == ';') continue;
    if (line.front() == '[') {
      if (line.back() != ']') throw io_error(path, "malformed section header '" + std::string(line) + "'", line_number);
      continue;
    }
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos)
      throw io_error(path, "expected 'key = value', got '" + std::string(line) + "'", line_number);
    const std::string_view key = detail::hci_trim(line.substr(0, eq)), value = detail::hci_trim(line.substr(eq + 1));
    for (Field& f : fields) {
      if (key != f.key) continue;
      if (f.seen) throw io_error(path, std::string(f.key) + " given twice", line_number);
      f.seen = true;
      const char* first = value.data();
      const char* last = value.data() + value.size();
      const auto bad = [&] {
        return io_error(path,
                        std::string(f.key) + " = '" + std::string(value) + "' is not " +
                            (f.whole ? "an integer" : "a number"),
                        line_number);
      };
      if (f.whole) {
        const auto [ptr, ec] = std::from_chars(first, last, *f.whole);
        if (ec != std::errc() || ptr != last || value.empty()) throw bad();
      } else {
        const auto [ptr, ec] = std::from_chars(first, last, *f.real);
        if (ec != std::errc() || ptr != last || value.empty() || !std::isfinite(*f.real)) throw bad();
      }
    }
  }
  for (const Field& f : fields)
    if (!f.seen && !f.optional) throw io_error(path, std::string("missing key ") + f.key);
  for (const Field& f : fields) {
    if (f.optional) continue;
    const bool positive = f.whole ? *f.whole > 0 : *f.real > 0;
    if (!positive) throw io_error(path, std::string(f.key) + " must be positive");
  }
  if (fields[8].seen != fields[9].seen) throw io_error(path, "disp_min and disp_max go together");
  if (fields[8].seen) {
    if (!(dmin < dmax)) throw io_error(path, "disp_min must be below disp_max");
    p.disparity_min = dmin;
    p.disparity_max = dmax;
  }
  return p;
}

/// Reads and parses `path` (a text file within `limits`); throws as `parse_hci_parameters`.
[[nodiscard]] inline HciParameters read_hci_parameters(const std::filesystem::path& path,
                                                       const LoadLimits& limits = {}) {
  return parse_hci_parameters(detail::read_text_file(path, limits, "parameters file"), path.string());
}

} // namespace mpr
