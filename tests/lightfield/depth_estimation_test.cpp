#include "lightfield/frame_test_scenes.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield/depth_estimation.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

namespace {

// A smooth texture on the plane z = depth: sums of sinusoids with periods of 1.3 to 4 units
// (10 to 32 pixels at z = 5 with focal 40), so that the images are band-limited (a hard-edged
// texture point-sampled per pixel biases every matcher towards whole-pixel disparities).
mpr::Rgb8 smooth_texture(double x, double y) {
  const auto channel = [&](double a, double b, double c, double d) {
    const double v = 0.5 + 0.25 * std::sin(a * x + b * y) + 0.2 * std::sin(c * x - d * y + 1.0);
    return static_cast<std::uint8_t>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
  };
  return mpr::Rgb8{channel(3.1, 1.3, 1.7, 4.7), channel(2.3, -3.7, 4.1, 1.9), channel(-1.9, 2.9, 3.3, -2.2)};
}

template <class T>
std::vector<mpr::Image<mpr::Rgb8>> smooth_images(const std::vector<mpr::PinholeCamera<T>>& cameras, double depth) {
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (const auto& cam : cameras) {
    mpr::Image<mpr::Rgb8> img(cam.width(), cam.height());
    const mpr::PinholeCamera<double> c(cam.K().template cast<double>(), cam.R().template cast<double>(),
                                       cam.t().template cast<double>(), cam.width(), cam.height());
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) {
        const mpr::Ray<double> r = c.ray_through({x, y});
        const mpr::Vec3<double> p = r.at((depth - r.origin.z()) / r.direction.z());
        img(x, y) = smooth_texture(p.x(), p.y());
      }
    images.push_back(std::move(img));
  }
  return images;
}

// `smooth_texture` on the tilted plane `plane` seen by `cameras`.
template <class T>
std::vector<mpr::Image<mpr::Rgb8>> smooth_tilted_images(const std::vector<mpr::PinholeCamera<T>>& cameras,
                                                        const mpr_test::TiltedPlane& plane) {
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (const auto& cam : cameras) {
    mpr::Image<mpr::Rgb8> img(cam.width(), cam.height());
    const mpr::PinholeCamera<double> c(cam.K().template cast<double>(), cam.R().template cast<double>(),
                                       cam.t().template cast<double>(), cam.width(), cam.height());
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) {
        const mpr::Ray<double> r = c.ray_through({x, y});
        const mpr::Vec3<double> p = r.at(plane.hit_t(r.origin, r.direction));
        img(x, y) = smooth_texture(p.x(), p.y());
      }
    images.push_back(std::move(img));
  }
  return images;
}

// The plane sweep as it was before the row kernels (scalar, per pixel, per plane, per neighbour;
// one thread): the reference the fast sweep must reproduce up to float rounding.
void domain_transform_line(float* v, const float* a, int n, std::ptrdiff_t step) {
  for (int k = 1; k < n; ++k) v[k * step] += a[k * step] * (v[(k - 1) * step] - v[k * step]);
  for (int k = n - 2; k >= 0; --k) v[k * step] += a[(k + 1) * step] * (v[(k + 1) * step] - v[k * step]);
}

