#pragma once
/// \file
/// The working memory of the plane sweep of `estimate_depth` (lightfield/depth_estimation.hpp):
/// images as planar float channels and 8-bit codes, the buffers one worker reuses from camera to camera, and
/// their size in bytes (which `PlaneSweepConfig::memory_limit` bounds).

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/kernels/sweep_code_kernels.hpp>
#include <mpr/lightfield/kernels/sweep_kernels.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mpr::detail {

/// Zeros before an image's first row (`SweepPlanes`).
inline constexpr std::ptrdiff_t kSweepPad = 16;

/// Row stride of `SweepPlanes` for images `width` pixels wide: room for one zero past the row's
/// end, rounded up to 16 floats.
[[nodiscard]] constexpr std::ptrdiff_t sweep_stride(int width) noexcept {
  return (static_cast<std::ptrdiff_t>(width) + 16) / 16 * 16;
}

/// An image as planar float channels (sRGB codes / 255), rows `stride` floats apart with at
/// least one zero past each row's end and `kSweepPad` before the first (read by the sweep
/// kernels with weight 0, or a rounding error of weight, at the image's border), and, for the
/// reference camera, its 8-bit codes (for the aggregation's colour edges).
struct SweepPlanes {
  std::vector<float> data;
  std::vector<Rgb8> codes;
  /// The same channels as planar 8-bit codes (`stride` apart, kSweepCodePad zeros before the
  /// first and after the last), for the 16-bit kernel (kernels/sweep_code_kernels.hpp).
  std::vector<std::uint8_t> code_planes;
  std::ptrdiff_t stride = 0;
  int width = 0, height = 0;
  [[nodiscard]] const float* channel(int c) const noexcept {
    return data.data() + kSweepPad + static_cast<std::ptrdiff_t>(c) * stride * height;
  }
  [[nodiscard]] const std::uint8_t* channel_codes(int c) const noexcept {
    return code_planes.data() + kSweepCodePad + static_cast<std::ptrdiff_t>(c) * stride * height;
  }
  [[nodiscard]] SweepImage view() const noexcept {
    return {{channel(0), channel(1), channel(2)}, stride, width, height};
  }
};

/// `image` into `p` (its buffers reused: only the padding is cleared, every pixel is written).
template <class Px>
void sweep_planes(const Image<Px>& image, bool keep_codes, SweepPlanes& p) {
  float unit[256]; // code / 255
  for (int c = 0; c < 256; ++c) unit[c] = static_cast<float>(c) / 255.0f;
  p.width = image.width();
  p.height = image.height();
  p.stride = sweep_stride(p.width);
  const std::size_t plane = static_cast<std::size_t>(p.stride) * static_cast<std::size_t>(p.height);
  p.data.resize(3 * plane + kSweepPad);
  p.code_planes.resize(3 * plane + 2 * kSweepCodePad);
  std::fill_n(p.data.begin(), kSweepPad, 0.0f);
  std::fill_n(p.code_planes.begin(), kSweepCodePad, std::uint8_t{0});
  std::fill_n(p.code_planes.end() - kSweepCodePad, kSweepCodePad, std::uint8_t{0});
  if (keep_codes) p.codes.resize(static_cast<std::size_t>(p.width) * static_cast<std::size_t>(p.height));
  const std::size_t w = static_cast<std::size_t>(p.width), tail = static_cast<std::size_t>(p.stride) - w;
  for (int y = 0; y < p.height; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(p.stride);
    float* out[3];
    std::uint8_t* codes[3];
    for (std::size_t c = 0; c < 3; ++c) {
      out[c] = p.data.data() + kSweepPad + c * plane + row;
      codes[c] = p.code_planes.data() + kSweepCodePad + c * plane + row;
      std::fill_n(out[c] + w, tail, 0.0f); // the zeros past the row's end
      std::fill_n(codes[c] + w, tail, std::uint8_t{0});
    }
    Rgb8* kept = keep_codes ? p.codes.data() + static_cast<std::size_t>(y) * w : nullptr;
    for (int x = 0; x < p.width; ++x) {
      Rgb8 c;
      if constexpr (std::is_same_v<Px, Rgb8>)
        c = image(x, y);
      else
        c = to_rgb8(image(x, y));
      out[0][x] = unit[c.r];
      out[1][x] = unit[c.g];
      out[2][x] = unit[c.b];
      codes[0][x] = c.r;
      codes[1][x] = c.g;
      codes[2][x] = c.b;
      if (kept) kept[x] = c;
    }
  }
}

