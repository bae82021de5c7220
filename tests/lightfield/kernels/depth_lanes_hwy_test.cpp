// The lane kernels of DepthProxy's batch path (lightfield/kernels/depth_lanes_hwy.hpp) at every
// SIMD level this CPU runs: the walk against the per-ray walk ((depth_proxy/depth_walk.hpp)), lane by
// lane, from first-camera searches and from searches that earlier cameras left (a t further on,
// a stretch seen free), and the whole batch path (`sample_rays`, `surface_rays`) against
// `sample(ray)` and `surface(ray)` on 8-bit and float frames. Bit for bit in builds whose per-ray
// code has no fused multiply-add; with one, within a small tolerance (the walk) or for a few rays.
#include "lightfield/frame_test_scenes.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/core/config.hpp>
#include <mpr/lightfield/depth_proxy.hpp>
#include <mpr/lightfield/frame_sampler.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <vector>

#if MPR_HAVE_HWY && defined(MPR_SIMD_X86)

namespace {

using Table = mpr::FrameTable<float, mpr::Color>;

// Whether the per-ray code may have fused multiply-adds (then a few decisions at a threshold
// may go the other way).
constexpr bool kFused =
#if defined(__FMA__) || defined(__FP_FAST_FMAF)
    true;
#else
    false;
#endif

bool same(float a, float b) {
  if (kFused)
    return a == b || std::abs(a - b) <= 1e-4f * std::max(std::abs(a), std::abs(b)) || (std::isnan(a) && std::isnan(b));
  return a == b || (std::isnan(a) && std::isnan(b));
}

// The 3 x 3 plane set (cameras spacing 1, 40 x 30 pixels, focal 30, plane z = 5) with one map
// that holds a step to depth 3 and a hole of +inf, frames of texel type Px.
template <class Px>
std::shared_ptr<const mpr::CameraFrameSet<float, Px>> stepped_set() {
  const auto cams = mpr_test::grid_cameras<float>(3, 3, 1.0, 40, 30, 30.0);
  std::vector<mpr::Image<float>> maps(cams.size(), mpr::Image<float>(40, 30, 5.0f));
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      if (x > 25) maps[4](x, y) = 3.0f;
      if (x < 6 && y < 6) maps[4](x, y) = std::numeric_limits<float>::infinity();
    }
  auto images = mpr_test::plane_images(cams, 5.0);
  if constexpr (std::is_same_v<Px, mpr::Rgb8>)
    return std::make_shared<const mpr::CameraFrameSet<float, Px>>(
        mpr::CameraFrameSet<float, Px>(cams, mpr_test::with_detail(images, 3, 0x0F, 0x07, 0x1F))
            .with_depth(std::move(maps)));
  else
    return std::make_shared<const mpr::CameraFrameSet<float, Px>>(
        mpr::CameraFrameSet<float, Px>(cams, std::move(images)).with_depth(std::move(maps)));
}

// Random rays across the set: from the camera plane and from inside the maps' box, some
// running toward the cameras.
std::vector<mpr::Ray<float>> random_rays(unsigned seed, int n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-2, 2), slope(-0.4, 0.4), inside(2.5, 5.5);
  std::vector<mpr::Ray<float>> rays;
  for (int i = 0; i < n; ++i) {
    const double z = i % 4 == 0 ? inside(rng) : 0.0;
    rays.push_back(
        {mpr::Vec3<float>(static_cast<float>(u(rng)), static_cast<float>(u(rng)), static_cast<float>(z)),
         mpr::Vec3<float>(static_cast<float>(slope(rng)), static_cast<float>(slope(rng)), i % 7 == 0 ? -1.0f : 1.0f)});
  }
  rays.push_back({mpr::Vec3<float>(0, 0, 0), mpr::Vec3<float>::Zero()}); // no direction
  return rays;
}