template <std::floating_point T, class Px>
mpr::DepthEstimate reference_depth(const mpr::CameraFrameSet<T, Px>& frames, std::size_t camera,
                                   const mpr::PlaneSweepConfig& config) {
  using namespace mpr;
  // The nearest cameras by centre distance.
  const PinholeCamera<T>& ref = frames.camera(camera);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (i != camera) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const T da = (frames.camera(a).centre() - ref.centre()).squaredNorm();
    const T db = (frames.camera(b).centre() - ref.centre()).squaredNorm();
    return da < db || (da == db && a < b);
  });
  order.resize(std::min<std::size_t>(order.size(), static_cast<std::size_t>(config.neighbours)));
  const int width = ref.width(), height = ref.height();
  const int m = static_cast<int>(order.size());
  const int best = std::min(config.best, m);
  // Colours are compared as sRGB codes / 255 (perceptually even: dark texture counts as much as
  // bright), three floats per pixel, for the camera and its neighbours.
  const auto codes = [&](std::size_t i) {
    const Image<Px>& image = frames.image(i);
    std::vector<float> v(3 * static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.height()));
    std::size_t k = 0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) {
        Rgb8 p;
        if constexpr (std::is_same_v<Px, Rgb8>)
          p = image(x, y);
        else
          p = to_rgb8(image(x, y));
        v[k++] = p.r / 255.0f;
        v[k++] = p.g / 255.0f;
        v[k++] = p.b / 255.0f;
      }
    return v;
  };
  const std::vector<float> rt = codes(camera);
  std::vector<std::vector<float>> nt;
  for (const std::size_t i : order) nt.push_back(codes(i));

  // Pixel p of the reference at depth d is X = C + d R^T K^-1 p; neighbour j sees it at
  // h = A_j + d M_j p (homogeneous), A_j = K_j (R_j C + t_j), M_j = K_j R_j R^T K^-1.
  const Mat3<double> back = ref.R().template cast<double>().transpose() * ref.K().template cast<double>().inverse();
  const Vec3<double> centre = ref.centre().template cast<double>();
  std::vector<Mat3<float>> M(static_cast<std::size_t>(m));
  std::vector<Vec3<float>> A(static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) {
    const PinholeCamera<T>& c = frames.camera(order[static_cast<std::size_t>(j)]);
    const Mat3<double> K = c.K().template cast<double>(), R = c.R().template cast<double>();
    M[static_cast<std::size_t>(j)] = (K * R * back).template cast<float>();
    A[static_cast<std::size_t>(j)] = (K * (R * centre + c.t().template cast<double>())).template cast<float>();
  }

  // Domain-transform feedback per link, from the reference image's colour differences.
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<float> ax(n, 0.0f), ay(n, 0.0f);
  const double sigma = std::max(config.spatial, 1e-6);
  const double base = std::exp(-std::sqrt(2.0) / sigma);
  const auto diff = [&](std::size_t a, std::size_t b) {
    float s = 0;
    for (std::size_t k = 0; k < 3; ++k) s += std::abs(rt[3 * a + k] - rt[3 * b + k]);
    return s;
  };
  const double ratio = sigma / config.range;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t k = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      if (x > 0) ax[k] = static_cast<float>(std::pow(base, 1 + ratio * diff(k, k - 1)));
      if (y > 0) ay[k] = static_cast<float>(std::pow(base, 1 + ratio * diff(k, k - static_cast<std::size_t>(width))));
    }

  std::vector<float> cost(n), best_cost(n, std::numeric_limits<float>::infinity()), sum(n, 0.0f), left(n, 0.0f),
      right(n, 0.0f), previous(n, 0.0f);
  std::vector<int> best_plane(n, 0);
  const double inv_near = 1 / config.near, inv_far = 1 / config.far;
  const auto depth_of = [&](double index) {
    return 1 / (inv_near + (inv_far - inv_near) * index / static_cast<double>(config.planes - 1));
  };
  const float tau = static_cast<float>(config.truncation);
  for (int plane = 0; plane < config.planes; ++plane) {
    const float d = static_cast<float>(depth_of(plane));
    for (int y = 0; y < height; ++y) {
      float costs[32];
      for (int x = 0; x < width; ++x) {
        const std::size_t k =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        const Vec3<float> p(static_cast<float>(x), static_cast<float>(y), 1.0f);
        int seen = 0;
        for (int j = 0; j < m; ++j) {
          const Vec3<float> h = A[static_cast<std::size_t>(j)] + d * (M[static_cast<std::size_t>(j)] * p);
          const PinholeCamera<T>& c = frames.camera(order[static_cast<std::size_t>(j)]);
          if (!(h.z() > 0)) continue;
          const float u = h.x() / h.z(), v = h.y() / h.z();
          if (!(u >= 0 && v >= 0 && u <= static_cast<float>(c.width() - 1) && v <= static_cast<float>(c.height() - 1)))
            continue;
          const int u0 = std::min(static_cast<int>(u), c.width() - 2 < 0 ? 0 : c.width() - 2);
          const int v0 = std::min(static_cast<int>(v), c.height() - 2 < 0 ? 0 : c.height() - 2);
          const int u1 = std::min(u0 + 1, c.width() - 1), v1 = std::min(v0 + 1, c.height() - 1);
          const float fu = u - static_cast<float>(u0), fv = v - static_cast<float>(v0);
          const float* t = nt[static_cast<std::size_t>(j)].data();
          const std::ptrdiff_t w = c.width();
          const float* t00 = t + 3 * (v0 * w + u0);
          const float* t10 = t + 3 * (v0 * w + u1);
          const float* t01 = t + 3 * (v1 * w + u0);
          const float* t11 = t + 3 * (v1 * w + u1);
          float s = 0;
          for (std::size_t ch = 0; ch < 3; ++ch) {
            const float a = t00[ch] * (1 - fu) + t10[ch] * fu, b = t01[ch] * (1 - fu) + t11[ch] * fu;
            s += std::abs((a * (1 - fv) + b * fv) - rt[3 * k + ch]);
          }
          costs[seen++] = std::min(s, tau);
        }
        // A neighbour that does not see the point counts as the truncation (the worst cost),
        // so a plane is not preferred because few neighbours see it; the best few are averaged.
        for (int j = seen; j < m; ++j) costs[j] = tau;
        std::partial_sort(costs, costs + best, costs + m);
        float c = 0;
        for (int j = 0; j < best; ++j) c += costs[j];
        cost[k] = c / static_cast<float>(best);
      }
    }
    if (config.spatial > 0) {
      for (int y = 0; y < height; ++y) {
        domain_transform_line(cost.data() + static_cast<std::ptrdiff_t>(y) * width,
                              ax.data() + static_cast<std::ptrdiff_t>(y) * width, width, 1);
      }
      for (int x = 0; x < width; ++x) {
        domain_transform_line(cost.data() + x, ay.data() + x, height, width);
      }
    }
    for (std::size_t k = 0; k < n; ++k) {
      const float c = cost[k];
      sum[k] += c;
      if (best_plane[k] == plane - 1) right[k] = c;
      if (c < best_cost[k]) {
        best_cost[k] = c;
        best_plane[k] = plane;
        left[k] = plane > 0 ? previous[k] : c;
        right[k] = c;
      }
      previous[k] = c;
    }
  }
  DepthEstimate out{Image<float>(width, height), Image<float>(width, height)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t k = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      const int b = best_plane[k];
      double offset = 0;
      if (b > 0 && b < config.planes - 1) {
        const double curvature = left[k] - 2.0 * best_cost[k] + right[k];
        if (curvature > 0) offset = std::clamp(0.5 * (left[k] - right[k]) / curvature, -0.5, 0.5);
      }
      out.depth(x, y) = static_cast<float>(depth_of(b + offset));
      const float mean = sum[k] / static_cast<float>(config.planes);
      out.confidence(x, y) = mean > 0 ? std::clamp(1.0f - best_cost[k] / mean, 0.0f, 1.0f) : 0.0f;
    }
  return out;
}

} // namespace

