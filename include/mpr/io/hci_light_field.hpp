#pragma once
/// \file
/// Loader of a scene of the 4D Light Field Benchmark (Honauer, Johannsen, Kondermann,
/// Goldluecke, ACCV 2016): a folder of `input_CamNNN.png` views of an equally spaced parallel
/// camera array (view NNN at grid row NNN / columns, column NNN % columns; 9x9 by default, the
/// centre view 40), any subset of them (e.g. the 33-view star of centre row, column and
/// diagonals), an optional `parameters.cfg` (io/hci_parameters.hpp) and an optional ground truth
/// `gt_disp_lowres.pfm`: the centre view's disparity in pixels per view step.
///
/// Geometry: the centre view's pixel (x, y) at disparity d appears in view (r, c) at
/// (x - d (c - c0), y - d (r - r0)) for the centre (r0, c0): the rectified planar array of
/// planar_camera_array.hpp with the cameras at ((c - c0) B, (r - r0) B, 0), so that
/// d = f B / Z - f B / z0 (lightfield/array_disparity.hpp). With `parameters.cfg`: the
/// benchmark's metric array (f from the focal length, sensor size and resolution, B the baseline
/// in metres, z0 the focus distance; depths in metres). Without it: an array calibrated in
/// disparity units, f = image width, B = 1 and z0 = f / `HciOptions::offset`, which reproduces
/// every disparity exactly; depth Z = f / (d + offset).

#include <mpr/camera/planar_camera_array.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/io/hci_parameters.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/load_limits.hpp>
#include <mpr/io/pfm.hpp>
#include <mpr/lightfield/array_disparity.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace mpr {

/// Choices for a scene without `parameters.cfg` (see the file comment).
struct HciOptions {
  /// Disparity range the scene is assumed to lie in (pixels per view step) when the parameters
  /// give none: the benchmark's scenes lie within [-4, 4].
  double disparity_min = -4;
  double disparity_max = 4;
  /// s of the disparity-unit array (pixels): depths stay positive for disparities above -s.
  /// Must exceed -disparity_min.
  double offset = 10;
  /// Grid size when there is no `parameters.cfg`.
  int cams_x = 9;
  int cams_y = 9;

  /// Throws `argument_error` naming the bad option.
  void validate() const {
    if (!std::isfinite(disparity_min) || !std::isfinite(disparity_max) || !(disparity_min < disparity_max))
      throw argument_error("disparity_min", "must be finite and below disparity_max");
    if (!std::isfinite(offset) || !(offset > -disparity_min))
      throw argument_error("offset", "must be finite and above -disparity_min");
    if (cams_x < 1 || cams_y < 1 || cams_x > 99 || cams_y > 99) throw argument_error("cams_x", "must be in 1..99");
  }
};

/// A loaded benchmark scene.
template <std::floating_point T>
struct HciLightField {
  /// The views found, in view-number order, named by their file names.
  CameraFrameSet<T, Rgb8> frames;
  /// The benchmark's view number of each frame.
  std::vector<int> views;
  /// Index into `frames` of the centre view.
  std::size_t centre = 0;
  /// Grid size and the centre's row and column.
  int cams_x = 9, cams_y = 9;
  /// Depth (world units of the cameras) <-> disparity (pixels per view step).
  ArrayDisparity disparity;
  /// The scene's disparity range ([meta] of the parameters, else `HciOptions`).
  double disparity_min = -4, disparity_max = 4;
  /// The parameters file, when the folder has one.
  std::optional<HciParameters> parameters;
  /// The centre view's true disparity (top row first), when the folder has `gt_disp_lowres.pfm`.
  std::optional<Image<float>> ground_truth;

