#pragma once
/// \file
/// A block of rows seen by a camera as one affine map: the points of a tile's rows on a planar
/// focal surface form an affine grid, and a camera whose depth is constant over that grid (a
/// focal plane parallel to a rectified array's image planes) sees it as an affine grid of pixel
/// positions. The interpolations that add a camera to a block of rows row by row
/// (`CylinderAperture`) then evaluate each run's pixel positions instead of projecting its points,
/// and whole-pixel shifts (`snap_to_texel`) read one camera row per output row.

#include <mpr/core/vec.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace mpr::detail {

/// Points p(i, q) = origin + i step_i + q step_q, double: i the index along a row, q the row;
/// `deviation`: the largest distance (world units, per coordinate) of a row's end point from
/// its grid point.
struct AffineGrid {
  Vec3<double> origin = Vec3<double>::Zero(), step_i = Vec3<double>::Zero(), step_q = Vec3<double>::Zero();
  double deviation = 0;
};

/// The grid through rows[q][i] (q < nrows, i < n), when every row's two end points lie on it
/// within the tolerance `evenly_spaced` allows inside a row (64 ulp of the end points'
/// magnitude): with rows each evenly spaced (the caller's check), the whole block then is, as a
/// row is (the points inside a row are taken to lie on its line, as a run's shift-and-add takes
/// them). False for fewer than two rows or points, or a non-finite point.
template <std::floating_point T>
[[nodiscard]] bool affine_grid(const Vec3<T>* const* rows, std::size_t nrows, std::size_t n,
                               AffineGrid& grid) noexcept {
  if (nrows < 2 || n < 2) return false;
  const Vec3<double> a = rows[0][0].template cast<double>(), b = rows[0][n - 1].template cast<double>();
  const Vec3<double> c = rows[nrows - 1][0].template cast<double>();
  grid.origin = a;
  grid.step_i = (b - a) / static_cast<double>(n - 1);
  grid.step_q = (c - a) / static_cast<double>(nrows - 1);
  grid.deviation = 0;
  for (std::size_t q = 0; q < nrows; ++q)
    for (const std::size_t i : {std::size_t(0), n - 1}) {
      const Vec3<double> p = rows[q][i].template cast<double>();
      const Vec3<double> want =
          grid.origin + static_cast<double>(i) * grid.step_i + static_cast<double>(q) * grid.step_q;
      const double scale = rows[q][0].template cast<double>().cwiseAbs().maxCoeff() +
                           rows[q][n - 1].template cast<double>().cwiseAbs().maxCoeff();
      const double tolerance = 64 * static_cast<double>(std::numeric_limits<T>::epsilon()) * scale;
      const double off = (p - want).cwiseAbs().maxCoeff();
      if (!(off <= tolerance)) return false;
      grid.deviation = std::max(grid.deviation, off);
    }
  return true;
}

/// How near a texel a camera coordinate x, computed in T, is taken as on it (`snap_to_texel`):
/// 1e-4 pixel, or 4 epsilon |x| where T's rounding at x is coarser than that (float beyond 210
/// pixels, where a projection is a few units in the last place off: Chess's coordinates at its
/// reference plane, up to 1400 pixels, come 1.2e-4 to 1.8e-4 pixel off their texels in float).
/// At most 6.7e-4 pixel for coordinates within 1400 pixels; 1e-4 in double.
template <std::floating_point T>
[[nodiscard]] T texel_snap(T x) noexcept {
  return std::max(T(1e-4), 4 * std::numeric_limits<T>::epsilon() * std::abs(x));
}

/// The texel and offset of the whole-pixel shift that starts at camera coordinate x: i =
/// floor(x), a = x - i, except that an offset within `texel_snap(x)` of a texel is taken as on it
/// (i the nearer texel, a = 0: an error below T's rounding of x, or of at most 1e-4 pixel, on
/// top of the shift-and-add's 1e-3 contract). Integer shifts -- a focus on the reference plane
/// of rectified data, e.g. every camera of Chess at z = 1000 and of the reference workload --
/// then read one texel per pixel and one camera row per output row instead of interpolating.
/// Precondition: |x| < 1e8.
template <std::floating_point T>
void snap_to_texel(T x, long& i, T& a) noexcept {
  const T kSnap = texel_snap(x);
  const T f = std::floor(x);
  i = static_cast<long>(f);
  a = x - f;
  if (a > 1 - kSnap) ++i;
  if (a < kSnap || a > 1 - kSnap) a = 0;
}

