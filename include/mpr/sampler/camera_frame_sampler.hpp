#pragma once
/// \file
/// `mpr::CameraFrameSampler<Interpolation>`: a ray sampler answering each ray from a set of
/// calibrated camera images (light field rendering, Levoy & Hanrahan 1996; dynamically
/// reparameterized light fields, Isaksen et al. 2000), as in the General Linear Camera system of
/// Yu & McMillan (ECCV 2004), which rendered from the Stanford camera array.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/sampler/camera_frame_index.hpp>
#include <mpr/sampler/camera_frame_interpolation.hpp>
#include <mpr/sampler/camera_frame_set.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

namespace mpr {

/// Answers a ray with the colour the cameras of a `CameraFrameSet` see at the ray's point.
///
/// The point is where the ray starts (`ray.origin`: the image-surface point, so the image
/// surface is the focal surface), or `ray.at(depth)` when `Config::depth` is set (with the GLC
/// selector, whose directions have unit normal component, that is `depth` world units behind
/// the image plane). Cameras are chosen by `Interpolation` (`NearestCamera`,
/// `SyntheticAperture`, `CylinderAperture`) using the distance from their centres to the ray
/// *line*; each chosen camera that sees the point (in front of it, projecting inside its image)
/// contributes its pixel there, reconstructed by `Config::filter`. Colour is linear (8-bit
/// frames are decoded with the exact sRGB table). A point no camera sees gets
/// `Config::background`; the result is never NaN for finite rays.
///
/// The sampler shares its frames through a `shared_ptr`, so copies are cheap and threads share
/// one set of images. Besides the per-ray `sample` (the contract), it offers `sample_rays`, a
/// batch form the renderer uses when present: it walks cameras in the outer loop for
/// `SyntheticAperture` and returns the same colours.
template <class Interpolation, std::floating_point T = float, class Px = Rgb8> class CameraFrameSampler {
  static_assert(std::is_same_v<Interpolation, NearestCamera> || std::is_same_v<Interpolation, SyntheticAperture> ||
                    std::is_same_v<Interpolation, CylinderAperture>,
                "Interpolation is NearestCamera, SyntheticAperture or CylinderAperture");

public:
  using scalar_type = T;
  using color_type = Color;
  using frame_set_type = CameraFrameSet<T, Px>;
  using interpolation_type = Interpolation;

  struct Config {
    /// Reconstruction of each camera's pixels.
    PixelFilter filter = PixelFilter::bilinear;
    /// When set, the colour is taken at `ray.at(*depth)` instead of `ray.origin`.
    std::optional<T> depth;
    /// The colour of a point that no chosen camera sees (linear RGB).
    Color background = Color::Zero();
  };

  /// Throws `argument_error` naming "frames" (null or empty), "radius" (cylinder radius not
  /// positive and finite), "depth" (not finite) or "background" (not finite).
  explicit CameraFrameSampler(std::shared_ptr<const frame_set_type> frames, Interpolation interpolation = {},
                              Config config = {})
      : frames_(std::move(frames)), interpolation_(interpolation), config_(config) {
    if (!frames_ || frames_->empty()) throw argument_error("frames", "no cameras");
    if constexpr (std::is_same_v<Interpolation, CylinderAperture>) interpolation_.validate();
    if (config_.depth && !std::isfinite(*config_.depth)) throw argument_error("depth", "not finite");
    if (!config_.background.allFinite()) throw argument_error("background", "not finite");
    std::vector<Vec3<T>> centres;
    cameras_.reserve(frames_->size());
    for (std::size_t i = 0; i < frames_->size(); ++i) {
      const PinholeCamera<T>& c = frames_->camera(i);
      centres.push_back(c.centre());
      CameraData d;
      Eigen::Matrix<T, 3, 4> P;
      P.template leftCols<3>() = c.K() * c.R();
      P.col(3) = c.K() * c.t();
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 4; ++k) d.P[r * 4 + k] = P(r, k);
      d.distorted = c.has_distortion();
      d.width = c.width();
      d.height = c.height();
      d.pixels = frames_->image(i).data();
      d.camera = &c;
      cameras_.push_back(d);
    }
    index_ = std::make_shared<const CameraCentreIndex<T>>(std::span<const Vec3<T>>(centres));
  }

