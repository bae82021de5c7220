// The light-field kernels (camera_frame_kernels.hpp): every SIMD variant against the portable
// one and against a long-double reference, on many lengths (vector bodies and tails) and on
// edge inputs; then the row paths of CameraFrameSampler that use them (nearest camera and
// cylinder aperture on planar arrays) against brute force and against per-pixel `sample`.
#include "lightfield/channel_values.hpp"
#include "lightfield/frame_test_scenes.hpp"
#include "simd_levels.hpp"

#include <catch2/catch.hpp>

#include <mpr/lightfield.hpp>
#include <mpr/lightfield/kernels/cylinder_weights.hpp>
#include <mpr/lightfield/kernels/sampler_rows.hpp>
#include <mpr/mpr.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace {

using mpr::detail::NearestCandidate;
using mpr::detail::PlaneAxes;
using mpr::detail::PlaneRays;
using mpr::detail::RowWeights;
using LD = long double;

// Lengths around every vector width (4, 8, 16 lanes) and their tails.
constexpr std::size_t kLengths[] = {0, 1, 2, 3, 7, 8, 15, 16, 17, 31, 33, 64, 100, 257};
// Entries past the end of every output, which no kernel may touch.
constexpr std::size_t kGuard = 19;

// The levels come from tests/simd_levels.hpp; a kernel variant is named by its level.
using Kernel = mpr::detail::SimdLevel;

const char* kernel_name(Kernel k) { return mpr::detail::simd_level_name(k); }

// The variants this CPU runs, portable first.
std::vector<Kernel> kernels() { return mpr_test::simd_levels(); }

bool cpu_avx2() { return mpr_test::runs(Kernel::avx2); }
bool cpu_avx512() { return mpr_test::runs(Kernel::avx512); }

Kernel dispatched() { return mpr::detail::simd_level(); }

mpr::detail::SimdLevel level(Kernel k) { return k; }

template <class C>
void shift_add_with(Kernel k, const C* a, const C* b, RowWeights w, const float* rw, float* acc, std::size_t m) {
  mpr::detail::shift_add_flat(a, b, w, rw, acc, m, level(k));
}

template <class T>
void plane_rays_with(Kernel k, const T* const (&soa)[6], std::size_t n, const PlaneAxes<T>& f, const PlaneRays<T>& out,
                     T* cos2) {
  mpr::detail::plane_rays(soa, n, f, out, cos2, level(k));
}

template <class T>
void prove_nearest_with(Kernel k, const PlaneRays<T>& rays, std::size_t n, const NearestCandidate<T>& c,
                        typename PlaneRays<T>::Flag* pass, T* scratch) {
  mpr::detail::prove_nearest(rays, n, c, pass, scratch, level(k));
}

template <class T>
bool evenly_spaced_with(Kernel k, const T* x, const T* y, const T* z, int n, T tolerance) {
  return mpr::detail::evenly_spaced(x, y, z, n, tolerance, level(k));
}

template <class T>
constexpr LD eps() {
  return static_cast<LD>(std::numeric_limits<T>::epsilon());
}

template <class T>
mpr::Vec3<LD> ld(const mpr::Vec3<T>& v) {
  return v.template cast<LD>();
}

// A random orthonormal frame (normal, two in-plane axes) around a random point.
template <class T>
PlaneAxes<T> random_frame(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0, 1);
  const mpr::Vec3<double> n = mpr::Vec3<double>(g(rng), g(rng), g(rng)).normalized();
  const mpr::Vec3<double> u = n.cross(mpr::Vec3<double>(g(rng), g(rng), g(rng))).normalized();
  const mpr::Vec3<double> v = n.cross(u);
  const auto t = [](double x) { return static_cast<T>(x); };
  return {t(3 * g(rng)), t(3 * g(rng)), t(3 * g(rng)), t(n.x()), t(n.y()), t(n.z()),
          t(u.x()),      t(u.y()),      t(u.z()),      t(v.x()), t(v.y()), t(v.z())};
}

template <class T>
mpr::Vec3<T> normal_of(const PlaneAxes<T>& f) {
  return {f.nx, f.ny, f.nz};
}
template <class T>
mpr::Vec3<T> u_of(const PlaneAxes<T>& f) {
  return {f.ux, f.uy, f.uz};
}
template <class T>
mpr::Vec3<T> v_of(const PlaneAxes<T>& f) {
  return {f.vx, f.vy, f.vz};
}

// Rays as structure of arrays (origins relative to the frame point, then directions), sized
// exactly n so that the sanitizers see any read past the end.
template <class T>
struct RayArrays {
  std::vector<T> soa[6];
  explicit RayArrays(std::size_t n) {
    for (std::vector<T>& v : soa) v.resize(n);
  }
  void set(std::size_t i, const mpr::Vec3<T>& o, const mpr::Vec3<T>& d) {
    for (int k = 0; k < 3; ++k) {
      soa[k][i] = o[k];
      soa[3 + k][i] = d[k];
    }
  }
  [[nodiscard]] mpr::Vec3<T> origin(std::size_t i) const { return {soa[0][i], soa[1][i], soa[2][i]}; }
  [[nodiscard]] mpr::Vec3<T> direction(std::size_t i) const { return {soa[3][i], soa[4][i], soa[5][i]}; }
};

template <class T>
constexpr T kSentinel = T(-12345.25);
constexpr std::int32_t kFlagSentinel = 0x5a5a5a5a;

// The outputs of `plane_rays`, each with kGuard sentinel entries past the end.
template <class T>
struct PlaneOut {
  using Flag = typename PlaneRays<T>::Flag;
  std::vector<T> xu, xv, du, dv, dd, cos2;
  std::vector<Flag> ok;
  std::size_t n;
  explicit PlaneOut(std::size_t size) : n(size) {
    for (std::vector<T>* v : {&xu, &xv, &du, &dv, &dd, &cos2}) v->assign(n + kGuard, kSentinel<T>);
    ok.assign(n + kGuard, static_cast<Flag>(kFlagSentinel));
  }
  [[nodiscard]] PlaneRays<T> rays() { return {xu.data(), xv.data(), du.data(), dv.data(), dd.data(), ok.data()}; }
  [[nodiscard]] bool guards_intact() const {
    for (std::size_t i = n; i < n + kGuard; ++i) {
      for (const std::vector<T>* v : {&xu, &xv, &du, &dv, &dd, &cos2})
        if ((*v)[i] != kSentinel<T>) return false;
      if (ok[i] != static_cast<Flag>(kFlagSentinel)) return false;
    }
    return true;
  }
};

template <class T>
void run_plane_rays(Kernel k, const RayArrays<T>& rays, std::size_t n, const PlaneAxes<T>& f, PlaneOut<T>& out) {
  const T* const soa[6] = {rays.soa[0].data(), rays.soa[1].data(), rays.soa[2].data(),
                           rays.soa[3].data(), rays.soa[4].data(), rays.soa[5].data()};
  plane_rays_with(k, soa, n, f, out.rays(), out.cos2.data());
}

// Edge rays for `plane_rays`; returns the ok flag it must produce (1, 0) or -1 where that depends
// on the scalar type in a way checked elsewhere.
template <class T>
int edge_ray(int which, const PlaneAxes<T>& f, std::mt19937_64& rng, mpr::Vec3<T>& o, mpr::Vec3<T>& d) {
  constexpr bool is_float = std::is_same_v<T, float>;
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
  std::uniform_real_distribution<double> unit(-1, 1);
  const mpr::Vec3<T> n = normal_of(f), u = u_of(f), v = v_of(f);
  o = mpr::Vec3<T>(static_cast<T>(4 * unit(rng)), static_cast<T>(4 * unit(rng)), static_cast<T>(4 * unit(rng)));
  switch (which) {
  case 0: // parallel to the plane
    d = u + T(0.5) * v;
    return 0;
  case 1: // within 0.006 degrees of the plane
    d = T(2) * v + T(2e-4) * n;
    return 0;
  case 2: // zero direction
    d = mpr::Vec3<T>::Zero();
    return 0;
  case 3: // NaN origin
    d = n + T(0.3) * u;
    o.x() = nan;
    return 0;
  case 4: // NaN direction
    d = n;
    d.z() = nan;
    return 0;
  case 5: // infinite origin
    d = n - T(0.2) * v;
    o.y() = inf;
    return 0;
  case 6: // infinite direction
    d = n;
    d.x() = -inf;
    return 0;
  case 7: // huge origin (1e30 world units), finite crossing
    o = T(1e30) * (T(0.6) * u + T(0.8) * v) + T(3) * n;
    d = n + T(0.25) * u;
    return 1;
  case 8: // huge direction: |d|^2 overflows in float
    d = T(1e30) * (n + T(0.2) * u);
    return is_float ? 0 : 1;
  case 9: // tiny direction: (d . n)^2 underflows to 0 in float
    d = T(1e-30) * (n + T(0.2) * u);
    return is_float ? 0 : 1;
  case 10: // tiny origin
    o = T(1e-30) * o;
    d = n + T(0.1) * v;
    return 1;
  case 11: // huge origin along the normal: the crossing cancels to near 0
    o = T(1e30) * n;
    d = n;
    return 1;
  case 12: // negative zero direction
    d = mpr::Vec3<T>(-T(0), -T(0), -T(0));
    return 0;
  default: // NaN and infinity together
    o = mpr::Vec3<T>(inf, nan, -inf);
    d = mpr::Vec3<T>(nan, inf, T(1));
    return 0;
  }
}
constexpr int kEdgeRays = 14;

