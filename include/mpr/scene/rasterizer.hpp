#pragma once
/// \file
/// A software rasterizer: renders a `Scene` through a `PinholeCamera` into a linear colour buffer
/// and a depth buffer, on the CPU, with no GPU and no OpenGL.
///
/// Pipeline (per triangle, in scene order): world -> camera coordinates `R X + t` -> homogeneous
/// pixel coordinates `(X, Y, W) = K (R X + t)`; clipping in homogeneous space against the near
/// plane `W >= near` (and, only when a vertex lies far off screen, against a guard band 4096
/// pixels around the image, so that fixed-point coordinates cannot overflow); projection to
/// pixel coordinates snapped to 1/256 pixel; coverage by exact 64-bit integer edge functions at
/// pixel centres with the top-left fill rule (a pixel centre on an edge shared by two triangles
/// is covered by exactly one of them); perspective-correct depth and barycentrics, evaluated
/// exactly from the triangle's camera-space plane at each pixel centre (so clipping and snapping
/// never perturb them); a z-buffer
/// on inverse camera depth (ties keep the earlier triangle). The image is cut into square tiles that are
/// rasterized in parallel; each tile processes its triangles in scene order, so the result does
/// not depend on the thread count. Visible pixels are shaded once, after visibility is resolved,
/// with `Scene::shade` -- the same function the ray caster uses.
///
/// Pixel convention: the camera's (OpenCV) convention, pixel (i, j) has its centre at (i, j) in
/// K's coordinates. The camera's radial distortion is not modelled (straight lines stay straight):
/// a distorted camera is rejected.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/color.hpp>
#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>
#include <mpr/core/parallel.hpp>
#include <mpr/scene/scene.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace mpr::scene {

/// Rasterizer settings.
struct RasterOptions {
  /// Worker threads (the caller included); 0 or less: all hardware threads.
  int threads = 0;
  /// Near clipping distance along the camera axis, world units; must be positive.
  double near = 1e-3;
  /// Tile edge in pixels (tiles are rasterized in parallel), 8 to 256.
  int tile = 32;
};

/// Colour and depth of a rasterized view. `depth` is the camera-space z (distance along the
/// viewing axis) of the visible surface, +inf where only background shows.
struct RasterImage {
  Image<Color> color;
  Image<float> depth;
};

namespace detail {

constexpr int kSubpixelBits = 8;
constexpr std::int64_t kSubpixel = std::int64_t{1} << kSubpixelBits;
constexpr double kGuard = 4096.0;

template <class T>
struct ClipVertex {
  T X, Y, W; // homogeneous pixel coordinates
};

/// The plane of a triangle in camera space, for exact per-pixel depth and barycentrics: with
/// r = K^-1 (x, y, 1) the ray of pixel (x, y) (camera z = 1), the hit is c = z r where
/// 1 / z = (n . r) / d = (alpha x + beta y + gamma) / d, and b1 = (c - c0) . g1, b2 = (c - c0) . g2.
/// Computed from the original triangle in double precision, so neither clipping nor vertex
/// snapping changes depth or interpolated attributes.
struct PlaneEquation {
  double alpha, beta, gamma, d;
  /// 1 / z = inv_alpha x + inv_beta y + inv_gamma (the z-test compares 1 / z: no division).
  double inv_alpha, inv_beta, inv_gamma;
  std::array<double, 3> c0, g1, g2;
};

struct ScreenTriangle {
  std::array<std::int64_t, 3> x, y; // fixed point, 1/256 pixel
  std::int64_t area;                // > 0
  int x0, y0, x1, y1;               // inclusive pixel bounding box, clipped to the image
  std::uint32_t plane;              // index into the plane equations
  std::uint32_t triangle;
  bool front;
};

/// Sutherland-Hodgman clipping of a convex polygon against f(v) = a X + b Y + c W + d >= 0.
template <class T>
int clip_polygon(const ClipVertex<T>* in, int n, ClipVertex<T>* out, T a, T b, T c, T d) noexcept {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const ClipVertex<T>& p = in[i];
    const ClipVertex<T>& q = in[(i + 1) % n];
    const T fp = a * p.X + b * p.Y + c * p.W + d;
    const T fq = a * q.X + b * q.Y + c * q.W + d;
    if (fp >= 0) out[m++] = p;
    if ((fp >= 0) != (fq >= 0)) {
      const T s = fp / (fp - fq);
      out[m++] = {p.X + s * (q.X - p.X), p.Y + s * (q.Y - p.Y), p.W + s * (q.W - p.W)};
    }
  }
  return m;
}

