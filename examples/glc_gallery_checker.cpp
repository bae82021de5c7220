// glc_gallery_checker: the nine classic GLC gallery views (Yu & McMillan, ECCV 2004) of a
// checkered ground plane, all on one image plane, as a 3x3 contact sheet, plus the same views
// rectified (ICCV 2005) so that the board's central 12 x 12 square fills each tile.
//
// usage: glc_gallery_checker [--size N] [OUTPUT_FOLDER]   (defaults: 240, glc-gallery-output)
#include "example_args.hpp"
#include <mpr/glc.hpp>

#include <mpr/mpr.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

int main(int argc, char** argv) try {
  using T = double;
  using V = mpr::Vec3<T>;
  const std::optional<mpr_example::Args> args =
      mpr_example::parse_args(argc, argv, "glc_gallery_checker", 240, 8, 4096, "glc-gallery-output");
  if (!args) return 0;
  const int size = args->size, threads = args->threads;
  const std::filesystem::path& out = args->out;

  // A 24 x 24-cell board on the ground y = 0, turned by 30 degrees so no board line is parallel
  // to a slit.
  mpr::CheckerboardPlane<T>::Config board;
  board.cell_u = V(std::cos(0.5236), 0, std::sin(0.5236));
  board.cell_v = V(-std::sin(0.5236), 0, std::cos(0.5236));
  board.cells = 12;
  const mpr::CheckerboardPlane<T> scene(board);

  // The demo's image plane: 10 x 10 units, 6 up and 9 back, looking at the origin.
  const V eye(0, 6, 9);
  const V forward = (V(0, 0, 0) - eye).normalized();
  const V right = forward.cross(V::UnitY()).normalized();
  const V down = forward.cross(right);
  const auto plane = mpr::PlanarSurface<T>::centred(eye, 10 * right, 10 * down);
  const V centre = V::Zero();
  const T scale = 12;
  const std::array<V, 4> square{V(-6, 0, -6), V(6, 0, -6), V(6, 0, 6), V(-6, 0, 6)};

  mpr::Image<mpr::Rgb8> sheet(3 * size, 3 * size), rectified(3 * size, 3 * size);
  for (std::size_t k = 0; k < mpr::glc::gallery.size(); ++k) {
    const auto& entry = mpr::glc::gallery[k];
    const auto selector = mpr::glc::gallery_view(entry.id, plane, centre, scale);
    const auto cl = mpr::glc::classify(plane, selector);
    const mpr::Region region(static_cast<int>(k % 3) * size, static_cast<int>(k / 3) * size, size, size);
    mpr::Renderer(plane, selector, scene).render(sheet.view(), region, {threads});
    // Rectified: the board's central square fills the tile (the views that see its four corners).
    std::string note = "not rectified";
    try {
      const auto quad = mpr::glc::target_region(plane, selector, square);
      const auto r = mpr::glc::rectify(plane, selector, quad);
      mpr::Renderer(r.surface, r.selector, scene).render(rectified.view(), region, {threads});
      note = "rectified";
    } catch (const mpr::argument_error& e) {
      mpr::Renderer(plane, selector, scene).render(rectified.view(), region, {threads});
      note = std::string("not rectified: ") + e.what();
    }
    std::printf("%c %-36s classified %-22s %s\n", entry.id, std::string(entry.name).c_str(),
                std::string(mpr::glc::to_string(cl.type)).c_str(), note.c_str());
  }
  mpr::write_png(out / "gallery.png", sheet);
  mpr::write_png(out / "gallery_rectified.png", rectified);
  std::printf("wrote %s and %s\n", (out / "gallery.png").string().c_str(),
              (out / "gallery_rectified.png").string().c_str());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "glc_gallery_checker: %s\n", e.what());
  return 1;
}
