// Numerical stability of the GLC classifier: random invariance, near-degenerate inputs.
// Figures quoted in docs/numerics.md come from these tests (run with -s to see the WARN lines).
#include "glc_test_util.hpp"

#include <mpr/glc.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>

using mpr::glc::Type;

namespace {

template <class T>
struct RandomGlc {
  mpr::PlanarSurface<T> plane;
  mpr::GlcSelector<T> selector;
};

using glc_test::Rng;

template <class T>
RandomGlc<T> random_glc(Rng& rng) {
  for (;;) {
    const mpr::Vec3<T> o = rng.vec<T>(-1, 1), w = rng.vec<T>(-1, 1), h = rng.vec<T>(-1, 1);
    if (!(w.cross(h).norm() > T(0.3) * w.norm() * h.norm()) || w.norm() < T(0.3) || h.norm() < T(0.3)) continue;
    const mpr::PlanarSurface<T> plane(o, w, h);
    const auto dir = [&]() {
      const mpr::Vec3<T> r = rng.vec<T>(-1, 1);
      return mpr::Vec3<T>(r - r.dot(plane.normal()) * plane.normal() + plane.normal());
    };
    const mpr::Vec3<T> d0 = dir(), d1 = dir(), d2 = dir();
    return {plane, mpr::GlcSelector<T>(plane, d0, d1, d2)};
  }
}

// The same GLC with generators re-chosen at uv points a, b, c of the original plane, moved along
// their rays to depth h (so the new image plane is parallel to the old one, h further along).
template <class T>
RandomGlc<T> rechoose(const RandomGlc<T>& g, const mpr::Vec2<T>& a, const mpr::Vec2<T>& b, const mpr::Vec2<T>& c, T h) {
  const auto at = [&](const mpr::Vec2<T>& uv) {
    return mpr::Vec3<T>(g.plane.point_at(uv) + h * g.selector.direction_at(uv));
  };
  const mpr::Vec3<T> pa = at(a), pb = at(b), pc = at(c);
  const mpr::PlanarSurface<T> plane(pa, mpr::Vec3<T>(pb - pa), mpr::Vec3<T>(pc - pa));
  return {plane, mpr::GlcSelector<T>(plane, g.selector.direction_at(a), g.selector.direction_at(b),
                                     g.selector.direction_at(c))};
}

template <class T>
RandomGlc<T> transformed(const RandomGlc<T>& g, T scale, const mpr::Vec3<T>& offset) {
  const mpr::PlanarSurface<T> plane(mpr::Vec3<T>(scale * g.plane.origin() + offset),
                                    mpr::Vec3<T>(scale * g.plane.width_vector()),
                                    mpr::Vec3<T>(scale * g.plane.height_vector()));
  return {plane, mpr::GlcSelector<T>(plane, g.selector.d00(), g.selector.d10(), g.selector.d01())};
}

template <class T>
std::string describe(const RandomGlc<T>& g) {
  std::ostringstream s;
  s.precision(17);
  s << "origin " << g.plane.origin().transpose() << " w " << g.plane.width_vector().transpose() << " h "
    << g.plane.height_vector().transpose() << " d00 " << g.selector.d00().transpose() << " d10 "
    << g.selector.d10().transpose() << " d01 " << g.selector.d01().transpose();
  return s.str();
}

} // namespace