/// The buffers of one camera's sweep, reused by the next camera a worker sweeps (so that they
/// are not page-faulted in again for every camera), all sized before the parallel parts start
/// (nothing is allocated inside a worker): about 145 bytes per pixel with four neighbours
/// (planar float images 60, the same as 8-bit codes 15, costs of 8 planes 32, argmin state 24,
/// feedback 8); see
/// `sweep_workspace_bytes`.
struct SweepWorkspace {
  SweepPlanes rt;
  std::vector<SweepPlanes> nt;
  std::vector<std::size_t> nt_camera; // the camera each of `nt` holds (`sweep_neighbour_planes`)
  std::vector<float> ax, ay, costs, best_cost, sum, left, right, previous;
  std::vector<int> best_plane;
  std::vector<float> keep;  // per block of rows: best + 1 cost rows (`plane_sweep`)
  std::vector<float> carry; // the backward vertical pass's rows, kSweepTrackPlanes per column
};

/// The bytes of a `SweepWorkspace` after sweeping a `width` x `height` camera against
/// neighbours of `neighbour_pixels` (width, height) with `best` kept costs, plus the two maps
/// the sweep returns (depth and confidence): what one worker of the plane sweep holds at most.
[[nodiscard]] inline double sweep_workspace_bytes(int width, int height,
                                                  const std::vector<std::pair<int, int>>& neighbour_pixels,
                                                  int best) noexcept {
  const auto planes = [](int w, int h) { // float channels and 8-bit codes
    const double plane = 3.0 * static_cast<double>(sweep_stride(w)) * h;
    return 4.0 * (plane + static_cast<double>(kSweepPad)) + (plane + 2.0 * static_cast<double>(kSweepCodePad));
  };
  const double n = static_cast<double>(width) * height, w = width;
  const int blocks = (height + kSweepLockstepRows - 1) / kSweepLockstepRows;
  double bytes = planes(width, height) + 3.0 * n; // the camera's planes and codes
  for (const auto& [nw, nh] : neighbour_pixels) bytes += planes(nw, nh);
  bytes += 4.0 * n * (2 + kSweepTrackPlanes + 6); // ax, ay; costs; best_cost, sum, left, right, previous, best_plane
  bytes += 4.0 * blocks * (best + 1) * w + 4.0 * kSweepTrackPlanes * w; // keep, carry
  return bytes + 8.0 * n;                                               // depth, confidence
}

/// `plane_sweep_bytes` (lightfield/depth_estimation.hpp) for camera `camera` compared with the
/// cameras `order`, `best` kept costs.
template <std::floating_point T, class Px>
[[nodiscard]] double sweep_bytes(const CameraFrameSet<T, Px>& frames, std::size_t camera,
                                 const std::vector<std::size_t>& order, int best) {
  std::vector<std::pair<int, int>> sizes;
  for (const std::size_t j : order) sizes.emplace_back(frames.camera(j).width(), frames.camera(j).height());
  const PinholeCamera<T>& ref = frames.camera(camera);
  return sweep_workspace_bytes(ref.width(), ref.height(), sizes, std::min(best, static_cast<int>(order.size())));
}

/// Throws `argument_error` ("memory_limit") when the sweep of camera `camera`, `bytes` of
/// working memory, needs more than `memory_limit` bytes (`PlaneSweepConfig::memory_limit`).
template <std::floating_point T, class Px>
void check_sweep_memory(const CameraFrameSet<T, Px>& frames, std::size_t camera, double bytes, double memory_limit) {
  if (bytes <= memory_limit) return;
  const PinholeCamera<T>& c = frames.camera(camera);
  const auto mib = [](double b) {
    char text[32];
    const double m = b / (1 << 20);
    std::snprintf(text, sizeof text, m >= 10 ? "%.0f" : "%.2g", m);
    return std::string(text);
  };
  throw argument_error("memory_limit", "the plane sweep of camera " + frames.name(camera) + " (" +
                                           std::to_string(c.width()) + "x" + std::to_string(c.height()) +
                                           ") needs about " + mib(bytes) + " MiB of working memory, more than the " +
                                           mib(memory_limit) + " MiB limit");
}

} // namespace mpr::detail
