// lightfield_refocus: refocuses the Stanford Chess light field (7x7 views, 1400x800) at several
// depths with each interpolation policy (nearest camera, full synthetic aperture, cylinder
// aperture), seen from the centre of the camera array.
//
// Writes refocus_montage.png (rows: depths 700, 760, 820, 880, 950, near to far; columns: nearest, synthetic aperture,
// cylinder; each tile rendered at half resolution in one multi-view render call) and
// refocus_<policy>_<depth>.png at full resolution for depths 720 and 880.
//
// usage: lightfield_refocus [DATA_DIR] [OUTPUT_FOLDER]   (defaults: MPR_DATA_DIR, lightfield-output)
#include "lightfield_common.hpp"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

using namespace lf_example;

int main(int argc, char** argv) try {
  const auto [out, frames, centre] = open_chess(argc, argv);
  const int w = centre.width(), h = centre.height();

  const mpr::CameraFrameSampler<mpr::NearestCamera, T> nearest(frames);
  const mpr::CameraFrameSampler<mpr::SyntheticAperture, T> full(frames);
  // About 12 cameras of the 5-unit grid lie within 10 units of a central ray.
  const mpr::CameraFrameSampler<mpr::CylinderAperture, T> cylinder(frames, mpr::CylinderAperture{10.0});

  // Depths in world units: the reference plane (zero disparity) is at 1000; the board spans
  // about 700 (front pieces) to 950 (back row).
  const std::vector<T> depths{700, 760, 820, 880, 950};
  const int tw = w / 2, th = h / 2;
  mpr::Image<mpr::Rgb8> montage(3 * tw, static_cast<int>(depths.size()) * th);
  for (std::size_t i = 0; i < depths.size(); ++i) {
    const mpr::PlanarSurface<T> plane = centre.image_plane(depths[i]);
    const mpr::GlcSelector<T> glc = mpr::pinhole_glc(centre, plane);
    const mpr::Renderer r_nearest(plane, glc, nearest);
    const mpr::Renderer r_full(plane, glc, full);
    const mpr::Renderer r_cylinder(plane, glc, cylinder);
    const int y = static_cast<int>(i) * th;
    mpr::render(montage.view(), mpr::RenderOptions{}, mpr::view(mpr::Region(0, y, tw, th), r_nearest),
                mpr::view(mpr::Region(tw, y, tw, th), r_full), mpr::view(mpr::Region(2 * tw, y, tw, th), r_cylinder));
  }
  mpr::write_png(out / "refocus_montage.png", montage);
  report(out / "refocus_montage.png");

  for (const T depth : {T(720), T(880)}) {
    const mpr::PlanarSurface<T> plane = centre.image_plane(depth);
    const mpr::GlcSelector<T> glc = mpr::pinhole_glc(centre, plane);
    const mpr::Region region(0, 0, w, h);
    mpr::Image<mpr::Rgb8> image(w, h);
    // `dir`: clang before 16 does not capture a structured binding (C++20 allows it).
    const auto save = [&, &dir = out](const char* name, const auto& sampler) {
      const mpr::Renderer renderer(plane, glc, sampler);
      const double s = seconds([&] { renderer.render(image.view(), region); });
      const auto path = dir / ("refocus_" + std::string(name) + "_" + std::to_string(static_cast<int>(depth)) + ".png");
      mpr::write_png(path, image);
      std::printf("%-18s depth %5.0f: %7.1f ms  ", name, static_cast<double>(depth), 1e3 * s);
      report(path);
    };
    save("nearest", nearest);
    save("synthetic_aperture", full);
    save("cylinder", cylinder);
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "lightfield_refocus: %s\n", e.what());
  return 1;
}