TEMPLATE_TEST_CASE("stability: 20,000 random GLCs keep their type under re-chosen generators, translation and scaling",
                   "[glc][stability]", float, double) {
  using T = TestType;
  Rng rng(20041);
  std::map<Type, int> histogram;
  int rechosen = 0, shifted_plane = 0, crossed_far = 0, translated = 0, scaled = 0;
  double worst_depth_shift = 0, worst_depth_scale = 0, worst_slit_translation = 0;
  std::string first_failure;
  for (int i = 0; i < 20000; ++i) {
    const RandomGlc<T> g = random_glc<T>(rng);
    const auto base = mpr::glc::classify(g.plane, g.selector);
    ++histogram[base.type];

    // Re-chosen generators: a random well-shaped triangle of the image, moved to a parallel
    // plane at depth h (not near a slit, where the new image triangle would collapse).
    mpr::Vec2<T> a, b, c;
    do {
      a = {T(rng.uniform(0, 1)), T(rng.uniform(0, 1))};
      b = {T(rng.uniform(0, 1)), T(rng.uniform(0, 1))};
      c = {T(rng.uniform(0, 1)), T(rng.uniform(0, 1))};
    } while (std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x()) < 0.1);
    // The same reference length as the base camera: `far` and the other tolerances are relative
    // to it, and the re-chosen generator triangle is smaller than the image.
    mpr::glc::ClassifyConfig<T> same_length;
    same_length.length = mpr::glc::two_plane(g.plane, g.selector).scale();
    const RandomGlc<T> re = rechoose(g, a, b, c, T(0));
    const auto other = mpr::glc::classify(re.plane, re.selector, same_length);
    if (other.type != base.type) {
      ++rechosen;
      if (first_failure.empty()) first_failure = "rechosen: " + describe(g);
    }
    // The same generators on a parallel plane at depth h (not near a slit, where the new image
    // triangle collapses): depths shift by -h, so a slit within |h| of `far` may cross it; any
    // other change of type is a failure.
    T h = T(rng.uniform(-1, 1));
    if (std::abs(base.characteristic(double(h))) < 0.2 * std::abs(base.characteristic.c)) h = 0;
    const RandomGlc<T> shifted = rechoose(g, a, b, c, h);
    const auto moved_plane = mpr::glc::classify(shifted.plane, shifted.selector, same_length);
    if (moved_plane.type != base.type) {
      const double far = double(same_length.far) * double(same_length.length);
      const bool near_far =
          !base.roots.complex && (std::abs(std::abs(base.roots.second) - far) <= std::abs(double(h)) * 1.01 ||
                                  std::abs(std::abs(base.roots.first) - far) <= std::abs(double(h)) * 1.01);
      if (near_far) {
        ++crossed_far;
      } else {
        ++shifted_plane;
        if (first_failure.empty()) first_failure = "parallel plane: " + describe(g);
      }
    } else if (base.type == Type::cross_slit) {
      // Depths are now measured from the plane at depth h.
      const double b0 = std::min(base.depths[0], base.depths[1]), b1 = std::max(base.depths[0], base.depths[1]);
      const double o0 = std::min(moved_plane.depths[0], moved_plane.depths[1]),
                   o1 = std::max(moved_plane.depths[0], moved_plane.depths[1]);
      worst_depth_shift = std::max({worst_depth_shift, std::abs(o0 - (b0 - double(h))) / std::max(1.0, std::abs(b0)),
                                    std::abs(o1 - (b1 - double(h))) / std::max(1.0, std::abs(b1))});
    }

    // Translation by up to 1e8 and scaling by 1e-6 .. 1e6.
    const mpr::Vec3<T> offset = rng.vec<T>(-1, 1) * T(std::pow(10.0, rng.uniform(0, 8)));
    const RandomGlc<T> tr = transformed(g, T(1), offset);
    const auto moved = mpr::glc::classify(tr.plane, tr.selector);
    if (moved.type != base.type) {
      ++translated;
      if (first_failure.empty()) first_failure = "translated: " + describe(g);
    } else if (base.type == Type::cross_slit) {
      const double err = (moved.slits[0].point - offset - base.slits[0].point).template cast<double>().norm();
      worst_slit_translation = std::max(worst_slit_translation, err / std::max(1.0, double(offset.norm())));
    }
    const T s = T(std::pow(10.0, rng.uniform(-6, 6)));
    const RandomGlc<T> sc = transformed(g, s, mpr::Vec3<T>(mpr::Vec3<T>::Zero()));
    const auto big = mpr::glc::classify(sc.plane, sc.selector);
    if (big.type != base.type) {
      ++scaled;
      if (first_failure.empty()) first_failure = "scaled: " + describe(g);
    } else if (base.type == Type::cross_slit) {
      for (int k = 0; k < 2; ++k)
        worst_depth_scale =
            std::max(worst_depth_scale, std::abs(double(big.depths[k]) / double(s) - double(base.depths[k])) /
                                            std::max(1.0, std::abs(double(base.depths[k]))));
    }
  }
  INFO(first_failure);
  CHECK(rechosen == 0);
  CHECK(shifted_plane == 0);
  CHECK(translated == 0);
  CHECK(scaled == 0);
  // Generic GLCs are cross-slit or bilinear (glc-math.md sec. 3.3: 77.7% / 22.3%).
  CHECK(histogram[Type::cross_slit] > 14000);
  CHECK(histogram[Type::bilinear] > 3500);
  std::ostringstream s;
  for (const auto& [type, count] : histogram) s << mpr::glc::to_string(type) << " " << count << "  ";
  WARN((sizeof(T) == 4 ? "float" : "double")
       << " random types: " << s.str() << "\n moved to a parallel plane: " << crossed_far
       << " slits crossed `far`; worst relative depth error after "
       << "re-choosing generators " << worst_depth_shift << ", after scaling " << worst_depth_scale
       << ", slit point after translation (relative to offset) " << worst_slit_translation);
  CHECK(worst_depth_shift < (sizeof(T) == 4 ? 1e-2 : 1e-8));
  // Measured 4.8e-6 (float) and 9.2e-15 (double) relative to the offset.
  CHECK(worst_slit_translation < (sizeof(T) == 4 ? 1e-4 : 1e-12));
  CHECK(worst_depth_scale < (sizeof(T) == 4 ? 1e-3 : 1e-10));
}

