#pragma once
/// \file
/// The homography of a plane sweep: where another camera sees the point at a given depth along
/// a reference camera's pixel ray. Shared by the plane-sweep depth estimation and the visual hull.

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/vec.hpp>

namespace mpr::detail {

/// Pixel p = (x, y, 1) of camera `ref` at depth d along its optical axis is the world point
/// X = C + d R^T K^-1 p; camera `other` sees it at the homogeneous pixel h = A + d M p, with
/// A = K_o (R_o C + t_o) and M = K_o R_o R^T K^-1 (lens distortion ignored).
struct DepthHomography {
  Mat3<double> M;
  Vec3<double> A;
};

template <std::floating_point T>
[[nodiscard]] DepthHomography depth_homography(const PinholeCamera<T>& ref, const PinholeCamera<T>& other) {
  const Mat3<double> back = ref.R().template cast<double>().transpose() * ref.K().template cast<double>().inverse();
  const Mat3<double> K = other.K().template cast<double>(), R = other.R().template cast<double>();
  return {K * R * back, K * (R * ref.centre().template cast<double>() + other.t().template cast<double>())};
}

} // namespace mpr::detail