  [[nodiscard]] const frame_set_type& frames() const noexcept { return *frames_; }
  [[nodiscard]] const Interpolation& interpolation() const noexcept { return interpolation_; }
  [[nodiscard]] const Config& config() const noexcept { return config_; }
  [[nodiscard]] const CameraCentreIndex<T>& index() const noexcept { return *index_; }

  /// The colour along `ray` (see the class comment).
  [[nodiscard]] Color sample(const Ray<T>& ray) const noexcept {
    const Vec3<T> X = config_.depth ? ray.at(*config_.depth) : ray.origin;
    float acc[3] = {0, 0, 0};
    if constexpr (std::is_same_v<Interpolation, SyntheticAperture>) {
      float weight = 0;
      for (const CameraData& c : cameras_) {
        T x, y;
        if (project(c, X, x, y)) {
          fetch_add(c, x, y, 1.0f, acc);
          weight += 1.0f;
        }
      }
      return finish(acc, weight);
    } else {
      return sample_selected(ray, X);
    }
  }

  /// `out[i] = sample(rays[i])` for every i (precondition: equal lengths), computed with the
  /// cameras in the outer loop where that helps. Bit-identical to `sample` per ray.
  void sample_rays(std::span<const Ray<T>> rays, std::span<Color> out) const noexcept {
    if constexpr (!std::is_same_v<Interpolation, SyntheticAperture>) {
      for (std::size_t i = 0; i < rays.size(); ++i) out[i] = sample(rays[i]);
    } else {
      constexpr std::size_t kChunk = 128;
      Vec3<T> points[kChunk];
      float acc[kChunk][3];
      float weight[kChunk];
      for (std::size_t start = 0; start < rays.size(); start += kChunk) {
        const std::size_t n = std::min(kChunk, rays.size() - start);
        for (std::size_t i = 0; i < n; ++i) {
          const Ray<T>& ray = rays[start + i];
          points[i] = config_.depth ? ray.at(*config_.depth) : ray.origin;
          acc[i][0] = acc[i][1] = acc[i][2] = 0;
          weight[i] = 0;
        }
        for (const CameraData& c : cameras_) {
          for (std::size_t i = 0; i < n; ++i) {
            T x, y;
            if (project(c, points[i], x, y)) {
              fetch_add(c, x, y, 1.0f, acc[i]);
              weight[i] += 1.0f;
            }
          }
        }
        for (std::size_t i = 0; i < n; ++i) out[start + i] = finish(acc[i], weight[i]);
      }
    }
  }

private:
  struct CameraData {
    T P[12]; // K [R | t], row-major
    bool distorted = false;
    int width = 0, height = 0;
    const Px* pixels = nullptr;
    const PinholeCamera<T>* camera = nullptr;
  };

  [[nodiscard]] Color finish(const float acc[3], float weight) const noexcept {
    if (!(weight > 0)) return config_.background;
    const float inv = 1.0f / weight;
    return Color(acc[0] * inv, acc[1] * inv, acc[2] * inv);
  }

  // Continuous pixel coordinates of X in camera c, if c sees it (in front, inside the image).
  [[nodiscard]] static bool project(const CameraData& c, const Vec3<T>& X, T& x, T& y) noexcept {
    if (c.distorted) {
      const std::optional<Vec2<T>> p = c.camera->project(X);
      if (!p) return false;
      x = p->x();
      y = p->y();
      return true;
    }
    const T* P = c.P;
    const T w = P[8] * X.x() + P[9] * X.y() + P[10] * X.z() + P[11];
    if (!(w > 0)) return false;
    const T inv = T(1) / w;
    x = (P[0] * X.x() + P[1] * X.y() + P[2] * X.z() + P[3]) * inv;
    y = (P[4] * X.x() + P[5] * X.y() + P[6] * X.z() + P[7]) * inv;
    return x >= T(-0.5) && x < static_cast<T>(c.width) - T(0.5) && y >= T(-0.5) &&
           y < static_cast<T>(c.height) - T(0.5);
  }