TEST_CASE("a plane sweep's working memory is counted, and bounded by memory_limit", "[depth_estimation]") {
  using T = float;
  // 3 x 2 cameras of 50 x 30 (rows not a multiple of the 16-float stride or of the lockstep
  // block), the middle one 70 x 30: neighbours of other sizes are counted at their own size.
  std::vector<mpr::PinholeCamera<T>> cams = mpr_test::grid_cameras<T>(3, 2, 0.3, 50, 30, 40.0);
  cams[1] = mpr::PinholeCamera<T>(cams[1].K(), cams[1].R(), cams[1].t(), 70, 30);
  const mpr::CameraFrameSet<T> frames(cams, smooth_images(cams, 5.0));
  mpr::PlaneSweepConfig config;
  config.near = 2;
  config.far = 20;
  config.planes = 12;
  config.threads = 2;
  // The count against what a sweep really holds: every buffer of the workspace (its size after
  // the sweep; capacities may exceed it by the allocator's rounding only) plus the two maps.
  for (const std::size_t camera : {std::size_t(0), std::size_t(1), std::size_t(4)}) {
    const std::vector<std::size_t> order = mpr::detail::sweep_neighbours(frames, camera, config);
    mpr::detail::SweepWorkspace ws;
    const mpr::DepthEstimate e = mpr::detail::plane_sweep(frames, camera, order, config, 2, ws);
    double held = 0;
    const auto add = [&](const auto& v) { held += static_cast<double>(v.size() * sizeof(v[0])); };
    add(ws.rt.data);
    add(ws.rt.codes);
    add(ws.rt.code_planes);
    for (const auto& p : ws.nt) {
      add(p.data);
      add(p.code_planes);
    }
    for (const auto* v :
         {&ws.ax, &ws.ay, &ws.costs, &ws.best_cost, &ws.sum, &ws.left, &ws.right, &ws.previous, &ws.keep, &ws.carry})
      add(*v);
    add(ws.best_plane);
    held += 4.0 * (e.depth.width() * e.depth.height() + e.confidence.width() * e.confidence.height());
    INFO("camera " << camera);
    CHECK(mpr::plane_sweep_bytes(frames, camera, config) == Approx(held).epsilon(1e-9));
  }
  // A limit below one camera's sweep names the field, the camera and the MiB needed; a limit
  // that holds one worker only gives the same maps as two workers.
  const double one = mpr::plane_sweep_bytes(frames, 1, config);
  config.memory_limit = one - 1;
  try {
    (void)mpr::estimate_depth_maps(frames, config);
    FAIL("no exception for a limit below one camera's sweep");
  } catch (const mpr::argument_error& e) {
    CHECK(e.parameter() == "memory_limit");
    CHECK_THAT(e.what(), Catch::Contains("frame 1 (70x30)") && Catch::Contains("MiB"));
  }
  CHECK_THROWS_AS(mpr::estimate_depth(frames, 1, config), mpr::argument_error);
  CHECK_NOTHROW((void)mpr::estimate_depth(frames, 0, config)); // the 50 x 30 cameras fit
  config.memory_limit = one;
  const std::vector<mpr::Image<float>> capped = mpr::estimate_depth_maps(frames, config);
  config.memory_limit = 1e12;
  const std::vector<mpr::Image<float>> free = mpr::estimate_depth_maps(frames, config);
  REQUIRE(capped.size() == free.size());
  // One worker sweeps each camera's rows on both threads, two sweep a camera each in row order:
  // the same maps up to the aggregation's float rounding (as in the test below).
  for (std::size_t i = 0; i < capped.size(); ++i) {
    int same = 0;
    for (int y = 0; y < capped[i].height(); ++y)
      for (int x = 0; x < capped[i].width(); ++x)
        same += std::abs(capped[i](x, y) - free[i](x, y)) <= 1e-4f * free[i](x, y);
    CHECK(same >= 0.99 * capped[i].width() * capped[i].height());
  }
}

