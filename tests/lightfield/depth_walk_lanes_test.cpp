// The sixteen-lane walk (lightfield/detail/depth_walk_lanes.hpp) against the per-ray walk
// (detail/depth_walk.hpp), lane by lane, from first-camera searches and from searches that
// earlier cameras left (a t further on, a stretch seen free): the same outcome (surface,
// escaped, passed on) and the same search afterwards, bit for bit in builds whose per-ray code
// has no fused multiply-add.
#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield.hpp>
#include <mpr/lightfield/detail/depth_walk_lanes.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#if defined(MPR_SIMD_X86)

namespace {

using Table = mpr::FrameTable<float, mpr::Color>;

MPR_TARGET_AVX512 void walk16(const Table::Camera& c, const float* d, float near, const mpr::detail::RayLanes& r,
                              unsigned lanes, const mpr::detail::WalkLanesResult& from, float tolerance,
                              mpr::detail::WalkLanesResult& out) {
  mpr::detail::walk_lanes16(c, d, near, r, lanes, from, tolerance, out);
}

bool same(float a, float b) {
#if defined(__FMA__) || defined(__FP_FAST_FMAF)
  return a == b || std::abs(a - b) <= 1e-4f * std::max(std::abs(a), std::abs(b)) || (std::isnan(a) && std::isnan(b));
#else
  return a == b || (std::isnan(a) && std::isnan(b));
#endif
}

} // namespace

TEST_CASE("walk_lanes16 ends every walk as depth_walk does", "[depth_proxy][simd]") {
  if (mpr::detail::simd_level() < mpr::detail::SimdLevel::avx512) {
    // Visible in every run's output (Catch prints WARN messages of passing tests): this check did
    // not run here. The per-ray walk it compares against is tested at every level
    // (depth_proxy_test, depth_walk_test).
    WARN("walk_lanes16 NOT TESTED: no AVX-512 on this CPU (or MPR_SIMD below it)");
    SUCCEED("skipped");
    return;
  }
  // One camera of a 3 x 3 grid (40 x 30 pixels) and a map with a near plane, a far step, a hole
  // that shows nothing (+inf) and a strip nearer than everything: rays hit, pass behind the
  // near strip, start behind it, leave the image, or escape through the hole.
  const auto cams = mpr_test::grid_cameras<float>(3, 3, 1.0, 40, 30, 30.0);
  std::vector<mpr::Image<float>> maps(cams.size(), mpr::Image<float>(40, 30, 5.0f));
  mpr::Image<float>& map = maps[4];
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      if (x >= 26) map(x, y) = 8.0f;
      if (x < 14 && y < 12) map(x, y) = std::numeric_limits<float>::infinity();
      if (y >= 24) map(x, y) = 2.0f;
    }
  const auto frames = std::make_shared<const mpr::CameraFrameSet<float, mpr::Color>>(
      mpr::CameraFrameSet<float, mpr::Color>(cams, mpr_test::plane_images(cams, 5.0)).with_depth(std::move(maps)));
  const Table table(frames);
  const Table::Camera& cam = table.camera(4);
  const float* d = frames->depth(4).data();
  const float near = frames->depth_near(4);
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f), slope(-0.35f, 0.35f), depth(-2.0f, 1.0f);
  std::uniform_real_distribution<float> along(-1.0f, 8.0f), length(0.01f, 4.0f);
  std::uniform_int_distribution<int> kind(0, 5);
  const float inf = std::numeric_limits<float>::infinity();
  int outcomes[3] = {0, 0, 0};
  int stretched = 0, changed = 0; // lanes that start with a stretch seen free; whose stretch moved
  for (const float tolerance : {0.01f, 0.001f}) {
    for (const float start : {-std::numeric_limits<float>::infinity(), 0.0f}) {
      for (int round = 0; round < 120; ++round) {
        mpr::detail::RayLanes r;
        mpr::Ray<float> rays[16];
        // Half the rounds start where a first camera starts; the others from searches that
        // earlier cameras left: t further on, a stretch seen free before, around or after it.
        mpr::detail::WalkLanesResult from;
        for (int l = 0; l < 16; ++l) {
          from.t[l] = start;
          from.skip_begin[l] = from.skip_end[l] = inf;
          if (round % 2 == 0) continue;
          const int k = kind(rng);
          if (k >= 3) from.t[l] = std::max(start, along(rng));
          if (k % 3 != 0) {
            from.skip_begin[l] = k % 3 == 1 ? along(rng) : from.t[l] + length(rng) - 0.5f;
            from.skip_end[l] = from.skip_begin[l] + length(rng);
          }
        }
        for (int l = 0; l < 16; ++l) {
          const mpr::Vec3<float> o(u(rng), u(rng), depth(rng));
          mpr::Vec3<float> v(slope(rng), slope(rng), 1.0f);
          if (l == 15) v = mpr::Vec3<float>(0.0f, 0.0f, -1.0f); // toward the camera: out of its view
          rays[l] = {o, v};
          r.ox[l] = o.x();
          r.oy[l] = o.y();
          r.oz[l] = o.z();
          r.vx[l] = v.x();
          r.vy[l] = v.y();
          r.vz[l] = v.z();
          r.inverse_length2[l] = 1 / v.squaredNorm();
          r.length[l] = v.norm();
        }
        const unsigned lanes = round % 3 == 0 ? 0xFFFFu : 0xA5F3u;
        mpr::detail::WalkLanesResult w;
        walk16(cam, d, near, r, lanes, from, tolerance, w);
        CHECK((w.hit & w.escaped) == 0);
        CHECK((w.hit | w.escaped | w.passed) == lanes);
        for (int l = 0; l < 16; ++l) {
          if (!(lanes >> l & 1u)) continue;
          mpr::detail::DepthSearch<float> search{from.t[l], from.skip_begin[l], from.skip_end[l]};
          if (search.skip_begin < inf) ++stretched;
          const mpr::detail::DepthWalk expected =
              mpr::detail::depth_walk<float, mpr::Color>(cam, d, near, rays[l], tolerance, search);
          INFO("tolerance " << tolerance << ", start " << start << ", round " << round << ", lane " << l);
          if (expected == mpr::detail::DepthWalk::hit) {
            ++outcomes[0];
            REQUIRE((w.hit >> l & 1u));
            CHECK(same(w.t[l], search.t));
          } else if (expected == mpr::detail::DepthWalk::escaped) {
            ++outcomes[1];
            REQUIRE((w.escaped >> l & 1u));
          } else {
            ++outcomes[2];
            REQUIRE((w.passed >> l & 1u));
            CHECK(same(w.t[l], search.t));
            CHECK(same(w.skip_begin[l], search.skip_begin));
            CHECK(same(w.skip_end[l], search.skip_end));
            if (search.skip_begin != from.skip_begin[l] || search.skip_end != from.skip_end[l]) ++changed;
          }
        }
      }
    }
  }
  INFO("hit " << outcomes[0] << ", escaped " << outcomes[1] << ", passed " << outcomes[2] << "; stretches " << stretched
              << ", changed " << changed);
  CHECK(outcomes[0] > 600); // every outcome seen often
  CHECK(outcomes[1] > 40);
  CHECK(outcomes[2] > 600);
  CHECK(stretched > 1000);
  CHECK(changed > 100);
}

#endif
