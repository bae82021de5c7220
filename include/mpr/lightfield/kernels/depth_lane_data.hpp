#pragma once
/// \file
/// What the lane kernels of `DepthProxy`'s batch path (kernels/depth_lanes_hwy.hpp) read and
/// write, as plain arrays of sixteen lanes (one ray per lane): the same at every SIMD target,
/// which takes the sixteen lanes in vectors of its own width (4, 8 or 16 floats).

#include <cstdint>

namespace mpr::detail {

/// The rays a batch of `DepthProxy::sample_rays` takes at once (one per lane).
inline constexpr int kDepthLanes = 16;

/// The most cameras a lane keeps (k + 1 of `DepthProxy`); larger k takes the per-ray path.
inline constexpr int kDepthLaneSlots = 8;

/// Sixteen rays, one per lane: origins o, directions v, 1 / |v|^2 and |v|.
struct RayLanes {
  alignas(64) float ox[16], oy[16], oz[16], vx[16], vy[16], vz[16], inverse_length2[16], length[16];
};

/// The cameras each lane keeps (slot j of lane l), best first, in the order in which
/// `DepthProxy::blend` tries them: the angle to the ray (`unit_acos` of the cosine), the pixel,
/// the camera (-1: empty).
struct LaneChoice {
  alignas(64) float penalty[kDepthLaneSlots][16], x[kDepthLaneSlots][16], y[kDepthLaneSlots][16];
  alignas(64) int camera[kDepthLaneSlots][16];
};

/// How the walks of `walk_lanes` ended, lane by lane (bit l: lane l): `hit` (t: the surface),
/// `escaped` (the ray runs to its vanishing point in front of everything the camera sees),
/// `passed` (t, skip_begin, skip_end: the search's `DepthSearch` after this camera, for the next).
struct WalkLanesResult {
  unsigned hit = 0, escaped = 0, passed = 0;
  alignas(64) float t[16], skip_begin[16], skip_end[16];
};

/// What `weigh_lanes` reads of a camera: its 8-bit texels (3 bytes each) and size, with
/// width x height < 2^31.
struct WeighCamera {
  const std::uint8_t* texels;
  int width, height;
};

/// What the lane kernels read of one camera: its 3 x 4 projection P (row-major, pixels), centre
/// and size, and its depth map (row-major, width x height < 2^31) with the nearest depth it shows.
struct LaneCamera {
  const float* P;
  float cx, cy, cz;
  int width, height;
  const float* depth;
  float near;
};

} // namespace mpr::detail
