#include <catch2/catch.hpp>

#include <mpr/lightfield/camera_index.hpp>

#include <random>
#include <vector>

TEMPLATE_TEST_CASE("CameraCentreIndex::nearest equals the brute-force choice", "[camera_frame_index]", float, double) {
  using T = TestType;
  std::mt19937 rng(2004);
  std::uniform_real_distribution<double> u(-1, 1);
  // A jittered 10 x 9 planar grid (the LFCA layout), a ring and a random cloud.
  std::vector<std::vector<mpr::Vec3<T>>> layouts(3);
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 10; ++i)
      layouts[0].emplace_back(static_cast<T>(i + 0.1 * u(rng)), static_cast<T>(j + 0.1 * u(rng)), T(0));
  for (int k = 0; k < 16; ++k)
    layouts[1].emplace_back(static_cast<T>(std::cos(k * 0.3927)), T(0.1), static_cast<T>(std::sin(k * 0.3927)));
  for (int k = 0; k < 200; ++k)
    layouts[2].emplace_back(static_cast<T>(u(rng)), static_cast<T>(u(rng)), static_cast<T>(u(rng)));
  for (const auto& centres : layouts) {
    const mpr::CameraCentreIndex<T> index(centres);
    REQUIRE(index.size() == centres.size());
    int mismatches = 0;
    for (int q = 0; q < 3000; ++q) {
      const mpr::Vec3<T> o(static_cast<T>(5 * u(rng)), static_cast<T>(5 * u(rng)), static_cast<T>(5 + 3 * u(rng)));
      const mpr::Vec3<T> d(static_cast<T>(0.5 * u(rng)), static_cast<T>(0.5 * u(rng)),
                           static_cast<T>(1 + 0.2 * u(rng)));
      const int a = index.nearest(o, d), b = index.nearest_brute_force(o, d);
      if (a != b) ++mismatches;
      // within() finds exactly the centres a linear scan finds.
      const T r = T(0.8);
      std::vector<int> found;
      index.within(o, d, r, [&](int i, T dist) {
        found.push_back(i);
        CHECK(dist < r);
      });
      const T inv = T(1) / d.squaredNorm();
      std::size_t expected = 0;
      for (const auto& c : centres)
        if (mpr::line_distance2(c, o, d, inv) < r * r) ++expected;
      CHECK(found.size() == expected);
    }
    CHECK(mismatches == 0);
  }
}

TEST_CASE("CameraCentreIndex handles empty sets, ties and degenerate lines", "[camera_frame_index]") {
  const mpr::CameraCentreIndex<double> empty{std::vector<mpr::Vec3<double>>{}};
  CHECK(empty.nearest({0, 0, 0}, {0, 0, 1}) == -1);
  const std::vector<mpr::Vec3<double>> pair{{-1, 0, 0}, {1, 0, 0}, {1, 0, 0}};
  const mpr::CameraCentreIndex<double> index(pair);
  CHECK(index.nearest({0, 0, 5}, {0, 0, 1}) == 0);   // exact tie: lowest index
  CHECK(index.nearest({0.5, 0, 5}, {0, 0, 1}) == 1); // duplicate centres: lowest index
  CHECK(index.nearest({0, 0, 5}, {0, 0, 0}) == -1);
  CHECK(index.nearest({0, 0, 5}, {std::nan(""), 0, 1}) == -1);
}
