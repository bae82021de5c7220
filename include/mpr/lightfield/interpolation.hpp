#pragma once
/// \file
/// The interpolation policies of `CameraFrameSampler`: which cameras answer a ray and with what
/// weights, and how a camera's pixels are reconstructed. Light field rendering (Levoy & Hanrahan,
/// SIGGRAPH 1996) and dynamically reparameterized light fields (Isaksen, McMillan & Gortler,
/// SIGGRAPH 2000), as used for General Linear Cameras by Yu & McMillan (ECCV 2004).

#include <mpr/core/error.hpp>

#include <cmath>

namespace mpr {

/// The camera whose centre is nearest to the ray *line* (not only the half-line), and the pixel
/// where that camera sees the ray's point. Ties (equal distance) go to the lowest camera index.
/// When that camera does not see the point (behind it or outside its image), the sampler's
/// background colour is returned.
struct NearestCamera {};

/// The unweighted average over every camera that sees the ray's point (in front of it and
/// inside its image): a synthetic aperture as wide as the whole array, focused on the point.
/// No camera sees it: the background colour.
struct SyntheticAperture {};

/// The cameras whose centres lie strictly within `radius` (world units) of the ray line,
/// weighted by the linear falloff `1 - d / radius` and renormalised over those that see the
/// point: a finite synthetic aperture centred on the ray. When no such camera sees the point
/// the nearest-camera answer is used (`NearestCamera`), so the result is never NaN.
struct CylinderAperture {
  double radius = 1.0;

  /// Throws `argument_error` ("radius") unless `radius` is positive and finite.
  void validate() const {
    if (!(radius > 0) || !std::isfinite(radius)) throw argument_error("radius", "must be positive and finite");
  }
};

/// Reconstruction of a camera image between pixel centres.
enum class PixelFilter {
  /// Bilinear interpolation of the four nearest pixel centres (edge pixels repeat), in linear
  /// colour.
  bilinear,
  /// The pixel whose square contains the point.
  nearest,
};

} // namespace mpr