// Random rays: origins within 10 of the frame point, directions of length 0.1 to 10.
template <class T>
void random_ray(std::mt19937_64& rng, mpr::Vec3<T>& o, mpr::Vec3<T>& d) {
  std::uniform_real_distribution<double> unit(-1, 1);
  std::normal_distribution<double> g(0, 1);
  o = mpr::Vec3<T>(static_cast<T>(10 * unit(rng)), static_cast<T>(10 * unit(rng)), static_cast<T>(10 * unit(rng)));
  const mpr::Vec3<double> dir = mpr::Vec3<double>(g(rng), g(rng), g(rng)).normalized();
  const double length = std::pow(10.0, unit(rng));
  d = (length * dir).template cast<T>();
}

// A planar array of cameras in frame coordinates: jittered grid centres (cu, cv) on the plane,
// and, per camera, the neighbour list and separation that `CameraFrameSampler` derives (the
// cameras within 1.5 x the nearest-neighbour distance, at most 8; the distance to the nearest
// camera not listed).
template <class T>
struct PlanarArray {
  std::vector<T> cu, cv;
  std::vector<std::vector<T>> nu, nv;
  std::vector<T> separation;
  T extent = 0;

  PlanarArray(int nx, int ny, double jitter, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> j(-jitter, jitter);
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        cu.push_back(static_cast<T>(x - 0.5 * (nx - 1) + j(rng)));
        cv.push_back(static_cast<T>(y - 0.5 * (ny - 1) + j(rng)));
      }
    const std::size_t n = cu.size();
    T mu = 0, mv = 0;
    for (std::size_t i = 0; i < n; ++i) {
      mu += cu[i];
      mv += cv[i];
    }
    mu /= static_cast<T>(n);
    mv /= static_cast<T>(n);
    for (std::size_t i = 0; i < n; ++i) extent = std::max(extent, std::hypot(cu[i] - mu, cv[i] - mv));
    nu.resize(n);
    nv.resize(n);
    separation.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<std::pair<T, std::size_t>> others;
      for (std::size_t k = 0; k < n; ++k)
        if (k != i) others.emplace_back(std::hypot(cu[i] - cu[k], cv[i] - cv[k]), k);
      std::sort(others.begin(), others.end());
      std::size_t k = 0;
      while (k < others.size() && k < 8 && others[k].first <= T(1.5) * others[0].first) {
        nu[i].push_back(cu[others[k].second]);
        nv[i].push_back(cv[others[k].second]);
        ++k;
      }
      separation[i] = k < others.size() ? others[k].first : std::numeric_limits<T>::infinity();
    }
  }

  [[nodiscard]] std::size_t size() const { return cu.size(); }

  // Camera i in world coordinates (frame coordinates of the rays: relative to the frame point).
  [[nodiscard]] mpr::Vec3<LD> centre(std::size_t i, const PlaneAxes<T>& f) const {
    return static_cast<LD>(cu[i]) * ld(u_of(f)) + static_cast<LD>(cv[i]) * ld(v_of(f));
  }

  // The candidate of `tile_nearest` for camera k over rays whose least cosine to the normal is
  // cos_min.
  [[nodiscard]] NearestCandidate<T> candidate(std::size_t k, T cos_min) const {
    const T margin = T(1e-4) * extent;
    const T reach = cos_min * separation[k] - margin;
    const T rho = reach > 0 ? reach / (cos_min + T(1.001)) : T(0);
    return {cu[k], cv[k], rho * rho, margin * margin, nu[k].data(), nv[k].data(), static_cast<int>(nu[k].size())};
  }
};

// Distance (squared, long double) from every camera to a ray; index of the nearest and the gap to
// the second (relative).
struct Nearest {
  int index = -1;
  LD best = 0, second = 0;
};