// `sample_rays` and `surface_rays` at `level` over `rays`, in spans of 1 to 40 rays (partial
// groups of sixteen), against `sample` and `surface` per ray; returns the rays that differ.
template <class Px>
std::size_t batch_differs(const mpr::DepthProxy& proxy, const mpr::FrameTable<float, Px>& table,
                          const std::vector<mpr::Ray<float>>& rays, mpr::detail::SimdLevel level) {
  std::vector<mpr::Color> colour(rays.size());
  std::vector<std::optional<float>> t(rays.size());
  std::size_t at = 0;
  for (std::size_t length = 1; at < rays.size(); length = length % 40 + 1) {
    const std::size_t n = std::min(length, rays.size() - at);
    const auto group = std::span<const mpr::Ray<float>>(rays).subspan(at, n);
    proxy.sample_rays(table, group, std::span<mpr::Color>(colour).subspan(at, n), level);
    proxy.surface_rays(table, group, std::span<std::optional<float>>(t).subspan(at, n), level);
    at += n;
  }
  std::size_t differ = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const mpr::Color one = proxy.sample(table, rays[i]);
    const std::optional<float> s = proxy.surface(table, rays[i]);
    const bool agree =
        (colour[i].array() == one.array()).all() && t[i].has_value() == s.has_value() && (!s || same(*t[i], *s));
    differ += agree ? 0 : 1;
  }
  return differ;
}

} // namespace

TEST_CASE("walk_lanes ends every walk as depth_walk does, at every SIMD level", "[depth_proxy][simd]") {
  mpr_test::for_each_simd_level([](mpr::detail::SimdLevel level) {
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
    const mpr::detail::LaneCamera lane{cam.P, cam.centre.x(), cam.centre.y(), cam.centre.z(), cam.width, cam.height, d,
                                       near};
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f), slope(-0.35f, 0.35f), depth(-2.0f, 1.0f);
    std::uniform_real_distribution<float> along(-1.0f, 8.0f), length(0.01f, 4.0f);
    std::uniform_int_distribution<int> kind(0, 5);
    const float inf = std::numeric_limits<float>::infinity();
    int outcomes[3] = {0, 0, 0};
    int stretched = 0, changed = 0; // lanes that start with a stretch seen free; whose stretch moved
    const std::int64_t target = mpr::kernels::depth_lanes_target(level);
    if (target == 0) {
      WARN("walk_lanes NOT TESTED at this level: no SSE4.2 on this CPU");
      return;
    }
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
          mpr::kernels::walk_lanes(target, lane, r, lanes, from, tolerance, w);
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
    INFO("hit " << outcomes[0] << ", escaped " << outcomes[1] << ", passed " << outcomes[2] << "; stretches "
                << stretched << ", changed " << changed);
    CHECK(outcomes[0] > 600); // every outcome seen often
    CHECK(outcomes[1] > 40);
    CHECK(outcomes[2] > 600);
    CHECK(stretched > 1000);
    CHECK(changed > 100);
  });
}

TEST_CASE("DepthProxy's batch path answers as the per-ray path at every SIMD level", "[depth_proxy][simd]") {
  // 8-bit frames (the weighing in lanes) with the bilinear and nearest filters and float frames,
  // several radii and k (k = 7: the most slots the lanes keep; k = 8 the per-ray path), the line
  // and the half-line: at every level the lanes run at, every ray's colour and surface as per ray.
  const auto rays = random_rays(17, 700);
  const auto rgb8 = stepped_set<mpr::Rgb8>();
  const auto linear = stepped_set<mpr::Color>();
  mpr::FrameSamplerConfig<float> config;
  config.depth = 5.0f;
  config.background = mpr::Color(0.1f, 0.2f, 0.3f);
  const mpr::FrameTable<float, mpr::Rgb8> bilinear(rgb8, config);
  mpr::FrameSamplerConfig<float> nearest_config = config;
  nearest_config.filter = mpr::PixelFilter::nearest;
  const mpr::FrameTable<float, mpr::Rgb8> nearest(rgb8, nearest_config);
  const mpr::FrameTable<float, mpr::Color> floats(linear, config);
  mpr_test::for_each_simd_level([&](mpr::detail::SimdLevel level) {
    if (mpr::detail::depth_lanes_target(level) == 0) WARN("no lanes at this level (no SSE4.2): per ray on both sides");
    for (const int k : {1, 4, 7, 8})
      for (const double radius : {0.05, 1.5, 4.0})
        for (const bool whole_line : {true, false}) {
          mpr::DepthProxy proxy{radius, k};
          proxy.whole_line = whole_line;
          INFO("k = " << k << ", radius " << radius << ", whole_line " << whole_line);
          const std::size_t allowed = kFused ? rays.size() / 50 : 0;
          CHECK(batch_differs(proxy, bilinear, rays, level) <= allowed);
          CHECK(batch_differs(proxy, nearest, rays, level) <= allowed);
          CHECK(batch_differs(proxy, floats, rays, level) <= allowed);
        }
  });
}

#else
TEST_CASE("DepthProxy's lane kernels: not built here", "[depth_proxy]") {
  SUCCEED("no Highway or not x86: the batch path answers per ray");
}
#endif
