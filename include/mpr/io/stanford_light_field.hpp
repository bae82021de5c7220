#pragma once
/// \file
/// Loader of the Stanford (New) Light Field Archive "rectified and cropped" format: a folder of
/// images named `out_RR_CC_<Y>_<X>.png` or `out_RR_CC_<Y>_<X>_.png` (grid row RR, grid column
/// CC, then the camera position on the camera plane as Y then X, known only up to scale and
/// offset). See planar_camera_array.hpp for the camera model and its metric options.

#include <mpr/camera/planar_camera_array.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/load_limits.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

namespace mpr {

/// One parsed archive file name.
struct StanfordViewName {
  int row = 0;
  int column = 0;
  double y = 0;
  double x = 0;
};

/// Parses `out_RR_CC_<Y>_<X>[_].<ext>`; empty when the name does not follow the pattern.
[[nodiscard]] inline std::optional<StanfordViewName> parse_stanford_view_name(const std::string& file_name) {
  const std::size_t dot = file_name.rfind('.');
  if (dot == std::string::npos || file_name.rfind("out_", 0) != 0) return std::nullopt;
  std::string stem = file_name.substr(4, dot - 4);
  if (!stem.empty() && stem.back() == '_') stem.pop_back();
  std::vector<std::string> parts;
  for (std::size_t start = 0;;) {
    const std::size_t end = stem.find('_', start);
    parts.push_back(stem.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  if (parts.size() != 4) return std::nullopt;
  StanfordViewName v;
  const auto whole_int = [](const std::string& s, int& out) {
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size() && out >= 0;
  };
  const auto whole_double = [](const std::string& s, double& out) {
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size() && std::isfinite(out);
  };
  if (!whole_int(parts[0], v.row) || !whole_int(parts[1], v.column) || !whole_double(parts[2], v.y) ||
      !whole_double(parts[3], v.x))
    return std::nullopt;
  return v;
}

/// Reads every `out_*` image of `folder` (sorted by row, then column) into a planar camera
/// array (see planar_camera_array.hpp; names are the file names). Image headers are read
/// first: sizes and `limits` (pixels per image, bytes of the whole set) are checked before any
/// image is decoded. Throws `io_error` naming the folder or file when the folder is missing or
/// unreadable, holds no matching image, a name starts with `out_` but does not parse or is not
/// a regular file (a broken link or a link loop included), two files share a grid cell, an
/// image cannot be read or exceeds a limit, images differ in size, or a position times
/// `options.scale` is not finite in T; `argument_error` for bad options.
template <std::floating_point T = double>
[[nodiscard]] CameraFrameSet<T, Rgb8> read_stanford_light_field(const std::filesystem::path& folder,
                                                                const PlanarArrayOptions& options = {},
                                                                const LoadLimits& limits = {}) {
  options.validate();
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) throw io_error(folder.string(), "not a folder");
  struct Entry {
    StanfordViewName view;
    std::filesystem::path path;
  };
  std::vector<Entry> entries;
  std::filesystem::directory_iterator it(folder, ec);
  if (ec) throw io_error(folder.string(), "cannot list the folder: " + ec.message());
  for (; it != std::filesystem::directory_iterator(); it.increment(ec)) {
    if (ec) throw io_error(folder.string(), "cannot list the folder: " + ec.message());
    const std::filesystem::path path = it->path();
    const std::string name = path.filename().string();
    if (name.rfind("out_", 0) != 0) continue;
    const bool regular = it->is_regular_file(ec);
    if (ec) throw io_error(path.string(), "cannot read: " + ec.message());
    if (!regular) {
      // Sub-folders named out_* are not images; a link that leads nowhere is an error.
      const bool folder_entry = it->is_directory(ec);
      if (!ec && folder_entry) continue;
      throw io_error(path.string(), "not a regular file" + (ec ? " (" + ec.message() + ")" : std::string()));
    }
    const std::optional<StanfordViewName> v = parse_stanford_view_name(name);
    if (!v) throw io_error(path.string(), "not a name of the form out_RR_CC_<Y>_<X>[_].png");
    entries.push_back({*v, path});
  }
  if (entries.empty()) throw io_error(folder.string(), "no out_RR_CC_<Y>_<X>.png images");
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.view.row != b.view.row ? a.view.row < b.view.row : a.view.column < b.view.column;
  });
  for (std::size_t i = 1; i < entries.size(); ++i)
    if (entries[i].view.row == entries[i - 1].view.row && entries[i].view.column == entries[i - 1].view.column)
      throw io_error(entries[i].path.string(), "same grid cell as " + entries[i - 1].path.filename().string());
  std::vector<std::filesystem::path> paths;
  std::vector<ImageInfo> infos;
  for (const Entry& e : entries) {
    paths.push_back(e.path);
    infos.push_back(read_image_info(e.path, limits));
    if (infos.back().width != infos[0].width || infos.back().height != infos[0].height)
      throw io_error(e.path.string(), "image is " + std::to_string(infos.back().width) + "x" +
                                          std::to_string(infos.back().height) + ", " +
                                          entries[0].path.filename().string() + " is " +
                                          std::to_string(infos[0].width) + "x" + std::to_string(infos[0].height));
  }
  check_set_budget(paths, infos, limits, CameraFrameSet<T, Rgb8>::holds_linear16());
  std::vector<Vec2<double>> positions;
  for (const Entry& e : entries) positions.emplace_back(e.view.x, e.view.y);
  const std::vector<Vec3<T>> centres = planar_array_centres<T>(positions, options);
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (!centres[i].allFinite())
      throw io_error(entries[i].path.string(), detail::position_overflow_reason<T>(positions[i], options));
  std::vector<PinholeCamera<T>> cameras;
  std::vector<Image<Rgb8>> images;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    Image<Rgb8> image = read_rgb8(entries[i].path, limits);
    if (image.width() != infos[0].width || image.height() != infos[0].height)
      throw io_error(entries[i].path.string(), "image changed size while loading");
    try {
      cameras.push_back(planar_array_camera<T>(centres[i], image.width(), image.height(), options));
    } catch (const argument_error& err) {
      throw io_error(entries[i].path.string(), std::string("no valid camera at this position: ") + err.what());
    }
    images.push_back(std::move(image));
    names.push_back(entries[i].path.filename().string());
    if (limits.progress) limits.progress(i + 1, entries.size());
  }
  // Built on z = 0 (planar_camera_array.hpp): hand the plane over instead of letting the samplers fit it.
  return CameraFrameSet<T, Rgb8>(std::move(cameras), std::move(images), std::move(names))
      .on_plane(Plane<T>{Vec3<T>::Zero(), Vec3<T>::UnitZ()});
}

} // namespace mpr