template <class T>
Nearest brute_force_ld(const PlanarArray<T>& array, const PlaneAxes<T>& f, const mpr::Vec3<T>& o,
                       const mpr::Vec3<T>& d) {
  Nearest out;
  out.best = out.second = std::numeric_limits<LD>::infinity();
  const mpr::Vec3<LD> O = ld(o), D = ld(d);
  const LD inv = 1 / D.squaredNorm();
  for (std::size_t i = 0; i < array.size(); ++i) {
    const LD d2 = mpr::line_distance2(array.centre(i, f), O, D, inv);
    if (d2 < out.best) {
      out.second = out.best;
      out.best = d2;
      out.index = static_cast<int>(i);
    } else if (d2 < out.second) {
      out.second = d2;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Test scenes for the sampler row paths.

// nx x ny cameras (R = I, looking along +z), spacing 1, centres jittered by up to `jitter` and
// lying on the plane z = tilt_x x + tilt_y y.
template <class T>
std::vector<mpr::PinholeCamera<T>> array_cameras(int nx, int ny, double jitter, double tilt_x, double tilt_y, int width,
                                                 int height, double focal, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> j(-jitter, jitter);
  std::vector<mpr::PinholeCamera<T>> cameras;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const double cx = x - 0.5 * (nx - 1) + j(rng), cy = y - 0.5 * (ny - 1) + j(rng);
      const mpr::Vec3<T> c(static_cast<T>(cx), static_cast<T>(cy), static_cast<T>(tilt_x * cx + tilt_y * cy));
      cameras.push_back(mpr_test::camera_at<T>(c, width, height, focal));
    }
  return cameras;
}

// A distinct 8-bit colour per camera index (i < 35), never black (the background).
mpr::Rgb8 camera_code(std::size_t i) {
  return {static_cast<std::uint8_t>(16 + 7 * i), static_cast<std::uint8_t>(255 - 5 * i),
          static_cast<std::uint8_t>((37 * i + 11) % 256)};
}

// The camera whose code is `p`; -1 for black, -2 for a colour that is no code.
int decode_camera(const mpr::Rgb8& p, std::size_t cameras) {
  if (p == mpr::Rgb8{0, 0, 0}) return -1;
  if (p.r < 16 || (p.r - 16) % 7 != 0) return -2;
  const std::size_t i = static_cast<std::size_t>((p.r - 16) / 7);
  return i < cameras && camera_code(i) == p ? static_cast<int>(i) : -2;
}

int rgb_difference(const mpr::Rgb8& a, const mpr::Rgb8& b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

// Smooth random 8-bit images: low-frequency waves with random phases per camera and channel.
template <class T>
std::vector<mpr::Image<mpr::Rgb8>> smooth_images(const std::vector<mpr::PinholeCamera<T>>& cameras, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> phase(0, 6.283185307179586);
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (const auto& cam : cameras) {
    double p[6];
    for (double& x : p) x = phase(rng);
    mpr::Image<mpr::Rgb8> img(cam.width(), cam.height());
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) {
        const auto wave = [&](int c) {
          return static_cast<float>(0.5 + 0.3 * std::sin(0.09 * x + p[c]) * std::cos(0.07 * y + p[c + 3]) +
                                    0.1 * std::sin(0.05 * (x + y) + p[(c + 1) % 6]));
        };
        img(x, y) = mpr::to_rgb8(mpr::Color(wave(0), wave(1), wave(2)));
      }
    images.push_back(std::move(img));
  }
  return images;
}

// The GLC on `plane` whose ray at uv passes through the point (a + b u, c + d v, 0): a cross-slit
// whose rays cross the plane z = 0 on a rectangle that sweeps over (and past) the array.
template <class T>
mpr::GlcSelector<T> sweep_glc(const mpr::PlanarSurface<T>& plane, T a, T b, T c, T d) {
  const auto dir = [&](T u, T v) {
    return mpr::Vec3<T>(plane.point_at({u, v}) - mpr::Vec3<T>(a + b * u, c + d * v, 0));
  };
  return mpr::GlcSelector<T>(plane, dir(0, 0), dir(1, 0), dir(0, 1));
}

// Rows of rays nearly parallel to the array plane z = 0 at height ~2 (lines that pass within a
// few units of the cameras), for the row paths' handling of rays that do not cross the plane.
// Row 0: a run of rays within 0.001 degrees of the plane; row 1: exactly parallel rays at both
// ends; row 2: every ray crosses, all at a grazing 3 degrees; row 3: ordinary rays.
template <class T>
std::vector<mpr::Ray<T>> grazing_rows(std::size_t width) {
  std::vector<mpr::Ray<T>> rays;
  for (int r = 0; r < 4; ++r)
    for (std::size_t i = 0; i < width; ++i) {
      const T x = T(-6) + T(12) * static_cast<T>(i) / static_cast<T>(width - 1);
      const mpr::Vec3<T> origin(x, T(0.3), T(2));
      T dz = (i % 2 == 0 ? T(0.05) : T(-0.05));
      if (r == 0 && i >= 40 && i < 56) dz = T(1e-5);
      if (r == 1 && (i == 0 || i + 1 == width)) dz = 0;
      if (r == 2) dz = T(0.05);
      const mpr::Vec3<T> direction =
          r == 3 ? mpr::Vec3<T>(T(0.1) * std::sin(static_cast<T>(i)), T(0.2), T(1)) : mpr::Vec3<T>(1, T(0.3), dz);
      rays.push_back({origin, direction});
    }
  return rays;
}

// Counts behind a test's checks, printed when MPR_TEST_STATS is set.
void report(const std::string& what) {
  if (std::getenv("MPR_TEST_STATS") != nullptr) WARN(what);
}

} // namespace

TEST_CASE("simd_level picks the widest kernel set the CPU runs", "[camera_frame_kernels]") {
  const std::vector<Kernel> available = kernels();
  INFO("kernels: portable" << (cpu_avx2() ? ", avx2" : "") << (cpu_avx512() ? ", avx512" : "")
                           << (mpr_test::runs(Kernel::avx512vbmi) ? ", avx512vbmi" : ""));
  const char* limit = std::getenv("MPR_SIMD");
  if (limit == nullptr) {
    CHECK(dispatched() == available.back());
  } else {
    CHECK(static_cast<int>(dispatched()) <= static_cast<int>(available.back()));
  }
  CHECK(std::string(mpr::detail::simd_level_name()).size() > 0);
}

TEMPLATE_TEST_CASE("shift_add_flat: every variant computes the bilinear shift-and-add of the portable kernel",
                   "[camera_frame_kernels]", std::uint16_t, float) {
  using C = TestType;
  std::mt19937_64 rng(20040 + sizeof(C));
  std::uniform_real_distribution<double> unit(0, 1);
  const float scale = std::is_same_v<C, float> ? 1.0f : 1.0f / 65535.0f;
  const auto channel = [&]() -> C {
    if constexpr (std::is_same_v<C, float>)
      return static_cast<float>(4 * unit(rng) - 1); // linear texels may be negative or above 1
    else
      return static_cast<C>(rng() % 65536);
  };
  const std::vector<Kernel> all = kernels();
  int failures = 0, simd_runs = 0;
  for (const std::size_t m : kLengths)
    for (int weighted = 0; weighted < 2; ++weighted)
      for (int trial = 0; trial < 3; ++trial) {
        std::vector<C> a(m + 3), b(m + 3);
        for (std::size_t j = 0; j < m + 3; ++j) {
          a[j] = channel();
          b[j] = channel();
        }
        // Trial 0: an integer offset (one weight 1, the others 0); then random offsets.
        const float ax = trial == 0 ? 0.0f : static_cast<float>(unit(rng));
        const float ay = trial == 0 ? 0.0f : static_cast<float>(unit(rng));
        const RowWeights w{(1 - ax) * (1 - ay) * scale, ax * (1 - ay) * scale, (1 - ax) * ay * scale, ax * ay * scale};
        std::vector<float> rw(m);
        for (float& x : rw) x = unit(rng) < 0.2 ? 0.0f : static_cast<float>(unit(rng));
        std::vector<float> acc0(m + kGuard, kSentinel<float>);
        for (std::size_t j = 0; j < m; ++j) acc0[j] = static_cast<float>(2 * unit(rng));
        const float* weights = weighted ? rw.data() : nullptr;
        // Reference in long double and the scale of its terms.
        std::vector<LD> ref(m), size(m);
        for (std::size_t j = 0; j < m; ++j) {
          const LD terms[4] = {LD(w.w00) * LD(a[j]), LD(w.w10) * LD(a[j + 3]), LD(w.w01) * LD(b[j]),
                               LD(w.w11) * LD(b[j + 3])};
          const LD r = weighted ? LD(rw[j]) : LD(1);
          ref[j] = LD(acc0[j]) + r * (terms[0] + terms[1] + terms[2] + terms[3]);
          size[j] = std::abs(LD(acc0[j])) +
                    r * (std::abs(terms[0]) + std::abs(terms[1]) + std::abs(terms[2]) + std::abs(terms[3]));
        }
        std::vector<float> portable;
        for (const Kernel k : all) {
          std::vector<float> acc = acc0;
          shift_add_with(k, a.data(), b.data(), w, weights, acc.data(), m);
          if (k == Kernel::portable)
            portable = acc;
          else
            ++simd_runs;
          for (std::size_t j = m; j < m + kGuard; ++j)
            if (acc[j] != kSentinel<float>) {
              ++failures;
              FAIL_CHECK(kernel_name(k) << ": wrote acc[" << j << "] past m = " << m);
            }
          for (std::size_t j = 0; j < m; ++j) {
            const LD to_ref = std::abs(LD(acc[j]) - ref[j]);
            const LD to_portable = std::abs(LD(acc[j]) - LD(portable[j]));
            if (to_ref > 8 * eps<float>() * size[j] || to_portable > LD(1e-6) * size[j]) {
              if (++failures <= 5)
                FAIL_CHECK(kernel_name(k)
                           << " m=" << m << " weighted=" << weighted << " j=" << j << ": "
                           << static_cast<double>(acc[j]) << " vs portable " << static_cast<double>(portable[j])
                           << ", reference " << static_cast<double>(ref[j]));
            }
          }
        }
      }
  CHECK(failures == 0);
  if (cpu_avx2()) CHECK(simd_runs > 0);
  // The dispatching entry point runs the variant simd_level() names, bit for bit.
  {
    const std::size_t m = 100;
    std::vector<C> a(m + 3), b(m + 3);
    for (std::size_t j = 0; j < m + 3; ++j) {
      a[j] = channel();
      b[j] = channel();
    }
    std::vector<float> rw(m, 0.5f), x(m, 1.0f), y(m, 1.0f);
    const RowWeights w{0.1f * scale, 0.2f * scale, 0.3f * scale, 0.4f * scale};
    mpr::detail::shift_add_flat(a.data(), b.data(), w, rw.data(), x.data(), m);
    shift_add_with(dispatched(), a.data(), b.data(), w, rw.data(), y.data(), m);
    CHECK(x == y);
  }
}

TEMPLATE_TEST_CASE("lerp_row and blend_rows: the separable shift-and-add at every level, 8-bit codes decoded",
                   "[camera_frame_kernels]", std::uint8_t, std::uint16_t, float) {
  using C = TestType;
  std::mt19937_64 rng(1996 + sizeof(C));
  std::uniform_real_distribution<double> unit(0, 1);
  const mpr_test::ChannelValues<C> channels;
  const std::uint16_t* lut = channels.lut;
  const float scale = channels.scale;
  const auto value = [&](C c) -> LD { return channels.value(c); };
  int failures = 0;
  for (const std::size_t n : kLengths)
    for (int trial = 0; trial < 3; ++trial) {
      const std::size_t m = 3 * n; // channels of n pixels
      std::vector<C> a(m + 3), b(m + 3);
      for (std::size_t j = 0; j < m + 3; ++j) {
        if constexpr (std::is_same_v<C, float>) {
          a[j] = static_cast<float>(4 * unit(rng) - 1);
          b[j] = static_cast<float>(4 * unit(rng) - 1);
        } else {
          a[j] = static_cast<C>(rng() % (std::is_same_v<C, std::uint8_t> ? 256 : 65536));
          b[j] = static_cast<C>(rng() % (std::is_same_v<C, std::uint8_t> ? 256 : 65536));
        }
      }
      const float ax = trial == 0 ? 0.0f : static_cast<float>(unit(rng));
      const float ay = trial == 0 ? 1.0f : static_cast<float>(unit(rng));
      std::vector<float> rw(n);
      for (float& w : rw) w = unit(rng) < 0.2 ? 0.0f : static_cast<float>(unit(rng));
      std::vector<float> acc0(m + kGuard, kSentinel<float>);
      for (std::size_t j = 0; j < m; ++j) acc0[j] = static_cast<float>(unit(rng));
      // Every level: `avx512` runs the word-permute AVX-512 kernel of CPUs without VBMI,
      // `avx512vbmi` the byte-permute one.
      for (const Kernel k : kernels())
        for (int weighted = 0; weighted < 2; ++weighted) {
          INFO(kernel_name(k));
          std::vector<float> h0(m + kGuard, kSentinel<float>), h1(m + kGuard, kSentinel<float>);
          // The weighted runs also ask for the other row ahead (a prefetch: the same values).
          const auto lerp = [&](const std::vector<C>& row, std::vector<float>& h, const std::vector<C>& other) {
            const C* ahead = weighted ? other.data() : nullptr;
            mpr::detail::lerp_row(row.data(), lut, ax, scale, h.data(), m, ahead, level(k));
          };
          lerp(a, h0, b);
          lerp(b, h1, a);
          std::vector<float> acc = acc0;
          mpr::detail::blend_rows(h0.data(), h1.data(), 1 - ay, ay, weighted ? rw.data() : nullptr, acc.data(), n,
                                  level(k));
          for (std::size_t j = m; j < m + kGuard; ++j)
            failures += h0[j] != kSentinel<float> || h1[j] != kSentinel<float> || acc[j] != kSentinel<float> ? 1 : 0;
          for (std::size_t j = 0; j < m; ++j) {
            const LD s = LD(scale);
            const LD ha = s * ((1 - LD(ax)) * value(a[j]) + LD(ax) * value(a[j + 3]));
            const LD hb = s * ((1 - LD(ax)) * value(b[j]) + LD(ax) * value(b[j + 3]));
            const LD r = weighted ? LD(rw[j / 3]) : 1.0L;
            const LD want = LD(acc0[j]) + r * ((1 - LD(ay)) * ha + LD(ay) * hb);
            const LD size = std::abs(LD(acc0[j])) + s * (std::abs(value(a[j])) + std::abs(value(a[j + 3])) +
                                                         std::abs(value(b[j])) + std::abs(value(b[j + 3])));
            if (!(std::abs(LD(acc[j]) - want) <= 8 * eps<float>() * size) && ++failures <= 5)
              FAIL_CHECK(kernel_name(k) << " n=" << n << " j=" << j << ": " << acc[j] << " vs "
                                        << static_cast<double>(want));
          }
        }
    }
  CHECK(failures == 0);
}

TEST_CASE("lerp_add_weighted_row_codes_vbmi: a camera row decoded, interpolated and added times each pixel's weight, "
          "the weights summed",
          "[camera_frame_kernels]") {
#if defined(MPR_SIMD_X86)
  if (!mpr_test::runs(Kernel::avx512vbmi)) {
    SUCCEED("no AVX-512 VBMI on this CPU (or MPR_SIMD below it): the one-pass weighted row kernel is not run");
    return;
  }
  std::mt19937_64 rng(2004);
  std::uniform_real_distribution<double> unit(0, 1);
  const mpr_test::ChannelValues<std::uint8_t> channels;
  int failures = 0, runs = 0;
  for (const std::size_t n : kLengths)
    for (int trial = 0; trial < 4; ++trial) {
      const std::size_t m = 3 * n;
      // At a whole-pixel offset (even trials) and a fractional one, without and with a negative
      // weight and the next row's prefetch.
      const float ax = trial % 2 == 0 ? 0.0f : static_cast<float>(unit(rng));
      // Exactly the codes the kernel may read (a[0, m + 3), a[0, m) at ax = 0), so that
      // sanitizers see an overread.
      std::vector<std::uint8_t> a(m + (ax == 0 ? 0 : 3));
      for (std::uint8_t& c : a) c = static_cast<std::uint8_t>(rng() % 256);
      std::vector<float> rw(n);
      for (float& w : rw) w = unit(rng) < 0.2 ? 0.0f : static_cast<float>(unit(rng));
      std::vector<float> acc0(m + kGuard, kSentinel<float>);
      for (std::size_t j = 0; j < m; ++j) acc0[j] = static_cast<float>(unit(rng));
      if (trial >= 2 && n > 0) rw[n / 2] = -0.5f; // a negative weight: not counted in the sums
      std::vector<float> acc = acc0;
      std::vector<float> weight0(n + kGuard, kSentinel<float>);
      for (std::size_t i = 0; i < n; ++i) weight0[i] = static_cast<float>(unit(rng));
      std::vector<float> weight = weight0;
      mpr::detail::lerp_add_weighted_row_codes_vbmi(a.data(), channels.lut, ax, channels.scale, rw.data(), acc.data(),
                                                    weight.data(), m, trial >= 2 ? a.data() : nullptr);
      ++runs;
      for (std::size_t j = m; j < m + kGuard; ++j) failures += acc[j] != kSentinel<float> ? 1 : 0;
      for (std::size_t i = n; i < n + kGuard; ++i) failures += weight[i] != kSentinel<float> ? 1 : 0;
      for (std::size_t i = 0; i < n; ++i)
        if (!(weight[i] == weight0[i] + std::max(rw[i], 0.0f)) && ++failures <= 5)
          FAIL_CHECK("weight n=" << n << " i=" << i << ": " << weight[i] << " vs " << weight0[i] << " + " << rw[i]);
      for (std::size_t j = 0; j < m; ++j) {
        const LD s = LD(channels.scale);
        const LD right = ax == 0 ? 0.0L : channels.value(a[j + 3]);
        const LD h = s * ((1 - LD(ax)) * channels.value(a[j]) + LD(ax) * right);
        const LD want = LD(acc0[j]) + LD(rw[j / 3]) * h;
        const LD size = std::abs(LD(acc0[j])) + s * (channels.value(a[j]) + right);
        if (!(std::abs(LD(acc[j]) - want) <= 8 * eps<float>() * size) && ++failures <= 5)
          FAIL_CHECK("n=" << n << " ax=" << ax << " j=" << j << ": " << acc[j] << " vs " << static_cast<double>(want));
      }
    }
  CHECK(failures == 0);
  CHECK(runs > 0);
#else
  SUCCEED("not an x86 build: the one-pass weighted row kernel is not compiled");
#endif
}

TEMPLATE_TEST_CASE("plane_rays: every variant finds the plane crossing of the portable kernel and rejects bad rays",
                   "[camera_frame_kernels]", float, double) {
  using T = TestType;
  using Flag = typename PlaneRays<T>::Flag;
  std::mt19937_64 rng(sizeof(T) == 4 ? 7 : 8);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::vector<Kernel> all = kernels();
  int failures = 0, edge_checked = 0, good_rays = 0;
  const auto fail = [&](const std::string& what) {
    if (++failures <= 8) FAIL_CHECK(what);
  };
  for (int trial = 0; trial < 4; ++trial) {
    const PlaneAxes<T> f = random_frame<T>(rng);
    const mpr::Vec3<LD> n = ld(normal_of(f)), u = ld(u_of(f)), v = ld(v_of(f));
    for (const std::size_t len : kLengths) {
      RayArrays<T> rays(len);
      std::vector<int> expected(len, -1);
      for (std::size_t i = 0; i < len; ++i) {
        mpr::Vec3<T> o, d;
        if (unit(rng) < 0.25)
          expected[i] = edge_ray(static_cast<int>(rng() % kEdgeRays), f, rng, o, d);
        else
          random_ray(rng, o, d);
        rays.set(i, o, d);
      }
      PlaneOut<T> portable(len);
      for (const Kernel k : all) {
        PlaneOut<T> out(len);
        run_plane_rays(k, rays, len, f, out);
        if (k == Kernel::portable) portable = out;
        const std::string where = std::string(kernel_name(k)) + " n=" + std::to_string(len);
        if (!out.guards_intact()) fail(where + ": wrote past the end");
        for (std::size_t i = 0; i < len; ++i) {
          const std::string at = where + " i=" + std::to_string(i);
          if (out.ok[i] != 0 && out.ok[i] != Flag(-1)) fail(at + ": ok is neither 0 nor all bits");
          if (out.ok[i] != portable.ok[i]) fail(at + ": ok differs from portable");
          if (expected[i] >= 0) {
            ++edge_checked;
            if ((out.ok[i] != 0) != (expected[i] == 1)) fail(at + ": edge ray got the wrong ok flag");
          }
          // The reference in long double.
          const mpr::Vec3<LD> O = ld(rays.origin(i)), D = ld(rays.direction(i));
          const LD dn = n.dot(D), length2 = D.squaredNorm();
          const bool finite = O.allFinite() && D.allFinite() && std::isfinite(length2);
          if (expected[i] < 0 && finite) {
            // Ordinary rays: ok unless within 1% of the angle threshold.
            const LD ratio = dn * dn / length2;
            if (std::abs(ratio - LD(1e-6)) > LD(1e-8) && (out.ok[i] != 0) != (ratio > LD(1e-6)))
              fail(at + ": ok flag disagrees with the reference angle test");
          }
          if (out.ok[i] == 0) {
            if (out.cos2[i] != T(1)) fail(at + ": cos2 is not 1 where ok is 0");
            continue;
          }
          ++good_rays;
          if (!(std::isfinite(out.xu[i]) && std::isfinite(out.xv[i]) && std::isfinite(out.dd[i])))
            fail(at + ": ok but not finite");
          const LD t = -n.dot(O) / dn;
          const mpr::Vec3<LD> X = O + t * D;
          const LD dl = std::sqrt(length2);
          const LD crossing_tol = 64 * eps<T>() * (O.norm() + std::abs(t) * dl) * (dl / std::abs(dn));
          const LD dir_tol = 8 * eps<T>() * dl;
          const auto near = [&](T got, LD want, LD tol, const char* name) {
            if (!(std::abs(LD(got) - want) <= tol))
              fail(at + ": " + name + " = " + std::to_string(static_cast<double>(got)) + ", reference " +
                   std::to_string(static_cast<double>(want)));
          };
          near(out.xu[i], u.dot(X), crossing_tol, "xu");
          near(out.xv[i], v.dot(X), crossing_tol, "xv");
          near(out.du[i], u.dot(D), dir_tol, "du");
          near(out.dv[i], v.dot(D), dir_tol, "dv");
          near(out.dd[i], length2, 8 * eps<T>() * length2, "dd");
          near(out.cos2[i], dn * dn / length2, 32 * eps<T>(), "cos2");
          if (k != Kernel::portable) {
            near(out.xu[i], LD(portable.xu[i]), 2 * crossing_tol, "xu vs portable");
            near(out.xv[i], LD(portable.xv[i]), 2 * crossing_tol, "xv vs portable");
            near(out.dd[i], LD(portable.dd[i]), 16 * eps<T>() * length2, "dd vs portable");
          }
        }
      }
    }
  }
  report("plane_rays: edge rays " + std::to_string(edge_checked) + ", crossing rays " + std::to_string(good_rays));
  CHECK(failures == 0);
  CHECK(edge_checked > 100);
  CHECK(good_rays > 1000);
  // Huge and tiny directions: the float kernels reject what overflows or underflows; double
  // keeps them (edge_ray's expectations), checked above. The dispatching entry point equals
  // the variant simd_level() names, bit for bit.
  {
    const PlaneAxes<T> f = random_frame<T>(rng);
    const std::size_t len = 77;
    RayArrays<T> rays(len);
    for (std::size_t i = 0; i < len; ++i) {
      mpr::Vec3<T> o, d;
      random_ray(rng, o, d);
      rays.set(i, o, d);
    }
    PlaneOut<T> a(len), b(len);
    const T* const soa[6] = {rays.soa[0].data(), rays.soa[1].data(), rays.soa[2].data(),
                             rays.soa[3].data(), rays.soa[4].data(), rays.soa[5].data()};
    mpr::detail::plane_rays(soa, len, f, a.rays(), a.cos2.data());
    run_plane_rays(dispatched(), rays, len, f, b);
    CHECK(a.xu == b.xu);
    CHECK(a.xv == b.xv);
    CHECK(a.ok == b.ok);
    CHECK(a.cos2 == b.cos2);
  }
}

TEMPLATE_TEST_CASE("plane_rays_affine: every variant finds the crossings of an evenly spaced row of rays",
                   "[camera_frame_kernels]", float, double) {
  using T = TestType;
  using Flag = typename PlaneRays<T>::Flag;
  std::mt19937_64 rng(sizeof(T) == 4 ? 17 : 18);
  std::uniform_real_distribution<double> unit(-1, 1);
  int failures = 0, good_rays = 0, rejected = 0;
  const auto fail = [&](const std::string& what) {
    if (++failures <= 8) FAIL_CHECK(what);
  };
  for (int trial = 0; trial < 24; ++trial) {
    const PlaneAxes<T> f = random_frame<T>(rng);
    const mpr::Vec3<LD> n = ld(normal_of(f)), u = ld(u_of(f)), v = ld(v_of(f));
    for (const std::size_t len : kLengths) {
      // A row of rays: origins and directions stepping evenly; every third trial a row that
      // sweeps through parallel to the plane (some rays rejected), the others crossing it.
      T first[6], step[6];
      for (int k = 0; k < 6; ++k) {
        first[k] = static_cast<T>(4 * unit(rng));
        step[k] = static_cast<T>((k < 3 ? 0.05 : 0.01) * unit(rng));
      }
      if (trial % 3 != 0) { // directions mostly along the normal: they cross
        const mpr::Vec3<T> along = normal_of(f) * static_cast<T>(unit(rng) < 0 ? -2 : 2);
        for (int k = 0; k < 3; ++k) first[3 + k] += along[k];
      }
      for (const Kernel k : kernels()) {
        PlaneOut<T> out(len);
        mpr::detail::plane_rays_affine(first, step, len, f, out.rays(), out.cos2.data(), level(k));
        const std::string where = std::string(kernel_name(k)) + " n=" + std::to_string(len);
        if (!out.guards_intact()) fail(where + ": wrote past the end");
        for (std::size_t i = 0; i < len; ++i) {
          const std::string at = where + " i=" + std::to_string(i);
          if (out.ok[i] != 0 && out.ok[i] != Flag(-1)) fail(at + ": ok is neither 0 nor all bits");
          // The reference in long double, from the row's exact origin and direction at i.
          mpr::Vec3<LD> O, D, O_mag, D_mag;
          for (int c = 0; c < 3; ++c) {
            O[c] = LD(first[c]) + LD(i) * LD(step[c]);
            D[c] = LD(first[3 + c]) + LD(i) * LD(step[3 + c]);
            O_mag[c] = std::abs(LD(first[c])) + LD(i) * std::abs(LD(step[c]));
            D_mag[c] = std::abs(LD(first[3 + c])) + LD(i) * std::abs(LD(step[3 + c]));
          }
          const LD dn = n.dot(D), length2 = D.squaredNorm(), ratio = dn * dn / length2;
          if (std::abs(ratio - LD(1e-6)) > LD(1e-6) && (out.ok[i] != 0) != (ratio > LD(1e-6)))
            fail(at + ": ok flag disagrees with the reference angle test");
          if (out.ok[i] == 0) {
            rejected += k == Kernel::portable ? 1 : 0; // the fixture's rays, counted at one level
            if (out.cos2[i] != T(1)) fail(at + ": cos2 is not 1 where ok is 0");
            continue;
          }
          good_rays += k == Kernel::portable ? 1 : 0;
          const LD t = -n.dot(O) / dn;
          const mpr::Vec3<LD> X = O + t * D;
          const LD dl = std::sqrt(length2);
          // The tolerance of the per-ray kernel's test, on the magnitudes of the terms the
          // row's evaluation adds (a + i b) instead of the ray's own.
          const LD crossing_tol = 64 * eps<T>() * (O_mag.norm() + std::abs(t) * D_mag.norm()) * (dl / std::abs(dn));
          const LD dir_tol = 8 * eps<T>() * D_mag.norm();
          const auto near = [&](T got, LD want, LD tol, const char* name) {
            if (!(std::abs(LD(got) - want) <= tol))
              fail(at + ": " + name + " = " + std::to_string(static_cast<double>(got)) + ", reference " +
                   std::to_string(static_cast<double>(want)));
          };
          near(out.xu[i], u.dot(X), crossing_tol, "xu");
          near(out.xv[i], v.dot(X), crossing_tol, "xv");
          near(out.du[i], u.dot(D), dir_tol, "du");
          near(out.dv[i], v.dot(D), dir_tol, "dv");
          near(out.dd[i], length2, 8 * eps<T>() * D_mag.squaredNorm(), "dd");
        }
      }
    }
  }
  report("plane_rays_affine: crossing rays " + std::to_string(good_rays) + ", rejected " + std::to_string(rejected));
  CHECK(failures == 0);
  CHECK(good_rays > 10000);
  CHECK(rejected >= 5);
}

TEMPLATE_TEST_CASE("prove_nearest: every variant agrees with the portable proof, and every proof is true",
                   "[camera_frame_kernels]", float, double) {
  using T = TestType;
  using Flag = typename PlaneRays<T>::Flag;
  std::mt19937_64 rng(sizeof(T) == 4 ? 31 : 32);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::vector<Kernel> all = kernels();
  int failures = 0, borderline = 0;
  long rays_total = 0, proved = 0, checked_proofs = 0;
  const auto fail = [&](const std::string& what) {
    if (++failures <= 8) FAIL_CHECK(what);
  };
  for (int layout = 0; layout < 3; ++layout) {
    const PlaneAxes<T> f = random_frame<T>(rng);
    const mpr::Vec3<T> n = normal_of(f), u = u_of(f), v = v_of(f);
    const PlanarArray<T> array(9, 7, layout == 0 ? 0.0 : 0.3, rng);
    for (const std::size_t len : kLengths)
      for (int trial = 0; trial < 6; ++trial) {
        // Rays crossing the plane within ~0.7 of camera k, at angles up to ~70 degrees from the
        // normal, from either side, with some rays that do not cross mixed in.
        const std::size_t k = rng() % array.size();
        RayArrays<T> rays(len);
        for (std::size_t i = 0; i < len; ++i) {
          mpr::Vec3<T> o, d;
          if (unit(rng) < 0.06) {
            edge_ray(static_cast<int>(rng() % 7), f, rng, o, d);
          } else {
            const T r = static_cast<T>(0.7 * std::sqrt(unit(rng))), phi = static_cast<T>(6.2831853 * unit(rng));
            const mpr::Vec3<T> x = (array.cu[k] + r * std::cos(phi)) * u + (array.cv[k] + r * std::sin(phi)) * v;
            const T slope = static_cast<T>(trial == 0 ? 0.05 : 2.5 * unit(rng)),
                    psi = static_cast<T>(6.2831853 * unit(rng));
            d = (unit(rng) < 0.5 ? T(1) : T(-1)) * n + slope * (std::cos(psi) * u + std::sin(psi) * v);
            d *= static_cast<T>(0.2 + 3 * unit(rng));
            o = x + static_cast<T>(12 * unit(rng) - 6) * d;
          }
          rays.set(i, o, d);
        }
        PlaneOut<T> plane(len);
        run_plane_rays(Kernel::portable, rays, len, f, plane);
        T cos2_min = 1;
        for (std::size_t i = 0; i < len; ++i)
          if (plane.ok[i] != 0) cos2_min = std::min(cos2_min, plane.cos2[i]);
        const NearestCandidate<T> candidate = array.candidate(k, std::sqrt(cos2_min));
        std::vector<Flag> portable;
        for (const Kernel kern : all) {
          std::vector<Flag> pass(len + kGuard, static_cast<Flag>(kFlagSentinel));
          std::vector<T> scratch(len + kGuard, kSentinel<T>);
          prove_nearest_with(kern, plane.rays(), len, candidate, pass.data(), scratch.data());
          if (kern == Kernel::portable) portable = pass;
          const std::string where = std::string(kernel_name(kern)) + " n=" + std::to_string(len);
          for (std::size_t i = len; i < len + kGuard; ++i)
            if (pass[i] != static_cast<Flag>(kFlagSentinel) || scratch[i] != kSentinel<T>)
              fail(where + ": wrote past the end");
          for (std::size_t i = 0; i < len; ++i) {
            const std::string at = where + " i=" + std::to_string(i);
            if (pass[i] != 0 && pass[i] != Flag(-1)) fail(at + ": pass is neither 0 nor all bits");
            if (pass[i] != 0 && plane.ok[i] == 0) fail(at + ": proved a ray that does not cross the plane");
            if (pass[i] != portable[i]) {
              // Only where a test of the proof is within rounding of its threshold (FMA).
              const LD xu = plane.xu[i], xv = plane.xv[i], du = plane.du[i], dv = plane.dv[i], dd = plane.dd[i];
              const auto terms = [&](T cu, T cv, LD& num, LD& size) {
                const LD eu = LD(cu) - xu, ev = LD(cv) - xv, r2 = eu * eu + ev * ev, ed = eu * du + ev * dv;
                num = r2 * dd - ed * ed;
                size = r2 * dd + ed * ed;
              };
              LD sk, size_k;
              terms(candidate.cu, candidate.cv, sk, size_k);
              const LD rk =
                  (LD(candidate.cu) - xu) * (LD(candidate.cu) - xu) + (LD(candidate.cv) - xv) * (LD(candidate.cv) - xv);
              LD slack = std::abs(LD(candidate.rho2) - rk) / (LD(candidate.rho2) + rk);
              const LD threshold = sk * LD(1.0001) + LD(candidate.margin2) * dd;
              for (int j = 0; j < candidate.neighbours; ++j) {
                LD q, size_j;
                terms(candidate.nu[j], candidate.nv[j], q, size_j);
                slack = std::min(slack, std::abs(q - threshold) / (size_j + size_k + LD(candidate.margin2) * dd));
              }
              if (slack <= 64 * eps<T>())
                ++borderline;
              else
                fail(at + ": pass differs from portable away from any threshold");
            }
            if (pass[i] == 0) continue;
            // Soundness: camera k is strictly the nearest camera to the ray line (long double).
            ++checked_proofs;
            const Nearest truth = brute_force_ld(array, f, rays.origin(i), rays.direction(i));
            if (truth.index != static_cast<int>(k) || !(truth.best < truth.second))
              fail(at + ": proved camera " + std::to_string(k) + " but the nearest is " + std::to_string(truth.index));
          }
        }
        for (std::size_t i = 0; i < len; ++i) {
          ++rays_total;
          if (portable[i] != 0) ++proved;
        }
      }
  }
  const std::string counts = "prove_nearest: rays " + std::to_string(rays_total) + ", proved " +
                             std::to_string(proved) + ", borderline " + std::to_string(borderline);
  report(counts);
  INFO(counts);
  CHECK(failures == 0);
  CHECK(borderline <= 2);
  // The proof is not vacuous: most rays that cross near camera k are proved.
  CHECK(proved * 3 > rays_total);
  CHECK(checked_proofs >= proved);
}

TEMPLATE_TEST_CASE(
    "cylinder_weights: the linear falloff 1 - d / r and its positive span, the SIMD kernels equal to the "
    "portable one",
    "[camera_frame_kernels]", float, double) {
  using T = TestType;
  std::mt19937_64 rng(sizeof(T) == 4 ? 41 : 42);
  std::uniform_real_distribution<double> unit(0, 1);
  int failures = 0, inside = 0, outside = 0, simd_runs = 0;
  const auto fail = [&](const std::string& what) {
    if (++failures <= 8) FAIL_CHECK(what);
  };
  const PlaneAxes<T> f = random_frame<T>(rng);
  const mpr::Vec3<T> n = normal_of(f), u = u_of(f), v = v_of(f);
  for (const double radius : {0.3, 1.2, 3.0})
    for (const std::size_t len : kLengths)
      for (int trial = 0; trial < 3; ++trial) {
        RayArrays<T> rays(len);
        for (std::size_t i = 0; i < len; ++i) {
          const mpr::Vec3<T> x = static_cast<T>(4 * unit(rng) - 2) * u + static_cast<T>(4 * unit(rng) - 2) * v;
          const mpr::Vec3<T> d = n + static_cast<T>(2 * unit(rng) - 1) * u + static_cast<T>(2 * unit(rng) - 1) * v;
          rays.set(i, mpr::Vec3<T>(x + static_cast<T>(10 * unit(rng) - 5) * d), d);
        }
        PlaneOut<T> plane(len);
        run_plane_rays(Kernel::portable, rays, len, f, plane);
        // Exactly sized inputs (sanitizers), as the sampler passes them.
        std::vector<T> xu(plane.xu.begin(), plane.xu.begin() + static_cast<std::ptrdiff_t>(len));
        std::vector<T> xv(plane.xv.begin(), plane.xv.begin() + static_cast<std::ptrdiff_t>(len));
        std::vector<T> du(plane.du.begin(), plane.du.begin() + static_cast<std::ptrdiff_t>(len));
        std::vector<T> dv(plane.dv.begin(), plane.dv.begin() + static_cast<std::ptrdiff_t>(len));
        std::vector<T> inv_dd(len);
        for (std::size_t i = 0; i < len; ++i) inv_dd[i] = T(1) / plane.dd[i];
        const T cu = static_cast<T>(2 * unit(rng) - 1), cv = static_cast<T>(2 * unit(rng) - 1);
        const T inv_radius = T(1) / static_cast<T>(radius);
        std::vector<float> w(len + kGuard, kSentinel<float>);
        const auto span = mpr::detail::cylinder_weights_portable(xu.data(), xv.data(), du.data(), dv.data(),
                                                                 inv_dd.data(), len, cu, cv, inv_radius, w.data());
        // [first, last): from the first to one past the last positive weight (n, n: none).
        const auto positive_span = [&](const std::vector<float>& ws) {
          std::size_t first = len, last = len;
          for (std::size_t i = 0; i < len; ++i)
            if (ws[i] > 0) {
              first = std::min(first, i);
              last = i + 1;
            }
          return std::array<std::size_t, 2>{first, last};
        };
        if (span != positive_span(w)) fail("portable span, n=" + std::to_string(len));
        std::vector<LD> tol(len);
        for (std::size_t i = 0; i < len; ++i) {
          const std::string at =
              "portable r=" + std::to_string(radius) + " n=" + std::to_string(len) + " i=" + std::to_string(i);
          const LD eu = LD(cu) - LD(xu[i]), ev = LD(cv) - LD(xv[i]), ed = eu * LD(du[i]) + ev * LD(dv[i]);
          const LD r2 = eu * eu + ev * ev, along = ed * ed * LD(inv_dd[i]);
          const LD d2 = std::max(r2 - along, LD(0));
          const LD want = std::max(LD(1) - std::sqrt(d2) * LD(inv_radius), LD(0));
          // |sqrt a - sqrt b| <= min(sqrt |a - b|, |a - b| / sqrt b); a - b is rounding in r2 - along.
          const LD delta = 32 * eps<T>() * (r2 + along);
          const LD dist_tol = d2 > 0 ? std::min(std::sqrt(delta), delta / std::sqrt(d2)) : std::sqrt(delta);
          tol[i] = dist_tol * LD(inv_radius) + 4 * eps<float>();
          if (!(std::abs(LD(w[i]) - want) <= tol[i]))
            fail(at + ": " + std::to_string(w[i]) + ", reference " + std::to_string(static_cast<double>(want)));
          if (want > tol[i])
            ++inside;
          else if (want == 0 && w[i] == 0)
            ++outside;
        }
        for (std::size_t i = len; i < len + kGuard; ++i)
          if (w[i] != kSentinel<float>) fail("portable wrote past the end");
        // Every level's kernel (for float the Highway one: SSE4 at portable, AVX2, AVX-512) against
        // the portable loop, and the default level's dispatch.
        for (const Kernel level : kernels()) {
          ++simd_runs;
          const std::string name = kernel_name(level);
          std::vector<float> w2(len + kGuard, kSentinel<float>);
          const auto span2 = mpr::detail::cylinder_weights(xu.data(), xv.data(), du.data(), dv.data(), inv_dd.data(),
                                                           len, cu, cv, inv_radius, w2.data(), level);
          for (std::size_t i = 0; i < len; ++i)
            if (!(std::abs(LD(w2[i]) - LD(w[i])) <= 2 * tol[i]))
              fail(name + " n=" + std::to_string(len) + " i=" + std::to_string(i) + ": " + std::to_string(w2[i]) +
                   " vs portable " + std::to_string(w[i]));
          if (span2 != positive_span(w2)) fail(name + " span, n=" + std::to_string(len));
          for (std::size_t i = len; i < len + kGuard; ++i)
            if (w2[i] != kSentinel<float>) fail(name + " wrote past the end");
          if (level != dispatched()) continue;
          std::vector<float> w3(len + kGuard, kSentinel<float>);
          const auto span3 = mpr::detail::cylinder_weights(xu.data(), xv.data(), du.data(), dv.data(), inv_dd.data(),
                                                           len, cu, cv, inv_radius, w3.data());
          if (w3 != w2 || span3 != span2) fail("cylinder_weights does not dispatch to " + name);
        }
      }
  CHECK(failures == 0);
  CHECK(inside > 100);
  CHECK(outside > 100);
  CHECK(simd_runs > 0);
}

TEMPLATE_TEST_CASE("the nearest-camera tile path shows exactly the brute-force nearest camera",
                   "[camera_frame_kernels][camera_frame_sampler]", float, double) {
  using T = TestType;
  struct Layout {
    const char* name;
    double jitter, tilt_x, tilt_y;
  };
  const Layout layouts[] = {{"7x5 grid", 0, 0, 0}, {"jittered", 0.3, 0, 0}, {"jittered, tilted", 0.25, 0.15, -0.1}};
  const int W = 160, H = 100;
  const mpr::Region region(0, 0, W, H);
  // Views: a perspective view through the array, a cross-slit whose rays cross the array plane
  // on a rectangle sweeping past its edges, and a tilted focal plane.
  const mpr::PinholeCamera<T> eye = mpr::PinholeCamera<T>::look_at(
      mpr::Vec3<T>(T(0.3), T(-0.2), T(-4)), mpr::Vec3<T>(0, 0, 8), mpr::Vec3<T>(0, -1, 0), T(0.9), W, H);
  const mpr::PlanarSurface<T> front = eye.image_plane(T(12));
  const mpr::PlanarSurface<T> flat(mpr::Vec3<T>(-8, -5, 8), mpr::Vec3<T>(16, 0, 0), mpr::Vec3<T>(0, 10, 0));
  const mpr::PinholeCamera<T> oblique = mpr::PinholeCamera<T>::look_at(
      mpr::Vec3<T>(T(-0.4), T(0.3), T(-3)), mpr::Vec3<T>(T(0.5), 0, 8), mpr::Vec3<T>(0, -1, 0), T(0.8), W, H);
  const mpr::PlanarSurface<T> tilted = oblique.image_plane(T(11)).tilted(T(0.3), T(0.2));
  const std::vector<std::pair<mpr::PlanarSurface<T>, mpr::GlcSelector<T>>> views{
      {front, mpr::pinhole_glc(eye, front)},
      {flat, sweep_glc(flat, T(-4.5), T(9), T(-3.5), T(7))},
      {tilted, mpr::pinhole_glc(oblique, tilted)}};
  long pixels = 0, ties = 0, background = 0;
  for (const Layout& layout : layouts) {
    const auto cams = array_cameras<T>(7, 5, layout.jitter, layout.tilt_x, layout.tilt_y, 24, 16, 6.0, 77);
    std::vector<mpr::Image<mpr::Rgb8>> images;
    for (std::size_t i = 0; i < cams.size(); ++i) images.emplace_back(24, 16, camera_code(i));
    const auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(cams, images);
    for (const mpr::PixelFilter filter : {mpr::PixelFilter::nearest, mpr::PixelFilter::bilinear}) {
      typename mpr::CameraFrameSampler<mpr::NearestCamera, T>::Config config;
      config.filter = filter;
      const mpr::CameraFrameSampler<mpr::NearestCamera, T> sampler(frames, {}, config);
      REQUIRE(sampler.planar_array());
      for (std::size_t view = 0; view < views.size(); ++view) {
        const mpr::Renderer renderer(views[view].first, views[view].second, sampler);
        mpr::Image<mpr::Rgb8> image(W, H);
        renderer.render(image.view(), region, mpr::RenderOptions{1});
        int wrong = 0, wrong_in_tie = 0, differs_from_sample = 0;
        std::string first;
        for (int y = 0; y < H; ++y)
          for (int x = 0; x < W; ++x) {
            ++pixels;
            const mpr::Ray<T> ray = renderer.ray_at({x, y}, region);
            const int k = sampler.index().nearest_brute_force(ray.origin, ray.direction);
            const int got = decode_camera(image(x, y), cams.size());
            const T inv = T(1) / ray.direction.squaredNorm();
            T best = std::numeric_limits<T>::infinity(), second = best;
            for (const auto& c : cams) {
              const T d2 = mpr::line_distance2(c.centre(), ray.origin, ray.direction, inv);
              if (d2 < best) {
                second = best;
                best = d2;
              } else if (d2 < second) {
                second = d2;
              }
            }
            if (second - best <= T(1e-5) * second) {
              // A tie: either camera is right, but it must be one of the tied ones.
              ++ties;
              if (got >= 0 && !(mpr::line_distance2(cams[static_cast<std::size_t>(got)].centre(), ray.origin,
                                                    ray.direction, inv) <= best * T(1 + 2e-5))) {
                ++wrong_in_tie;
              }
              continue;
            }
            const bool seen = k >= 0 && cams[static_cast<std::size_t>(k)].project(ray.origin).has_value();
            const int want = seen ? k : -1;
            if (want < 0) ++background;
            if (got != want && ++wrong == 1)
              first = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): camera " + std::to_string(got) +
                      ", brute force " + std::to_string(want);
            if (mpr::to_rgb8(renderer.shade({x, y}, region)) != image(x, y)) ++differs_from_sample;
          }
        INFO(layout.name << ", filter " << (filter == mpr::PixelFilter::nearest ? "nearest" : "bilinear") << ", view "
                         << view << ": " << first);
        CHECK(wrong == 0);
        CHECK(wrong_in_tie == 0);
        CHECK(differs_from_sample == 0);
      }
    }
  }
  const std::string counts = "nearest tiles: pixels " + std::to_string(pixels) + ", ties skipped " +
                             std::to_string(ties) + ", background " + std::to_string(background);
  report(counts);
  INFO(counts);
  CHECK(ties * 200 < pixels); // ties are rare: under 0.5 %
  CHECK(background * 20 < pixels);
  // Rays that do not cross the camera plane (nearly or exactly parallel to it), mixed in rows
  // with rays that do, through the tile interface directly.
  const auto cams = array_cameras<T>(7, 5, 0.3, 0, 0, 24, 16, 6.0, 78);
  std::vector<mpr::Image<mpr::Rgb8>> images;
  for (std::size_t i = 0; i < cams.size(); ++i) images.emplace_back(24, 16, camera_code(i));
  const mpr::CameraFrameSampler<mpr::NearestCamera, T> sampler(
      std::make_shared<const mpr::CameraFrameSet<T>>(cams, images));
  const std::size_t width = 96;
  const std::vector<mpr::Ray<T>> rays = grazing_rows<T>(width);
  std::vector<mpr::Color> out(rays.size());
  sampler.sample_tile(rays, static_cast<int>(width), out);
  int wrong = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const int k = sampler.index().nearest_brute_force(rays[i].origin, rays[i].direction);
    const int got = decode_camera(mpr::to_rgb8(out[i]), cams.size());
    const bool seen = k >= 0 && cams[static_cast<std::size_t>(k)].project(rays[i].origin).has_value();
    if (got != (seen ? k : -1) || mpr::to_rgb8(out[i]) != mpr::to_rgb8(sampler.sample(rays[i]))) ++wrong;
  }
  CHECK(wrong == 0);
}

