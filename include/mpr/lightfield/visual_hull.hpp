#pragma once
/// \file
/// The visual hull (Laurentini 1994) of an object photographed against a plain background, as a
/// depth map per camera: the nearest point along each pixel's ray that every other camera sees
/// inside its silhouette. The object lies inside its hull, so the hull's front is a lower bound
/// on the true depth, and a background pixel sees nothing. `constrain_to_visual_hull` applies
/// both to depth maps estimated from colour (`estimate_depth_maps`), which on object-on-background
/// sets (the Middlebury temple and dino rings) otherwise put background pixels and weakly
/// textured object pixels at random depths inside the swept range.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/parallel.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/frame_set.hpp>
#include <mpr/lightfield/plane_sweep/depth_homography.hpp>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

namespace mpr {

/// A silhouette policy: `foreground(rgb8)` tells whether a pixel shows the object.
template <class S>
concept Silhouette = std::copy_constructible<S> && requires(const S& s, Rgb8 p) {
  { s.foreground(p) } -> std::same_as<bool>;
};

/// The object is every pixel whose brightest channel reaches `threshold` (sRGB code); the
/// background is darker (a black backdrop, as in the Middlebury multi-view sets).
struct BrightnessSilhouette {
  /// sRGB code in 1..255.
  int threshold = 20;
  [[nodiscard]] bool foreground(Rgb8 p) const noexcept { return std::max({p.r, p.g, p.b}) >= threshold; }
};

/// Settings of `visual_hull_depth`. Depths are along the camera's optical axis, world units.
struct VisualHullConfig {
  /// Depth range searched, 0 < near < far, finite.
  double near = 1;
  double far = 100;
  /// Depths tried between near and far, uniform in inverse depth, 2..4096: the hull's front is
  /// answered by the last depth before the first one inside it, a lower bound within one step
  /// where the hull is thicker along the ray than a step (a thinner part between two depths is
  /// missed): choose steps of about one pixel of parallax between neighbouring cameras.
  int planes = 256;
  /// Worker threads (the caller included); 0 or less: all hardware threads.
  int threads = 0;
};

/// Throws `argument_error` naming "near", "far" or "planes".
inline void validate(const VisualHullConfig& c) {
  if (!(c.near >= 1e-30 && c.near <= 1e30)) throw argument_error("near", "must lie in [1e-30, 1e30]");
  if (!(c.far > c.near && c.far <= 1e30)) throw argument_error("far", "must lie beyond near, at most 1e30");
  if (c.planes < 2 || c.planes > 4096) throw argument_error("planes", "must be in 2..4096");
}

/// The visual hull's depth in camera `camera` of `frames`: per pixel, +inf where the camera's
/// own silhouette shows background; else the depth before the first of the config's depths at
/// which every other camera that sees the point (in front of it, inside its image) sees it on its
/// silhouette (one of the four pixel centres around its projection is foreground) (`near` when that is the first); +inf
/// when there is none (the silhouettes disagree along that ray). Throws `argument_error` for a bad config, a camera
/// index out of range ("camera") or lens distortion ("frames").
template <std::floating_point T, class Px, Silhouette S = BrightnessSilhouette>
[[nodiscard]] Image<float> visual_hull_depth(const CameraFrameSet<T, Px>& frames, std::size_t camera,
                                             const S& silhouette = {}, const VisualHullConfig& config = {}) {
  validate(config);
  if (camera >= frames.size()) throw argument_error("camera", "index out of range");
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (frames.camera(i).has_distortion())
      throw argument_error("frames", frames.name(i) + ": lens distortion is not supported by the visual hull");
  const auto rgb8 = [](const Px& p) {
    if constexpr (std::is_same_v<Px, Rgb8>)
      return p;
    else
      return to_rgb8(p);
  };
  // Every camera's silhouette, one byte per pixel, and its support: 1 where any of the pixels
  // (x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1) is foreground, so that a point projecting
  // anywhere between those four pixel centres counts as inside when one of them is (the pixel
  // grid then never carves off a sliver of the object: the hull stays a superset).
  std::vector<std::vector<std::uint8_t>> masks(frames.size()), support(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const Image<Px>& image = frames.image(i);
    const int w = image.width(), h = image.height();
    const auto at = [w](int x, int y) {
      return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
    };
    masks[i].resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) masks[i][at(x, y)] = silhouette.foreground(rgb8(image(x, y))) ? 1 : 0;
    support[i].resize(masks[i].size());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int x1 = std::min(x + 1, w - 1), y1 = std::min(y + 1, h - 1);
        support[i][at(x, y)] = masks[i][at(x, y)] | masks[i][at(x1, y)] | masks[i][at(x, y1)] | masks[i][at(x1, y1)];
      }
  }
  // Camera j sees pixel p of the reference at depth d at h = A_j + d M_j p (homogeneous).
  const PinholeCamera<T>& ref = frames.camera(camera);
  struct Other {
    detail::DepthHomography h;
    int width, height;
    const std::uint8_t* mask;
  };
  std::vector<Other> others;
  for (std::size_t j = 0; j < frames.size(); ++j)
    if (j != camera)
      others.push_back({detail::depth_homography(ref, frames.camera(j)), frames.camera(j).width(),
                        frames.camera(j).height(), support[j].data()});
  const double inv_near = 1 / config.near, inv_far = 1 / config.far;
  std::vector<double> depths(static_cast<std::size_t>(config.planes));
  for (int k = 0; k < config.planes; ++k)
    depths[static_cast<std::size_t>(k)] =
        1 / (inv_near + (inv_far - inv_near) * static_cast<double>(k) / static_cast<double>(config.planes - 1));
  const int width = ref.width(), height = ref.height();
  Image<float> out(width, height, std::numeric_limits<float>::infinity());
  const std::uint8_t* own = masks[camera].data();
  detail::parallel_rows(0, height, config.threads, [&](int y) noexcept {
    for (int x = 0; x < width; ++x) {
      if (own[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] == 0)
        continue;
      const Vec3<double> p(x, y, 1);
      // The camera that rejected the last depth is tried first at the next one.
      std::size_t first = 0;
      for (std::size_t k = 0; k < depths.size(); ++k) {
        const double d = depths[k];
        bool inside = true;
        for (std::size_t n = 0; n < others.size() && inside; ++n) {
          const std::size_t j = (first + n) % others.size();
          const Other& o = others[j];
          const Vec3<double> h = o.h.A + d * (o.h.M * p);
          if (!(h.z() > 0)) continue;
          const double u = h.x() / h.z(), v = h.y() / h.z();
          if (!(u >= -0.5 && v >= -0.5 && u < o.width - 0.5 && v < o.height - 0.5)) continue; // unseen: no constraint
          const int ui = std::max(static_cast<int>(std::floor(u)), 0),
                    vi = std::max(static_cast<int>(std::floor(v)), 0);
          if (o.mask[static_cast<std::size_t>(vi) * static_cast<std::size_t>(o.width) + static_cast<std::size_t>(ui)] ==
              0) {
            inside = false;
            first = j;
          }
        }
        if (inside) {
          out(x, y) = static_cast<float>(depths[k > 0 ? k - 1 : 0]);
          break;
        }
      }
    }
  });
  return out;
}

/// `visual_hull_depth` of every camera, in camera order.
template <std::floating_point T, class Px, Silhouette S = BrightnessSilhouette>
[[nodiscard]] std::vector<Image<float>> visual_hull_depth_maps(const CameraFrameSet<T, Px>& frames,
                                                               const S& silhouette = {},
                                                               const VisualHullConfig& config = {}) {
  std::vector<Image<float>> maps;
  maps.reserve(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) maps.push_back(visual_hull_depth(frames, i, silhouette, config));
  return maps;
}

/// Makes `depth` (e.g. estimated from colour) agree with the visual hull `hull` of the same
/// camera: +inf where the hull is +inf (background, or no consistent depth), and never nearer
/// than the hull's front. Throws `argument_error` ("hull") when the sizes differ.
inline void constrain_to_visual_hull(Image<float>& depth, const Image<float>& hull) {
  if (depth.width() != hull.width() || depth.height() != hull.height())
    throw argument_error("hull", "its size differs from the depth map's");
  for (int y = 0; y < depth.height(); ++y)
    for (int x = 0; x < depth.width(); ++x) {
      const float h = hull(x, y);
      depth(x, y) = std::isinf(h) ? h : std::max(depth(x, y), h);
    }
}

} // namespace mpr