  /// Depths of the nearest and farthest disparity of the range (for a plane sweep).
  [[nodiscard]] double near_depth() const noexcept { return disparity.depth(disparity_max); }
  [[nodiscard]] double far_depth() const noexcept { return disparity.depth(disparity_min); }
  /// Grid row and column of frame `i`.
  [[nodiscard]] int row(std::size_t i) const noexcept { return views[i] / cams_x; }
  [[nodiscard]] int column(std::size_t i) const noexcept { return views[i] % cams_x; }
};

/// The view number of file name `input_CamNNN.png` (NNN one to three digits), or -1.
[[nodiscard]] inline int parse_hci_view_name(const std::string& name) noexcept {
  const std::string prefix = "input_Cam", suffix = ".png";
  if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return -1;
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.empty() || digits.size() > 3) return -1;
  int v = 0;
  for (const char c : digits) {
    if (c < '0' || c > '9') return -1;
    v = v * 10 + (c - '0');
  }
  return v;
}

/// Reads the benchmark scene in `folder` (see the file comment). Image headers are read first,
/// and sizes, `limits` and the parameters are checked before any image is decoded. Throws
/// `io_error` naming the file (or the folder) when the folder cannot be listed, a file named
/// `input_Cam*` is not `input_CamNNN.png` or not a regular file, two files give the same view,
/// a view number lies outside the grid (an extra view), the centre view is missing, an image
/// cannot be read, exceeds a limit or differs in size from the others, `parameters.cfg` is
/// malformed (hci_parameters.hpp) or disagrees with the images (resolution), or
/// `gt_disp_lowres.pfm` cannot be read or is not the size of the views. `argument_error` for bad
/// options.
template <std::floating_point T = double>
[[nodiscard]] HciLightField<T> read_hci_light_field(const std::filesystem::path& folder, const HciOptions& options = {},
                                                    const LoadLimits& limits = {}) {
  options.validate();
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) throw io_error(folder.string(), "not a folder");
  HciLightField<T> lf;
  const std::filesystem::path cfg = folder / "parameters.cfg";
  if (std::filesystem::exists(cfg, ec)) lf.parameters = read_hci_parameters(cfg, limits);
  lf.cams_x = lf.parameters ? lf.parameters->cams_x : options.cams_x;
  lf.cams_y = lf.parameters ? lf.parameters->cams_y : options.cams_y;
  const int count = lf.cams_x * lf.cams_y, centre_view = (lf.cams_y / 2) * lf.cams_x + lf.cams_x / 2;
  std::vector<std::filesystem::path> by_view(static_cast<std::size_t>(count));
  std::filesystem::directory_iterator it(folder, ec);
  if (ec) throw io_error(folder.string(), "cannot list the folder: " + ec.message());
  for (; it != std::filesystem::directory_iterator(); it.increment(ec)) {
    if (ec) throw io_error(folder.string(), "cannot list the folder: " + ec.message());
    const std::filesystem::path path = it->path();
    const std::string name = path.filename().string();
    if (name.rfind("input_Cam", 0) != 0) continue;
    const int v = parse_hci_view_name(name);
    if (v < 0) throw io_error(path.string(), "not a view name of the form input_CamNNN.png");
    if (!it->is_regular_file(ec) || ec) throw io_error(path.string(), "not a regular file");
    if (v >= count)
      throw io_error(path.string(), "view " + std::to_string(v) + " is outside the " + std::to_string(lf.cams_x) + "x" +
                                        std::to_string(lf.cams_y) + " array (views 0.." + std::to_string(count - 1) +
                                        ")");
    std::filesystem::path& slot = by_view[static_cast<std::size_t>(v)];
    if (!slot.empty()) throw io_error(path.string(), "same view as " + slot.filename().string());
    slot = path;
  }
  if (by_view[static_cast<std::size_t>(centre_view)].empty())
    throw io_error(folder.string(), "no centre view (view " + std::to_string(centre_view) + ", input_Cam" +
                                        std::string(centre_view < 10    ? "00"
                                                    : centre_view < 100 ? "0"
                                                                        : "") +
                                        std::to_string(centre_view) + ".png)");
  std::vector<std::filesystem::path> paths;
  std::vector<ImageInfo> infos;
  for (int v = 0; v < count; ++v) {
    const std::filesystem::path& path = by_view[static_cast<std::size_t>(v)];
    if (path.empty()) continue;
    if (v == centre_view) lf.centre = lf.views.size();
    lf.views.push_back(v);
    paths.push_back(path);
    infos.push_back(read_image_info(path, limits));
    if (infos.back().width != infos[0].width || infos.back().height != infos[0].height)
      throw io_error(path.string(), "image is " + std::to_string(infos.back().width) + "x" +
                                        std::to_string(infos.back().height) + ", " + paths[0].filename().string() +
                                        " is " + std::to_string(infos[0].width) + "x" +
                                        std::to_string(infos[0].height));
  }
  const int width = infos[0].width, height = infos[0].height;
  if (lf.parameters && (lf.parameters->width != width || lf.parameters->height != height))
    throw io_error(cfg.string(), "image resolution " + std::to_string(lf.parameters->width) + "x" +
                                     std::to_string(lf.parameters->height) + " disagrees with the views (" +
                                     std::to_string(width) + "x" + std::to_string(height) + ")");
  check_set_budget(paths, infos, limits, CameraFrameSet<T, Rgb8>::holds_linear16());
  const std::filesystem::path gt_path = folder / "gt_disp_lowres.pfm";
  if (std::filesystem::exists(gt_path, ec)) {
    Image<float> gt = read_pfm(gt_path, limits);
    if (gt.width() != width || gt.height() != height)
      throw io_error(gt_path.string(), "ground truth is " + std::to_string(gt.width()) + "x" +
                                           std::to_string(gt.height()) + ", the views are " + std::to_string(width) +
                                           "x" + std::to_string(height));
    lf.ground_truth = std::move(gt);
  }
  // The array: metric from the parameters, else in disparity units (file comment).
  PlanarArrayOptions array;
  array.centre = false;
  double spacing = 1;
  if (lf.parameters) {
    array.focal_length = lf.parameters->focal_length_px();
    array.reference_depth = lf.parameters->focus_distance_m;
    spacing = lf.parameters->baseline_mm / 1000.0;
    lf.disparity = lf.parameters->disparity();
    lf.disparity_min = lf.parameters->disparity_min.value_or(options.disparity_min);
    lf.disparity_max = lf.parameters->disparity_max.value_or(options.disparity_max);
  } else {
    array.focal_length = width;
    array.reference_depth = width / options.offset;
    lf.disparity = ArrayDisparity{static_cast<double>(width), options.offset};
    lf.disparity_min = options.disparity_min;
    lf.disparity_max = options.disparity_max;
  }
  if (!(lf.disparity_min > -lf.disparity.offset))
    throw io_error(cfg.string(), "disp_min lies at or beyond the array's infinity (-f B / focus distance)");
  std::vector<PinholeCamera<T>> cameras;
  std::vector<Image<Rgb8>> images;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    Image<Rgb8> image = read_rgb8(paths[i], limits);
    if (image.width() != width || image.height() != height)
      throw io_error(paths[i].string(), "image changed size while loading");
    const Vec3<T> c(static_cast<T>((lf.column(i) - lf.cams_x / 2) * spacing),
                    static_cast<T>((lf.row(i) - lf.cams_y / 2) * spacing), T(0));
    cameras.push_back(planar_array_camera<T>(c, width, height, array));
    images.push_back(std::move(image));
    names.push_back(paths[i].filename().string());
    if (limits.progress) limits.progress(i + 1, paths.size());
  }
  lf.frames = CameraFrameSet<T, Rgb8>(std::move(cameras), std::move(images), std::move(names))
                  .on_plane(Plane<T>{Vec3<T>::Zero(), Vec3<T>::UnitZ()});
  return lf;
}

} // namespace mpr