/// Pixel positions x = x[0] + x[1] i + x[2] q, y likewise, of an `AffineGrid`'s points.
struct AffineSight {
  double x[3] = {0, 0, 0}, y[3] = {0, 0, 0};

  /// The position of grid point (i, q), in the sampler's scalar.
  template <std::floating_point T>
  void at(double i, double q, T& px, T& py) const noexcept {
    px = static_cast<T>(x[0] + x[1] * i + x[2] * q);
    py = static_cast<T>(y[0] + y[1] * i + y[2] * q);
  }
};

/// Whether a camera that sees a group of nrows rows of w points by `sight` reads each row from
/// one camera row: one pixel a point along its rows, and every row's height on a texel
/// (`snap_to_texel`), so that `shift_add` adds it in one pass.
[[nodiscard]] inline bool one_row_runs(const AffineSight& sight, std::size_t w, std::size_t nrows) noexcept {
  const double span = static_cast<double>(w);
  if (!(std::abs(sight.x[1] - 1) * span <= 1e-4 && std::abs(sight.y[1]) * span <= 1e-4)) return false;
  for (std::size_t q = 0; q < nrows; ++q) {
    const double y = sight.y[0] + sight.y[2] * static_cast<double>(q);
    long texel = 0;
    double offset = 1;
    if (std::abs(y) < 1e8) snap_to_texel(y, texel, offset);
    if (offset != 0) return false;
  }
  return true;
}

/// How the undistorted camera with projection P (K [R | t], 3x4 row-major) sees the grid's
/// points with i in [0, n - 1] and q in [0, nrows - 1]: true, with `sight`, when they all lie in
/// front of it and the affine map through the grid's origin places every row's end points
/// within `tolerance` pixels of their projections (a depth constant over the block up to that).
/// The bound, with w = w0 + wi i + wq q the depth, x = N / w and w_min a lower bound of w over
/// the block: the perspective division moves a grid point by |N / w - N / w0| <= max |N / w0| *
/// max |w - w0| / w_min (both maxima at the block's corners), and a point `deviation` away from
/// its grid point projects at most (|P_x| + |x| |P_w|) deviation / (w_min - |P_w| deviation)
/// further (|.| the sums of the rows' first three magnitudes).
template <std::floating_point T>
[[nodiscard]] bool affine_sight(const T* P, const AffineGrid& grid, std::size_t n, std::size_t nrows, double tolerance,
                                AffineSight& sight) noexcept {
  double row[3][3];
  for (int r = 0; r < 3; ++r) {
    const Vec3<double> m(static_cast<double>(P[4 * r]), static_cast<double>(P[4 * r + 1]),
                         static_cast<double>(P[4 * r + 2]));
    row[r][0] = m.dot(grid.origin) + static_cast<double>(P[4 * r + 3]);
    row[r][1] = m.dot(grid.step_i);
    row[r][2] = m.dot(grid.step_q);
  }
  const double di = static_cast<double>(n - 1), dq = static_cast<double>(nrows - 1);
  const double w0 = row[2][0];
  const double spread = std::abs(row[2][1]) * di + std::abs(row[2][2]) * dq; // max |w - w0|
  const double w_min = w0 + std::min(row[2][1] * di, 0.0) + std::min(row[2][2] * dq, 0.0);
  if (!(w_min > 0) || !std::isfinite(spread)) return false;
  double largest = 0; // max |N / w0| over the corners, both coordinates
  for (const double ci : {0.0, di})
    for (const double cq : {0.0, dq})
      largest = std::max({largest, std::abs(row[0][0] + row[0][1] * ci + row[0][2] * cq),
                          std::abs(row[1][0] + row[1][1] * ci + row[1][2] * cq)});
  largest /= w0;
  const auto magnitude = [P](int r) {
    return std::abs(static_cast<double>(P[4 * r])) + std::abs(static_cast<double>(P[4 * r + 1])) +
           std::abs(static_cast<double>(P[4 * r + 2]));
  };
  const double perspective = largest * spread / w_min;
  const double reach = largest + perspective;                 // max |x|, |y| of the projections
  const double w_off = w_min - magnitude(2) * grid.deviation; // the least depth of a point off the grid
  if (!(w_off > 0)) return false;
  const double off = (std::max(magnitude(0), magnitude(1)) + reach * magnitude(2)) * grid.deviation / w_off;
  if (!(perspective + off <= tolerance)) return false;
  for (int k = 0; k < 3; ++k) {
    sight.x[k] = row[0][k] / w0;
    sight.y[k] = row[1][k] / w0;
  }
  return true;
}

} // namespace mpr::detail