TEMPLATE_TEST_CASE("the cylinder tile path renders the per-pixel image, fallback to the nearest camera included",
                   "[camera_frame_kernels][camera_frame_sampler]", float, double) {
  using T = TestType;
  const int W = 160, H = 100;
  const mpr::Region region(0, 0, W, H);
  // A focal plane parallel to the array at the cameras' pixel scale (weighted shift-and-add)
  // and the same plane tilted (per ray), each seen by a cross-slit whose rays cross the array
  // plane on a rectangle reaching 3.5 and 2.5 spacings past its edges.
  mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
  K(0, 0) = K(1, 1) = T(48);
  K(0, 2) = T(0.5) * (W - 1);
  K(1, 2) = T(0.5) * (H - 1);
  const mpr::PinholeCamera<T> straight(K, mpr::Mat3<T>::Identity(), mpr::Vec3<T>(T(-0.1), T(0.2), 0), W, H);
  const mpr::PlanarSurface<T> parallel = straight.image_plane(T(12));
  const mpr::PlanarSurface<T> tilted = parallel.tilted(T(0.25), T(-0.2));
  const std::vector<std::pair<mpr::PlanarSurface<T>, mpr::GlcSelector<T>>> views{
      {parallel, sweep_glc(parallel, T(-6.5), T(13), T(-4.5), T(9))},
      {tilted, sweep_glc(tilted, T(-6.5), T(13), T(-4.5), T(9))}};
  const std::vector<mpr::Ray<T>> grazing = grazing_rows<T>(96);
  long fallback = 0, blended = 0, grazing_weighed = 0;
  for (const double jitter : {0.0, 0.3}) {
    const auto cams = array_cameras<T>(7, 5, jitter, 0, 0, 192, 128, 48.0, 91);
    const auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(cams, smooth_images(cams, 5));
    for (const double radius : {0.3, 1.2, 3.0}) {
      const mpr::CameraFrameSampler<mpr::CylinderAperture, T> sampler(frames, mpr::CylinderAperture{radius});
      REQUIRE(sampler.planar_array());
      for (std::size_t view = 0; view < views.size(); ++view) {
        const mpr::Renderer renderer(views[view].first, views[view].second, sampler);
        mpr::Image<mpr::Rgb8> image(W, H);
        renderer.render(image.view(), region, mpr::RenderOptions{1});
        int worst = 0;
        for (int y = 0; y < H; ++y)
          for (int x = 0; x < W; ++x) {
            worst = std::max(worst, rgb_difference(mpr::to_rgb8(renderer.shade({x, y}, region)), image(x, y)));
            const mpr::Ray<T> ray = renderer.ray_at({x, y}, region);
            int within = 0;
            sampler.index().within(ray.origin, ray.direction, static_cast<T>(radius), [&](int, T) { ++within; });
            fallback += within == 0 ? 1 : 0;
            blended += within >= 2 ? 1 : 0;
          }
        INFO("jitter " << jitter << ", radius " << radius << ", view " << view);
        CHECK(worst <= 1);
      }
      // Rows with rays that do not cross the plane take the fallback path and still match.
      std::vector<mpr::Color> out(grazing.size());
      sampler.sample_tile(grazing, 96, out);
      int worst = 0;
      for (std::size_t i = 0; i < grazing.size(); ++i) {
        worst = std::max(worst, rgb_difference(mpr::to_rgb8(out[i]), mpr::to_rgb8(sampler.sample(grazing[i]))));
        int within = 0;
        sampler.index().within(grazing[i].origin, grazing[i].direction, static_cast<T>(radius),
                               [&](int, T) { ++within; });
        grazing_weighed += within > 0 ? 1 : 0;
      }
      INFO("grazing rows, jitter " << jitter << ", radius " << radius);
      CHECK(worst <= 1);
    }
  }
  const std::string counts = "cylinder tiles: fallback " + std::to_string(fallback) + ", blended " +
                             std::to_string(blended) + ", grazing weighed " + std::to_string(grazing_weighed);
  report(counts);
  INFO(counts);
  CHECK(fallback > 1000);
  CHECK(blended > 1000);
  CHECK(grazing_weighed > 100);
}

