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

#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
#include <immintrin.h>
/// x86 with GCC/Clang: the row kernels have an AVX2+FMA version chosen at run time (or at
/// compile time under -mavx2 -mfma), next to the SSE2 and portable ones.
#define MPR_LF_X86_KERNELS 1
#endif

namespace mpr {

namespace detail {

/// The bilinear weights of one shift-and-add row, channel scale of the texel type folded in.
struct RowWeights {
  float w00, w10, w01, w11;
};

/// acc[i] += rw[i] * (w00 a[i] + w10 a[i+1] + w01 b[i] + w11 b[i+1]) for i in [0, n) (texels
/// times their scale; rw == nullptr: weight 1). Reads a[0..n] and b[0..n]. Portable version.
template <class Texel>
inline void shift_add_row_portable(const Texel* a, const Texel* b, RowWeights w, const float* rw, float (*acc)[4],
                                   std::size_t n) noexcept {
  for (std::size_t i = 0; i < n; ++i) {
    const float r = rw != nullptr ? rw[i] : 1.0f;
    for (int k = 0; k < 4; ++k)
      acc[i][k] += r * (w.w00 * static_cast<float>(a[i].c[k]) + w.w10 * static_cast<float>(a[i + 1].c[k]) +
                        w.w01 * static_cast<float>(b[i].c[k]) + w.w11 * static_cast<float>(b[i + 1].c[k]));
  }
}

#if defined(MPR_LF_X86_KERNELS)
#if defined(__SSE2__)
[[nodiscard]] inline __m128 load_texel_sse2(const LinearTexel* p) noexcept { return _mm_load_ps(p->c); }
[[nodiscard]] inline __m128 load_texel_sse2(const FixedTexel* p) noexcept {
  const __m128i q = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p));
  return _mm_cvtepi32_ps(_mm_unpacklo_epi16(q, _mm_setzero_si128()));
}

/// SSE2 version of `shift_add_row_portable` (one pixel per step, the previous texels reused).
template <class Texel>
inline void shift_add_row_sse2(const Texel* a, const Texel* b, RowWeights w, const float* rw, float (*acc)[4],
                               std::size_t n) noexcept {
  const __m128 v00 = _mm_set1_ps(w.w00), v10 = _mm_set1_ps(w.w10), v01 = _mm_set1_ps(w.w01), v11 = _mm_set1_ps(w.w11);
  __m128 a0 = load_texel_sse2(a), b0 = load_texel_sse2(b);
  for (std::size_t i = 0; i < n; ++i) {
    const __m128 a1 = load_texel_sse2(a + i + 1), b1 = load_texel_sse2(b + i + 1);
    __m128 sum = _mm_add_ps(_mm_add_ps(_mm_mul_ps(v00, a0), _mm_mul_ps(v10, a1)),
                            _mm_add_ps(_mm_mul_ps(v01, b0), _mm_mul_ps(v11, b1)));
    if (rw != nullptr) sum = _mm_mul_ps(sum, _mm_set1_ps(rw[i]));
    _mm_storeu_ps(acc[i], _mm_add_ps(_mm_loadu_ps(acc[i]), sum));
    a0 = a1;
    b0 = b1;
  }
}
#endif

// Two texels (8 floats) starting at p.
[[nodiscard]] __attribute__((target("avx2,fma"))) inline __m256 load_texels2_avx2(const LinearTexel* p) noexcept {
  return _mm256_loadu_ps(p->c);
}
[[nodiscard]] __attribute__((target("avx2,fma"))) inline __m256 load_texels2_avx2(const FixedTexel* p) noexcept {
  return _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))));
}

/// AVX2+FMA version of `shift_add_row_portable`: two pixels per step. Call only where the CPU
/// has AVX2 and FMA (`cpu_has_avx2_fma`).
template <class Texel>
__attribute__((target("avx2,fma"))) inline void shift_add_row_avx2(const Texel* a, const Texel* b, RowWeights w,
                                                                   const float* rw, float (*acc)[4],
                                                                   std::size_t n) noexcept {
  const __m256 v00 = _mm256_set1_ps(w.w00), v10 = _mm256_set1_ps(w.w10), v01 = _mm256_set1_ps(w.w01),
               v11 = _mm256_set1_ps(w.w11);
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    __m256 sum = _mm256_mul_ps(v00, load_texels2_avx2(a + i));
    sum = _mm256_fmadd_ps(v10, load_texels2_avx2(a + i + 1), sum);
    sum = _mm256_fmadd_ps(v01, load_texels2_avx2(b + i), sum);
    sum = _mm256_fmadd_ps(v11, load_texels2_avx2(b + i + 1), sum);
    float* o = acc[i];
    if (rw != nullptr) {
      const __m256 r = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_set1_ps(rw[i])), _mm_set1_ps(rw[i + 1]), 1);
      _mm256_storeu_ps(o, _mm256_fmadd_ps(r, sum, _mm256_loadu_ps(o)));
    } else {
      _mm256_storeu_ps(o, _mm256_add_ps(_mm256_loadu_ps(o), sum));
    }
  }
  if (i < n) shift_add_row_portable(a + i, b + i, w, rw != nullptr ? rw + i : nullptr, acc + i, n - i);
}

