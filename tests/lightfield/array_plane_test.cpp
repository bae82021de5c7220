// ArrayPlane: the plane of a planar camera array, its neighbour lists and separations, checked
// by hand on a small grid, and the rejection of non-planar layouts.
#include <mpr/lightfield/array_plane.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

TEMPLATE_TEST_CASE("ArrayPlane::fit on a 3 x 2 grid", "[lightfield][array_plane]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  // Camera index = row * 3 + column, spacing 1, in the plane y = 4 (normal along y).
  std::vector<V> centres;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) centres.emplace_back(T(c), T(4), T(r));
  const auto plane = mpr::ArrayPlane<T>::fit(centres);
  REQUIRE(plane.has_value());
  CHECK(std::abs(std::abs(plane->normal.y()) - 1) < T(1e-6));
  CHECK(std::abs(plane->axis_u.dot(plane->normal)) < T(1e-6));
  CHECK(std::abs(plane->axis_v.dot(plane->normal)) < T(1e-6));
  CHECK((plane->point - V(1, 4, T(0.5))).norm() < T(1e-6));
  CHECK(plane->extent == Approx(std::sqrt(1.25)).epsilon(1e-6));
  // Corner camera 0 at (0, 0): nearest neighbours at distance 1 (cameras 1 and 3), the diagonal
  // camera 4 at sqrt(2) < 1.5 is listed too; the nearest unlisted (camera 2) is 2 away.
  const auto listed = [&](std::size_t i) {
    std::vector<int> n(plane->neighbours.begin() + plane->neighbours_begin[i],
                       plane->neighbours.begin() + plane->neighbours_end[i]);
    std::sort(n.begin(), n.end());
    return n;
  };
  CHECK(listed(0) == std::vector<int>{1, 3, 4});
  CHECK(plane->separation[0] == Approx(2).epsilon(1e-6));
  // Middle camera 1 at (1, 0): 0, 2 and 4 at distance 1, 3 and 5 at sqrt(2); none left.
  CHECK(listed(1) == std::vector<int>{0, 2, 3, 4, 5});
  CHECK(std::isinf(plane->separation[1]));
  // In-plane coordinates reproduce the distances.
  for (std::size_t i = 0; i < centres.size(); ++i)
    for (std::size_t j = 0; j < centres.size(); ++j) {
      const T du = plane->centre_u[i] - plane->centre_u[j], dv = plane->centre_v[i] - plane->centre_v[j];
      CHECK(std::sqrt(du * du + dv * dv) == Approx((centres[i] - centres[j]).norm()).margin(1e-5));
    }
  // hit(): a ray from (0.5, 0, 0.5) along (0, 2, 0) crosses y = 4 at (0.5, 4, 0.5), cosine 1.
  V x = V::Zero();
  T cosine = 0;
  REQUIRE(plane->hit(mpr::Ray<T>{V(T(0.5), 0, T(0.5)), V(0, 2, 0)}, x, cosine));
  CHECK((x - V(T(0.5), 4, T(0.5))).norm() < T(1e-5));
  CHECK(cosine == Approx(1));
  // A ray within 0.06 degrees of the plane has no reliable crossing.
  CHECK_FALSE(plane->hit(mpr::Ray<T>{V(0, 0, 0), V(1, T(1e-4), 0)}, x, cosine));
}

TEMPLATE_TEST_CASE("ArrayPlane::fit rejects layouts that are not planar arrays", "[lightfield][array_plane]", float,
                   double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  CHECK_FALSE(mpr::ArrayPlane<T>::fit(std::vector<V>{}).has_value());
  CHECK_FALSE(mpr::ArrayPlane<T>::fit(std::vector<V>{V(1, 2, 3)}).has_value());
  CHECK_FALSE(mpr::ArrayPlane<T>::fit(std::vector<V>{V(1, 2, 3), V(1, 2, 3)}).has_value());
  // A grid with one camera lifted by 1e-3 of the extent: not planar.
  std::vector<V> centres{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, T(1.5e-3))};
  CHECK_FALSE(mpr::ArrayPlane<T>::fit(centres).has_value());
  centres.back().z() = 0;
  CHECK(mpr::ArrayPlane<T>::fit(centres).has_value());
  // A ring (Middlebury-like) is not planar either when it has height.
  std::vector<V> ring;
  for (int k = 0; k < 16; ++k)
    ring.emplace_back(T(std::cos(k * 0.4)), T(std::sin(k * 0.4)), T(0.3 * std::sin(k * 1.3)));
  CHECK_FALSE(mpr::ArrayPlane<T>::fit(ring).has_value());
}

TEMPLATE_TEST_CASE("ArrayPlane::fit takes a known plane's normal instead of testing planarity",
                   "[lightfield][array_plane]", float, double) {
  using T = TestType;
  using V = mpr::Vec3<T>;
  // A 3 x 3 grid on z = 0 with one centre lifted by 1e-3 of the spacing: too far off for the
  // test of planarity (1e-6 of the extent), so an unknown plane is refused ...
  std::vector<V> centres;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) centres.emplace_back(T(c), T(r), T(0));
  centres[4].z() = T(1e-3);
  CHECK_FALSE(mpr::ArrayPlane<T>::fit(centres).has_value());
  // ... but a plane the caller declares is used as given (normal normalized), with in-plane
  // axes orthogonal to it and coordinates that reproduce the in-plane offsets.
  const auto plane = mpr::ArrayPlane<T>::fit(centres, mpr::Plane<T>{V::Zero(), V(0, 0, 2)});
  REQUIRE(plane.has_value());
  CHECK(plane->normal == V::UnitZ());
  CHECK(std::abs(plane->axis_u.dot(plane->normal)) < T(1e-6));
  CHECK(std::abs(plane->axis_v.dot(plane->normal)) < T(1e-6));
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const T du = plane->centre_u[i] - plane->centre_u[0], dv = plane->centre_v[i] - plane->centre_v[0];
    const T dx = centres[i].x() - centres[0].x(), dy = centres[i].y() - centres[0].y();
    CHECK(std::sqrt(du * du + dv * dv) == Approx(std::sqrt(dx * dx + dy * dy)).margin(1e-5));
  }
  // The same centres declared on a plane through them: identical to the fit of the exact grid.
  centres[4].z() = T(0);
  const auto fitted = mpr::ArrayPlane<T>::fit(centres);
  const auto given = mpr::ArrayPlane<T>::fit(centres, mpr::Plane<T>{V::Zero(), V::UnitZ()});
  REQUIRE(fitted.has_value());
  REQUIRE(given.has_value());
  CHECK(std::abs(fitted->normal.dot(given->normal)) == Approx(1));
  CHECK(fitted->neighbours == given->neighbours);
  CHECK(fitted->separation == given->separation);
}
