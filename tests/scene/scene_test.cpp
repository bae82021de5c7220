#include <mpr/scene/scene.hpp>
#include <mpr/scene/shapes.hpp>
#include <mpr/scene/texture.hpp>

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <map>

namespace {

template <class T>
mpr::scene::Mesh<T> one_triangle() {
  mpr::scene::Mesh<T> m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}};
  return m;
}

/// Every directed edge of a closed, consistently oriented surface appears exactly once, and its
/// reverse exactly once (positions compared by value, since builders duplicate vertices).
template <class T>
bool closed_and_consistent(const mpr::scene::Scene<T>& scene) {
  std::map<std::array<T, 6>, int> edges;
  for (const auto& t : scene.triangles())
    for (int j = 0; j < 3; ++j) {
      const auto& a = t.p[j];
      const auto& b = t.p[(j + 1) % 3];
      ++edges[{a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}];
    }
  for (const auto& [e, count] : edges) {
    if (count != 1) return false;
    const auto reverse = edges.find({e[3], e[4], e[5], e[0], e[1], e[2]});
    if (reverse == edges.end() || reverse->second != 1) return false;
  }
  return true;
}

template <class T>
bool outward(const mpr::scene::Scene<T>& scene, const mpr::Vec3<T>& centre) {
  for (const auto& t : scene.triangles()) {
    const mpr::Vec3<T> centroid = (t.p[0] + t.p[1] + t.p[2]) / T(3);
    if (!(t.normal.dot(centroid - centre) > 0)) return false;
  }
  return true;
}

} // namespace

TEMPLATE_TEST_CASE("shape builders make closed, outward-facing meshes", "[scene][shapes]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  SECTION("box") {
    mpr::scene::Scene<T> s;
    CHECK(s.add(mpr::scene::box<T>(V(-1, 0, 2), V(1, 3, 2.5), mpr::Color(1, 0, 0))) == 12);
    CHECK(closed_and_consistent(s));
    CHECK(outward(s, V(0, 1.5, 2.25)));
  }
  SECTION("sphere") {
    mpr::scene::Scene<T> s;
    CHECK(s.add(mpr::scene::sphere<T>(V(1, 2, 3), T(0.5), mpr::Color(1, 1, 1), 12, 7)) == 12 * 2 * 6);
    CHECK(s.degenerate_skipped() == 0);
    CHECK(closed_and_consistent(s));
    CHECK(outward(s, V(1, 2, 3)));
    for (const auto& t : s.triangles())
      for (const auto& p : t.p) CHECK((p - V(1, 2, 3)).norm() == Approx(0.5).epsilon(1e-5));
  }
  SECTION("cylinder") {
    mpr::scene::Scene<T> s;
    CHECK(s.add(mpr::scene::cylinder<T>(V(0, 0, 0), V(0, 0, 2), T(0.3), mpr::Color(1, 1, 1), 10)) == 40);
    CHECK(closed_and_consistent(s));
    CHECK(outward(s, V(0, 0, 1)));
  }
  SECTION("quad normal and texture coordinates") {
    const auto q = mpr::scene::quad<T>(V(0, 0, 0), V(2, 0, 0), V(0, 0, -3), mpr::Color(1, 1, 1), T(4), T(6));
    mpr::scene::Scene<T> s;
    s.add(q);
    for (const auto& t : s.triangles()) CHECK(t.normal.y() == Approx(1));
    CHECK(q.uvs[3].x() == T(4)); // the corner origin + u + v
    CHECK(q.uvs[3].y() == T(6));
    const auto cells = mpr::scene::quad<T>(V(0, 0, 0), V(3, 0, 0), V(0, 2, 0), mpr::Color(1, 1, 1), T(1), T(1), 3, 2);
    CHECK(cells.triangles.size() == 12);
    CHECK(cells.positions.size() == 12); // shared grid vertices
    CHECK_THROWS_AS(mpr::scene::quad<T>(V(0, 0, 0), V(3, 0, 0), V(0, 2, 0), mpr::Color(1, 1, 1), T(1), T(1), 0, 2),
                    mpr::argument_error);
  }
  SECTION("bad arguments") {
    const mpr::Color c(1, 1, 1);
    const T nan = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_AS(mpr::scene::box<T>(V(0, 0, 0), V(1, 0, 1), c), mpr::argument_error);
    CHECK_THROWS_AS(mpr::scene::box<T>(V(nan, 0, 0), V(1, 1, 1), c), mpr::argument_error);
    CHECK_THROWS_AS(mpr::scene::sphere<T>(V(0, 0, 0), T(0), c), mpr::argument_error);
    CHECK_THROWS_AS(mpr::scene::sphere<T>(V(0, 0, 0), T(1), c, 2, 5), mpr::argument_error);
    CHECK_THROWS_AS(mpr::scene::cylinder<T>(V(0, 0, 0), V(0, 0, 0), T(1), c), mpr::argument_error);
    CHECK_THROWS_AS(mpr::scene::quad<T>(V(0, 0, 0), V(1, 0, 0), V(2, 0, 0), c), mpr::argument_error);
  }
}

