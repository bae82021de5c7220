#pragma once
/// \file
/// `mpr::CheckerboardPlane`: an analytic ray sampler (a checkered plane found by ray-plane
/// intersection). Exact and cheap, it is the reference for tests and the first demo.

#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/geometry/plane.hpp>

#include <cmath>
#include <limits>

namespace mpr {

/// A checkerboard on the plane `origin + a * cell_u + b * cell_v` (a, b real). Cell (i, j) =
/// (floor(a), floor(b)) is `dark` when i + j is odd; light cells alternate between `light` and
/// `light_alt` in 2x2 blocks, so the board's orientation and scale stay readable in distorted
/// views. With `cells > 0` the board covers only |i|, |j| < cells; rays that miss it, hit it
/// behind their origin, or run parallel to it return `background`.
template <std::floating_point T>
class CheckerboardPlane {
public:
  using scalar_type = T;

  struct Config {
    Vec3<T> origin = Vec3<T>::Zero();
    /// Edge vectors of one cell, world units; must be finite and not parallel.
    Vec3<T> cell_u = Vec3<T>::UnitX();
    Vec3<T> cell_v = Vec3<T>::UnitY();
    /// Half-size of the board in cells; 0 for an infinite board.
    int cells = 0;
    Color dark{0.05f, 0.05f, 0.06f};
    Color light{0.85f, 0.80f, 0.70f};
    Color light_alt{0.55f, 0.70f, 0.85f};
    Color background{0.20f, 0.22f, 0.28f};
  };

  CheckerboardPlane() : CheckerboardPlane(Config{}) {}
  /// Throws `argument_error` for non-finite or parallel cell vectors or negative `cells`.
  explicit CheckerboardPlane(const Config& config) : config_(config) {
    if (!config.origin.allFinite()) throw argument_error("origin", "not finite");
    if (!config.cell_u.allFinite()) throw argument_error("cell_u", "not finite");
    if (!config.cell_v.allFinite()) throw argument_error("cell_v", "not finite");
    if (config.cells < 0) throw argument_error("cells", "negative");
    const Vec3<T> n = config.cell_u.cross(config.cell_v);
    if (!(n.norm() > 16 * std::numeric_limits<T>::epsilon() * config.cell_u.norm() * config.cell_v.norm()))
      throw argument_error("cell_v", "zero or parallel to cell_u");
    plane_ = Plane<T>{config.origin, n};
    cells_ = PlaneBasis<T>(config.origin, config.cell_u, config.cell_v);
  }

  [[nodiscard]] const Config& config() const noexcept { return config_; }

  /// Board coordinates (a, b) where `ray` meets the plane, if it does so at t >= 0.
  [[nodiscard]] bool intersect(const Ray<T>& ray, T& a, T& b) const noexcept {
    const T t = plane_.crossing_parameter(ray);
    if (!(t >= 0) || !std::isfinite(t)) return false; // parallel, behind, or NaN
    const Vec2<T> ab = cells_.coordinates(ray.at(t));
    a = ab.x();
    b = ab.y();
    return std::isfinite(a) && std::isfinite(b);
  }

  /// The colour of cell (i, j) (no bounds check).
  [[nodiscard]] Color cell_color(long long i, long long j) const noexcept {
    if ((i + j) & 1) return config_.dark;
    return ((i >> 1) + (j >> 1)) & 1 ? config_.light_alt : config_.light;
  }

  [[nodiscard]] Color sample(const Ray<T>& ray) const noexcept {
    T a, b;
    if (!intersect(ray, a, b)) return config_.background;
    const T fa = std::floor(a), fb = std::floor(b);
    const T limit = config_.cells > 0 ? static_cast<T>(config_.cells) : T(1) / T(0);
    // Also keeps the integer conversion below in range.
    constexpr T kMaxCell = T(1u << 23);
    if (!(std::abs(fa + T(0.5)) < limit && std::abs(fb + T(0.5)) < limit) || std::abs(fa) > kMaxCell ||
        std::abs(fb) > kMaxCell)
      return config_.background;
    return cell_color(static_cast<long long>(fa), static_cast<long long>(fb));
  }

private:
  Config config_;
  Plane<T> plane_;
  PlaneBasis<T> cells_;
};

} // namespace mpr