namespace {

// 3 x 3 cameras 0.3 apart, width x height pixels, focal 40, facing a textured plane at z = 5.
template <class T>
mpr::CameraFrameSet<T> textured_plane_grid(int width, int height) {
  const auto cams = mpr_test::grid_cameras<T>(3, 3, 0.3, width, height, 40.0);
  return mpr::CameraFrameSet<T>(cams, smooth_images(cams, 5.0));
}

// A sweep of `planes` planes from depth 2 to 20 on `threads` workers, else the defaults.
mpr::PlaneSweepConfig sweep_2_to_20(int planes, int threads) {
  mpr::PlaneSweepConfig config;
  config.near = 2;
  config.far = 20;
  config.planes = planes;
  config.threads = threads;
  return config;
}

} // namespace

TEMPLATE_TEST_CASE("a plane sweep recovers the depth of a textured plane", "[depth_estimation]", float, double) {
  using T = TestType;
  const auto cams = mpr_test::grid_cameras<T>(3, 3, 0.3, 48, 36, 40.0);
  const mpr::CameraFrameSet<T> frames = textured_plane_grid<T>(48, 36);
  mpr::PlaneSweepConfig config = sweep_2_to_20(48, 2);
  const mpr::DepthEstimate e = mpr::estimate_depth(frames, 4, config);
  REQUIRE(e.depth.width() == 48);
  REQUIRE(e.confidence.height() == 36);
  std::vector<double> errors;
  for (int y = 4; y < 32; ++y)
    for (int x = 4; x < 44; ++x) {
      errors.push_back(std::abs(static_cast<double>(e.depth(x, y)) - 5.0) / 5.0);
      CHECK(e.confidence(x, y) >= 0.0f);
      CHECK(e.confidence(x, y) <= 1.0f);
    }
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2), errors.end());
  const double median = errors[errors.size() / 2];
  INFO("median relative depth error " << median);
  // One plane step is about 2.5% of the depth at z = 5; the parabola refines below it.
  CHECK(median < 0.01);
  // Every camera's map, ready for with_depth (positive, finite).
  config.planes = 16;
  const std::vector<mpr::Image<float>> maps = mpr::estimate_depth_maps(frames, config);
  REQUIRE(maps.size() == 9);
  CHECK(mpr::CameraFrameSet<T>(frames).with_depth(maps).has_depth());
  // A flat grey set has no texture: the confidence is zero where every neighbour sees the pixel
  // at every plane (without aggregation, which would spread the image border's costs inward).
  config.spatial = 0;
  const std::vector<mpr::Image<mpr::Rgb8>> grey(9, mpr::Image<mpr::Rgb8>(48, 36, mpr::Rgb8{128, 128, 128}));
  const mpr::DepthEstimate flat = mpr::estimate_depth(mpr::CameraFrameSet<T>(cams, grey), 4, config);
  CHECK(flat.confidence(24, 18) < 0.05f);
  CHECK(e.confidence(24, 18) > 0.3f);
}

