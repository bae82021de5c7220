// lightfield_multiperspective: a cross-slit and a pushbroom view through the Stanford Chess
// light field, built directly from General Linear Camera corner rays (two-plane form: where
// each corner ray crosses the camera plane z = 0 and the focal plane z = 820).
//
// - pinhole.png:    reference, every ray through the array centre.
// - cross_slit.png: the camera-plane crossing sweeps across the array (x from -15 to +15) with
//   the image column, and stays at y = 0: the rays pass a horizontal slit (y = 0 on the camera
//   plane) and a vertical slit behind it at z = A zf / (A - W).
// - pushbroom.png:  the crossing moves exactly with the focal-plane point along x, so rays are
//   parallel in x (orthographic) and perspective in y through the horizontal slit. The
//   aperture of the array (about 30 units) bounds the pushbroom's width on the focal plane, so
//   the picture shows a 30-unit wide strip, stretched 8x horizontally.
// Rays are answered with a cylinder aperture of radius 6 (a few cameras per ray).
//
// usage: lightfield_multiperspective [DATA_DIR] [OUTPUT_FOLDER]
#include "lightfield_common.hpp"

#include <cstdio>
#include <exception>

using namespace lf_example;

int main(int argc, char** argv) try {
  const auto [out, frames, centre] = open_chess(argc, argv);
  const mpr::CameraFrameSampler<mpr::CylinderAperture, T> sampler(frames, mpr::CylinderAperture{6.0});

  // Half the array width along x (centres run from about -16 to +16).
  T half = 0;
  for (const auto& c : frames->cameras()) half = std::max(half, std::abs(c.centre().x()));
  half *= T(0.95);
  const T zf = 820;
  const mpr::PlanarSurface<T> plane = centre.image_plane(zf);
  const int w = centre.width(), h = centre.height();

  // `dir`: clang before 16 does not capture a structured binding (C++20 allows it).
  const auto save = [&, &dir = out](const char* name, const mpr::PlanarSurface<T>& surface,
                                    const mpr::GlcSelector<T>& glc, int width, int height) {
    const mpr::Renderer renderer(surface, glc, sampler);
    mpr::Image<mpr::Rgb8> image(width, height);
    renderer.render(image.view(), mpr::Region(0, 0, width, height));
    mpr::write_png(dir / name, image);
    report(dir / name);
  };

  const mpr::Vec3<T> o = mpr::Vec3<T>::Zero();
  save("pinhole.png", plane, two_plane_glc(plane, o, o, o), w, h);

  const mpr::Vec3<T> left(-half, 0, 0), right(half, 0, 0);
  save("cross_slit.png", plane, two_plane_glc(plane, left, right, left), w, h);
  const T A = 2 * half, W = plane.width_vector().norm();
  std::printf("cross-slit: horizontal slit y = 0 at z = 0, vertical slit x = 0 at z = %.1f (focal plane z = %.0f)\n",
              static_cast<double>(A * zf / (A - W)), static_cast<double>(zf));

  // Pushbroom: a focal-plane strip exactly as wide as the swept aperture.
  const mpr::PlanarSurface<T> strip =
      mpr::PlanarSurface<T>::centred(mpr::Vec3<T>(0, 0, zf), mpr::Vec3<T>(A, 0, 0), plane.height_vector());
  save("pushbroom.png", strip, two_plane_glc(strip, left, right, left), 8 * static_cast<int>(A * w / W + 1), h);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "lightfield_multiperspective: %s\n", e.what());
  return 1;
}
