#pragma once
/// \file
/// Disparity of a rectified planar camera array (planar_camera_array.hpp, the HCI 4D light-field
/// benchmark): a point at depth Z moves by d = f B / Z - s pixels between neighbouring views,
/// for focal length f (pixels), view spacing B (world units) and a constant s (the disparity of
/// the reference plane z0 is 0: s = f B / z0). The benchmark's ground truth and submissions are
/// such disparities of the centre view; `estimate_depth` and `DepthProxy` work in depth.

#include <mpr/core/error.hpp>
#include <mpr/core/image.hpp>

#include <cmath>
#include <string>

namespace mpr {

/// d = focal_baseline / Z - offset (pixels per one-view step) and back.
struct ArrayDisparity {
  /// f B: focal length in pixels times the spacing of neighbouring views (world units), > 0.
  double focal_baseline = 1;
  /// s = f B / z0 for the plane z0 of zero disparity (pixels); points at depth Z > 0 have
  /// disparity above -offset.
  double offset = 0;

  /// Throws `argument_error` ("focal_baseline", "offset") unless f B > 0 and both are finite.
  void validate() const {
    if (!(focal_baseline > 0) || !std::isfinite(focal_baseline))
      throw argument_error("focal_baseline", "must be positive and finite");
    if (!std::isfinite(offset)) throw argument_error("offset", "must be finite");
  }
  /// Disparity (pixels) of depth `z` > 0.
  [[nodiscard]] double disparity(double z) const noexcept { return focal_baseline / z - offset; }
  /// Depth of disparity `d`; positive for d > -offset, infinity at d = -offset, negative beyond.
  [[nodiscard]] double depth(double d) const noexcept { return focal_baseline / (d + offset); }
};

/// The disparity map of depth map `depth` (every depth > 0 and finite: else `argument_error`
/// "depth" naming the pixel).
[[nodiscard]] inline Image<float> disparity_from_depth(ImageView<const float> depth, const ArrayDisparity& a) {
  a.validate();
  Image<float> out(depth.width(), depth.height());
  for (int y = 0; y < depth.height(); ++y)
    for (int x = 0; x < depth.width(); ++x) {
      const float z = depth(x, y);
      if (!(z > 0) || !std::isfinite(z))
        throw argument_error("depth", "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                          ") is not a positive finite depth");
      out(x, y) = static_cast<float>(a.disparity(z));
    }
  return out;
}

/// The depth map of disparity map `disparity` (every disparity finite and above -offset: else
/// `argument_error` "disparity" naming the pixel).
[[nodiscard]] inline Image<float> depth_from_disparity(ImageView<const float> disparity, const ArrayDisparity& a) {
  a.validate();
  Image<float> out(disparity.width(), disparity.height());
  for (int y = 0; y < disparity.height(); ++y)
    for (int x = 0; x < disparity.width(); ++x) {
      const float d = disparity(x, y);
      const double z = a.depth(d);
      if (!std::isfinite(d) || !(z > 0) || !std::isfinite(static_cast<float>(z)))
        throw argument_error("disparity", "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                              ") is not finite or lies at or beyond the array's infinity (-offset)");
      out(x, y) = static_cast<float>(z);
    }
  return out;
}

} // namespace mpr