TEMPLATE_TEST_CASE("a plane sweep recovers the depth of a tilted plane pixel by pixel", "[depth_estimation]", float,
                   double) {
  using T = TestType;
  // The plane z = 5 + 0.3 x - 0.2 y: over the middle camera's image its depth runs from about
  // 3.6 to 6.4, about 0.04 (0.8%) per pixel; the truth at pixel (x, y) is the camera z of where
  // that pixel's ray meets the plane, in closed form (`TiltedPlane::hit_t`; R = I, centre z = 0).
  const mpr_test::TiltedPlane plane;
  const auto cams = mpr_test::grid_cameras<T>(3, 3, 0.3, 48, 36, 40.0);
  const mpr::CameraFrameSet<T> frames(cams, smooth_tilted_images(cams, plane));
  const mpr::DepthEstimate e = mpr::estimate_depth(frames, 4, sweep_2_to_20(48, 2));
  const mpr::PinholeCamera<double> c(cams[4].K().template cast<double>(), cams[4].R().template cast<double>(),
                                     cams[4].t().template cast<double>(), 48, 36);
  std::vector<double> errors;
  double nearest = 1e9, farthest = 0;
  for (int y = 4; y < 32; ++y)
    for (int x = 4; x < 44; ++x) {
      const mpr::Ray<double> r = c.ray_through({x, y});
      const double truth = r.at(plane.hit_t(r.origin, r.direction)).z();
      nearest = std::min(nearest, truth);
      farthest = std::max(farthest, truth);
      errors.push_back(std::abs(static_cast<double>(e.depth(x, y)) - truth) / truth);
    }
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], p90 = errors[errors.size() * 9 / 10];
  INFO("relative depth error: median " << median << ", 90th percentile " << p90 << "; truth " << nearest << " to "
                                       << farthest);
  CHECK(farthest - nearest > 2.0); // a constant map would be off by 20% at the ends
  CHECK(median < 0.005);
  CHECK(p90 < 0.01);
}

TEST_CASE("a workspace reused from camera to camera keeps the neighbours it holds and gives a fresh one's maps",
          "[depth_estimation]") {
  const mpr::CameraFrameSet<float> frames = textured_plane_grid<float>(48, 36);
  const mpr::PlaneSweepConfig config = sweep_2_to_20(16, 1);
  mpr::detail::SweepWorkspace reused;
  std::map<std::size_t, const float*> held; // camera -> its planes' buffer after the last sweep
  int moved = 0;
  for (const std::size_t camera : {4, 3, 5, 0, 8, 4, 1}) {
    INFO("camera " << camera);
    const std::vector<std::size_t> order = mpr::detail::sweep_neighbours(frames, camera, config);
    const mpr::DepthEstimate a = mpr::detail::plane_sweep(frames, camera, order, config, 1, reused);
    mpr::detail::SweepWorkspace fresh;
    const mpr::DepthEstimate b = mpr::detail::plane_sweep(frames, camera, order, config, 1, fresh);
    REQUIRE(reused.nt.size() == order.size());
    REQUIRE(reused.nt_camera.size() == order.size());
    for (std::size_t j = 0; j < order.size(); ++j) {
      CHECK(reused.nt_camera[j] == order[j]);
      CHECK(reused.nt[j].data == fresh.nt[j].data);
      CHECK(reused.nt[j].code_planes == fresh.nt[j].code_planes);
      // A camera held before keeps its buffer (moved, not converted again).
      const auto before = held.find(order[j]);
      if (before != held.end()) {
        CHECK(reused.nt[j].data.data() == before->second);
        moved += reused.nt[j].data.data() == before->second;
      }
    }
    held.clear();
    for (std::size_t j = 0; j < order.size(); ++j) held[order[j]] = reused.nt[j].data.data();
    int differ = 0;
    for (int y = 0; y < 36; ++y)
      for (int x = 0; x < 48; ++x) differ += a.depth(x, y) != b.depth(x, y);
    CHECK(differ == 0);
  }
  CHECK(moved >= 6);
}