TEMPLATE_TEST_CASE("evenly_spaced: every variant tells evenly spaced points from others; min_of, widen_bounds",
                   "[camera_frame_kernels]", float, double) {
  using T = TestType;
  std::mt19937_64 rng(sizeof(T) == 4 ? 51 : 52);
  std::uniform_real_distribution<double> unit(-1, 1);
  const std::vector<Kernel> all = kernels();
  int failures = 0, even_rows = 0, uneven_rows = 0;
  const auto fail = [&](const std::string& what) {
    if (++failures <= 8) FAIL_CHECK(what);
  };
  for (const std::size_t len : kLengths)
    for (int trial = 0; trial < 8; ++trial) {
      const int n = static_cast<int>(len);
      std::vector<T> x(len), y(len), z(len);
      const mpr::Vec3<double> p0(20 * unit(rng), 20 * unit(rng), 20 * unit(rng));
      const mpr::Vec3<double> step(unit(rng), unit(rng), 0.1 * unit(rng));
      for (std::size_t i = 0; i < len; ++i) {
        const mpr::Vec3<double> p = p0 + static_cast<double>(i) * step;
        x[i] = static_cast<T>(p.x());
        y[i] = static_cast<T>(p.y());
        z[i] = static_cast<T>(p.z());
      }
      // As the sampler sets it: 64 eps times the size of the end points.
      const T tolerance = T(64) * std::numeric_limits<T>::epsilon() * static_cast<T>(2 * p0.cwiseAbs().maxCoeff() + 20);
      // Trial 0: exact; 1..3: one inner point moved by 10 x the tolerance (in x, y or z);
      // 4: one inner point NaN; 5: infinite; others: moved by a tenth of the tolerance.
      bool want = true;
      if (n >= 3 && trial > 0) {
        const std::size_t i = 1 + rng() % (len - 2);
        std::vector<T>* axis[3] = {&x, &y, &z};
        if (trial <= 3) {
          (*axis[trial - 1])[i] += T(10) * tolerance;
          want = false;
        } else if (trial == 4) {
          (*axis[rng() % 3])[i] = std::numeric_limits<T>::quiet_NaN();
          want = false;
        } else if (trial == 5) {
          (*axis[rng() % 3])[i] = std::numeric_limits<T>::infinity();
          want = false;
        } else {
          (*axis[rng() % 3])[i] += T(0.1) * tolerance;
        }
      }
      (want ? even_rows : uneven_rows) += 1;
      for (const Kernel k : all) {
        const bool got = evenly_spaced_with(k, x.data(), y.data(), z.data(), n, tolerance);
        if (got != want)
          fail(std::string(kernel_name(k)) + " n=" + std::to_string(n) + " trial " + std::to_string(trial) + ": " +
               (got ? "even" : "not even"));
      }
      if (mpr::detail::evenly_spaced(x.data(), y.data(), z.data(), n, tolerance) != want)
        fail("dispatch n=" + std::to_string(n));
    }
  CHECK(failures == 0);
  CHECK(uneven_rows > 50);
  // min_of: the least value (+inf for none), whatever the length and position.
  for (const std::size_t len : kLengths) {
    std::vector<T> v(len);
    for (T& e : v) e = static_cast<T>(100 * unit(rng));
    if (len > 0) v[rng() % len] = T(-1000);
    const T want = len == 0 ? std::numeric_limits<T>::infinity() : *std::min_element(v.begin(), v.end());
    CHECK(mpr::detail::min_of(v.data(), len) == want);
    if (len > 0) {
      v[len - 1] = -std::numeric_limits<T>::infinity(); // in the tail
      CHECK(mpr::detail::min_of(v.data(), len) == -std::numeric_limits<T>::infinity());
    }
  }
  // widen_bounds: the bounds grown to every value, kept where the values lie inside them.
  for (const std::size_t len : kLengths) {
    std::vector<T> v(len);
    for (T& e : v) e = static_cast<T>(100 * unit(rng) - 50);
    if (len > 0) v[rng() % len] = T(-1000);
    if (len > 0) v[len - 1] = T(1000); // in the tail
    T lo = std::numeric_limits<T>::infinity(), hi = -lo;
    mpr::detail::widen_bounds(v.data(), len, lo, hi);
    CHECK(lo == (len == 0 ? std::numeric_limits<T>::infinity() : *std::min_element(v.begin(), v.end())));
    CHECK(hi == (len == 0 ? -std::numeric_limits<T>::infinity() : *std::max_element(v.begin(), v.end())));
    T wide_lo = T(-5000), wide_hi = T(5000);
    mpr::detail::widen_bounds(v.data(), len, wide_lo, wide_hi);
    CHECK(wide_lo == T(-5000));
    CHECK(wide_hi == T(5000));
  }
}