inline std::int64_t floor_div(std::int64_t a, std::int64_t b) noexcept {
  const std::int64_t q = a / b;
  return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

} // namespace detail

/// Rasterizes `scene` as seen by `camera` into `color` and `depth`, which must both have the
/// camera's size. Throws `argument_error` ("color", "depth", "camera", "near", "tile") for
/// mismatched buffers, a distorted camera or bad options; never throws once rendering starts.
template <std::floating_point T>
void rasterize(const Scene<T>& scene, const PinholeCamera<T>& camera, ImageView<Color> color, ImageView<float> depth,
               const RasterOptions& options = {}) {
  const int width = camera.width(), height = camera.height();
  if (color.width() != width || color.height() != height)
    throw argument_error("color", "buffer size differs from the camera's image size");
  if (depth.width() != width || depth.height() != height)
    throw argument_error("depth", "buffer size differs from the camera's image size");
  if (camera.has_distortion()) throw argument_error("camera", "radial distortion is not supported by the rasterizer");
  if (!(options.near > 0) || !std::isfinite(options.near)) throw argument_error("near", "must be positive and finite");
  if (options.tile < 8 || options.tile > 256) throw argument_error("tile", "must be between 8 and 256 pixels");

  using detail::ClipVertex;
  using detail::PlaneEquation;
  using detail::ScreenTriangle;
  const Mat3<T>& K = camera.K();
  const Mat3<T>& R = camera.R();
  const Vec3<T>& t = camera.t();
  const Vec3<T>& centre = camera.centre();
  const T near = static_cast<T>(options.near);
  const T guard = static_cast<T>(detail::kGuard);
  const T gx1 = static_cast<T>(width) + guard, gy1 = static_cast<T>(height) + guard;

  // 1. Set-up: transform, clip, project, snap; in scene order.
  std::vector<ScreenTriangle> screen;
  std::vector<PlaneEquation> planes;
  screen.reserve(scene.size());
  planes.reserve(scene.size());
  const Eigen::Matrix3d K_inverse = K.template cast<double>().inverse();
  const auto& triangles = scene.triangles();
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle<T>& tri = triangles[i];
    ClipVertex<T> poly[2][9];
    int n = 3;
    bool all_inside = true, all_near_out = true;
    for (int j = 0; j < 3; ++j) {
      const Vec3<T> c = R * tri.p[j] + t;
      const T X = K(0, 0) * c.x() + K(0, 1) * c.y() + K(0, 2) * c.z();
      const T Y = K(1, 1) * c.y() + K(1, 2) * c.z();
      poly[0][j] = {X, Y, c.z()};
      if (c.z() >= near) all_near_out = false;
      const bool in =
          c.z() >= near && X >= -guard * c.z() && X <= gx1 * c.z() && Y >= -guard * c.z() && Y <= gy1 * c.z();
      all_inside = all_inside && in;
    }
    if (all_near_out) continue;
    int cur = 0;
    if (!all_inside) {
      const T clip_planes[5][4] = {
          {0, 0, 1, -near}, {1, 0, guard, 0}, {-1, 0, gx1, 0}, {0, 1, guard, 0}, {0, -1, gy1, 0}};
      for (const auto& pl : clip_planes) {
        n = detail::clip_polygon(poly[cur], n, poly[1 - cur], pl[0], pl[1], pl[2], pl[3]);
        cur = 1 - cur;
        if (n < 3) break;
      }
      if (n < 3) continue;
    }
    const bool front = (tri.p[0] - centre).dot(tri.normal) < 0;
    {
      const Eigen::Vector3d c0 = (R * tri.p[0] + t).template cast<double>();
      const Eigen::Vector3d e1 = (R * tri.p[1] + t).template cast<double>() - c0;
      const Eigen::Vector3d e2 = (R * tri.p[2] + t).template cast<double>() - c0;
      const Eigen::Vector3d normal = e1.cross(e2);
      const double nn = normal.squaredNorm();
      const double d = normal.dot(c0);
      if (!(nn > 0) || d == 0 || !std::isfinite(d)) continue;     // seen edge-on: covers no area
      const Eigen::Vector3d abc = K_inverse.transpose() * normal; // n . (K^-1 (x, y, 1))
      const Eigen::Vector3d g1 = e2.cross(normal) / nn, g2 = normal.cross(e1) / nn;
      planes.push_back({abc.x(),
                        abc.y(),
                        abc.z(),
                        d,
                        abc.x() / d,
                        abc.y() / d,
                        abc.z() / d,
                        {c0.x(), c0.y(), c0.z()},
                        {g1.x(), g1.y(), g1.z()},
                        {g2.x(), g2.y(), g2.z()}});
    }
    const std::uint32_t plane_index = static_cast<std::uint32_t>(planes.size() - 1);
    // Project and snap every polygon vertex, then fan-triangulate.
    std::array<std::int64_t, 9> fx{}, fy{};
    for (int j = 0; j < n; ++j) {
      const ClipVertex<T>& v = poly[cur][j];
      // Inside the guard band, so the values fit easily; round half away from zero.
      const double sx = static_cast<double>(v.X / v.W) * static_cast<double>(detail::kSubpixel);
      const double sy = static_cast<double>(v.Y / v.W) * static_cast<double>(detail::kSubpixel);
      fx[j] = static_cast<std::int64_t>(sx + (sx >= 0 ? 0.5 : -0.5));
      fy[j] = static_cast<std::int64_t>(sy + (sy >= 0 ? 0.5 : -0.5));
    }
    for (int k = 1; k + 1 < n; ++k) {
      int idx[3] = {0, k, k + 1};
      std::int64_t area =
          (fx[idx[1]] - fx[idx[0]]) * (fy[idx[2]] - fy[idx[0]]) - (fy[idx[1]] - fy[idx[0]]) * (fx[idx[2]] - fx[idx[0]]);
      if (area == 0) continue;
      if (area < 0) {
        std::swap(idx[1], idx[2]);
        area = -area;
      }
      ScreenTriangle s;
      std::int64_t minx = std::numeric_limits<std::int64_t>::max(), maxx = std::numeric_limits<std::int64_t>::min();
      std::int64_t miny = minx, maxy = maxx;
      for (int j = 0; j < 3; ++j) {
        s.x[j] = fx[idx[j]];
        s.y[j] = fy[idx[j]];
        minx = std::min(minx, s.x[j]);
        maxx = std::max(maxx, s.x[j]);
        miny = std::min(miny, s.y[j]);
        maxy = std::max(maxy, s.y[j]);
      }
      // Pixel centres at integers: the first centre >= min and the last <= max.
      const std::int64_t px0 = -detail::floor_div(-minx, detail::kSubpixel),
                         px1 = detail::floor_div(maxx, detail::kSubpixel);
      const std::int64_t py0 = -detail::floor_div(-miny, detail::kSubpixel),
                         py1 = detail::floor_div(maxy, detail::kSubpixel);
      s.x0 = static_cast<int>(std::max<std::int64_t>(px0, 0));
      s.x1 = static_cast<int>(std::min<std::int64_t>(px1, width - 1));
      s.y0 = static_cast<int>(std::max<std::int64_t>(py0, 0));
      s.y1 = static_cast<int>(std::min<std::int64_t>(py1, height - 1));
      if (s.x0 > s.x1 || s.y0 > s.y1) continue;
      s.area = area;
      s.plane = plane_index;
      s.triangle = static_cast<std::uint32_t>(i);
      s.front = front;
      screen.push_back(s);
    }
  }

  // 2. Binning into tiles (each list stays in scene order).
  const int ts = options.tile;
  const int tiles_x = (width + ts - 1) / ts, tiles_y = (height + ts - 1) / ts;
  std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(tiles_x) * tiles_y);
  for (std::size_t k = 0; k < screen.size(); ++k) {
    const ScreenTriangle& s = screen[k];
    for (int ty = s.y0 / ts; ty <= s.y1 / ts; ++ty)
      for (int tx = s.x0 / ts; tx <= s.x1 / ts; ++tx)
        bins[static_cast<std::size_t>(ty) * tiles_x + tx].push_back(static_cast<std::uint32_t>(k));
  }

  // 3. Tiles in parallel: visibility, then shading of the visible pixels.
  const Color background = scene.background();
  mpr::detail::parallel_rows(0, tiles_x * tiles_y, options.threads, [&](int tile) noexcept {
    const int tx0 = (tile % tiles_x) * ts, ty0 = (tile / tiles_x) * ts;
    const int tw = std::min(ts, width - tx0), th = std::min(ts, height - ty0);
    // Per-pixel winner (screen triangle) and its 1 / z, in tile-local storage: on the stack for
    // tiles up to 64 x 64, else allocated once per tile (never per pixel).
    constexpr int kStackPixels = 64 * 64;
    std::uint32_t winner[kStackPixels];
    float nearness[kStackPixels];
    std::vector<std::uint32_t> big_winner;
    std::vector<float> big_nearness;
    std::uint32_t* win = winner;
    float* near_buf = nearness;
    if (tw * th > kStackPixels) {
      try {
        big_winner.resize(static_cast<std::size_t>(tw) * th);
        big_nearness.resize(static_cast<std::size_t>(tw) * th);
      } catch (...) {
        return;
      }
      win = big_winner.data();
      near_buf = big_nearness.data();
    }
    std::fill(near_buf, near_buf + tw * th, 0.0f); // 1 / z = 0: infinitely far
    for (std::uint32_t k : bins[static_cast<std::size_t>(tile)]) {
      const ScreenTriangle& s = screen[k];
      const int x0 = std::max(s.x0, tx0), x1 = std::min(s.x1, tx0 + tw - 1);
      const int y0 = std::max(s.y0, ty0), y1 = std::min(s.y1, ty0 + th - 1);
      // Edge j is opposite vertex j: from vertex a = j+1 to b = j+2; E > 0 inside.
      std::int64_t step_x[3], step_y[3], row_start[3], bias[3];
      for (int j = 0; j < 3; ++j) {
        const int a = (j + 1) % 3, b = (j + 2) % 3;
        const std::int64_t dx = s.x[b] - s.x[a], dy = s.y[b] - s.y[a];
        step_x[j] = -dy * detail::kSubpixel;
        step_y[j] = dx * detail::kSubpixel;
        row_start[j] = dx * (y0 * detail::kSubpixel - s.y[a]) - dy * (x0 * detail::kSubpixel - s.x[a]);
        // Top-left rule (y down): a top edge is horizontal with the interior below (dx > 0), a
        // left edge has the interior to its right (dy < 0). Pixels exactly on other edges are out.
        bias[j] = (dy < 0 || (dy == 0 && dx > 0)) ? 0 : -1;
      }
      const PlaneEquation& pe = planes[s.plane];
      // Wide triangles: solve each row's covered span exactly from the integer edge functions
      // (no stepping over empty pixels of the bounding box); narrow ones: test pixel by pixel.
      const bool spans = x1 - x0 >= 16;
      for (int y = y0; y <= y1; ++y) {
        const double row_term = pe.inv_beta * y + pe.inv_gamma;
        float* nrow = near_buf + (y - ty0) * tw - tx0;
        std::uint32_t* wrow = win + (y - ty0) * tw - tx0;
        if (spans) {
          std::int64_t lo = x0, hi = x1;
          for (int j = 0; j < 3; ++j) {
            const std::int64_t e = row_start[j] + bias[j], sx = step_x[j]; // inside: e + (x - x0) sx >= 0
            if (sx > 0)
              lo = std::max(lo, x0 - detail::floor_div(e, sx)); // x - x0 >= ceil(-e / sx)
            else if (sx < 0)
              hi = std::min(hi, x0 + detail::floor_div(e, -sx));
            else if (e < 0)
              hi = lo - 1;
          }
          for (int x = static_cast<int>(lo); x <= static_cast<int>(hi); ++x) {
            const float inv_z = static_cast<float>(pe.inv_alpha * x + row_term);
            if (inv_z > nrow[x]) {
              nrow[x] = inv_z;
              wrow[x] = k;
            }
          }
        } else {
          std::int64_t e0 = row_start[0], e1 = row_start[1], e2 = row_start[2];
          for (int x = x0; x <= x1; ++x, e0 += step_x[0], e1 += step_x[1], e2 += step_x[2]) {
            if ((e0 + bias[0]) < 0 || (e1 + bias[1]) < 0 || (e2 + bias[2]) < 0) continue;
            const float inv_z = static_cast<float>(pe.inv_alpha * x + row_term);
            if (inv_z > nrow[x]) {
              nrow[x] = inv_z;
              wrow[x] = k;
            }
          }
        }
        row_start[0] += step_y[0];
        row_start[1] += step_y[1];
        row_start[2] += step_y[2];
      }
    }
    // Shading: recompute the winner's perspective-correct barycentrics at each visible pixel.
    for (int y = 0; y < th; ++y) {
      Color* crow = color.row(ty0 + y) + tx0;
      float* drow = depth.row(ty0 + y) + tx0;
      const std::uint32_t* wrow = win + y * tw;
      const float* nrow = near_buf + y * tw;
      for (int x = 0; x < tw; ++x) {
        if (!(nrow[x] > 0.0f)) {
          crow[x] = background;
          drow[x] = std::numeric_limits<float>::infinity();
          continue;
        }
        const ScreenTriangle& s = screen[wrow[x]];
        const PlaneEquation& pe = planes[s.plane];
        const double px = tx0 + x, py = ty0 + y;
        const double z = pe.d / (pe.alpha * px + pe.beta * py + pe.gamma);
        drow[x] = static_cast<float>(z);
        const Eigen::Vector3d c = z * (K_inverse * Eigen::Vector3d(px, py, 1.0));
        const double cx = c.x() - pe.c0[0], cy = c.y() - pe.c0[1], cz = c.z() - pe.c0[2];
        const T b1 = static_cast<T>(cx * pe.g1[0] + cy * pe.g1[1] + cz * pe.g1[2]);
        const T b2 = static_cast<T>(cx * pe.g2[0] + cy * pe.g2[1] + cz * pe.g2[2]);
        crow[x] = scene.shade(s.triangle, b1, b2, s.front);
      }
    }
  });
}

/// Rasterizes into new buffers of the camera's size (see the overload above).
template <std::floating_point T>
[[nodiscard]] RasterImage rasterize(const Scene<T>& scene, const PinholeCamera<T>& camera,
                                    const RasterOptions& options = {}) {
  RasterImage out{Image<Color>(camera.width(), camera.height()), Image<float>(camera.width(), camera.height())};
  rasterize(scene, camera, out.color.view(), out.depth.view(), options);
  return out;
}

} // namespace mpr::scene