TEST_CASE("extreme plane sweep settings stay finite: a huge truncation acts as 3, a tiny range cuts every "
          "colour edge",
          "[depth_estimation]") {
  const mpr::CameraFrameSet<float> frames = textured_plane_grid<float>(40, 30);
  mpr::PlaneSweepConfig config = sweep_2_to_20(32, 1);
  config.best = 4;
  const auto same = [](const mpr::DepthEstimate& a, const mpr::DepthEstimate& b) {
    for (int y = 0; y < a.depth.height(); ++y)
      for (int x = 0; x < a.depth.width(); ++x)
        if (!(a.depth(x, y) == b.depth(x, y)) || !(a.confidence(x, y) == b.confidence(x, y))) return false;
    return true;
  };
  const auto finite_and_near = [](const mpr::DepthEstimate& e) {
    int near = 0; // pixels within 5% of the plane
    for (int y = 0; y < e.depth.height(); ++y)
      for (int x = 0; x < e.depth.width(); ++x) {
        if (!std::isfinite(e.depth(x, y)) || !std::isfinite(e.confidence(x, y))) return -1;
        near += std::abs(e.depth(x, y) - 5.0f) <= 0.25f;
      }
    return near;
  };
  // Costs are at most 3, so truncations of 3 and of 1e39 (infinite as a float) are the same
  // sweep; an unseen neighbour counts 3 in both.
  config.truncation = 3;
  const mpr::DepthEstimate three = mpr::estimate_depth(frames, 4, config);
  config.truncation = 1e39;
  const mpr::DepthEstimate huge = mpr::estimate_depth(frames, 4, config);
  CHECK(same(three, huge));
  CHECK(finite_and_near(huge) > 40 * 30 / 2);
  // A subnormal range: the spatial-to-range ratio overflows; every colour difference cuts the
  // aggregation, equal colours do not (no NaN), as with a tiny normal range.
  config.truncation = 0.3;
  config.range = 1e-320;
  const mpr::DepthEstimate subnormal = mpr::estimate_depth(frames, 4, config);
  config.range = 1e-30;
  const mpr::DepthEstimate tiny = mpr::estimate_depth(frames, 4, config);
  CHECK(same(subnormal, tiny));
  CHECK(finite_and_near(subnormal) > 40 * 30 / 2);
}

TEST_CASE("the sweep's neighbours: the row and column through the camera, else the nearest", "[depth_estimation]") {
  using T = double;
  // A 4 x 3 grid, 0.5 apart (exact distances; camera index = row * 4 + column).
  const auto grid = mpr_test::grid_cameras<T>(4, 3, 0.5, 16, 12, 16.0);
  const mpr::CameraFrameSet<T> frames(grid, smooth_images(grid, 5.0));
  mpr::PlaneSweepConfig config; // axes, 16 neighbours
  using List = std::vector<std::size_t>;
  // Camera 5 (row 1, column 1): its row 4, 6, 7 (nearest first), then its column 1, 9; the
  // diagonals (0, 2, 8, 10) and cells off both lines are left out.
  CHECK(mpr::detail::sweep_neighbours(frames, 5, config) == List{4, 6, 7, 1, 9});
  // Corner 0: row 1, 2, 3; column 4, 8.
  CHECK(mpr::detail::sweep_neighbours(frames, 0, config) == List{1, 2, 3, 4, 8});
  // Half each of an even count; an odd count gives the row the extra one; a short column gives
  // its share to the row.
  config.neighbours = 2;
  CHECK(mpr::detail::sweep_neighbours(frames, 0, config) == List{1, 4});
  config.neighbours = 3;
  CHECK(mpr::detail::sweep_neighbours(frames, 0, config) == List{1, 2, 4});
  config.neighbours = 5;
  CHECK(mpr::detail::sweep_neighbours(frames, 0, config) == List{1, 2, 3, 4, 8});
  config.neighbours = 4;
  config.best = 2;
  // A column of one camera beside the row (a 4 x 2 grid's camera 0 has column {4} only): nearest
  // by distance, which takes the diagonal 5 (0.71) before 2 (1.0).
  const auto two_rows = mpr_test::grid_cameras<T>(4, 2, 0.5, 16, 12, 16.0);
  const mpr::CameraFrameSet<T> short_columns(two_rows, smooth_images(two_rows, 5.0));
  CHECK(mpr::detail::sweep_neighbours(short_columns, 0, config) == List{1, 4, 5, 2});
  config.selection = mpr::NeighbourSelection::nearest;
  List nearest = mpr::detail::sweep_neighbours(frames, 5, config); // the four at 0.5, tied up to rounding
  std::sort(nearest.begin(), nearest.end());
  CHECK(nearest == List{1, 4, 6, 9});
}

