#pragma once
/// \file
/// `mpr::downsampled`: a camera frame set at 1/k of its cameras' scale, each image box-filtered
/// in linear light over k x k blocks (the next levels of a mip-map pyramid, Williams 1983).
///
/// Why: a frame sampler interpolates bilinearly on the frames it is given. When the output has
/// fewer pixels than the cameras see of the same surface (a 700x400 refocus of 1400x800 Chess
/// frames), each output pixel then reads four full-resolution texels of its own per camera: the
/// render costs about as much as a full-size one, and the image aliases (it point-samples a
/// 2-texel footprint). Sampling the frames prefiltered to the output's scale reads a quarter of
/// the texels and averages each footprint. It is a different filter from bilinear sampling of
/// the full frames (a 2x2 box followed by a bilinear tent, 4 texels wide, instead of a tent 2
/// texels wide), chosen by the caller: the samplers' per-ray contract is bilinear sampling of
/// the set they hold, whichever that is.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/parallel.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mpr {

/// The camera of an image downsampled by `factor`: same pose and distortion, intrinsics scaled
/// so that a pixel of the new image covers the `factor` x `factor` block of old pixels whose
/// average it holds. With pixel centres at integer coordinates (see `PinholeCamera`), old
/// coordinate x maps to (x - (factor - 1) / 2) / factor. Size: the old size / factor, rounded
/// down (the last columns and rows that fill no block are dropped). Throws `argument_error`
/// ("factor") unless 1 <= factor <= the camera's width and height.
template <std::floating_point T>
[[nodiscard]] PinholeCamera<T> downsampled(const PinholeCamera<T>& camera, int factor) {
  if (factor < 1) throw argument_error("factor", std::to_string(factor) + " (a downsampling factor is at least 1)");
  if (factor > camera.width() || factor > camera.height())
    throw argument_error("factor", std::to_string(factor) + " exceeds the camera's size, " +
                                       std::to_string(camera.width()) + "x" + std::to_string(camera.height()));
  const T s = T(1) / static_cast<T>(factor);
  const T shift = -static_cast<T>(factor - 1) / static_cast<T>(2 * factor);
  Mat3<T> A = Mat3<T>::Identity();
  A(0, 0) = s;
  A(1, 1) = s;
  A(0, 2) = shift;
  A(1, 2) = shift;
  const Mat3<T> K = A * camera.K();
  // R was checked when `camera` was built, perhaps with a looser tolerance than the default.
  const T orthogonality = (camera.R().transpose() * camera.R() - Mat3<T>::Identity()).cwiseAbs().maxCoeff();
  return PinholeCamera<T>(K, camera.R(), camera.t(), camera.width() / factor, camera.height() / factor,
                          camera.distortion(), std::max(PinholeCamera<T>::default_rotation_tolerance(), orthogonality));
}