TEMPLATE_TEST_CASE("Scene::add rejects bad meshes with clear errors", "[scene][bad_input]", float, double) {
  using T = TestType;
  mpr::scene::Scene<T> s;
  auto m = one_triangle<T>();
  SECTION("empty mesh") {
    m.triangles.clear();
    CHECK_THROWS_WITH(s.add(m, "empty"), Catch::Contains("empty") && Catch::Contains("no triangles"));
  }
  SECTION("NaN vertex") {
    m.positions[1].y() = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_WITH(s.add(m, "bunny"), Catch::Contains("bunny") && Catch::Contains("position 1"));
  }
  SECTION("infinite vertex") {
    m.positions[2].z() = std::numeric_limits<T>::infinity();
    CHECK_THROWS_AS(s.add(m), mpr::argument_error);
  }
  SECTION("index out of range") {
    m.triangles[0][2] = 3;
    CHECK_THROWS_WITH(s.add(m), Catch::Contains("index 3"));
  }
  SECTION("colour count") {
    m.colors = {mpr::Color(1, 0, 0)};
    CHECK_THROWS_WITH(s.add(m), Catch::Contains("colors"));
  }
  SECTION("texture that was never added") {
    m.texture = 0;
    m.uvs.assign(3, mpr::Vec2<T>::Zero());
    CHECK_THROWS_WITH(s.add(m), Catch::Contains("texture 0"));
  }
  SECTION("textured mesh without uvs") {
    m.texture =
        s.add_texture(mpr::scene::Texture(mpr::scene::checker_image(2, 2, mpr::Color(1, 1, 1), mpr::Color(0, 0, 0))));
    CHECK_THROWS_WITH(s.add(m), Catch::Contains("uv"));
  }
  CHECK(s.empty()); // nothing half-added
}

TEMPLATE_TEST_CASE("degenerate triangles are skipped and counted", "[scene][bad_input]", float, double) {
  using T = TestType;
  mpr::scene::Mesh<T> m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {1e-30, 0, 0}};
  m.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 0, 2}, {1, 1, 1}, {0, 4, 2}};
  mpr::scene::Scene<T> s;
  // Skipped: collinear {0,1,3}, repeated indices {0,0,2} and {1,1,1}, and the sliver {0,4,2}
  // whose area relative to its squared edge length (~1e-30) is far below rounding.
  CHECK(s.add(m) == 1);
  CHECK(s.degenerate_skipped() == 4);
  CHECK(s.textured_triangles() == 0);
}

TEST_CASE("textures wrap, use OBJ orientation and survive NaN", "[scene][texture]") {
  mpr::Image<mpr::Color> image(2, 2);
  image(0, 0) = mpr::Color(1, 0, 0); // top-left
  image(1, 0) = mpr::Color(0, 1, 0); // top-right
  image(0, 1) = mpr::Color(0, 0, 1); // bottom-left
  image(1, 1) = mpr::Color(1, 1, 1);
  const mpr::scene::Texture tex(image);
  CHECK((tex.sample(0.25f, 0.25f) == mpr::Color(0, 0, 1)).all()); // v up: bottom row
  CHECK((tex.sample(0.75f, 0.75f) == mpr::Color(0, 1, 0)).all());
  CHECK((tex.sample(1.25f, -0.75f) == mpr::Color(0, 0, 1)).all()); // repeat
  CHECK((tex.sample(std::nanf(""), 0.75f) == mpr::Color(1, 0, 0)).all());
  CHECK_THROWS_AS(mpr::scene::Texture(mpr::Image<mpr::Color>()), mpr::argument_error);
  CHECK_THROWS_AS(mpr::scene::checker_image(5, 2, mpr::Color(1, 1, 1), mpr::Color(0, 0, 0)), mpr::argument_error);
  CHECK_THROWS_AS(mpr::scene::grid_image(8, 8, mpr::Color(1, 1, 1), mpr::Color(0, 0, 0)), mpr::argument_error);
}

TEMPLATE_TEST_CASE("Lambert shading: ambient plus the lit side only", "[scene][shading]", float, double) {
  using T = TestType;
  mpr::scene::Scene<T> s;
  auto m = one_triangle<T>(); // normal +z
  m.color = mpr::Color(0.5f, 0.5f, 0.5f);
  s.add(m);
  mpr::scene::Lighting<T> light;
  light.ambient = mpr::Color(0.1f, 0.1f, 0.1f);
  light.diffuse = mpr::Color(1, 1, 1);
  light.towards_light = mpr::Vec3<T>(0, 0, 2); // straight above the front side
  s.set_lighting(light);
  CHECK(s.shade(0, T(0.2), T(0.2), true)[0] == Approx(0.5f * 1.1f));
  CHECK(s.shade(0, T(0.2), T(0.2), false)[0] == Approx(0.05f)); // back side: ambient only
  light.towards_light = mpr::Vec3<T>(0, 0, 0);
  CHECK_THROWS_AS(s.set_lighting(light), mpr::argument_error);
  CHECK_THROWS_AS(s.set_background(mpr::Color(std::nanf(""), 0, 0)), mpr::argument_error);
}

TEMPLATE_TEST_CASE("vertex colours interpolate, uniform colours stay exact", "[scene][shading]", float, double) {
  using T = TestType;
  mpr::scene::Scene<T> s;
  auto m = one_triangle<T>();
  m.colors = {mpr::Color(1, 0, 0), mpr::Color(0, 1, 0), mpr::Color(0, 0, 1)};
  s.add(m);
  auto u = one_triangle<T>();
  u.color = mpr::Color(0.3f, 0.6f, 0.9f);
  s.add(u);
  mpr::scene::Lighting<T> light;
  light.ambient = mpr::Color(1, 1, 1);
  light.diffuse = mpr::Color(0, 0, 0);
  s.set_lighting(light);
  // Weights 0.3, 0.2, 0.5 for p[0], p[1], p[2]: all different, so exchanging any two shows.
  const mpr::Color c = s.shade(0, T(0.2), T(0.5), true);
  CHECK(c[0] == Approx(0.3f));
  CHECK(c[1] == Approx(0.2f));
  CHECK(c[2] == Approx(0.5f));
  CHECK(!s.triangles()[0].uniform_color);
  CHECK(s.triangles()[1].uniform_color);
  CHECK((s.shade(1, T(0.1), T(0.7), true) == mpr::Color(0.3f, 0.6f, 0.9f)).all());
}