TEST_CASE("a plane sweep refuses a bad camera index, a single camera and lens distortion", "[depth_estimation]") {
  using T = double;
  const auto cams = mpr_test::grid_cameras<T>(2, 1, 0.3, 16, 12, 16.0);
  const mpr::CameraFrameSet<T> frames(cams, smooth_images(cams, 5.0));
  mpr::PlaneSweepConfig config;
  CHECK_THROWS_AS(mpr::estimate_depth(frames, 2, config), mpr::argument_error);
  CHECK_THROWS_AS(mpr::estimate_depth(frames.without(1), 0, config), mpr::argument_error);
  std::vector<mpr::PinholeCamera<T>> distorted = cams;
  distorted[1] =
      mpr::PinholeCamera<T>(cams[1].K(), cams[1].R(), cams[1].t(), 16, 12, mpr::PinholeCamera<T>::Distortion{0.1, 0});
  const mpr::CameraFrameSet<T> bad(distorted, smooth_images(cams, 5.0), {"a", "b"});
  CHECK_THROWS_WITH(mpr::estimate_depth(bad, 0, config), Catch::Contains("b: lens distortion"));
}

namespace {

// How far `fast` is from `reference`: the share of pixels whose depth agrees to 1e-4 relative
// (and confidence to 1e-3), and the largest relative depth difference anywhere.
struct Agreement {
  double share = 0, worst = 0;
};

Agreement agreement(const mpr::DepthEstimate& fast, const mpr::DepthEstimate& reference) {
  Agreement a;
  int same = 0;
  for (int y = 0; y < fast.depth.height(); ++y)
    for (int x = 0; x < fast.depth.width(); ++x) {
      const double d = reference.depth(x, y), e = std::abs(fast.depth(x, y) - d) / d;
      a.worst = std::max(a.worst, e);
      same += e <= 1e-4 && std::abs(fast.confidence(x, y) - reference.confidence(x, y)) <= 1e-3f;
    }
  a.share = same / static_cast<double>(fast.depth.width() * fast.depth.height());
  return a;
}

} // namespace