TEMPLATE_TEST_CASE("stability: a perturbed pinhole", "[glc][stability]", float, double) {
  using T = TestType;
  Rng rng(7);
  int still_pinhole = 0, not_pinhole = 0;
  const int n = 500;
  for (int i = 0; i < n; ++i) {
    const mpr::PlanarSurface<T> plane(rng.vec<T>(-1, 1), mpr::Vec3<T>(1, T(rng.uniform(-0.2, 0.2)), 0),
                                      mpr::Vec3<T>(T(rng.uniform(-0.2, 0.2)), 1, 0));
    const mpr::Vec3<T> centre = plane.centre() + rng.vec<T>(-1, 1) - T(rng.uniform(1, 4)) * plane.normal();
    const auto sel = mpr::glc::perspective(plane, centre);
    REQUIRE(mpr::glc::classify(plane, sel).type == Type::pinhole);
    // Perpendicular to d10 (a change along it would not move the ray).
    const mpr::Vec3<T> r = rng.vec<T>(-1, 1), d = sel.d10().normalized();
    const mpr::Vec3<T> unit = (r - r.dot(d) * d).normalized();
    const auto perturbed = [&](double relative) {
      const mpr::Vec3<T> d10 = sel.d10() + T(relative) * sel.d10().norm() * unit;
      return mpr::GlcSelector<T>(plane, sel.d00(), d10, sel.d01());
    };
    still_pinhole += mpr::glc::classify(plane, perturbed(1e-12)).type == Type::pinhole;
    not_pinhole += mpr::glc::classify(plane, perturbed(1e-3)).type != Type::pinhole;
  }
  CHECK(still_pinhole == n);
  CHECK(not_pinhole == n);
}

TEMPLATE_TEST_CASE("stability: pencils and twisted orthographic cameras built from exact parameters",
                   "[glc][stability]", float, double) {
  using T = TestType;
  Rng rng(11);
  int pencils = 0, twisted = 0;
  double worst_split = 0, worst_depth = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const mpr::PlanarSurface<T> plane(rng.vec<T>(-1, 1), mpr::Vec3<T>(T(rng.uniform(0.5, 2)), 0, 0),
                                      mpr::Vec3<T>(T(rng.uniform(-0.3, 0.3)), T(rng.uniform(0.5, 2)), 0));
    const T depth = T(rng.uniform(1, 10)) * (rng.uniform(0, 1) < 0.5 ? -1 : 1);
    const mpr::Vec3<T> point = plane.centre() + rng.vec<T>(-1, 1) + depth * plane.normal();
    const mpr::Vec3<T> along(T(rng.uniform(-1, 1)), T(rng.uniform(-1, 1)), 0);
    const T twist = T(rng.uniform(0.2, 1)) / std::abs(depth);
    const auto cl = mpr::glc::classify(plane, mpr::glc::pencil(plane, mpr::glc::Line<T>{point, along}, twist));
    pencils += cl.type == Type::pencil;
    const auto& r = cl.roots;
    const double split = r.complex ? 2 * r.imag : std::abs(r.first - r.second);
    worst_split = std::max(worst_split, split / std::abs(double(depth)));
    worst_depth =
        std::max(worst_depth, std::abs(double(cl.depths[0]) - double((point - plane.centre()).dot(plane.normal()))) /
                                  std::abs(double(depth)));
    const mpr::Vec3<T> direction = rng.vec<T>(-0.5, 0.5) + plane.normal();
    const auto tw =
        mpr::glc::classify(plane, mpr::glc::twisted_orthographic(plane, direction, along, T(rng.uniform(0.2, 1))));
    twisted += tw.type == Type::twisted_orthographic;
  }
  WARN((sizeof(T) == 4 ? "float" : "double") << " pencils: worst double-root split " << worst_split
                                             << " relative, worst slit depth error " << worst_depth << " relative");
  CHECK(pencils == n);
  CHECK(twisted == n);
  // The split must stay inside the classifier's double-root tolerance `relative_depth` (1e-6 in
  // double, 1e-2 in float; docs/numerics.md: measured 6.3e-8 and 1.5e-3), and the slit's depth
  // is recovered to a few ulps (measured 7.0e-16 and 5.5e-7).
  CHECK(worst_split < (sizeof(T) == 4 ? 1e-2 : 1e-6));
  CHECK(worst_depth < (sizeof(T) == 4 ? 1e-5 : 1e-13));
}

