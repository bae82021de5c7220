// Renders a tiny pinhole view of the analytic checkerboard through the installed headers and
// writes/reads a PNG (exercising the stb link), then checks a known pixel.
#include <mpr/mpr.hpp>

#include <cstdio>
#include <filesystem>

int main() {
  using T = double;
  const mpr::PlanarSurface<T> plane({-1, -1, 1}, {2, 0, 0}, {0, 2, 0});
  const mpr::Vec3<T> eye = mpr::Vec3<T>::Zero();
  const mpr::GlcSelector<T> pinhole(plane, plane.point_at({0, 0}) - eye, plane.point_at({1, 0}) - eye,
                                    plane.point_at({0, 1}) - eye);
  mpr::CheckerboardPlane<T>::Config board;
  board.origin = {0, 0, 4};
  const mpr::Renderer renderer(plane, pinhole, mpr::CheckerboardPlane<T>(board));
  mpr::Image<mpr::Rgb8> image(16, 16);
  renderer.render(image.view(), mpr::Region(0, 0, 16, 16));
  const auto path = std::filesystem::temp_directory_path() / "mpr_consumer.png";
  mpr::write_png(path, image);
  const mpr::Image<mpr::Rgb8> back = mpr::read_rgb8(path);
  // Pixel (8, 8) looks along +z just right/below the centre: board cell (0, 0), a light cell.
  const bool ok = back == image && image(8, 8) == mpr::to_rgb8(board.light);
  std::printf(ok ? "mpr consumer: ok\n" : "mpr consumer: FAILED\n");
  return ok ? 0 : 1;
}
