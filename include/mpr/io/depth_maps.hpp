#pragma once
/// \file
/// The depth maps of a `CameraFrameSet` on disk: one PFM file per camera (pfm.hpp), named after
/// the camera's frame (`cam_000_001.png` -> `cam_000_001.pfm`), and a colour-mapped PNG preview
/// of a depth map with a legend of its depth range.

#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/label.hpp>
#include <mpr/io/image_io.hpp>
#include <mpr/io/load_limits.hpp>
#include <mpr/io/pfm.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace mpr {

/// The PFM file name of the depth map of frame `frame_name`: its file name with the extension
/// replaced by `.pfm` (folders dropped).
[[nodiscard]] inline std::filesystem::path depth_map_name(const std::string& frame_name) {
  return std::filesystem::path(frame_name).filename().replace_extension(".pfm");
}

/// Reads one depth map per frame of `frames` from `folder` (`depth_map_name` of each frame), for
/// `CameraFrameSet::with_depth`. Throws `io_error` naming the file when it cannot be read (see
/// `read_pfm`), its size differs from its camera's, or a depth is NaN, zero or negative
/// (+inf is "nothing seen").
template <std::floating_point T, class Px>
[[nodiscard]] std::vector<Image<float>> read_depth_maps(const std::filesystem::path& folder,
                                                        const CameraFrameSet<T, Px>& frames,
                                                        const LoadLimits& limits = {}) {
  std::vector<Image<float>> maps;
  maps.reserve(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::filesystem::path path = folder / depth_map_name(frames.name(i));
    Image<float> map = read_pfm(path, limits);
    const PinholeCamera<T>& camera = frames.camera(i);
    if (map.width() != camera.width() || map.height() != camera.height())
      throw io_error(path.string(), "depth map is " + std::to_string(map.width()) + "x" + std::to_string(map.height()) +
                                        " but camera " + frames.name(i) + " is " + std::to_string(camera.width()) +
                                        "x" + std::to_string(camera.height()));
    for (int y = 0; y < map.height(); ++y)
      for (int x = 0; x < map.width(); ++x)
        if (!(map(x, y) > 0))
          throw io_error(path.string(), "depth " + std::to_string(map(x, y)) + " at pixel (" + std::to_string(x) +
                                            ", " + std::to_string(y) +
                                            ") (depths are positive, +inf where nothing was seen)");
    if (limits.progress) limits.progress(i + 1, frames.size());
    maps.push_back(std::move(map));
  }
  return maps;
}

/// Writes the depth maps of `frames` into `folder` (which must exist), one PFM per camera named
/// by `depth_map_name`. Throws `argument_error` ("depth maps") when the set carries none, and
/// `io_error` naming the file when a write fails.
template <std::floating_point T, class Px>
void write_depth_maps(const std::filesystem::path& folder, const CameraFrameSet<T, Px>& frames) {
  if (!frames.has_depth()) throw argument_error("depth maps", "the frame set carries none");
  for (std::size_t i = 0; i < frames.size(); ++i) write_pfm(folder / depth_map_name(frames.name(i)), frames.depth(i));
}

/// The finite depth range of a depth map.
struct DepthRange {
  float near = std::numeric_limits<float>::infinity();
  float far = -std::numeric_limits<float>::infinity();
  /// False when the map has no finite depth.
  [[nodiscard]] bool valid() const noexcept { return near <= far; }
};

/// The smallest and largest finite depth of `depth`.
[[nodiscard]] inline DepthRange depth_range(ImageView<const float> depth) noexcept {
  DepthRange r;
  for (int y = 0; y < depth.height(); ++y)
    for (int x = 0; x < depth.width(); ++x)
      if (std::isfinite(depth(x, y))) {
        r.near = std::min(r.near, depth(x, y));
        r.far = std::max(r.far, depth(x, y));
      }
  return r;
}

/// The preview colour of `t` in [0, 1] (0 near: light yellow, through green and blue, to 1 far:
/// dark violet), a perceptually ordered ramp interpolated between five key colours.
[[nodiscard]] inline Rgb8 depth_ramp(float t) noexcept {
  static constexpr std::array<std::array<float, 3>, 5> keys{
      {{250, 230, 40}, {90, 200, 100}, {30, 140, 140}, {55, 75, 140}, {65, 10, 80}}};
  const float s = std::clamp(std::isfinite(t) ? t : 1.0f, 0.0f, 1.0f) * 4.0f;
  const int k = std::min(static_cast<int>(s), 3);
  const float a = s - static_cast<float>(k);
  std::array<std::uint8_t, 3> c{};
  for (std::size_t j = 0; j < 3; ++j)
    c[j] = static_cast<std::uint8_t>(
        std::lround(keys[static_cast<std::size_t>(k)][j] * (1 - a) + keys[static_cast<std::size_t>(k) + 1][j] * a));
  return Rgb8{c[0], c[1], c[2]};
}

/// A colour-mapped preview of `depth`: each finite depth coloured by `depth_ramp` linearly
/// between `range.near` and `range.far` (default: the map's own `depth_range`), "nothing seen"
/// (+inf) black, and below the map a legend strip: the ramp from near to far with the two depths
/// written at its ends, and "INF: BLACK". An empty map gives an empty image.
[[nodiscard]] inline Image<Rgb8> depth_preview(ImageView<const float> depth, DepthRange range = {}) {
  if (depth.empty()) return {};
  if (!range.valid()) range = depth_range(depth);
  if (!range.valid()) range = {1, 1};
  const float span = range.far > range.near ? range.far - range.near : 1.0f;
  const LabelStyle style{depth.width() >= 240 ? 2 : 1, Rgb8{255, 255, 255}, Rgb8{0, 0, 0}, true};
  const int legend = label_size("0", style).second * 2 + 6;
  Image<Rgb8> out(depth.width(), depth.height() + legend, Rgb8{0, 0, 0});
  for (int y = 0; y < depth.height(); ++y)
    for (int x = 0; x < depth.width(); ++x)
      if (std::isfinite(depth(x, y))) out(x, y) = depth_ramp((depth(x, y) - range.near) / span);
  const int bar = legend / 2;
  for (int y = depth.height() + 2; y < depth.height() + bar; ++y)
    for (int x = 0; x < depth.width(); ++x)
      out(x, y) = depth_ramp(depth.width() > 1 ? static_cast<float>(x) / static_cast<float>(depth.width() - 1) : 0.0f);
  char near_text[32], far_text[32];
  std::snprintf(near_text, sizeof near_text, "%.4g", static_cast<double>(range.near));
  std::snprintf(far_text, sizeof far_text, "%.4g", static_cast<double>(range.far));
  const int text_y = depth.height() + bar + 1;
  draw_label(out.view(), 0, text_y, near_text, style);
  const std::string inf = "INF: BLACK";
  draw_label(out.view(), (depth.width() - label_size(inf, style).first) / 2, text_y, inf, style);
  draw_label(out.view(), depth.width() - label_size(far_text, style).first, text_y, far_text, style);
  return out;
}

/// Writes `depth_preview(depth, range)` as a PNG (see `write_png`).
inline void write_depth_preview(const std::filesystem::path& path, ImageView<const float> depth,
                                DepthRange range = {}) {
  if (depth.empty()) throw io_error(path.string(), "cannot write an empty image");
  write_png(path, depth_preview(depth, range));
}

} // namespace mpr