namespace detail {

/// Image `in` box-filtered over `factor` x `factor` blocks into `out` (of size in / factor), the
/// sums of a row in `sum` and `mean` (3 x out.width() floats each); see `downsampled`.
template <class Px>
void box_filter_image(const Image<Px>& in, Image<Px>& out, int factor, float* sum, float* mean) noexcept {
  const int w = out.width();
  const std::size_t m = static_cast<std::size_t>(w) * 3;
  const float weight = 1.0f / static_cast<float>(factor * factor);
  for (int y = 0; y < out.height(); ++y) {
    std::fill(sum, sum + m, 0.0f);
    for (int dy = 0; dy < factor; ++dy) {
      const Px* row = &in(0, y * factor + dy);
      for (int x = 0; x < w; ++x)
        for (int dx = 0; dx < factor; ++dx) {
          const Px& p = row[x * factor + dx];
          float* s = sum + 3 * x;
          if constexpr (std::is_same_v<Px, Rgb8>) {
            s[0] += srgb8_to_linear(p.r);
            s[1] += srgb8_to_linear(p.g);
            s[2] += srgb8_to_linear(p.b);
          } else {
            s[0] += p[0];
            s[1] += p[1];
            s[2] += p[2];
          }
        }
    }
    for (std::size_t j = 0; j < m; ++j) mean[j] = sum[j] * weight;
    Px* dst = &out(0, y);
    if constexpr (std::is_same_v<Px, Rgb8>) {
      static_assert(sizeof(Rgb8) == 3, "an Rgb8 row is a flat array of codes");
      linear_to_srgb8_row(mean, &dst->r, m);
    } else {
      for (int x = 0; x < w; ++x) dst[x] = Color(mean[3 * x], mean[3 * x + 1], mean[3 * x + 2]);
    }
  }
}

/// Depth map `in` reduced to the nearest depth of each block into `out` (see `downsampled`).
inline void nearest_depth_image(const Image<float>& in, Image<float>& out, int factor) noexcept {
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) {
      float nearest = std::numeric_limits<float>::infinity();
      for (int dy = 0; dy < factor; ++dy)
        for (int dx = 0; dx < factor; ++dx) nearest = std::min(nearest, in(x * factor + dx, y * factor + dy));
      out(x, y) = nearest;
    }
}

} // namespace detail

/// `frames` at 1/`factor` of their scale: every camera as `downsampled(camera, factor)`, every
/// image the average in linear light of each `factor` x `factor` block (8-bit frames re-encoded
/// to the nearest sRGB code by the exact encoder, so a block of one colour keeps its code; linear
/// frames keep the average unclamped), depth maps (when the set carries them) the nearest finite
/// depth of each block (+inf where the block saw nothing: a visibility test against the coarse
/// map then errs towards the foreground), the names and the array plane unchanged. `factor` 1
/// returns a copy. The cameras are shared among `threads` workers (the caller included; 0 or
/// less: all hardware threads); the result does not depend on their number. Throws
/// `argument_error` ("factor") when `factor` < 1 or exceeds a camera's width or height (naming
/// the camera).
template <std::floating_point T, class Px>
[[nodiscard]] CameraFrameSet<T, Px> downsampled(const CameraFrameSet<T, Px>& frames, int factor, int threads = 0) {
  if (factor < 1) throw argument_error("factor", std::to_string(factor) + " (a downsampling factor is at least 1)");
  if (factor == 1) return frames;
  const std::size_t n = frames.size();
  std::vector<PinholeCamera<T>> cameras;
  cameras.reserve(n);
  for (std::size_t i = 0; i < n; ++i) try {
      cameras.push_back(downsampled(frames.camera(i), factor));
    } catch (const argument_error& e) {
      throw argument_error("factor", frames.name(i) + ": " + e.reason());
    }
  std::vector<Image<Px>> images;
  std::vector<Image<float>> depths;
  std::vector<std::size_t> scratch_at(n + 1, 0); // each camera's two rows of sums in `scratch`
  images.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    images.emplace_back(cameras.back().width(), cameras.back().height());
    if (frames.has_depth()) depths.emplace_back(cameras.back().width(), cameras.back().height());
    scratch_at[i + 1] = scratch_at[i] + 6 * static_cast<std::size_t>(cameras.back().width());
  }
  std::vector<float> scratch(scratch_at[n]);
  detail::parallel_rows(0, static_cast<int>(n), threads, [&](int camera) noexcept {
    const auto i = static_cast<std::size_t>(camera);
    float* sum = scratch.data() + scratch_at[i];
    detail::box_filter_image(frames.image(i), images[i], factor, sum, sum + (scratch_at[i + 1] - scratch_at[i]) / 2);
    if (frames.has_depth()) detail::nearest_depth_image(frames.depth(i), depths[i], factor);
  });
  CameraFrameSet<T, Px> out =
      CameraFrameSet<T, Px>(std::move(cameras), std::move(images), frames.names()).with_depth(std::move(depths));
  if (frames.array_plane()) return std::move(out).on_plane(*frames.array_plane());
  return out;
}

} // namespace mpr
