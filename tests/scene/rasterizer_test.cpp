#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <memory>

namespace {

/// A camera at the origin looking along +z with focal length `f` pixels and the principal point
/// at pixel (0, 0): the world point (X, Y, 1) projects to pixel (f X, f Y).
template <class T>
mpr::PinholeCamera<T> simple_camera(T f, int w, int h) {
  mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
  K(0, 0) = f;
  K(1, 1) = f;
  return mpr::PinholeCamera<T>(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>::Zero(), w, h);
}

/// A triangle in the plane z = 1 whose vertices project to the given pixel coordinates (f = 8).
template <class T>
mpr::scene::Mesh<T> pixel_triangle(T x0, T y0, T x1, T y1, T x2, T y2) {
  mpr::scene::Mesh<T> m;
  m.positions = {{x0 / 8, y0 / 8, 1}, {x1 / 8, y1 / 8, 1}, {x2 / 8, y2 / 8, 1}};
  m.triangles = {{0, 1, 2}};
  return m;
}

} // namespace

TEMPLATE_TEST_CASE("top-left fill rule: shared edges and vertices are covered exactly once", "[scene][raster]", float,
                   double) {
  using T = TestType;
  // A 4 x 4 grid of cells, vertices on pixel centres, both diagonals mixed: every edge passes
  // through pixel centres. Small cells use the per-pixel edge test, large ones (>= 16 pixels
  // wide) the exact per-row span solver; both must give the same rule.
  const int cell = GENERATE(4, 19);
  const int w = 4 * cell + 8, h = w;
  const auto camera = simple_camera<T>(8, w, h);
  mpr::Image<int> count(w, h, 0);
  int triangles = 0;
  const auto add = [&](T x0, T y0, T x1, T y1, T x2, T y2) {
    mpr::scene::Scene<T> s;
    s.add(pixel_triangle<T>(x0, y0, x1, y1, x2, y2));
    const auto r = mpr::scene::rasterize(s, camera, {.threads = 1});
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (std::isfinite(r.depth(x, y))) ++count(x, y);
    ++triangles;
  };
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const T x0 = T(2 + cell * i), y0 = T(2 + cell * j), x1 = x0 + T(cell), y1 = y0 + T(cell);
      if ((i + j) % 2) {
        add(x0, y0, x1, y0, x1, y1);
        add(x0, y0, x1, y1, x0, y1); // clockwise on screen: orientation must not matter
      } else {
        add(x0, y0, x1, y0, x0, y1);
        add(x1, y0, x1, y1, x0, y1);
      }
    }
  const int last = 2 + 4 * cell;
  int once = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      REQUIRE(count(x, y) <= 1); // no double coverage
      if (x >= 2 && x < last && y >= 2 && y < last) {
        CHECK(count(x, y) == 1); // no cracks; the top and left borders are in, bottom/right out
        ++once;
      } else {
        CHECK(count(x, y) == 0);
      }
    }
  CHECK(triangles == 32);
  CHECK(once == (4 * cell) * (4 * cell));
}

TEMPLATE_TEST_CASE("the z-buffer keeps the nearest surface whatever the order", "[scene][raster]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto camera = simple_camera<T>(8, 16, 16);
  for (bool near_first : {true, false}) {
    mpr::scene::Scene<T> s;
    const auto near = mpr::scene::quad<T>(V(0, 0, 1), V(2, 0, 0), V(0, 2, 0), mpr::Color(1, 0, 0));
    const auto far = mpr::scene::quad<T>(V(0, 0, 3), V(6, 0, 0), V(0, 6, 0), mpr::Color(0, 1, 0));
    if (near_first) {
      s.add(near);
      s.add(far);
    } else {
      s.add(far);
      s.add(near);
    }
    const auto r = mpr::scene::rasterize(s, camera, {.threads = 2});
    CHECK(r.depth(8, 8) == Approx(1));
    CHECK(r.color(8, 8)[0] > 0);
    CHECK(r.color(8, 8)[1] == 0);
  }
}

TEMPLATE_TEST_CASE("near-plane clipping: a floor passing under and behind the camera", "[scene][raster]", float,
                   double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  // Camera 1.5 above an infinite-looking floor, looking horizontally along -z.
  const int w = 64, h = 48;
  const auto camera = mpr::PinholeCamera<T>::look_at(V(0, 1.5, 0), V(0, 1.5, -1), V(0, 1, 0), T(1.2), w, h);
  mpr::scene::Scene<T> s;
  s.add(mpr::scene::quad<T>(V(-500, 0, 500), V(1000, 0, 0), V(0, 0, -1000), mpr::Color(1, 1, 1)));
  const auto r = mpr::scene::rasterize(s, camera, {.threads = 2});
  const T f = camera.K()(1, 1), cy = camera.K()(1, 2);
  int checked = 0;
  for (int y = 0; y < h; ++y) {
    const T below = static_cast<T>(y) - cy; // pixels below the horizon
    for (int x = 0; x < w; ++x) {
      if (below > 1) {
        // A floor point at depth z appears f * 1.5 / z pixels below the horizon.
        const T expected = f * T(1.5) / below;
        if (expected < 490) {
          CHECK(r.depth(x, y) == Approx(expected).epsilon(1e-4));
          ++checked;
        }
      } else if (below < -1) {
        CHECK(std::isinf(r.depth(x, y)));
        CHECK((r.color(x, y) == s.background()).all());
      }
    }
  }
  CHECK(checked > 500);
}