TEMPLATE_TEST_CASE("stability: a pushbroom whose second slit is at 1e12 is a pushbroom", "[glc][stability]", float,
                   double) {
  using T = TestType;
  const auto plane = glc_test::unit_plane<T>();
  // Gradient K = diag(-1/2, -1/far): slits at depths 2 and `far`.
  const auto make = [&](double far) {
    const T k = T(-1 / far);
    return mpr::GlcSelector<T>(plane, mpr::Vec3<T>(0, 0, 1), mpr::Vec3<T>(-0.5, 0, 1), mpr::Vec3<T>(0, k, 1));
  };
  const auto cl = mpr::glc::classify(plane, make(1e12));
  CHECK(cl.type == Type::pushbroom);
  CHECK(cl.depths[0] == Approx(2).epsilon(1e-6));
  CHECK(cl.roots.second == Approx(1e12).epsilon(1e-6));
  // The same camera with the slit at 20: a cross-slit camera (so the test can fail).
  CHECK(mpr::glc::classify(plane, make(20)).type == Type::cross_slit);
  // Beyond `far` (1e6 plane sizes in double, 300 in float) the slit is at infinity.
  mpr::glc::ClassifyConfig<T> config;
  CHECK(mpr::glc::classify(plane, make(0.5 * double(config.far)), config).type == Type::cross_slit);
  CHECK(mpr::glc::classify(plane, make(2 * double(config.far)), config).type == Type::pushbroom);
  config.far = T(1e13);
  CHECK(mpr::glc::classify(plane, make(1e12), config).type == Type::cross_slit);
}

TEST_CASE("stability: conditioning experiments of the reference note", "[glc][stability]") {
  const auto plane = glc_test::unit_plane<double>();
  // Pinhole K = -I/2 with a Jordan perturbation: discriminant exactly 0; pencil above the lateral
  // tolerance, pinhole below it.
  const auto jordan = [&](double eps) {
    return mpr::GlcSelector<double>(plane, mpr::Vec3<double>(0, 0, 1), mpr::Vec3<double>(-0.5, 0, 1),
                                    mpr::Vec3<double>(eps, -0.5, 1));
  };
  CHECK(mpr::glc::classify(plane, jordan(1e-6)).type == Type::pencil);
  CHECK(mpr::glc::classify(plane, jordan(1e-6)).characteristic.discriminant == 0);
  CHECK(mpr::glc::classify(plane, jordan(1e-12)).type == Type::pinhole);
  // Cross-slit K = diag(-1/2, -1/2 + g): the discriminant keeps its sign and size for tiny g.
  for (const double g : {1e-4, 1e-8, 1e-10}) {
    const mpr::GlcSelector<double> sel(plane, mpr::Vec3<double>(0, 0, 1), mpr::Vec3<double>(-0.5, 0, 1),
                                       mpr::Vec3<double>(0, -0.5 + g, 1));
    const auto cl = mpr::glc::classify(plane, sel);
    const double k22 = -0.5 + g; // g as represented
    const double exact = (-0.5 - k22) * (-0.5 - k22);
    CHECK(cl.characteristic.discriminant == Approx(exact).epsilon(1e-12));
  }
  // Pencil + delta in K21: sqrt growth of the split; delta < 0 gives a complex pair.
  const auto bent = [&](double delta) {
    return mpr::GlcSelector<double>(plane, mpr::Vec3<double>(0, 0, 1), mpr::Vec3<double>(-0.5, delta, 1),
                                    mpr::Vec3<double>(0.5, -0.5, 1));
  };
  const auto plus = mpr::glc::classify(plane, bent(1e-12));
  // Slits 5.7e-6 apart at depth 2: above relative_depth (1e-6), so a cross-slit camera.
  CHECK(plus.type == Type::cross_slit);
  CHECK(std::abs(plus.depths[1] - plus.depths[0]) == Approx(5.66e-6).epsilon(1e-2));
  const auto minus = mpr::glc::classify(plane, bent(-1e-12));
  CHECK(minus.type == Type::bilinear);
  // The unperturbed pencil.
  CHECK(mpr::glc::classify(plane, bent(0)).type == Type::pencil);
}
