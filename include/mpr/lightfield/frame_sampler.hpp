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
#include <mpr/lightfield/camera_index.hpp>
#include <mpr/lightfield/interpolation.hpp>
#include <mpr/lightfield/detail/kernels.hpp>
#include <mpr/lightfield/frame_set.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
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
template <class Interpolation, std::floating_point T = float, class Px = Rgb8>
class CameraFrameSampler {
  static_assert(std::is_same_v<Interpolation, NearestCamera> || std::is_same_v<Interpolation, SyntheticAperture> ||
                    std::is_same_v<Interpolation, CylinderAperture>,
                "Interpolation is NearestCamera, SyntheticAperture or CylinderAperture");

public:
  using scalar_type = T;
  using color_type = Color;
  using frame_set_type = CameraFrameSet<T, Px>;
  using interpolation_type = Interpolation;
  using texel_type = typename frame_set_type::texel_type;

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
      d.centre = c.centre();
      d.distorted = c.has_distortion();
      d.width = c.width();
      d.height = c.height();
      d.texels = frames_->texels(i).data();
      d.camera = &c;
      cameras_.push_back(d);
    }
    index_ = std::make_shared<const CameraCentreIndex<T>>(std::span<const Vec3<T>>(centres));
    detect_plane(centres);
  }

  [[nodiscard]] const frame_set_type& frames() const noexcept { return *frames_; }
  [[nodiscard]] const Interpolation& interpolation() const noexcept { return interpolation_; }
  [[nodiscard]] const Config& config() const noexcept { return config_; }
  [[nodiscard]] const CameraCentreIndex<T>& index() const noexcept { return *index_; }
  /// True when every camera centre lies on one plane (a planar array): then the batch path
  /// proves nearest-camera choices and bounds cylinder candidates on that plane.
  [[nodiscard]] bool planar_array() const noexcept { return planar_; }

  /// The colour along `ray` (see the class comment).
  [[nodiscard]] Color sample(const Ray<T>& ray) const noexcept {
    const Vec3<T> X = point_of(ray);
    if constexpr (std::is_same_v<Interpolation, SyntheticAperture>) {
      float acc[3] = {0, 0, 0};
      float weight = 0;
      for (const CameraData& c : cameras_) {
        T x, y;
        if (project(c, X, x, y)) {
          fetch_add(c, x, y, 1.0f, acc);
          weight += 1.0f;
        }
      }
      return finish(acc, weight);
    } else if constexpr (std::is_same_v<Interpolation, NearestCamera>) {
      return colour_from(index_->nearest(ray.origin, ray.direction), X);
    } else {
      return cylinder(ray, X);
    }
  }

  /// `out[i] = sample(rays[i])` for every i (precondition: equal lengths), computed with the
  /// cameras in the outer loop (`SyntheticAperture`), with nearest-camera choices proved from
  /// the previous ray's choice (`NearestCamera` on a planar array), or with one candidate list
  /// per run of rays (`CylinderAperture` on a planar array). Equal to `sample` up to float
  /// rounding in the order of summation (see `sample_rays_synthetic`).
  void sample_rays(std::span<const Ray<T>> rays, std::span<Color> out) const noexcept {
    if constexpr (std::is_same_v<Interpolation, SyntheticAperture>) {
      for (std::size_t start = 0; start < rays.size(); start += kChunk)
        sample_rays_synthetic(rays.subspan(start, std::min(kChunk, rays.size() - start)), out.subspan(start));
    } else if constexpr (std::is_same_v<Interpolation, NearestCamera>) {
      int hint = -1;
      for (std::size_t i = 0; i < rays.size(); ++i) {
        const int k = nearest_with_hint(rays[i], hint);
        out[i] = colour_from(k, point_of(rays[i]));
        hint = k;
      }
    } else {
      for (std::size_t start = 0; start < rays.size(); start += kChunk)
        sample_rays_cylinder(rays.subspan(start, std::min(kChunk, rays.size() - start)), out.subspan(start));
    }
  }

  /// `out[i] = sample(rays[i])` for the rays of `rays.size() / width` consecutive output rows
  /// (the renderer's optional tile interface, `TileRaySampler`; preconditions there). For
  /// `SyntheticAperture` each camera is walked once per tile: rows whose points are evenly
  /// spaced and seen one camera pixel apart are added by shift-and-add over the whole row, so
  /// the camera rows shared by neighbouring output rows are read while still in cache. The
  /// other policies, and rows that do not qualify, go through `sample_rays`. Working memory is
  /// a per-thread buffer; if it cannot grow, rows are done one by one.
  void sample_tile(std::span<const Ray<T>> rays, int width, std::span<Color> out) const noexcept {
    const std::size_t w = width > 0 ? static_cast<std::size_t>(width) : rays.size();
    if constexpr (std::is_same_v<Interpolation, SyntheticAperture>) {
      if (w > 0 && tile_synthetic(rays, w, out)) return;
    } else if constexpr (std::is_same_v<Interpolation, NearestCamera>) {
      if (planar_ && w > 0 && tile_nearest(rays, w, out)) return;
    } else {
      if (planar_ && w > 0 && tile_cylinder(rays, w, out)) return;
    }
    for (std::size_t start = 0; start < rays.size(); start += std::max<std::size_t>(w, 1))
      sample_rays(rays.subspan(start, std::min(w, rays.size() - start)), out.subspan(start));
  }