TEMPLATE_TEST_CASE("perspective-correct interpolation matches the ray caster", "[scene][raster]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  // A strongly slanted triangle with red/green/blue vertices: affine interpolation in screen
  // space would be far off; perspective-correct interpolation agrees with the exact ray hit.
  mpr::scene::Mesh<T> m;
  m.positions = {V(-2, -1, 1.5), V(2, -1, 1.5), V(0, -1, 30)};
  m.colors = {mpr::Color(1, 0, 0), mpr::Color(0, 1, 0), mpr::Color(0, 0, 1)};
  m.triangles = {{0, 1, 2}};
  auto scene = std::make_shared<mpr::scene::Scene<T>>();
  scene->add(m);
  mpr::scene::Lighting<T> light;
  light.ambient = mpr::Color(1, 1, 1);
  light.diffuse = mpr::Color(0, 0, 0);
  scene->set_lighting(light);
  const int w = 80, h = 60;
  const auto camera = mpr::PinholeCamera<T>::look_at(V(0, 0, 0), V(0, 0, 1), V(0, 1, 0), T(1.0), w, h);
  const auto r = mpr::scene::rasterize(*scene, camera, {.threads = 1});
  const auto plane = camera.image_plane(T(1));
  const mpr::Renderer caster(
      plane, mpr::pinhole_glc(camera, plane),
      mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>(std::shared_ptr<const mpr::scene::Scene<T>>(scene)));
  mpr::Image<mpr::Color> cast(w, h);
  caster.render(cast.view(), mpr::Region(0, 0, w, h), {1});
  int compared = 0;
  float worst = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!std::isfinite(r.depth(x, y)) || (cast(x, y) == scene->background()).all()) continue;
      worst = std::max(worst, (r.color(x, y) - cast(x, y)).abs().maxCoeff());
      ++compared;
    }
  INFO("worst colour difference " << worst << " over " << compared << " pixels");
  CHECK(compared > 200);
  CHECK(worst < 2e-3f);
}

TEST_CASE("the rasterized image does not depend on threads or tile size", "[scene][raster]") {
  const auto scene = mpr::scene::classroom<float>();
  const auto camera = mpr::PinholeCamera<float>::look_at({2, 1.6f, 4}, {-1, 1, -10}, {0, 1, 0}, 1.1f, 120, 90);
  const auto a = mpr::scene::rasterize(scene, camera, {.threads = 1, .tile = 32});
  const auto b = mpr::scene::rasterize(scene, camera, {.threads = 3, .tile = 16});
  const auto c = mpr::scene::rasterize(scene, camera, {.threads = 2, .tile = 128});
  CHECK(a.color == b.color);
  CHECK(a.color == c.color);
  CHECK(a.depth == b.depth);
  CHECK(a.depth == c.depth);
}

TEST_CASE("rasterize rejects bad buffers, cameras and options", "[scene][raster][bad_input]") {
  const auto scene = mpr::scene::classroom<float>();
  const auto camera = simple_camera<float>(8, 16, 16);
  mpr::Image<mpr::Color> color(16, 16), small(8, 16);
  mpr::Image<float> depth(16, 16);
  CHECK_THROWS_AS(mpr::scene::rasterize(scene, camera, small.view(), depth.view()), mpr::argument_error);
  CHECK_THROWS_AS(mpr::scene::rasterize(scene, camera, color.view(), depth.view(), {.near = 0}), mpr::argument_error);
  CHECK_THROWS_AS(mpr::scene::rasterize(scene, camera, color.view(), depth.view(), {.tile = 4}), mpr::argument_error);
  const mpr::PinholeCamera<float> distorted(camera.K(), camera.R(), camera.t(), 16, 16, {0.1f, 0});
  CHECK_THROWS_WITH(mpr::scene::rasterize(scene, distorted, color.view(), depth.view()), Catch::Contains("distortion"));
  // An empty scene renders the background.
  const auto r = mpr::scene::rasterize(mpr::scene::Scene<float>{}, camera);
  CHECK(std::isinf(r.depth(3, 3)));
}

TEMPLATE_TEST_CASE("the z-buffer: coincident triangles tie, and the earlier triangle keeps the pixel",
                   "[scene][raster]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto camera = simple_camera<T>(8, 16, 16);
  // Two copies of the same quad at z = 2 (equal depth at every pixel), red and green, added in
  // both orders: every covered pixel shows the one added first, whatever the threads and tiles.
  for (const bool red_first : {true, false})
    for (const int threads : {1, 3}) {
      mpr::scene::Scene<T> s;
      const auto red = mpr::scene::quad<T>(V(0, 0, 2), V(3, 0, 0), V(0, 3, 0), mpr::Color(1, 0, 0));
      const auto green = mpr::scene::quad<T>(V(0, 0, 2), V(3, 0, 0), V(0, 3, 0), mpr::Color(0, 1, 0));
      s.add(red_first ? red : green);
      s.add(red_first ? green : red);
      const auto r = mpr::scene::rasterize(s, camera, {.threads = threads});
      int covered = 0, wrong = 0;
      for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
          if (!std::isfinite(static_cast<double>(r.depth(x, y)))) continue;
          ++covered;
          const mpr::Color c = r.color(x, y);
          const bool shows_red = c[0] > 0 && c[1] == 0, shows_green = c[1] > 0 && c[0] == 0;
          wrong += (red_first ? shows_red : shows_green) ? 0 : 1;
        }
      INFO((red_first ? "red" : "green") << " first, " << threads << " threads");
      CHECK(covered == 144); // the quad spans pixels [0, 12) x [0, 12) (f = 8, side 3 at z = 2)
      CHECK(wrong == 0);
    }
}
