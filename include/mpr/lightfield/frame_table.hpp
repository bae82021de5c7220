#pragma once
/// \file
/// `mpr::FrameTable<T, Px>`: the immutable state every light-field interpolation reads -- the
/// frames, one projection record per camera, the ball tree over the centres, the sampler
/// settings and, for planar arrays, the plane of the centres (`ArrayPlane`) -- plus the per-ray
/// operations on it that every interpolation shares: the ray's point, projection into a camera,
/// pixel reconstruction and the weighted average. Built once and shared by `shared_ptr<const>`
/// among samplers (and threads), like the scene of `SceneSampler`.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/lightfield/array_plane.hpp>
#include <mpr/lightfield/camera_index.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace mpr {

/// Reconstruction of a camera image between pixel centres.
enum class PixelFilter {
  /// Bilinear interpolation of the four nearest pixel centres (edge pixels repeat), in linear
  /// colour.
  bilinear,
  /// The pixel whose square contains the point.
  nearest,
};

/// Settings shared by every interpolation of a `FrameTable` (and so of a `CameraFrameSampler`).
template <std::floating_point T>
struct FrameSamplerConfig {
  /// Reconstruction of each camera's pixels.
  PixelFilter filter = PixelFilter::bilinear;
  /// When set, the colour is taken at `ray.at(*depth)` instead of `ray.origin` (with the GLC
  /// selector, whose directions have unit normal component, `depth` world units behind the image
  /// plane). Unset: the image surface is the focal surface.
  std::optional<T> depth;
  /// The colour of a point that no chosen camera sees (linear RGB).
  Color background = Color::Zero();
};

/// The frames of a `CameraFrameSet` prepared for sampling (see the file comment). All member
/// functions are `const`; the per-ray ones are `noexcept` and allocation-free.
template <std::floating_point T, class Px = Rgb8>
class FrameTable {
public:
  using scalar_type = T;
  using frame_set_type = CameraFrameSet<T, Px>;
  using texel_type = typename frame_set_type::texel_type;
  using Config = FrameSamplerConfig<T>;

  /// One camera as the samplers read it.
  struct Camera {
    /// K [R | t], row-major: pixel (x, y) of a world point X is (P0 X, P1 X) / (P2 X).
    T P[12];
    Vec3<T> centre;
    /// True when the camera has lens distortion (then `PinholeCamera::project` is used).
    bool distorted = false;
    int width = 0, height = 0;
    /// Row-major `width * height` linear texels.
    const texel_type* texels = nullptr;
    /// Their channels as 16-bit linear values (`CameraFrameSet::linear16`), or nullptr.
    const std::uint16_t* linear = nullptr;
    const PinholeCamera<T>* camera = nullptr;
  };

