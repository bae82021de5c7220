#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield.hpp>

#include <memory>
#include <vector>

// CylinderAperture's weights, hand-worked at radii other than 1 (where d / r and d / r^2, or
// 1 - d / r and 1 - (d / r)^2, would agree for no camera).
TEMPLATE_TEST_CASE("CylinderAperture weighs 1 - d / r at radius 1.5 and 0.75 (hand-worked)", "[cylinder][oracle]",
                   float, double) {
  using T = TestType;
  // Five cameras at x = -1, -0.5, 0, 0.5, 1 on z = 0 showing constant colours c_0 ... c_4. Rays
  // from (0.2, 0, 5) (the focal surface: the colour is taken there, seen by every camera) along
  // z lie at distances 1.2, 0.7, 0.2, 0.3, 0.8 from the cameras.
  const auto cams = mpr_test::grid_cameras<T>(5, 1, 0.5, 40, 30, 30.0);
  const auto frames = std::make_shared<const mpr::CameraFrameSet<T, mpr::Color>>(cams, mpr_test::constant_images(cams));
  const auto c = [](std::size_t i) { return mpr_test::constant_colour(i); };
  // r = 1.5: weights 1 - d / 1.5 = 0.2, 8/15, 13/15, 0.8, 7/15 (sum 43/15).
  const mpr::Color wide =
      (0.2f * c(0) + (8.0f / 15) * c(1) + (13.0f / 15) * c(2) + 0.8f * c(3) + (7.0f / 15) * c(4)) / (43.0f / 15);
  // r = 0.75: only d < 0.75: 1 - 0.7 / 0.75 = 1/15, 1 - 0.2 / 0.75 = 11/15, 1 - 0.3 / 0.75 = 0.6.
  const mpr::Color narrow = ((1.0f / 15) * c(1) + (11.0f / 15) * c(2) + 0.6f * c(3)) / (1.0f / 15 + 11.0f / 15 + 0.6f);
  for (const auto& [radius, expected] : {std::pair{1.5, wide}, std::pair{0.75, narrow}}) {
    const mpr::CameraFrameSampler<mpr::CylinderAperture, T, mpr::Color> sampler(frames, mpr::CylinderAperture{radius});
    const mpr::Ray<T> ray{mpr::Vec3<T>(T(0.2), 0, 5), mpr::Vec3<T>(0, 0, 1)};
    std::vector<mpr::Ray<T>> rays(19, ray);
    std::vector<mpr::Color> batch(rays.size());
    sampler.sample_rays(rays, batch);
    const mpr::Color single = sampler.sample(ray);
    INFO("radius " << radius << ": expected " << expected.transpose() << ", got " << single.transpose());
    CHECK((single - expected).abs().maxCoeff() < 1e-5f);
    for (const mpr::Color& b : batch) CHECK((b - expected).abs().maxCoeff() < 1e-5f);
  }
}