/// Whether this CPU runs the AVX2+FMA kernels (checked once).
[[nodiscard]] inline bool cpu_has_avx2_fma() noexcept {
#if defined(__AVX2__) && defined(__FMA__)
  return true;
#else
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return yes;
#endif
}
#endif

/// The row kernel `shift_add_row` uses on this machine: "avx2+fma", "sse2" or "portable".
[[nodiscard]] inline const char* shift_add_kernel_name() noexcept {
#if defined(MPR_LF_X86_KERNELS)
  if (cpu_has_avx2_fma()) return "avx2+fma";
#if defined(__SSE2__)
  return "sse2";
#endif
#endif
  return "portable";
}

/// `shift_add_row_portable` with the fastest kernel this machine runs.
template <class Texel>
inline void shift_add_row(const Texel* a, const Texel* b, RowWeights w, const float* rw, float (*acc)[4],
                          std::size_t n) noexcept {
#if defined(MPR_LF_X86_KERNELS)
  if (cpu_has_avx2_fma()) return shift_add_row_avx2(a, b, w, rw, acc, n);
#if defined(__SSE2__)
  return shift_add_row_sse2(a, b, w, rw, acc, n);
#endif
#endif
  shift_add_row_portable(a, b, w, rw, acc, n);
}

} // namespace detail

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
      alignas(16) float acc[4] = {0, 0, 0, 0};
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
    T separation = 0; // distance to the nearest centre not in the neighbour list
    int neighbours_begin = 0, neighbours_end = 0; // into neighbours_
  };

  // Per-thread working memory of `sample_tile`.
  struct TileScratch {
    std::vector<Vec3<T>> points;
    std::vector<float> acc; // 4 per ray, 16-byte aligned rows of 4 floats
    std::vector<float> weight;
    std::vector<unsigned char> even;
  };

  bool tile_synthetic(std::span<const Ray<T>> rays, std::size_t w, std::span<Color> out) const noexcept {
    const std::size_t n = rays.size(), rows = n / w;
    thread_local TileScratch scratch;
    try {
      if (scratch.points.size() < n) scratch.points.resize(n);
      if (scratch.acc.size() < 4 * n + 4) scratch.acc.resize(4 * n + 4);
      if (scratch.weight.size() < n) scratch.weight.resize(n);
      if (scratch.even.size() < rows) scratch.even.resize(rows);
    } catch (...) {
      return false;
    }
    Vec3<T>* points = scratch.points.data();
    // 16-byte alignment of the accumulators (the vector itself only guarantees alignof(float)).
    float* acc_base = scratch.acc.data();
    while (reinterpret_cast<std::uintptr_t>(acc_base) % 16 != 0) ++acc_base;
    float(*acc)[4] = reinterpret_cast<float(*)[4]>(acc_base);
    float* weight = scratch.weight.data();
    for (std::size_t i = 0; i < n; ++i) {
      points[i] = point_of(rays[i]);
      acc[i][0] = acc[i][1] = acc[i][2] = acc[i][3] = 0;
      weight[i] = 0;
    }
    for (std::size_t r = 0; r < rows; ++r)
      scratch.even[r] = config_.filter == PixelFilter::bilinear && w >= 8 && evenly_spaced(points + r * w, w);
    for (const CameraData& c : cameras_) {
      for (std::size_t r = 0; r < rows; ++r) {
        const std::size_t o = r * w;
        if (scratch.even[r] && !c.distorted) {
          if (shift_add(c, points + o, w, acc + o, weight + o)) continue;
          // The whole row does not fit the affine model within tolerance: try it in chunks.
          for (std::size_t s0 = 0; s0 < w; s0 += kChunk) {
            const std::size_t m = std::min(kChunk, w - s0);
            if (m >= 8 && shift_add(c, points + o + s0, m, acc + o + s0, weight + o + s0)) continue;
            add_per_ray(c, points + o + s0, m, acc + o + s0, weight + o + s0);
          }
          continue;
        }
        add_per_ray(c, points + o, w, acc + o, weight + o);
      }
    }
    for (std::size_t i = 0; i < n; ++i) out[i] = finish(acc[i], weight[i]);
    return true;
  }

  // acc[i] += pixel of camera c at points[i], weight[i] += 1, for every point c sees.
  void add_per_ray(const CameraData& c, const Vec3<T>* points, std::size_t n, float (*acc)[4],
                   float* weight) const noexcept {
    for (std::size_t i = 0; i < n; ++i) {
      T x, y;
      if (project(c, points[i], x, y)) {
        fetch_add(c, x, y, 1.0f, acc[i]);
        weight[i] += 1.0f;
      }
    }
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
    alignas(16) float acc[4] = {0, 0, 0, 0};
    fetch_add(c, x, y, 1.0f, acc);
    return finish(acc, 1.0f);
  }

  [[nodiscard]] Color finish(const float acc[4], float weight) const noexcept {
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

  // acc += weight * (pixel of camera c at continuous (x, y)); (x, y) lies inside the image.
  void fetch_add(const CameraData& c, T x, T y, float weight, float acc[4]) const noexcept {
    const float scaled = weight * texel_type::scale;
    if (config_.filter == PixelFilter::nearest) {
      const int ix = std::min(static_cast<int>(std::floor(x + T(0.5))), c.width - 1);
      const int iy = std::min(static_cast<int>(std::floor(y + T(0.5))), c.height - 1);
      const texel_type& v = c.texels[static_cast<std::ptrdiff_t>(iy) * c.width + ix];
      for (int k = 0; k < 4; ++k) acc[k] += scaled * static_cast<float>(v.c[k]);
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
    for (int k = 0; k < 4; ++k)
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
    alignas(16) float acc[kChunk][4];
    float weight[kChunk];
    Vec3<T> points[kChunk];
    for (std::size_t i = 0; i < n; ++i) {
      points[i] = point_of(rays[i]);
      acc[i][0] = acc[i][1] = acc[i][2] = acc[i][3] = 0;
      weight[i] = 0;
    }
    const bool even = n >= 8 && evenly_spaced(points, n);
    for (const CameraData& c : cameras_) {
      if (even && config_.filter == PixelFilter::bilinear && !c.distorted && shift_add(c, points, n, acc, weight))
        continue;
      for (std::size_t i = 0; i < n; ++i) {
        T x, y;
        if (project(c, points[i], x, y)) {
          fetch_add(c, x, y, 1.0f, acc[i]);
          weight[i] += 1.0f;
        }
      }
    }
    for (std::size_t i = 0; i < n; ++i) out[i] = finish(acc[i], weight[i]);
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
  bool shift_add(const CameraData& c, const Vec3<T>* points, std::size_t n, float (*acc)[4], float* weight,
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
    const auto per_ray = [&](std::size_t begin, std::size_t end) noexcept {
      for (std::size_t i = begin; i < end; ++i) {
        const float w = ray_weight != nullptr ? ray_weight[i] : 1.0f;
        T x, y;
        if (w > 0 && project(c, points[i], x, y)) {
          fetch_add(c, x, y, w, acc[i]);
          weight[i] += w;
        }
      }
    };
    per_ray(0, i_begin);
    per_ray(i_end, n);
    // Bilinear interpolation is continuous, so a position off by the tolerance across a pixel
    // boundary changes the colour by at most tolerance x the local gradient.
    const float ax = static_cast<float>(x0 - fx), ay = static_cast<float>(y0 - fy);
    const float sc = texel_type::scale;
    const detail::RowWeights w{(1 - ax) * (1 - ay) * sc, ax * (1 - ay) * sc, (1 - ax) * ay * sc, ax * ay * sc};
    const texel_type* a = c.texels + static_cast<std::ptrdiff_t>(iy) * c.width + ix;
    const texel_type* b = a + c.width;
    detail::shift_add_row(a + i_begin, b + i_begin, w, ray_weight != nullptr ? ray_weight + i_begin : nullptr,
                          acc + i_begin, i_end - i_begin);
    if (ray_weight != nullptr) {
      for (std::size_t i = i_begin; i < i_end; ++i)
        if (ray_weight[i] > 0) weight[i] += ray_weight[i];
    } else {
      for (std::size_t i = i_begin; i < i_end; ++i) weight[i] += 1.0f;
    }
    return true;
  }

  [[nodiscard]] Color cylinder(const Ray<T>& ray, const Vec3<T>& X) const noexcept {
    const T radius = static_cast<T>(interpolation_.radius);
    alignas(16) float acc[4] = {0, 0, 0, 0};
    float weight = 0;
    index_->within(ray.origin, ray.direction, radius, [&](int i, T d) noexcept { add_cylinder(i, d, radius, X, acc, weight); });
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
    alignas(16) float acc[kChunk][4];
    float weight[kChunk];
    T inverse_length2[kChunk];
    float ray_weight[kChunk];
    for (std::size_t i = 0; i < n; ++i) {
      points[i] = point_of(rays[i]);
      acc[i][0] = acc[i][1] = acc[i][2] = acc[i][3] = 0;
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
      if (even && !c.distorted && hi - lo >= 8 &&
          shift_add(c, points + lo, hi - lo, acc + lo, weight + lo, ray_weight + lo))
        continue;
      for (std::size_t i = lo; i < hi; ++i) {
        T x, y;
        if (ray_weight[i] > 0 && project(c, points[i], x, y)) {
          fetch_add(c, x, y, ray_weight[i], acc[i]);
          weight[i] += ray_weight[i];
        }
      }
    }
    for (std::size_t i = 0; i < n; ++i)
      out[i] = weight[i] > 0 ? finish(acc[i], weight[i])
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
  T extent_ = 0;
};

} // namespace mpr
