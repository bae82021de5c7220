#pragma once
/// \file
/// `mpr::ArrayPlane<T>`: the plane of a planar camera array as the light-field row paths use it
/// -- a point, the unit normal and two in-plane axes, every centre in in-plane coordinates, and
/// per camera its near neighbours and the distance to the nearest camera not among them (the
/// facts the nearest-camera proofs rest on).

#include <mpr/core/ray.hpp>
#include <mpr/core/vec.hpp>
#include <mpr/geometry/plane.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace mpr {

/// The plane of a planar camera array (see the file comment). Built by `fit`.
template <std::floating_point T>
struct ArrayPlane {
  /// Cameras listed as neighbours of one camera, at most (nearest first).
  static constexpr std::size_t kMaxNeighbours = 8;

  /// The mean of the centres, the unit normal (least-variance direction) and the in-plane unit
  /// axes (largest and middle variance), world frame.
  Vec3<T> point = Vec3<T>::Zero();
  Vec3<T> normal = Vec3<T>::UnitZ();
  Vec3<T> axis_u = Vec3<T>::UnitX(), axis_v = Vec3<T>::UnitY();
  /// Largest distance of a centre from `point`, world units.
  T extent = 0;
  /// Per camera: in-plane centre coordinates along `axis_u`, `axis_v`.
  std::vector<T> centre_u, centre_v;
  /// Per camera i: its neighbours are `neighbours[neighbours_begin[i] .. neighbours_end[i])`
  /// (the cameras within 1.5 x its nearest-neighbour distance, at most `kMaxNeighbours`), and
  /// `separation[i]` is the distance to the nearest camera not listed (+inf when none).
  std::vector<int> neighbours, neighbours_begin, neighbours_end;
  std::vector<T> separation;
  /// In-plane coordinates of `neighbours[m]`.
  std::vector<T> neighbour_u, neighbour_v;

  /// The plane of `centres` when they are planar (every centre within 1e-6 x extent of the
  /// least-squares plane) and at least two distinct; else nullopt. When the caller knows the
  /// plane (`known`: a loader built the array on it, `CameraFrameSet::array_plane`), its normal
  /// is used and planarity is not tested again; the in-plane axes, a free choice, are the
  /// principal directions of the centres either way.
  [[nodiscard]] static std::optional<ArrayPlane> fit(std::span<const Vec3<T>> centres,
                                                     const std::optional<Plane<T>>& known = std::nullopt) {
    const std::size_t n = centres.size();
    if (n < 2) return std::nullopt;
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
    if (!(extent > 0)) return std::nullopt;
    const Eigen::SelfAdjointEigenSolver<Mat3<double>> eig(cov);
    const Vec3<double> normal = known ? Vec3<double>(known->normal.template cast<double>().normalized())
                                      : Vec3<double>(eig.eigenvectors().col(0).normalized());
    if (!known) {
      double off = 0;
      for (const Vec3<T>& c : centres) off = std::max(off, std::abs(normal.dot(c.template cast<double>() - mean)));
      if (!(off <= 1e-6 * extent)) return std::nullopt;
    }
    ArrayPlane p;
    p.neighbours_begin.resize(n);
    p.neighbours_end.resize(n);
    p.separation.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<std::pair<T, int>> others;
      for (std::size_t j = 0; j < n; ++j)
        if (j != i) others.emplace_back((centres[i] - centres[j]).norm(), static_cast<int>(j));
      std::sort(others.begin(), others.end());
      p.neighbours_begin[i] = static_cast<int>(p.neighbours.size());
      std::size_t k = 0;
      while (k < others.size() && k < kMaxNeighbours && others[k].first <= T(1.5) * others[0].first)
        p.neighbours.push_back(others[k++].second);
      p.neighbours_end[i] = static_cast<int>(p.neighbours.size());
      p.separation[i] = k < others.size() ? others[k].first : std::numeric_limits<T>::infinity();
    }
    p.normal = normal.template cast<T>();
    p.point = mean.template cast<T>();
    p.axis_u = eig.eigenvectors().col(2).normalized().template cast<T>();
    p.axis_v = eig.eigenvectors().col(1).normalized().template cast<T>();
    p.centre_u.resize(n);
    p.centre_v.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      p.centre_u[i] = p.axis_u.dot(centres[i] - p.point);
      p.centre_v[i] = p.axis_v.dot(centres[i] - p.point);
    }
    for (const int j : p.neighbours) {
      p.neighbour_u.push_back(p.centre_u[static_cast<std::size_t>(j)]);
      p.neighbour_v.push_back(p.centre_v[static_cast<std::size_t>(j)]);
    }
    p.extent = static_cast<T>(extent);
    return p;
  }

  /// Where the ray line meets the plane (`x`, world frame) and the cosine of its angle to the
  /// normal; false when the ray is within ~0.06 degrees of the plane or the crossing is not finite.
  [[nodiscard]] bool hit(const Ray<T>& ray, Vec3<T>& x, T& cosine) const noexcept {
    const T nd = normal.dot(ray.direction);
    const T length = ray.direction.norm();
    if (!(std::abs(nd) > T(1e-3) * length)) return false;
    x = Plane<T>{point, normal}.crossing(ray);
    cosine = std::abs(nd) / length;
    return x.allFinite();
  }
};

} // namespace mpr
