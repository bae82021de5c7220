#include <catch2/catch.hpp>

#include <mpr/lightfield/visual_hull.hpp>

#include <cmath>
#include <limits>
#include <vector>

namespace {

// A white sphere of radius 1 at the origin on black, seen by 8 cameras of 64 x 48 on a ring of
// radius 5 in the plane y = 0.3 (so the ring is not a great circle of the sphere), looking at the
// origin; the exact depth along camera i's axis of the sphere under each pixel.
struct SphereRing {
  std::vector<mpr::PinholeCamera<double>> cameras;
  std::vector<mpr::Image<mpr::Rgb8>> images;
  std::vector<mpr::Image<float>> depth;
};

SphereRing sphere_ring() {
  SphereRing s;
  for (int i = 0; i < 8; ++i) {
    const double a = 2 * 3.14159265358979 * i / 8;
    const auto cam =
        mpr::PinholeCamera<double>::look_at(mpr::Vec3<double>(5 * std::sin(a), 0.3, 5 * std::cos(a)),
                                            mpr::Vec3<double>::Zero(), mpr::Vec3<double>(0, 1, 0), 0.6, 64, 48);
    mpr::Image<mpr::Rgb8> image(64, 48, mpr::Rgb8{0, 0, 0});
    mpr::Image<float> depth(64, 48, std::numeric_limits<float>::infinity());
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) {
        const mpr::Ray<double> r = cam.ray_through({x, y});
        const mpr::Vec3<double> d = r.direction.normalized();
        const double b = r.origin.dot(d), c = r.origin.squaredNorm() - 1, disc = b * b - c;
        if (disc < 0) continue;
        const double t = -b - std::sqrt(disc);
        image(x, y) = mpr::Rgb8{255, 255, 255};
        depth(x, y) = static_cast<float>(cam.forward().dot(r.origin + t * d - cam.centre()));
      }
    s.cameras.push_back(cam);
    s.images.push_back(std::move(image));
    s.depth.push_back(std::move(depth));
  }
  return s;
}

} // namespace

TEST_CASE("visual hull settings are checked, naming the field", "[visual_hull]") {
  mpr::VisualHullConfig c;
  CHECK_NOTHROW(mpr::validate(c));
  c.near = 0;
  CHECK_THROWS_WITH(mpr::validate(c), Catch::Contains("near"));
  c = {};
  c.far = 0.5;
  CHECK_THROWS_WITH(mpr::validate(c), Catch::Contains("far"));
  c = {};
  c.planes = 1;
  CHECK_THROWS_WITH(mpr::validate(c), Catch::Contains("planes"));
  const SphereRing s = sphere_ring();
  const mpr::CameraFrameSet<double> frames(s.cameras, s.images);
  CHECK_THROWS_WITH(mpr::visual_hull_depth(frames, 8), Catch::Contains("camera"));
  mpr::Image<float> d(3, 3, 1.0f);
  CHECK_THROWS_WITH(mpr::constrain_to_visual_hull(d, mpr::Image<float>(3, 2, 1.0f)), Catch::Contains("hull"));
}

TEST_CASE("the visual hull of a sphere seen from a ring bounds its depth from the front, closely", "[visual_hull]") {
  const SphereRing s = sphere_ring();
  const mpr::CameraFrameSet<double> frames(s.cameras, s.images);
  mpr::VisualHullConfig config;
  config.near = 3;
  config.far = 7;
  config.planes = 400; // steps of about 0.01 at depth 4
  const std::vector<mpr::Image<float>> hull = mpr::visual_hull_depth_maps(frames, mpr::BrightnessSilhouette{}, config);
  REQUIRE(hull.size() == 8);
  int object = 0, near_front = 0, above = 0, unseen = 0;
  for (std::size_t i = 0; i < 8; ++i)
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) {
        const float h = hull[i](x, y), truth = s.depth[i](x, y);
        INFO("camera " << i << " pixel (" << x << ", " << y << ")");
        // Background: nothing seen. Object: a finite depth, but for a few rim pixels whose ray only
        // grazes the sphere, between two of the depths tried.
        if (std::isinf(truth)) {
          REQUIRE(std::isinf(h));
          continue;
        }
        ++object;
        if (std::isinf(h)) {
          ++unseen;
          continue;
        }
        // A lower bound on the depth, but for rim pixels where the silhouettes' pixel steps cut a
        // little off the sphere.
        if (h > truth + 0.02f) ++above;
        if (truth - h < 0.15) ++near_front;
      }
  INFO(object << " object pixels, " << near_front << " within 0.15 of the sphere, " << above << " behind it, " << unseen
              << " unseen");
  CHECK(above == 0);
  CHECK(unseen < object / 50);
  // Eight views carve the sphere closely: most object pixels lie within 0.15 of its surface, and
  // the centre pixel (sphere at depth 4) at least 3.9.
  CHECK(near_front > 0.8 * object);
  CHECK(hull[0](32, 24) > 3.9f);
  CHECK(hull[0](32, 24) <= s.depth[0](32, 24));
}

TEST_CASE("depth maps constrained to the visual hull: background unseen, never in front of the hull", "[visual_hull]") {
  const float inf = std::numeric_limits<float>::infinity();
  mpr::Image<float> depth(3, 1, 5.0f);
  mpr::Image<float> hull(3, 1, 4.0f);
  hull(1, 0) = 6.0f; // the estimate lies in front of the hull there
  hull(2, 0) = inf;  // background
  mpr::constrain_to_visual_hull(depth, hull);
  CHECK(depth(0, 0) == 5.0f);
  CHECK(depth(1, 0) == 6.0f);
  CHECK(std::isinf(depth(2, 0)));
}
