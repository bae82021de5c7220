// mpr-demo: the README's first command. Renders a checkered ground plane through three General
// Linear Cameras on one image plane -- perspective, orthographic and cross-slit -- and writes one
// PNG per view plus all three side by side in a single multi-view render. Anti-aliased: each pixel
// averages --spp scrambled Sobol samples (box filter; default 4), so the board's edges show no
// staircases.
//
// usage: mpr-demo [--size N] [--threads N] [--spp N] [OUTPUT_FOLDER]   (defaults: 480, all, 4, mpr-demo-output)
#include "example_args.hpp"

#include <mpr/mpr.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

namespace {

using T = double;
using Vec3 = mpr::Vec3<T>;

struct Frame {
  Vec3 centre, right, down, forward;
};

// A unit frame at `eye_point` looking at `target`, y up.
Frame look_at(const Vec3& eye_point, const Vec3& target) {
  const Vec3 forward = (target - eye_point).normalized();
  const Vec3 right = forward.cross(Vec3::UnitY()).normalized();
  const Vec3 down = forward.cross(right);
  return {eye_point, right, down, forward};
}

// Corner directions of a camera whose horizontal rays pass a vertical line at distance `fx`
// behind the plane and whose vertical rays pass a horizontal line at `fy` behind it: a pinhole
// for fx == fy, a cross-slit camera otherwise (Yu & McMillan 2004; Zomet et al. 2003).
mpr::GlcSelector<T> two_slit(const mpr::PlanarSurface<T>& plane, const Frame& f, T fx, T fy) {
  const auto direction = [&](T u, T v) {
    const Vec3 offset = plane.point_at({u, v}) - f.centre;
    return Vec3(f.forward + offset.dot(f.right) / fx * f.right + offset.dot(f.down) / fy * f.down);
  };
  return {plane, direction(0, 0), direction(1, 0), direction(0, 1)};
}

} // namespace

int main(int argc, char** argv) try {
  const std::optional<mpr_example::Args> args =
      mpr_example::parse_args(argc, argv, "mpr-demo", 480, 8, 8192, "mpr-demo-output", 4);
  if (!args) return 0;
  const int size = args->size, threads = args->threads;
  const std::filesystem::path& out = args->out;

  // The scene: a 12 x 12-cell checkerboard on the ground plane y = 0.
  mpr::CheckerboardPlane<T>::Config board;
  // Turned by 30 degrees so that no board line is parallel to a slit: those lines bend into
  // conics in the cross-slit view, while the perspective view keeps them straight.
  board.cell_u = Vec3(std::cos(0.5236), 0, std::sin(0.5236));
  board.cell_v = Vec3(-std::sin(0.5236), 0, std::cos(0.5236));
  board.cells = 6;
  const mpr::CheckerboardPlane<T> scene(board);

  // One image plane for every camera: 10 x 10 units, looking down at the board's centre. The
  // orthographic view sees the plane's footprint; the others diverge from lines behind it.
  const Frame f = look_at(Vec3(0, 6, 9), Vec3(0, 0, 0));
  const auto plane = mpr::PlanarSurface<T>::centred(f.centre, 10 * f.right, 10 * f.down);

  // --spp samples per pixel (scrambled Sobol points), averaged by the box filter.
  const mpr::Supersample<mpr::OwenSobol> sampling{mpr::OwenSobol(args->spp)};
  const mpr::Renderer perspective(plane, two_slit(plane, f, 10, 10), scene, sampling);
  const mpr::Renderer orthographic(plane, mpr::GlcSelector<T>(plane, f.forward, f.forward, f.forward), scene, sampling);
  const mpr::Renderer cross_slit(plane, two_slit(plane, f, 4, 40), scene, sampling);

  const auto save = [&](const char* name, const auto& renderer) {
    mpr::Image<mpr::Rgb8> image(size, size);
    renderer.render(image.view(), mpr::Region(0, 0, size, size), {threads});
    const auto path = out / name;
    mpr::write_png(path, image);
    std::printf("wrote %s\n", path.string().c_str());
  };
  save("perspective.png", perspective);
  save("orthographic.png", orthographic);
  save("cross_slit.png", cross_slit);

  // The same three views side by side in one render call (one region each).
  mpr::Image<mpr::Rgb8> strip(3 * size, size);
  mpr::render(strip.view(), mpr::RenderOptions{threads}, mpr::view(mpr::Region(0, 0, size, size), perspective),
              mpr::view(mpr::Region(size, 0, size, size), orthographic),
              mpr::view(mpr::Region(2 * size, 0, size, size), cross_slit));
  mpr::write_png(out / "side_by_side.png", strip);
  std::printf("wrote %s\n", (out / "side_by_side.png").string().c_str());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "mpr-demo: %s\n", e.what());
  return 1;
}