  [[nodiscard]] static const float* linear(const Px& p, float (&tmp)[3]) noexcept {
    if constexpr (std::is_same_v<Px, Rgb8>) {
      tmp[0] = srgb8_to_linear(p.r);
      tmp[1] = srgb8_to_linear(p.g);
      tmp[2] = srgb8_to_linear(p.b);
      return tmp;
    } else {
      return p.data();
    }
  }

  // acc += weight * (pixel of camera c at continuous (x, y)); (x, y) lies inside the image.
  void fetch_add(const CameraData& c, T x, T y, float weight, float acc[3]) const noexcept {
    float tmp[3];
    if (config_.filter == PixelFilter::nearest) {
      const int ix = std::min(static_cast<int>(std::floor(x + T(0.5))), c.width - 1);
      const int iy = std::min(static_cast<int>(std::floor(y + T(0.5))), c.height - 1);
      const float* v = linear(c.pixels[static_cast<std::ptrdiff_t>(iy) * c.width + ix], tmp);
      for (int k = 0; k < 3; ++k) acc[k] += weight * v[k];
      return;
    }
    const T fx0 = std::floor(x), fy0 = std::floor(y);
    const float ax = static_cast<float>(x - fx0), ay = static_cast<float>(y - fy0);
    const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
    const int xa = std::max(x0, 0), xb = std::min(x0 + 1, c.width - 1);
    const int ya = std::max(y0, 0), yb = std::min(y0 + 1, c.height - 1);
    const Px* ra = c.pixels + static_cast<std::ptrdiff_t>(ya) * c.width;
    const Px* rb = c.pixels + static_cast<std::ptrdiff_t>(yb) * c.width;
    const float w00 = (1 - ax) * (1 - ay) * weight, w10 = ax * (1 - ay) * weight;
    const float w01 = (1 - ax) * ay * weight, w11 = ax * ay * weight;
    const float* v = linear(ra[xa], tmp);
    for (int k = 0; k < 3; ++k) acc[k] += w00 * v[k];
    v = linear(ra[xb], tmp);
    for (int k = 0; k < 3; ++k) acc[k] += w10 * v[k];
    v = linear(rb[xa], tmp);
    for (int k = 0; k < 3; ++k) acc[k] += w01 * v[k];
    v = linear(rb[xb], tmp);
    for (int k = 0; k < 3; ++k) acc[k] += w11 * v[k];
  }

  [[nodiscard]] Color nearest_camera(const Ray<T>& ray, const Vec3<T>& X) const noexcept {
    const int i = index_->nearest(ray.origin, ray.direction);
    if (i < 0) return config_.background;
    const CameraData& c = cameras_[static_cast<std::size_t>(i)];
    T x, y;
    if (!project(c, X, x, y)) return config_.background;
    float acc[3] = {0, 0, 0};
    fetch_add(c, x, y, 1.0f, acc);
    return finish(acc, 1.0f);
  }

  [[nodiscard]] Color sample_selected(const Ray<T>& ray, const Vec3<T>& X) const noexcept {
    if constexpr (std::is_same_v<Interpolation, NearestCamera>) {
      return nearest_camera(ray, X);
    } else {
      const T radius = static_cast<T>(interpolation_.radius);
      float acc[3] = {0, 0, 0};
      float weight = 0;
      index_->within(ray.origin, ray.direction, radius, [&](int i, T d) noexcept {
        const CameraData& c = cameras_[static_cast<std::size_t>(i)];
        const float w = static_cast<float>(T(1) - d / radius);
        T x, y;
        if (!(w > 0) || !project(c, X, x, y)) return;
        fetch_add(c, x, y, w, acc);
        weight += w;
      });
      if (!(weight > 0)) return nearest_camera(ray, X);
      return finish(acc, weight);
    }
  }

  std::shared_ptr<const frame_set_type> frames_;
  Interpolation interpolation_;
  Config config_;
  std::vector<CameraData> cameras_;
  std::shared_ptr<const CameraCentreIndex<T>> index_;
};

} // namespace mpr