  /// Throws `argument_error` naming "frames" (null or empty), "depth" (not finite) or
  /// "background" (not finite).
  explicit FrameTable(std::shared_ptr<const frame_set_type> frames, const Config& config = {})
      : frames_(std::move(frames)), config_(config) {
    if (!frames_ || frames_->empty()) throw argument_error("frames", "no cameras");
    if (config_.depth && !std::isfinite(*config_.depth)) throw argument_error("depth", "not finite");
    if (!config_.background.allFinite()) throw argument_error("background", "not finite");
    std::vector<Vec3<T>> centres;
    cameras_.reserve(frames_->size());
    for (std::size_t i = 0; i < frames_->size(); ++i) {
      const PinholeCamera<T>& c = frames_->camera(i);
      centres.push_back(c.centre());
      Camera d;
      Eigen::Matrix<T, 3, 4> P;
      P.template leftCols<3>() = c.K() * c.R();
      P.col(3) = c.K() * c.t();
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 4; ++k) d.P[r * 4 + k] = P(r, k);
      d.centre = c.centre();
      d.distorted = c.has_distortion();
      d.width = c.width();
      d.height = c.height();
      d.texels = frames_->texels(i).data();
      d.linear = frames_->linear16(i);
      d.camera = &c;
      cameras_.push_back(d);
    }
    index_ = CameraCentreIndex<T>(std::span<const Vec3<T>>(centres));
    plane_ = ArrayPlane<T>::fit(centres, frames_->array_plane());
  }

  [[nodiscard]] const frame_set_type& frames() const noexcept { return *frames_; }
  [[nodiscard]] const Config& config() const noexcept { return config_; }
  [[nodiscard]] std::size_t size() const noexcept { return cameras_.size(); }
  [[nodiscard]] const std::vector<Camera>& cameras() const noexcept { return cameras_; }
  [[nodiscard]] const Camera& camera(std::size_t i) const noexcept { return cameras_[i]; }
  /// Ball tree over the camera centres ("nearest to a line", "within r of a line").
  [[nodiscard]] const CameraCentreIndex<T>& index() const noexcept { return index_; }
  /// The plane of the centres when the array is planar (every centre within 1e-6 of the array's
  /// extent of one plane), else nullopt.
  [[nodiscard]] const std::optional<ArrayPlane<T>>& plane() const noexcept { return plane_; }

  /// The point whose colour a ray asks for: `ray.at(*config().depth)`, or `ray.origin`.
  [[nodiscard]] Vec3<T> point_of(const Ray<T>& ray) const noexcept {
    return config_.depth ? ray.at(*config_.depth) : ray.origin;
  }

  /// Continuous pixel coordinates of X in camera c, if c sees it (in front, inside the image).
  [[nodiscard]] static bool project(const Camera& c, const Vec3<T>& X, T& x, T& y) noexcept {
    if (c.distorted) {
      const std::optional<Vec2<T>> p = c.camera->project(X);
      if (!p) return false;
      x = p->x();
      y = p->y();
      return true;
    }
    return project_any(c, X, x, y) && x >= T(-0.5) && x < static_cast<T>(c.width) - T(0.5) && y >= T(-0.5) &&
           y < static_cast<T>(c.height) - T(0.5);
  }

  /// Continuous pixel coordinates of X in an undistorted camera c, inside the image or not;
  /// false when X is not in front of c.
  [[nodiscard]] static bool project_any(const Camera& c, const Vec3<T>& X, T& x, T& y) noexcept {
    const T* P = c.P;
    const T w = P[8] * X.x() + P[9] * X.y() + P[10] * X.z() + P[11];
    if (!(w > 0)) return false;
    const T inv = T(1) / w;
    x = (P[0] * X.x() + P[1] * X.y() + P[2] * X.z() + P[3]) * inv;
    y = (P[4] * X.x() + P[5] * X.y() + P[6] * X.z() + P[7]) * inv;
    return std::isfinite(x) && std::isfinite(y);
  }

  /// acc[0..2] += weight * (pixel of camera c at continuous (x, y), reconstructed by
  /// `config().filter`); precondition: (x, y) lies inside the image (as `project` ensures).
  void fetch_add(const Camera& c, T x, T y, float weight, float* acc) const noexcept {
    const float scaled = weight * texel_type::scale;
    const std::uint16_t* lut = texel_decode_table<texel_type>();
    const auto value = [lut](auto channel) { return detail::channel_value(channel, lut); };
    if (config_.filter == PixelFilter::nearest) {
      const int ix = std::min(static_cast<int>(std::floor(x + T(0.5))), c.width - 1);
      const int iy = std::min(static_cast<int>(std::floor(y + T(0.5))), c.height - 1);
      const texel_type& v = c.texels[static_cast<std::ptrdiff_t>(iy) * c.width + ix];
      for (int k = 0; k < 3; ++k) acc[k] += scaled * value(v.c[k]);
      return;
    }
    const T fx0 = std::floor(x), fy0 = std::floor(y);
    const float ax = static_cast<float>(x - fx0), ay = static_cast<float>(y - fy0);
    const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
    const int xa = std::max(x0, 0), xb = std::min(x0 + 1, c.width - 1);
    const int ya = std::max(y0, 0), yb = std::min(y0 + 1, c.height - 1);
    const texel_type* ra = c.texels + static_cast<std::ptrdiff_t>(ya) * c.width;
    const texel_type* rb = c.texels + static_cast<std::ptrdiff_t>(yb) * c.width;
    const float w00 = (1 - ax) * (1 - ay) * scaled, w10 = ax * (1 - ay) * scaled;
    const float w01 = (1 - ax) * ay * scaled, w11 = ax * ay * scaled;
    for (int k = 0; k < 3; ++k)
      acc[k] +=
          w00 * value(ra[xa].c[k]) + w10 * value(ra[xb].c[k]) + w01 * value(rb[xa].c[k]) + w11 * value(rb[xb].c[k]);
  }

  /// Adds camera c's pixel at X to (acc, weight) with weight `w`, if c sees X; returns whether it did.
  bool add_seen(const Camera& c, const Vec3<T>& X, float w, float* acc, float& weight) const noexcept {
    T x, y;
    if (!project(c, X, x, y)) return false;
    fetch_add(c, x, y, w, acc);
    weight += w;
    return true;
  }

  /// The weighted average acc / weight, or the background when the weight is not positive.
  [[nodiscard]] Color finish(const float* acc, float weight) const noexcept {
    if (!(weight > 0)) return config_.background;
    const float inv = 1.0f / weight;
    return Color(acc[0] * inv, acc[1] * inv, acc[2] * inv);
  }

  /// `finish` for n pixels at once: out[i] = finish(acc + 3 i, weight[i]), vectorised. Returns
  /// whether every weight was positive (no pixel took the background). Precondition: no weight
  /// is NaN (the adders add only positive weights).
  bool finish_all(const float* acc, const float* weight, std::size_t n, Color* out) const noexcept {
    // Color is three packed floats (static_assert in color.hpp): the outputs are one flat array.
    detail::average_rows(acc, weight, out->data(), n);
    if (detail::min_of(weight, n) > 0) return true; // every pixel seen: no background to put in
    for (std::size_t i = 0; i < n; ++i)
      if (!(weight[i] > 0)) out[i] = config_.background;
    return false;
  }

  /// Camera `camera`'s colour at X: the background when `camera < 0` or it does not see X.
  [[nodiscard]] Color camera_color(int camera, const Vec3<T>& X) const noexcept {
    if (camera < 0) return config_.background;
    float acc[3] = {0, 0, 0};
    float weight = 0;
    if (!add_seen(cameras_[static_cast<std::size_t>(camera)], X, 1.0f, acc, weight)) return config_.background;
    return finish(acc, 1.0f);
  }

  /// acc[3 i ..] += pixel of camera c at points[i], weight[i] += 1, for every point c sees
  /// (i in [0, n)). With `ray_weight` (not nullptr): weighted by ray_weight[i], rays of weight
  /// <= 0 skipped.
  void add_per_ray(const Camera& c, const Vec3<T>* points, std::size_t n, float* acc, float* weight,
                   const float* ray_weight = nullptr) const noexcept {
    for (std::size_t i = 0; i < n; ++i) {
      const float w = ray_weight != nullptr ? ray_weight[i] : 1.0f;
      if (w > 0) add_seen(c, points[i], w, acc + 3 * i, weight[i]);
    }
  }

private:
  std::shared_ptr<const frame_set_type> frames_;
  Config config_;
  std::vector<Camera> cameras_;
  CameraCentreIndex<T> index_;
  std::optional<ArrayPlane<T>> plane_;
};

} // namespace mpr