private:
  static constexpr std::size_t kChunk = 256;

  struct CameraData {
    T P[12]; // K [R | t], row-major
    Vec3<T> centre;
    bool distorted = false;
    int width = 0, height = 0;
    const texel_type* texels = nullptr;
    const PinholeCamera<T>* camera = nullptr;
    T separation = 0;                             // distance to the nearest centre not in the neighbour list
    int neighbours_begin = 0, neighbours_end = 0; // into neighbours_
  };

  // Per-thread working memory of `sample_tile`.
  struct TileScratch {
    std::vector<Vec3<T>> points;
    std::vector<float> acc; // 3 per ray (r g b), the layout of the texel rows
    std::vector<float> weight;
    std::vector<unsigned char> even;
  };

  bool tile_synthetic(std::span<const Ray<T>> rays, std::size_t w, std::span<Color> out) const noexcept {
    const std::size_t n = rays.size(), rows = n / w;
    thread_local TileScratch scratch;
    try {
      if (scratch.points.size() < n) scratch.points.resize(n);
      if (scratch.acc.size() < 3 * n) scratch.acc.resize(3 * n);
      if (scratch.weight.size() < n) scratch.weight.resize(n);
      if (scratch.even.size() < rows) scratch.even.resize(rows);
    } catch (...) {
      return false;
    }
    Vec3<T>* points = scratch.points.data();
    float* acc = scratch.acc.data();
    float* weight = scratch.weight.data();
    for (std::size_t i = 0; i < n; ++i) {
      points[i] = point_of(rays[i]);
      weight[i] = 0;
    }
    std::fill(acc, acc + 3 * n, 0.0f);
    for (std::size_t r = 0; r < rows; ++r)
      scratch.even[r] = config_.filter == PixelFilter::bilinear && w >= 8 && evenly_spaced(points + r * w, w);
    for (const CameraData& c : cameras_) {
      for (std::size_t r = 0; r < rows; ++r) {
        const std::size_t o = r * w;
        if (scratch.even[r] && !c.distorted) {
          if (shift_add(c, points + o, w, acc + 3 * o, weight + o)) continue;
          // The whole row does not fit the affine model within tolerance: try it in chunks.
          for (std::size_t s0 = 0; s0 < w; s0 += kChunk) {
            const std::size_t m = std::min(kChunk, w - s0);
            if (m >= 8 && shift_add(c, points + o + s0, m, acc + 3 * (o + s0), weight + o + s0)) continue;
            add_per_ray(c, points + o + s0, m, acc + 3 * (o + s0), weight + o + s0);
          }
          continue;
        }
        add_per_ray(c, points + o, w, acc + 3 * o, weight + o);
      }
    }
    for (std::size_t i = 0; i < n; ++i) out[i] = finish(acc + 3 * i, weight[i]);
    return true;
  }

  // Per-thread working memory of the row paths on planar arrays (`tile_nearest`,
  // `tile_cylinder`), sized for one output row.
  struct RowScratch {
    using Flag = typename detail::PlaneRays<T>::Flag;
    std::vector<Vec3<T>> points;
    std::vector<float> acc, weight, ray_weight;
    std::vector<int> camera;
    std::vector<T> soa[6]; // ray origins relative to the plane point, then directions
    std::vector<T> at[3];  // the points relative to the plane point, when `Config::depth` is set
    std::vector<T> xu, xv, du, dv, dd, cos2, inv_dd;
    std::vector<Flag> ok;

    // False when memory runs out.
    bool reserve(std::size_t w) noexcept {
      try {
        if (points.size() < w) {
          points.resize(w);
          for (std::vector<float>* v : {&acc, &weight, &ray_weight}) v->resize(v == &acc ? 3 * w : w);
          camera.resize(w);
          for (std::vector<T>& v : soa) v.resize(w);
          for (std::vector<T>& v : at) v.resize(w);
          for (std::vector<T>* v : {&xu, &xv, &du, &dv, &dd, &cos2, &inv_dd}) v->resize(w);
          ok.resize(w);
        }
        return true;
      } catch (...) {
        return false;
      }
    }
    [[nodiscard]] detail::PlaneRays<T> plane_rays(std::size_t offset = 0) noexcept {
      return {xu.data() + offset, xv.data() + offset, du.data() + offset,
              dv.data() + offset, dd.data() + offset, ok.data() + offset};
    }
  };

  // The points of one row of rays and where the rays cross the camera plane (scratch.xu ...,
  // see `detail::PlaneRays`). Returns the least cosine between a crossing ray and the plane
  // normal (1 when none crosses); `all_cross` tells whether every ray does, `even` whether the
  // points are evenly spaced (`evenly_spaced`; only asked for bilinear filtering and w >= 8).
  T prepare_row(const Ray<T>* row, std::size_t w, RowScratch& scratch, bool& all_cross, bool& even) const noexcept {
    const detail::PlaneFrame<T> frame{plane_point_.x(),  plane_point_.y(),  plane_point_.z(), plane_normal_.x(),
                                      plane_normal_.y(), plane_normal_.z(), axis_u_.x(),      axis_u_.y(),
                                      axis_u_.z(),       axis_v_.x(),       axis_v_.y(),      axis_v_.z()};
    T* const soa[6] = {scratch.soa[0].data(), scratch.soa[1].data(), scratch.soa[2].data(),
                       scratch.soa[3].data(), scratch.soa[4].data(), scratch.soa[5].data()};
    for (std::size_t i = 0; i < w; ++i) {
      const Ray<T>& ray = row[i];
      soa[0][i] = ray.origin.x() - frame.px;
      soa[1][i] = ray.origin.y() - frame.py;
      soa[2][i] = ray.origin.z() - frame.pz;
      soa[3][i] = ray.direction.x();
      soa[4][i] = ray.direction.y();
      soa[5][i] = ray.direction.z();
      scratch.points[i] = point_of(ray);
    }
    const T* const soa_in[6] = {soa[0], soa[1], soa[2], soa[3], soa[4], soa[5]};
    detail::plane_rays(soa_in, w, frame, scratch.plane_rays(), scratch.cos2.data());
    all_cross = std::find(scratch.ok.begin(), scratch.ok.begin() + static_cast<std::ptrdiff_t>(w), 0) ==
                scratch.ok.begin() + static_cast<std::ptrdiff_t>(w);
    even = false;
    if (config_.filter == PixelFilter::bilinear && w >= 8) {
      const T* p[3] = {soa[0], soa[1], soa[2]};
      if (config_.depth) {
        const T depth = *config_.depth;
        for (int k = 0; k < 3; ++k) {
          T* q = scratch.at[k].data();
          for (std::size_t i = 0; i < w; ++i) q[i] = soa[k][i] + depth * soa[k + 3][i];
          p[k] = q;
        }
      }
      even = evenly_spaced_points(scratch.points.data(), p, w);
    }
    return std::sqrt(std::min(T(1), detail::min_of(scratch.cos2.data(), w)));
  }

  static constexpr std::size_t kProofBlock = 32;

  // Nearest camera on a planar array, a row at a time. The choice: once camera k is chosen for
  // a pixel, the following pixels are proved to keep k a block at a time (`prove_nearest`,
  // vectorised); the first pixel the proof does not cover gets `nearest_with_hint`, which is
  // exact (a proof of its own or the ball tree). The block proof uses the same two facts as
  // `nearest_with_hint`: (a) every listed neighbour j is farther than k by a margin; (b) an
  // unlisted camera j has distance >= cos(theta) |c_j - x| >= cos(theta) (sep_k - r) with
  // r = |c_k - x| the in-plane distance to the crossing x, while d_k <= r; so d_j > d_k when
  // r < rho = (cos_min sep_k - margin) / (cos_min + 1.001), cos_min the least cosine of the row.
  // The colour: each run of pixels with one camera is a shift-and-add of one camera row when
  // the run's points are seen one camera pixel apart (as in `sample_rays_synthetic`), else
  // per ray. Equal to `sample` up to the affine model's 1e-3 pixel.
  bool tile_nearest(std::span<const Ray<T>> rays, std::size_t w, std::span<Color> out) const noexcept {
    using Flag = typename RowScratch::Flag;
    const std::size_t rows = rays.size() / w;
    thread_local RowScratch scratch;
    if (!scratch.reserve(w)) return false;
    const T margin = T(1e-4) * extent_;
    Flag pass[kProofBlock];
    T threshold[kProofBlock];
    for (std::size_t r = 0; r < rows; ++r) {
      const Ray<T>* row = rays.data() + r * w;
      bool all_cross = true, even = false;
      const T cos_min = prepare_row(row, w, scratch, all_cross, even);
      int* camera = scratch.camera.data();
      int k = -1, prepared = -1;
      detail::NearestCandidate<T> candidate{};
      for (std::size_t i = 0; i < w;) {
        if (k >= 0) {
          if (prepared != k) {
            const CameraData& c = cameras_[static_cast<std::size_t>(k)];
            const T reach = cos_min * c.separation - margin;
            const T rho = reach > 0 ? reach / (cos_min + T(1.001)) : T(0);
            candidate = {centre_u_[static_cast<std::size_t>(k)],
                         centre_v_[static_cast<std::size_t>(k)],
                         rho * rho,
                         margin * margin,
                         neighbour_u_.data() + c.neighbours_begin,
                         neighbour_v_.data() + c.neighbours_begin,
                         c.neighbours_end - c.neighbours_begin};
            prepared = k;
          }
          const std::size_t m = std::min(kProofBlock, w - i);
          detail::prove_nearest(scratch.plane_rays(i), m, candidate, pass, threshold);
          std::size_t p = 0;
          while (p < m && pass[p] != 0) camera[i + p++] = k;
          i += p;
          if (p == m) continue;
        }
        k = nearest_with_hint(row[i], k);
        camera[i++] = k;
      }
      const Vec3<T>* points = scratch.points.data();
      Color* o = out.data() + r * w;
      for (std::size_t s0 = 0; s0 < w;) {
        const int kk = camera[s0];
        std::size_t e = s0 + 1;
        while (e < w && camera[e] == kk) ++e;
        bool copied = false;
        if (even && kk >= 0 && e - s0 >= 8 && !cameras_[static_cast<std::size_t>(kk)].distorted) {
          float* acc = scratch.acc.data() + 3 * s0;
          float* weight = scratch.weight.data() + s0;
          std::fill(acc, acc + 3 * (e - s0), 0.0f);
          std::fill(weight, weight + (e - s0), 0.0f);
          copied = shift_add(cameras_[static_cast<std::size_t>(kk)], points + s0, e - s0, acc, weight);
          // One camera: weight is exactly 1 where it added its pixel, 0 where it sees nothing.
          if (copied)
            for (std::size_t i = s0; i < e; ++i) {
              const float* a = acc + 3 * (i - s0);
              o[i] = weight[i - s0] > 0 ? Color(a[0], a[1], a[2]) : config_.background;
            }
        }
        if (!copied)
          for (std::size_t i = s0; i < e; ++i) o[i] = colour_from(kk, points[i]);
        s0 = e;
      }
    }
    return true;
  }

  static constexpr std::size_t kSegment = 64;

  // Cylinder aperture on a planar array, a row at a time, cameras in the outer loop. A camera
  // can weigh only rays whose plane crossing lies within radius / cos_min of its centre, so each
  // camera is tried only on the 64-pixel segments whose crossings' bounding box is that close;
  // there its weights are computed for all rays at once (`cylinder_weights`, vectorised), and
  // the rays it weighs are added by a weighted shift-and-add (or per ray). Rays that no camera
  // weighs get the nearest camera, as in `sample`. A row with a ray that does not cross the
  // plane goes through `sample_rays`.
  bool tile_cylinder(std::span<const Ray<T>> rays, std::size_t w, std::span<Color> out) const noexcept {
    const std::size_t rows = rays.size() / w;
    thread_local RowScratch scratch;
    if (!scratch.reserve(w)) return false;
    const T radius = static_cast<T>(interpolation_.radius), inv_radius = T(1) / radius;
    const T margin = T(1e-4) * extent_;
    const std::size_t segments = (w + kSegment - 1) / kSegment;
    constexpr std::size_t kMaxSegments = 64;
    if (segments > kMaxSegments) return false;
    T lo_u[kMaxSegments], hi_u[kMaxSegments], lo_v[kMaxSegments], hi_v[kMaxSegments];
    for (std::size_t r = 0; r < rows; ++r) {
      const Ray<T>* row = rays.data() + r * w;
      Color* o = out.data() + r * w;
      bool all_cross = true, even = false;
      const T cos_min = prepare_row(row, w, scratch, all_cross, even);
      if (!all_cross) {
        sample_rays(std::span<const Ray<T>>(row, w), std::span<Color>(o, w));
        continue;
      }
      for (std::size_t i = 0; i < w; ++i) scratch.inv_dd[i] = T(1) / scratch.dd[i];
      for (std::size_t g = 0; g < segments; ++g) {
        lo_u[g] = lo_v[g] = std::numeric_limits<T>::infinity();
        hi_u[g] = hi_v[g] = -std::numeric_limits<T>::infinity();
        for (std::size_t i = g * kSegment; i < std::min(w, (g + 1) * kSegment); ++i) {
          lo_u[g] = std::min(lo_u[g], scratch.xu[i]);
          hi_u[g] = std::max(hi_u[g], scratch.xu[i]);
          lo_v[g] = std::min(lo_v[g], scratch.xv[i]);
          hi_v[g] = std::max(hi_v[g], scratch.xv[i]);
        }
      }
      const T reach = radius / cos_min * T(1.001) + margin;
      const Vec3<T>* points = scratch.points.data();
      float* acc = scratch.acc.data();
      float* weight = scratch.weight.data();
      float* ray_weight = scratch.ray_weight.data();
      std::fill(acc, acc + 3 * w, 0.0f);
      std::fill(weight, weight + w, 0.0f);
      T row_lo_u = lo_u[0], row_hi_u = hi_u[0], row_lo_v = lo_v[0], row_hi_v = hi_v[0];
      for (std::size_t g = 1; g < segments; ++g) {
        row_lo_u = std::min(row_lo_u, lo_u[g]);
        row_hi_u = std::max(row_hi_u, hi_u[g]);
        row_lo_v = std::min(row_lo_v, lo_v[g]);
        row_hi_v = std::max(row_hi_v, hi_v[g]);
      }
      for (std::size_t k = 0; k < cameras_.size(); ++k) {
        const T cu = centre_u_[k], cv = centre_v_[k];
        // Most cameras are out of reach of the whole row.
        if (cu < row_lo_u - reach || cu > row_hi_u + reach || cv < row_lo_v - reach || cv > row_hi_v + reach) continue;
        std::size_t first = segments, last = 0;
        for (std::size_t g = 0; g < segments; ++g) {
          const T gu = std::max({lo_u[g] - cu, cu - hi_u[g], T(0)}), gv = std::max({lo_v[g] - cv, cv - hi_v[g], T(0)});
          if (gu * gu + gv * gv < reach * reach) {
            first = std::min(first, g);
            last = g + 1;
          }
        }
        if (first >= last) continue;
        const std::size_t b0 = first * kSegment, b1 = std::min(w, last * kSegment);
        detail::cylinder_weights(scratch.xu.data() + b0, scratch.xv.data() + b0, scratch.du.data() + b0,
                                 scratch.dv.data() + b0, scratch.inv_dd.data() + b0, b1 - b0, cu, cv, inv_radius,
                                 ray_weight + b0);
        // The rays the camera weighs: from the first to the last positive weight (a scan from
        // each end, which stops at the cylinder's edge).
        std::size_t lo = b0, hi = b1;
        while (lo < hi && !(ray_weight[lo] > 0)) ++lo;
        while (hi > lo && !(ray_weight[hi - 1] > 0)) --hi;
        if (lo >= hi) continue;
        add_weighted(cameras_[k], points + lo, hi - lo, even, acc + 3 * lo, weight + lo, ray_weight + lo);
      }
      for (std::size_t i = 0; i < w; ++i)
        o[i] = weight[i] > 0 ? finish(acc + 3 * i, weight[i])
                             : colour_from(index_->nearest(row[i].origin, row[i].direction), points[i]);
    }
    return true;
  }

  // acc[i] += pixel of camera c at points[i], weight[i] += 1, for every point c sees.
  // With `ray_weight` (not nullptr): weighted by ray_weight[i], rays of weight <= 0 skipped.
  void add_per_ray(const CameraData& c, const Vec3<T>* points, std::size_t n, float* acc, float* weight,
                   const float* ray_weight = nullptr) const noexcept {
    for (std::size_t i = 0; i < n; ++i) {
      const float w = ray_weight != nullptr ? ray_weight[i] : 1.0f;
      T x, y;
      if (w > 0 && project(c, points[i], x, y)) {
        fetch_add(c, x, y, w, acc + 3 * i);
        weight[i] += w;
      }
    }
  }

  // Camera c's weighted contribution to a run of rays: shift-and-add when the run qualifies
  // (`even`: its points are evenly spaced), else per ray.
  void add_weighted(const CameraData& c, const Vec3<T>* points, std::size_t n, bool even, float* acc, float* weight,
                    const float* ray_weight) const noexcept {
    if (even && !c.distorted && n >= 8 && shift_add(c, points, n, acc, weight, ray_weight)) return;
    add_per_ray(c, points, n, acc, weight, ray_weight);
  }

  [[nodiscard]] Vec3<T> point_of(const Ray<T>& ray) const noexcept {
    return config_.depth ? ray.at(*config_.depth) : ray.origin;
  }

  void detect_plane(const std::vector<Vec3<T>>& centres) {
    planar_ = false;
    const std::size_t n = centres.size();
    if (n < 2) return;
    Vec3<double> mean = Vec3<double>::Zero();
    for (const Vec3<T>& c : centres) mean += c.template cast<double>();
    mean /= static_cast<double>(n);
    Mat3<double> cov = Mat3<double>::Zero();
    double extent = 0;
    for (const Vec3<T>& c : centres) {
      const Vec3<double> d = c.template cast<double>() - mean;
      cov += d * d.transpose();
      extent = std::max(extent, d.norm());
    }
    if (!(extent > 0)) return;
    const Eigen::SelfAdjointEigenSolver<Mat3<double>> eig(cov);
    const Vec3<double> normal = eig.eigenvectors().col(0).normalized();
    double off = 0;
    for (const Vec3<T>& c : centres) off = std::max(off, std::abs(normal.dot(c.template cast<double>() - mean)));
    if (!(off <= 1e-6 * extent)) return;
    // Per camera: the cameras within 1.5 x its nearest-neighbour distance (at most
    // kMaxNeighbours, nearest first) and the distance to the nearest camera not listed.
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<std::pair<T, int>> others;
      for (std::size_t j = 0; j < n; ++j)
        if (j != i) others.emplace_back((centres[i] - centres[j]).norm(), static_cast<int>(j));
      std::sort(others.begin(), others.end());
      CameraData& c = cameras_[i];
      c.neighbours_begin = static_cast<int>(neighbours_.size());
      std::size_t k = 0;
      while (k < others.size() && k < kMaxNeighbours && others[k].first <= T(1.5) * others[0].first)
        neighbours_.push_back(others[k++].second);
      c.neighbours_end = static_cast<int>(neighbours_.size());
      c.separation = k < others.size() ? others[k].first : std::numeric_limits<T>::infinity();
    }
    plane_normal_ = normal.template cast<T>();
    plane_point_ = mean.template cast<T>();
    // In-plane axes (the other two eigenvectors) and every centre in those coordinates, for the
    // row proofs of `tile_nearest`.
    axis_u_ = eig.eigenvectors().col(2).normalized().template cast<T>();
    axis_v_ = eig.eigenvectors().col(1).normalized().template cast<T>();
    centre_u_.resize(n);
    centre_v_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      centre_u_[i] = axis_u_.dot(centres[i] - plane_point_);
      centre_v_[i] = axis_v_.dot(centres[i] - plane_point_);
    }
    for (const int j : neighbours_) {
      neighbour_u_.push_back(centre_u_[static_cast<std::size_t>(j)]);
      neighbour_v_.push_back(centre_v_[static_cast<std::size_t>(j)]);
    }
    extent_ = static_cast<T>(extent);
    planar_ = true;
  }

  // Where the ray line meets the camera plane, and the cosine of its angle to the normal.
  [[nodiscard]] bool plane_hit(const Ray<T>& ray, Vec3<T>& x, T& cosine) const noexcept {
    const T nd = plane_normal_.dot(ray.direction);
    const T length = ray.direction.norm();
    if (!(std::abs(nd) > T(1e-3) * length)) return false;
    x = ray.origin + (plane_normal_.dot(plane_point_ - ray.origin) / nd) * ray.direction;
    cosine = std::abs(nd) / length;
    return x.allFinite();
  }

  // The nearest camera, trying `hint` first. On a planar array, camera k is provably the
  // unique nearest to the line when (a) every listed neighbour j is strictly farther from the
  // line, and (b) every other camera is too: such a c_j has distance >= cos(theta) |c_j - x|
  // >= cos(theta) (separation_k - |c_k - x|), where x is where the line meets the camera plane
  // and theta its angle to the plane normal; (b) requires that bound to exceed d_k. When a
  // neighbour is nearer, the proof is retried from it (a short walk); otherwise, or on a
  // non-planar array, the ball tree decides.
  [[nodiscard]] int nearest_with_hint(const Ray<T>& ray, int hint) const noexcept {
    if (planar_ && hint >= 0) {
      Vec3<T> x = Vec3<T>::Zero();
      T cosine = 0;
      const T dd = ray.direction.squaredNorm();
      if (dd > 0 && std::isfinite(dd) && plane_hit(ray, x, cosine)) {
        const T inv = T(1) / dd;
        const T margin = T(1e-4) * extent_;
        int k = hint;
        for (int step = 0; step < 4; ++step) {
          const CameraData& c = cameras_[static_cast<std::size_t>(k)];
          const T dk2 = line_distance2(c.centre, ray.origin, ray.direction, inv);
          int nearer = -1;
          T best = dk2;
          bool proved = true;
          for (int m = c.neighbours_begin; m < c.neighbours_end; ++m) {
            const int j = neighbours_[static_cast<std::size_t>(m)];
            const T dj2 = line_distance2(cameras_[static_cast<std::size_t>(j)].centre, ray.origin, ray.direction, inv);
            if (dj2 < best) {
              best = dj2;
              nearer = j;
            }
            if (!(dj2 > dk2 * T(1.0001) + margin * margin)) proved = false;
          }
          if (nearer >= 0) {
            k = nearer;
            continue;
          }
          if (proved && cosine * (c.separation - (c.centre - x).norm()) > std::sqrt(dk2) * T(1.001) + margin) return k;
          break;
        }
      }
    }
    return index_->nearest(ray.origin, ray.direction);
  }

  [[nodiscard]] Color colour_from(int camera, const Vec3<T>& X) const noexcept {
    if (camera < 0) return config_.background;
    const CameraData& c = cameras_[static_cast<std::size_t>(camera)];
    T x, y;
    if (!project(c, X, x, y)) return config_.background;
    float acc[3] = {0, 0, 0};
    fetch_add(c, x, y, 1.0f, acc);
    return finish(acc, 1.0f);
  }

  [[nodiscard]] Color finish(const float* acc, float weight) const noexcept {
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
    return project_any(c, X, x, y) && x >= T(-0.5) && x < static_cast<T>(c.width) - T(0.5) && y >= T(-0.5) &&
           y < static_cast<T>(c.height) - T(0.5);
  }

  // Continuous pixel coordinates of X in an undistorted camera c, inside the image or not;
  // false when X is not in front of c.
  [[nodiscard]] static bool project_any(const CameraData& c, const Vec3<T>& X, T& x, T& y) noexcept {
    const T* P = c.P;
    const T w = P[8] * X.x() + P[9] * X.y() + P[10] * X.z() + P[11];
    if (!(w > 0)) return false;
    const T inv = T(1) / w;
    x = (P[0] * X.x() + P[1] * X.y() + P[2] * X.z() + P[3]) * inv;
    y = (P[4] * X.x() + P[5] * X.y() + P[6] * X.z() + P[7]) * inv;
    return std::isfinite(x) && std::isfinite(y);
  }

  // acc[0..2] += weight * (pixel of camera c at continuous (x, y)); (x, y) lies inside the image.
  void fetch_add(const CameraData& c, T x, T y, float weight, float* acc) const noexcept {
    const float scaled = weight * texel_type::scale;
    if (config_.filter == PixelFilter::nearest) {
      const int ix = std::min(static_cast<int>(std::floor(x + T(0.5))), c.width - 1);
      const int iy = std::min(static_cast<int>(std::floor(y + T(0.5))), c.height - 1);
      const texel_type& v = c.texels[static_cast<std::ptrdiff_t>(iy) * c.width + ix];
      for (int k = 0; k < 3; ++k) acc[k] += scaled * static_cast<float>(v.c[k]);
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
      acc[k] += w00 * static_cast<float>(ra[xa].c[k]) + w10 * static_cast<float>(ra[xb].c[k]) +
                w01 * static_cast<float>(rb[xa].c[k]) + w11 * static_cast<float>(rb[xb].c[k]);
  }

  // Synthetic aperture over one run of rays, cameras in the outer loop. When the run's points
  // are evenly spaced along a line (a row of a planar image surface) and a camera sees them one
  // camera pixel apart along its rows, wholly inside its image, the bilinear weights are the
  // same for the whole run and the camera adds a shifted copy of two of its rows
  // (shift-and-add); the positions then follow the affine model of the run's end points, which
  // differs from the per-ray projection by at most 1e-3 pixel (checked), i.e. a colour change
  // below one 8-bit level after averaging.
  void sample_rays_synthetic(std::span<const Ray<T>> rays, std::span<Color> out) const noexcept {
    const std::size_t n = rays.size();
    float acc[3 * kChunk];
    float weight[kChunk];
    Vec3<T> points[kChunk];
    for (std::size_t i = 0; i < n; ++i) {
      points[i] = point_of(rays[i]);
      weight[i] = 0;
    }
    std::fill(acc, acc + 3 * n, 0.0f);
    const bool even = config_.filter == PixelFilter::bilinear && n >= 8 && evenly_spaced(points, n);
    for (const CameraData& c : cameras_) add_weighted(c, points, n, even, acc, weight, nullptr);
    for (std::size_t i = 0; i < n; ++i) out[i] = finish(acc + 3 * i, weight[i]);
  }

  // `evenly_spaced` for points also given as coordinates relative to the plane point (SoA,
  // vectorised); the tolerance is that of the absolute points.
  [[nodiscard]] static bool evenly_spaced_points(const Vec3<T>* p, const T* const (&relative)[3],
                                                 std::size_t n) noexcept {
    if (n > static_cast<std::size_t>(std::numeric_limits<int>::max())) return evenly_spaced(p, n);
    const T scale = p[0].cwiseAbs().maxCoeff() + p[n - 1].cwiseAbs().maxCoeff();
    const T tolerance = T(64) * std::numeric_limits<T>::epsilon() * scale;
    return detail::evenly_spaced(relative[0], relative[1], relative[2], static_cast<int>(n), tolerance);
  }

  // Points p_i = p_0 + i (p_{n-1} - p_0) / (n - 1) up to rounding.
  [[nodiscard]] static bool evenly_spaced(const Vec3<T>* p, std::size_t n) noexcept {
    const Vec3<T> step = (p[n - 1] - p[0]) / static_cast<T>(n - 1);
    const T scale = p[0].cwiseAbs().maxCoeff() + p[n - 1].cwiseAbs().maxCoeff();
    const T tolerance = T(64) * std::numeric_limits<T>::epsilon() * scale;
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const Vec3<T> predicted = p[0] + static_cast<T>(i) * step;
      if (!((p[i] - predicted).cwiseAbs().maxCoeff() <= tolerance)) return false;
    }
    return true;
  }

  // The shift-and-add case of `sample_rays_synthetic`; false (nothing added) when it does not apply.
  // `ray_weight`: the weight of camera c for each ray (nullptr: 1 for every ray; <= 0: none).
  bool shift_add(const CameraData& c, const Vec3<T>* points, std::size_t n, float* acc, float* weight,
                 const float* ray_weight = nullptr) const noexcept {
    T x0, y0, x1, y1, xm, ym;
    if (!project_any(c, points[0], x0, y0) || !project_any(c, points[n - 1], x1, y1) ||
        !project_any(c, points[n / 2], xm, ym))
      return false;
    const T span = static_cast<T>(n - 1);
    constexpr T kTolerance = T(1e-3);
    if (!(std::abs(x1 - x0 - span) <= kTolerance && std::abs(y1 - y0) <= kTolerance)) return false;
    if (!(std::abs(xm - x0 - static_cast<T>(n / 2)) <= kTolerance && std::abs(ym - y0) <= kTolerance)) return false;
    // Rows wholly above or below the image: nothing to add (every per-ray y is outside too).
    if (y0 < T(-0.5) - kTolerance || y0 >= static_cast<T>(c.height) - T(0.5) + kTolerance) return true;
    const T fx = std::floor(x0), fy = std::floor(y0);
    if (!(std::abs(fx) < T(1e8))) return false; // keeps the integer conversion in range
    const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
    if (iy < 0 || iy + 1 > c.height - 1) return false; // the clamped border rows: per ray
    // Pixels i whose two texels ix + i, ix + i + 1 lie inside the row are shifted and added;
    // the others (near or past the left and right edges) go through the per-ray code.
    const long first = std::max(0L, -static_cast<long>(ix));
    const long last = std::min(static_cast<long>(n), static_cast<long>(c.width) - 1 - ix);
    if (first >= last) return false;
    const std::size_t i_begin = static_cast<std::size_t>(first), i_end = static_cast<std::size_t>(last);
    add_per_ray(c, points, i_begin, acc, weight, ray_weight);
    add_per_ray(c, points + i_end, n - i_end, acc + 3 * i_end, weight + i_end,
                ray_weight != nullptr ? ray_weight + i_end : nullptr);
    // Bilinear interpolation is continuous, so a position off by the tolerance across a pixel
    // boundary changes the colour by at most tolerance x the local gradient.
    const float ax = static_cast<float>(x0 - fx), ay = static_cast<float>(y0 - fy);
    const float sc = texel_type::scale;
    const detail::RowWeights w{(1 - ax) * (1 - ay) * sc, ax * (1 - ay) * sc, (1 - ax) * ay * sc, ax * ay * sc};
    const texel_type* a = c.texels + static_cast<std::ptrdiff_t>(iy) * c.width + ix;
    const texel_type* b = a + c.width;
#if defined(__GNUC__) || defined(__clang__)
    // The next output row reads row iy + 2 over about the same columns: ask for it now. Short
    // runs (nearest camera, cylinder aperture) are too short for the hardware prefetcher to pick
    // them up; on long ones (whole-row refocusing) it does, and the extra prefetches cost time.
    if (iy + 2 < c.height && i_end - i_begin < 1024) {
      const char* next = reinterpret_cast<const char*>(b + c.width + i_begin);
      const char* end = reinterpret_cast<const char*>(b + c.width + i_end + 1);
      for (; next < end; next += 64) __builtin_prefetch(next);
    }
#endif
    add_rows(a + i_begin, b + i_begin, w, ray_weight != nullptr ? ray_weight + i_begin : nullptr, acc + 3 * i_begin,
             i_end - i_begin);
    if (ray_weight != nullptr) {
      for (std::size_t i = i_begin; i < i_end; ++i)
        if (ray_weight[i] > 0) weight[i] += ray_weight[i];
    } else {
      for (std::size_t i = i_begin; i < i_end; ++i) weight[i] += 1.0f;
    }
    return true;
  }

  // The shift-and-add kernel over the n pixels of rows a and b (flat channel arrays); with
  // per-ray weights, those are spread over the three channel slots of each pixel first, a
  // stack buffer at a time.
  static void add_rows(const texel_type* a, const texel_type* b, detail::RowWeights w, const float* ray_weight,
                       float* acc, std::size_t n) noexcept {
    using channel = typename texel_type::channel_type;
    // Texels are packed channel triples (static_assert in camera_frame_set.hpp): a row is one
    // flat array of 3 n channels.
    const channel* fa = a->c;
    const channel* fb = b->c;
    if (ray_weight == nullptr) return detail::shift_add_flat(fa, fb, w, nullptr, acc, 3 * n);
    constexpr std::size_t kStep = 256;
    float spread[3 * kStep];
    for (std::size_t s0 = 0; s0 < n; s0 += kStep) {
      const std::size_t m = std::min(kStep, n - s0);
      for (std::size_t i = 0; i < m; ++i) spread[3 * i] = spread[3 * i + 1] = spread[3 * i + 2] = ray_weight[s0 + i];
      detail::shift_add_flat(fa + 3 * s0, fb + 3 * s0, w, spread, acc + 3 * s0, 3 * m);
    }
  }

  [[nodiscard]] Color cylinder(const Ray<T>& ray, const Vec3<T>& X) const noexcept {
    const T radius = static_cast<T>(interpolation_.radius);
    float acc[3] = {0, 0, 0};
    float weight = 0;
    index_->within(ray.origin, ray.direction, radius,
                   [&](int i, T d) noexcept { add_cylinder(i, d, radius, X, acc, weight); });
    if (!(weight > 0)) return colour_from(index_->nearest(ray.origin, ray.direction), X);
    return finish(acc, weight);
  }

  void add_cylinder(int i, T d, T radius, const Vec3<T>& X, float acc[4], float& weight) const noexcept {
    const CameraData& c = cameras_[static_cast<std::size_t>(i)];
    const float w = static_cast<float>(T(1) - d / radius);
    T x, y;
    if (!(w > 0) || !project(c, X, x, y)) return;
    fetch_add(c, x, y, w, acc);
    weight += w;
  }

  // Cylinder aperture over one run of rays: on a planar array, the cameras that can lie within
  // the radius of any ray of the run are those within radius / cos(theta_min) of the run's
  // plane crossings (bounding box), collected once; each ray then tests only those.
  void sample_rays_cylinder(std::span<const Ray<T>> rays, std::span<Color> out) const noexcept {
    const std::size_t n = rays.size();
    const T radius = static_cast<T>(interpolation_.radius);
    Vec3<T> lo = Vec3<T>::Constant(std::numeric_limits<T>::infinity()), hi = -lo;
    T cos_min = 1;
    bool ok = planar_;
    for (std::size_t i = 0; i < n && ok; ++i) {
      Vec3<T> x = Vec3<T>::Zero();
      T cosine = 0;
      ok = plane_hit(rays[i], x, cosine);
      if (!ok) break;
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
      cos_min = std::min(cos_min, cosine);
    }
    if (!ok) {
      for (std::size_t i = 0; i < n; ++i) out[i] = sample(rays[i]);
      return;
    }
    int candidates[kMaxCandidates];
    int count = 0;
    const T reach = radius / cos_min * T(1.001) + T(1e-4) * extent_;
    for (std::size_t k = 0; k < cameras_.size(); ++k) {
      const Vec3<T> nearest_point = cameras_[k].centre.cwiseMax(lo).cwiseMin(hi);
      if ((cameras_[k].centre - nearest_point).norm() < reach) {
        if (count == kMaxCandidates) {
          for (std::size_t i = 0; i < n; ++i) out[i] = sample(rays[i]);
          return;
        }
        candidates[count++] = static_cast<int>(k);
      }
    }
    const T r2 = radius * radius;
    Vec3<T> points[kChunk];
    float acc[3 * kChunk];
    float weight[kChunk];
    T inverse_length2[kChunk];
    float ray_weight[kChunk];
    for (std::size_t i = 0; i < n; ++i) {
      points[i] = point_of(rays[i]);
      acc[3 * i] = acc[3 * i + 1] = acc[3 * i + 2] = 0;
      weight[i] = 0;
      const T dd = rays[i].direction.squaredNorm();
      inverse_length2[i] = dd > 0 && std::isfinite(dd) ? T(1) / dd : T(0);
    }
    const bool even = n >= 8 && config_.filter == PixelFilter::bilinear && evenly_spaced(points, n);
    for (int j = 0; j < count; ++j) {
      const CameraData& c = cameras_[static_cast<std::size_t>(candidates[j])];
      // [lo, hi): the rays this camera weighs; shift-and-add covers just that sub-run.
      std::size_t lo = n, hi = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const T d2 = inverse_length2[i] > 0
                         ? line_distance2(c.centre, rays[i].origin, rays[i].direction, inverse_length2[i])
                         : r2;
        ray_weight[i] = d2 < r2 ? static_cast<float>(T(1) - std::sqrt(d2) / radius) : 0.0f;
        if (ray_weight[i] > 0) {
          lo = std::min(lo, i);
          hi = i + 1;
        }
      }
      if (lo >= hi) continue;
      add_weighted(c, points + lo, hi - lo, even, acc + 3 * lo, weight + lo, ray_weight + lo);
    }
    for (std::size_t i = 0; i < n; ++i)
      out[i] = weight[i] > 0 ? finish(acc + 3 * i, weight[i])
                             : colour_from(index_->nearest(rays[i].origin, rays[i].direction), points[i]);
  }

  static constexpr int kMaxCandidates = 512;
  static constexpr std::size_t kMaxNeighbours = 8;
  std::vector<int> neighbours_;

  std::shared_ptr<const frame_set_type> frames_;
  Interpolation interpolation_;
  Config config_;
  std::vector<CameraData> cameras_;
  std::shared_ptr<const CameraCentreIndex<T>> index_;
  bool planar_ = false;
  Vec3<T> plane_normal_ = Vec3<T>::UnitZ();
  Vec3<T> plane_point_ = Vec3<T>::Zero();
  Vec3<T> axis_u_ = Vec3<T>::UnitX(), axis_v_ = Vec3<T>::UnitY();
  std::vector<T> centre_u_, centre_v_, neighbour_u_, neighbour_v_;
  T extent_ = 0;
};

} // namespace mpr