TEST_CASE("average_rows: the sums over positive weights at every level, 0 elsewhere", "[camera_frame_kernels]") {
  // Weights of every kind the finish sees (counts, fractions) and the ones it must not divide by.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float kinds[] = {0.0f, 1.0f, 3.0f, 0.37f, -1.0f, -0.0f, nan, std::numeric_limits<float>::denorm_min(), 48.0f};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> colour(0.0f, 50.0f);
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{8}, std::size_t{9},
                              std::size_t{255}, std::size_t{256}, std::size_t{257}, std::size_t{600}}) {
    std::vector<float> weight(n), acc(3 * n);
    for (std::size_t i = 0; i < n; ++i) weight[i] = kinds[(i * 5 + n) % std::size(kinds)];
    for (float& a : acc) a = colour(rng);
    mpr_test::for_each_simd_level([&](Kernel level) {
      std::vector<float> out(3 * n + 1, -7.0f);
      mpr::detail::average_rows(acc.data(), weight.data(), out.data(), n, level);
      int wrong = 0;
      for (std::size_t j = 0; j < 3 * n; ++j) {
        const float w = weight[j / 3];
        const float expected = w > 0 ? acc[j] * (1.0f / w) : 0.0f;
        wrong += std::bit_cast<std::uint32_t>(out[j]) != std::bit_cast<std::uint32_t>(expected) ? 1 : 0;
      }
      INFO("n " << n << ", level " << mpr::detail::simd_level_name(level));
      CHECK(wrong == 0);
      CHECK(out[3 * n] == -7.0f); // nothing written past the row
    });
  }
}