TEMPLATE_TEST_CASE("the vectorised plane sweep agrees with the per-pixel sweep", "[depth_estimation]", float, double) {
  using T = TestType;
  mpr::PlaneSweepConfig config;
  // The reference picks the nearest cameras; four of them, two kept, take the fused kernel.
  config.selection = mpr::NeighbourSelection::nearest;
  config.neighbours = 4;
  config.best = 2;
  config.near = 2;
  config.far = 20;
  config.planes = 40;
  config.threads = 2;
  config.median.radius = 0; // the reference has no final filters
  config.snap.jump = std::numeric_limits<double>::infinity();
  config.integer_costs = false; // float costs as the reference's (16-bit ones: below)
  // On one worker (blocks in order, the forward vertical pass per block) and on two (blocks in
  // parallel, the vertical passes down column strips).
  const auto check = [&](const mpr::CameraFrameSet<T>& frames, std::size_t camera) {
    const mpr::DepthEstimate slow = reference_depth(frames, camera, config);
    for (const int threads : {1, 2}) {
      mpr::PlaneSweepConfig c = config;
      c.threads = threads;
      const Agreement a = agreement(mpr::estimate_depth(frames, camera, c), slow);
      INFO("threads " << threads << " neighbours " << c.neighbours << " best " << c.best << " spatial " << c.spatial);
      INFO("share agreeing " << a.share << ", worst relative difference " << a.worst);
      CHECK(a.share >= 0.99);
      // Elsewhere the same plane or its neighbour (a near tie decided by rounding).
      CHECK(a.worst < 0.06);
    }
  };
  // A rectified 4 x 3 grid (every neighbour row a translation), the plane's edges leaving the
  // neighbours' views.
  const auto grid = mpr_test::grid_cameras<T>(4, 3, 0.3, 50, 34, 40.0);
  const mpr::CameraFrameSet<T> rectified(grid, smooth_images(grid, 6.0));
  check(rectified, 5);
  config.spatial = 0;
  check(rectified, 0);
  config.spatial = 6;
  config.neighbours = 7;
  config.best = 3;
  config.truncation = 0.15;
  check(rectified, 6);
  // More kept costs than the fused cost-and-insert kernel takes (the separate insertion).
  config.neighbours = 9;
  config.best = 5;
  check(rectified, 1);
  config = {};
  config.selection = mpr::NeighbourSelection::nearest;
  config.neighbours = 4;
  config.best = 2;
  config.near = 2;
  config.far = 20;
  config.planes = 40;
  config.threads = 1;
  config.median.radius = 0;
  config.snap.jump = std::numeric_limits<double>::infinity();
  // Converging cameras with different focal lengths: projective rows (the per-pixel path).
  std::vector<mpr::PinholeCamera<T>> turned;
  for (int i = 0; i < 5; ++i) {
    const double angle = 0.04 * (i - 2), focal = 38.0 + 2 * i;
    mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
    K(0, 0) = static_cast<T>(focal);
    K(1, 1) = static_cast<T>(focal * 1.02);
    K(0, 2) = T(23.5);
    K(1, 2) = T(16.5);
    const mpr::Mat3<T> R = Eigen::AngleAxis<T>(static_cast<T>(angle), mpr::Vec3<T>::UnitY()).toRotationMatrix() *
                           Eigen::AngleAxis<T>(static_cast<T>(0.01 * i), mpr::Vec3<T>::UnitX()).toRotationMatrix();
    const mpr::Vec3<T> centre(static_cast<T>(0.3 * (i - 2)), static_cast<T>(0.05 * i), 0);
    turned.emplace_back(K, R, -(R * centre), 48, 34);
  }
  const mpr::CameraFrameSet<T> projective(turned, smooth_images(turned, 6.0));
  check(projective, 2);
  check(projective, 4);
}

TEMPLATE_TEST_CASE("16-bit costs find the depth that float costs find", "[depth_estimation]", float, double) {
  // A rectified 5 x 3 grid seeing a smooth plane at depth 6: camera 7's row and column (six
  // neighbours, best 3) take the chunked kernel, on 16-bit codes or in float. Both recover the
  // plane alike, and agree to the same plane at every pixel.
  using T = TestType;
  const auto grid = mpr_test::grid_cameras<T>(5, 3, 0.3, 60, 40, 40.0);
  const mpr::CameraFrameSet<T> frames(grid, smooth_images(grid, 6.0));
  mpr::PlaneSweepConfig config;
  config.best = 3;
  config.near = 2;
  config.far = 20;
  config.planes = 48;
  config.threads = 1;
  const auto near = [](const mpr::DepthEstimate& e) {
    int n = 0;
    for (int y = 0; y < e.depth.height(); ++y)
      for (int x = 0; x < e.depth.width(); ++x) n += std::abs(e.depth(x, y) - 6.0f) <= 0.06f;
    return n;
  };
  for (const double spatial : {0.0, 12.0}) {
    config.spatial = spatial;
    config.integer_costs = false;
    const mpr::DepthEstimate f = mpr::estimate_depth(frames, 7, config);
    config.integer_costs = true;
    const mpr::DepthEstimate i = mpr::estimate_depth(frames, 7, config);
    const Agreement a = agreement(i, f);
    INFO("spatial " << spatial << ": within 1 % of the plane: float " << near(f) << ", 16-bit " << near(i) << " of "
                    << 60 * 40 << "; agreeing to 1e-4 " << a.share << ", worst " << a.worst);
    CHECK(near(i) >= near(f) - 60 * 40 / 100);
    CHECK(near(f) >= 60 * 40 * 9 / 10);
    // The same plane everywhere, refined within a sixth of the planes' spacing (about 6 % of
    // the depth at 6).
    CHECK(a.worst < 0.01);
  }
}
