#include "glc_test_util.hpp"

#include <mpr/core/image.hpp>
#include <mpr/render/renderer.hpp>
#include <mpr/glc/gallery.hpp>
#include <mpr/glc/rectify.hpp>
#include <mpr/scene/checkerboard_plane.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using mpr::glc::Type;

namespace {

// The demo's setup: an image plane 10 units wide, 9 units up and 9 back from a board at the origin.
template <class T>
mpr::PlanarSurface<T> demo_plane() {
  using V = mpr::Vec3<T>;
  const V eye(0, 6, 9);
  const V forward = (V(0, 0, 0) - eye).normalized();
  const V right = forward.cross(V::UnitY()).normalized();
  const V down = forward.cross(right);
  return mpr::PlanarSurface<T>::centred(eye, T(10) * right, T(10) * down);
}

template <class Surface, class Selector, class Sampler>
bool renders_finite(const Surface& s, const Selector& r, const Sampler& m) {
  const mpr::Renderer renderer(s, r, m);
  mpr::Image<mpr::Color> image(48, 48);
  renderer.render(image.view(), mpr::Region(0, 0, 48, 48), mpr::RenderOptions{1});
  // Also the raw rays: finite origin and direction everywhere.
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) {
      const auto ray = renderer.ray_at({x, y}, mpr::Region(0, 0, 48, 48));
      if (!ray.origin.allFinite() || !ray.direction.allFinite()) return false;
      if (!image(x, y).allFinite()) return false;
    }
  return true;
}

} // namespace

TEMPLATE_TEST_CASE("gallery: the nine views classify as their types", "[glc][gallery]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto plane = demo_plane<T>();
  REQUIRE(mpr::glc::gallery.size() == 9);
  // Several scene sizes and distances, including a scene smaller than the plane and far away.
  for (const T scale : {T(4), T(12), T(40)})
    for (const V& centre : {V(0, 0, 0), V(2, -1, -3), V(0, -60, -90)}) {
      for (const auto& entry : mpr::glc::gallery) {
        INFO("view " << entry.id << " scale " << scale << " centre " << centre.transpose());
        const auto sel = mpr::glc::gallery_view(entry.id, plane, centre, scale);
        CHECK(mpr::glc::classify(plane, sel).type == entry.type);
      }
    }
  CHECK_THROWS_WITH(mpr::glc::gallery_view('J', plane, V::Zero(), T(1)), Catch::Contains("id"));
  CHECK_THROWS_WITH(mpr::glc::gallery_view('A', plane, V(0, 12, 18), T(1)), Catch::Contains("scene_centre"));
  CHECK_THROWS_WITH(mpr::glc::gallery_view('A', plane, V::Zero(), T(0)), Catch::Contains("scale"));
  CHECK(mpr::glc::classify(plane, mpr::glc::gallery_view('g', plane, V::Zero(), T(12))).type == Type::cross_slit);
}

TEMPLATE_TEST_CASE("gallery: rendering never produces NaN or Inf, through slits and with near-parallel rays",
                   "[glc][gallery][render]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto plane = demo_plane<T>();
  const V centre = V::Zero();
  typename mpr::CheckerboardPlane<T>::Config ground;
  ground.cell_u = V(1, 0, 0);
  ground.cell_v = V(0, 0, 1);
  const mpr::CheckerboardPlane<T> board(ground);
  for (const auto& entry : mpr::glc::gallery) {
    INFO("view " << entry.id);
    const auto sel = mpr::glc::gallery_view(entry.id, plane, centre, T(12));
    CHECK(renders_finite(plane, sel, board));
    const auto cl = mpr::glc::classify(plane, sel);
    // A board through each slit (or the pinhole centre), facing along the plane normal: rays
    // cross it exactly at the slit.
    for (int k = 0; k < std::max(cl.slit_count, cl.type == Type::pinhole ? 1 : 0); ++k) {
      typename mpr::CheckerboardPlane<T>::Config at_slit;
      at_slit.origin = cl.type == Type::pinhole ? cl.centre : cl.slits[static_cast<std::size_t>(k)].point;
      at_slit.cell_u = plane.width_vector().normalized() / T(3);
      at_slit.cell_v = plane.height_vector().normalized() / T(3);
      CHECK(renders_finite(plane, sel, mpr::CheckerboardPlane<T>(at_slit)));
    }
    // A board almost parallel to the rays at the image centre (1e-6 rad off).
    const mpr::Ray<T> mid = sel.ray_at({0, 0}, {T(0.5), T(0.5)}, plane.centre());
    typename mpr::CheckerboardPlane<T>::Config grazing;
    grazing.origin = plane.centre() + T(5) * mid.direction;
    grazing.cell_u = mid.direction.normalized();
    grazing.cell_v = (plane.width_vector().normalized() + T(1e-6) * plane.normal()).normalized();
    CHECK(renders_finite(plane, sel, mpr::CheckerboardPlane<T>(grazing)));
  }
  // Rays almost parallel to the image plane: an oblique orthographic camera 1e-4 rad from
  // grazing, and a bilinear one whose rays turn to grazing at the image corners.
  const auto steep = mpr::glc::oblique_orthographic(plane, T(1.5707), T(0));
  CHECK(renders_finite(plane, steep, board));
  CHECK(mpr::glc::classify(plane, steep).type == Type::orthographic);
  const auto twisting = mpr::glc::bilinear(plane, plane.normal(), T(0), T(1e3));
  CHECK(renders_finite(plane, twisting, board));
  CHECK(mpr::glc::classify(plane, twisting).type == Type::bilinear);
}

TEMPLATE_TEST_CASE("gallery: rectified views render finite and put the scene square into the image",
                   "[glc][gallery][rectify]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  const auto plane = demo_plane<T>();
  typename mpr::CheckerboardPlane<T>::Config ground;
  ground.cell_u = V(1, 0, 0);
  ground.cell_v = V(0, 0, 1);
  const mpr::CheckerboardPlane<T> board(ground);
  // The square of side 12 on the ground, centred at the origin.
  const std::array<V, 4> square{V(-6, 0, -6), V(6, 0, -6), V(6, 0, 6), V(-6, 0, 6)};
  for (const char id : {'C', 'I', 'D'}) {
    INFO("view " << id);
    const auto sel = mpr::glc::gallery_view(id, plane, V::Zero(), T(12));
    const auto quad = mpr::glc::target_region(plane, sel, square);
    const auto rect = mpr::glc::rectify(plane, sel, quad);
    CHECK(renders_finite(rect.surface, rect.selector, board));
    // Output corner k shows square corner k.
    const std::array<mpr::Vec2<T>, 4> corners{mpr::Vec2<T>(0, 0), mpr::Vec2<T>(1, 0), mpr::Vec2<T>(1, 1),
                                              mpr::Vec2<T>(0, 1)};
    for (std::size_t k = 0; k < 4; ++k) {
      const mpr::Ray<T> r = rect.selector.ray_at({0, 0}, corners[k], rect.surface.point_at(corners[k]));
      CHECK(glc_test::distance_to_line(r, square[k]) <= (sizeof(T) == 4 ? 1e-3 : 1e-9) * 20);
    }
  }
}
