// lightfield_two_views: one output image, two views, one render call: the real Stanford Chess
// light field on the left (refocused through a cylinder aperture) and the analytic
// checkerboard scene (mpr::CheckerboardPlane) on the right, each with its own surface,
// selector and sampler types.
//
// usage: lightfield_two_views [DATA_DIR] [OUTPUT_FOLDER]
#include "lightfield_common.hpp"

#include <cmath>
#include <cstdio>
#include <exception>

using namespace lf_example;

int main(int argc, char** argv) try {
  const auto [out, frames, centre] = open_chess(argc, argv);
  const mpr::PlanarSurface<T> focal = centre.image_plane(T(820));
  const mpr::Renderer chess(focal, mpr::pinhole_glc(centre, focal),
                            mpr::CameraFrameSampler<mpr::CylinderAperture, T>(frames, mpr::CylinderAperture{10.0}));

  // The synthetic scene: a board on the ground plane y = 0 seen from above and in front.
  mpr::CheckerboardPlane<T>::Config board;
  board.cells = 6;
  board.cell_u = mpr::Vec3<T>(1, 0, 0);
  board.cell_v = mpr::Vec3<T>(0, 0, 1);
  const auto eye_camera = mpr::PinholeCamera<T>::look_at(mpr::Vec3<T>(0, 5, -9), mpr::Vec3<T>(0, 0, 0),
                                                         mpr::Vec3<T>(0, 1, 0), T(0.9), 700, 400);
  const mpr::PlanarSurface<T> plane = eye_camera.image_plane(T(8));
  const mpr::Renderer synthetic(plane, mpr::pinhole_glc(eye_camera, plane), mpr::CheckerboardPlane<T>(board));

  mpr::Image<mpr::Rgb8> image(1400, 400);
  mpr::render(image.view(), mpr::RenderOptions{}, mpr::view(mpr::Region(0, 0, 700, 400), chess),
              mpr::view(mpr::Region(700, 0, 700, 400), synthetic));
  mpr::write_png(out / "two_views.png", image);
  report(out / "two_views.png");
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "lightfield_two_views: %s\n", e.what());
  return 1;
}
