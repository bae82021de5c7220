// lightfield_temple: a novel view of the Middlebury temple (16 calibrated views on a ring,
// Stanford spherical gantry) half way between two captured views, focused on a plane through
// the centre of the temple's bounding box, with each interpolation policy.
//
// Writes temple_novel.png: [captured view A | nearest | cylinder | synthetic aperture |
// captured view B], and temple_novel_<policy>.png.
//
// usage: lightfield_temple [DATA_DIR] [OUTPUT_FOLDER] [VIEW_A]   (VIEW_A: 0-based, default 3; --help)
#include "lightfield_common.hpp"

#include <charconv>
#include <cstdio>
#include <exception>
#include <string>
#include <system_error>
#include <vector>

using namespace lf_example;

int main(int argc, char** argv) try {
  const std::vector<std::string> args = positional_args(
      argc, argv, {"VIEW_A"}, "  VIEW_A         0-based index of the first of the two views (default 3)\n");
  std::size_t a = 3;
  if (args.size() > 2) {
    const std::string& text = args[2];
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), a);
    if (ec != std::errc{} || end != text.data() + text.size())
      throw mpr::argument_error("VIEW_A", "'" + text + "' is not a view index (0, 1, 2, ...)");
  }
  const std::filesystem::path data = data_dir(args.empty() ? nullptr : args[0].c_str());
  const std::filesystem::path out = args.size() > 1 ? args[1] : default_output;
  std::filesystem::create_directories(out);
  const auto frames = std::make_shared<const mpr::CameraFrameSet<T>>(mpr::read_par_file<T>(
      data / "middlebury" / "templeSparseRing" / "templeSR_par.txt", load_limits_with_progress()));
  if (a + 1 >= frames->size())
    throw mpr::argument_error("VIEW_A", "must be below " + std::to_string(frames->size() - 1));
  const mpr::PinholeCamera<T>& ca = frames->camera(a);
  const mpr::PinholeCamera<T>& cb = frames->camera(a + 1);
  // Centre of the bounding box given in the data set's README.txt.
  const mpr::Vec3<T> target(T(0.5 * (-0.073568 + 0.028855)), T(0.5 * (0.021728 + 0.181892)),
                            T(0.5 * (-0.012445 + 0.062736)));
  const T distance = T(0.5) * ((ca.centre() - target).norm() + (cb.centre() - target).norm());
  const mpr::Vec3<T> mid = T(0.5) * (ca.centre() + cb.centre());
  const mpr::Vec3<T> eye = target + distance * (mid - target).normalized();
  const mpr::Vec3<T> up = -(ca.R().row(1) + cb.R().row(1)).transpose();
  const T fov = 2 * std::atan(T(0.5) * static_cast<T>(ca.height()) / ca.K()(1, 1));
  const auto novel = mpr::PinholeCamera<T>::look_at(eye, target, up, fov, ca.width(), ca.height());
  std::printf("novel view between %s and %s, %.3f from each (baseline %.3f)\n", frames->name(a).c_str(),
              frames->name(a + 1).c_str(), static_cast<double>((eye - ca.centre()).norm()),
              static_cast<double>((ca.centre() - cb.centre()).norm()));

  const mpr::PlanarSurface<T> plane = novel.image_plane(distance);
  const mpr::GlcSelector<T> glc = mpr::pinhole_glc(novel, plane);
  const mpr::CameraFrameSampler<mpr::NearestCamera, T> nearest(frames);
  const T radius = (ca.centre() - cb.centre()).norm();
  const mpr::CameraFrameSampler<mpr::CylinderAperture, T> cylinder(frames, mpr::CylinderAperture{radius});
  const mpr::CameraFrameSampler<mpr::SyntheticAperture, T> full(frames);

  const int w = novel.width(), h = novel.height();
  mpr::Image<mpr::Rgb8> strip(5 * w, h);
  const auto paste = [&](const mpr::Image<mpr::Rgb8>& img, int slot) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) strip(slot * w + x, y) = img(x, y);
  };
  paste(frames->image(a), 0);
  paste(frames->image(a + 1), 4);
  const mpr::Renderer r_nearest(plane, glc, nearest);
  const mpr::Renderer r_cylinder(plane, glc, cylinder);
  const mpr::Renderer r_full(plane, glc, full);
  mpr::render(strip.view(), mpr::RenderOptions{}, mpr::view(mpr::Region(w, 0, w, h), r_nearest),
              mpr::view(mpr::Region(2 * w, 0, w, h), r_cylinder), mpr::view(mpr::Region(3 * w, 0, w, h), r_full));
  mpr::write_png(out / "temple_novel.png", strip);
  report(out / "temple_novel.png");
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "lightfield_temple: %s\n", e.what());
  return 1;
}
