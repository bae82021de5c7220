// mpr-gallery: the nine General Linear Cameras of Yu & McMillan (ECCV 2004, fig. 3) -- perspective,
// orthographic, oblique orthographic, pushbroom, twisted orthographic, twisted orthographic
// looking down, cross-slit, pencil and bilinear -- all on ONE image plane, looking at the built-in
// classroom scene, ray cast through a BVH. Writes one PNG per view, a 3 x 3 contact sheet rendered
// in a single multi-view call, and the perspective view rasterized by the software rasterizer
// (identical to view A's pixel-centre render up to edge pixels). Anti-aliased: each pixel averages
// --spp scrambled Sobol samples (box filter; default 4, enough to remove the staircases on the
// checkered floor; mpr::Supersample in include/mpr/sampling/).
//
// usage: mpr-gallery [--width N] [--threads N] [--spp N] [OUTPUT_FOLDER]
//        (defaults: 480, all, 4, mpr-gallery-output)
#include "example_args.hpp"
#include <mpr/glc.hpp>

#include <mpr/camera/pinhole_camera.hpp>
#include <mpr/core/label.hpp>
#include <mpr/mpr.hpp>
#include <mpr/scene.hpp>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace {

using T = float;
using Vec3 = mpr::Vec3<T>;

constexpr std::array<std::pair<char, const char*>, 9> kViews = {{{'A', "perspective"},
                                                                 {'B', "orthographic"},
                                                                 {'C', "oblique"},
                                                                 {'D', "pushbroom"},
                                                                 {'E', "twisted_orthographic"},
                                                                 {'F', "twisted_orthographic_down"},
                                                                 {'G', "cross_slit"},
                                                                 {'H', "pencil"},
                                                                 {'I', "bilinear"}}};

/// The share of a view's rays (a 64 x 48 grid over its output) whose first hit is the back of a
/// surface: rays that start outside the room and see the outer side of a wall.
template <class Surface, class Selector, class Sampler>
double share_seeing_backs(const Surface& surface, const Selector& selector, const Sampler& sampler) {
  constexpr int nx = 64, ny = 48;
  int backs = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const mpr::Vec2<T> uv((T(i) + T(0.5)) / nx, (T(j) + T(0.5)) / ny);
      const mpr::Ray<T> ray = selector.ray_at(mpr::Pixel{}, uv, surface.point_at(uv));
      const mpr::scene::Hit<T> hit = sampler.bvh().closest_hit(ray);
      if (hit.valid() && ray.direction.dot(sampler.scene().triangles()[hit.triangle].normal) > 0) ++backs;
    }
  return double(backs) / (nx * ny);
}

/// "A perspective", ..., "I bilinear": the labels of the contact sheets' tiles.
std::array<std::string, 9> tile_labels() {
  std::array<std::string, 9> labels;
  for (std::size_t k = 0; k < 9; ++k)
    labels[k] = std::string(1, mpr::glc::gallery[k].id) + " " + std::string(mpr::glc::gallery[k].name);
  return labels;
}

} // namespace

int main(int argc, char** argv) try {
  const std::optional<mpr_example::Args> args =
      mpr_example::parse_args(argc, argv, "mpr-gallery", 480, 16, 8192, "mpr-gallery-output", 4);
  if (!args) return 0;
  const int width = args->size, threads = args->threads;
  const std::filesystem::path& out = args->out;
  const int height = width * 3 / 4;

  const auto start = std::chrono::steady_clock::now();
  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scene::classroom<T>());
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast> sampler(scene);
  std::printf("classroom: %zu triangles, BVH built in %.1f ms\n", scene->size(),
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());

  // One image plane, 8 x 6 m, its lower edge just above the floor, looking slightly down.
  const Vec3 centre(0, 3.1f, 3.0f);
  const Vec3 forward = (Vec3(0, 1.6f, -8) - centre).normalized();
  const Vec3 right = forward.cross(Vec3::UnitY()).normalized();
  const Vec3 down = forward.cross(right);
  const auto plane = mpr::PlanarSurface<T>::centred(centre, T(8) * right, T(6) * down);
  // The gallery cameras of the GLC module, aimed at the middle of the room and framing ~14 m.
  const Vec3 scene_centre(0, 1.6f, -8);
  const T scene_scale = 14;

  // --spp scrambled Sobol samples per pixel, averaged (box filter): no staircase edges.
  const mpr::Supersample<mpr::OwenSobol> sampling{mpr::OwenSobol(args->spp)};
  std::printf("%d samples per pixel (--spp)\n", args->spp);
  using R = mpr::Renderer<mpr::PlanarSurface<T>, mpr::GlcSelector<T>,
                          mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>, mpr::Supersample<mpr::OwenSobol>>;
  std::vector<R> renderers;
  for (const auto& v : kViews)
    renderers.emplace_back(plane, mpr::glc::gallery_view(v.first, plane, scene_centre, scene_scale), sampler, sampling);

  const mpr::RenderOptions options{threads};
  for (std::size_t k = 0; k < kViews.size(); ++k) {
    mpr::Image<mpr::Rgb8> image(width, height);
    renderers[k].render(image.view(), mpr::Region(0, 0, width, height), options);
    const auto path = out / (std::string(1, kViews[k].first) + "_" + kViews[k].second + ".png");
    mpr::write_png(path, image);
    std::printf("wrote %s\n", path.string().c_str());
  }

  // The contact sheet: all nine views in one multi-view render call (row-major A..I).
  mpr::Image<mpr::Rgb8> sheet(3 * width, 3 * height);
  const auto region = [&](int k) { return mpr::Region((k % 3) * width, (k / 3) * height, width, height); };
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    mpr::render(sheet.view(), options, mpr::view(region(static_cast<int>(I)), renderers[I])...);
  }
  (std::make_index_sequence<9>{});
  // Thin separators between the views.
  for (int y = 0; y < sheet.height(); ++y)
    for (int x = 0; x < sheet.width(); ++x)
      if (x % width == 0 || y % height == 0) sheet(x, y) = mpr::Rgb8{255, 255, 255};
  mpr::label_tiles(sheet.view(), width, height, tile_labels(), mpr::LabelStyle{width >= 400 ? 2 : 1});
  mpr::write_png(out / "contact_sheet.png", sheet);
  std::printf("wrote %s\n", (out / "contact_sheet.png").string().c_str());

  // Rectified views (Yu & McMillan, ICCV 2005): each view resampled through the homography of
  // the image plane that makes the back wall's central 8.8 x 6.6 m rectangle fill the output, so
  // the skewed views (oblique, twisted, bilinear) look natural again. One contact sheet.
  const std::array<Vec3, 4> wall = {Vec3(-4.4f, 5.4f, -14), Vec3(4.4f, 5.4f, -14), Vec3(4.4f, -1.2f, -14),
                                    Vec3(-4.4f, -1.2f, -14)};
  mpr::Image<mpr::Rgb8> rectified_sheet(3 * width, 3 * height, mpr::Rgb8{255, 255, 255});
  for (std::size_t k = 0; k < kViews.size(); ++k) {
    const mpr::GlcSelector<T>& glc = renderers[k].selector();
    try {
      const mpr::glc::Rectified<T> r = mpr::glc::rectify(plane, glc, mpr::glc::target_region(plane, glc, wall));
      const mpr::Renderer rectified(r.surface, r.selector, sampler, sampling);
      rectified.render(rectified_sheet.view(), region(static_cast<int>(k)), options);
      // Rays start on the image plane. Rectifying a steep view moves the part of the plane it
      // uses sideways, possibly out of the room; say so where the picture shows it.
      const double backs = share_seeing_backs(r.surface, r.selector, sampler);
      if (backs > 0.01)
        std::printf("view %c rectified: %.0f%% of its rays start outside the classroom (they run far sideways on "
                    "their way to the back wall) and see the outer side of a wall there\n",
                    kViews[k].first, 100 * backs);
    } catch (const mpr::error& e) {
      std::printf("view %c: no rectified variant (%s)\n", kViews[k].first, e.what());
    }
  }
  for (int y = 0; y < rectified_sheet.height(); ++y)
    for (int x = 0; x < rectified_sheet.width(); ++x)
      if (x % width == 0 || y % height == 0) rectified_sheet(x, y) = mpr::Rgb8{255, 255, 255};
  mpr::label_tiles(rectified_sheet.view(), width, height, tile_labels(), mpr::LabelStyle{width >= 400 ? 2 : 1});
  mpr::write_png(out / "contact_sheet_rectified.png", rectified_sheet);
  std::printf("wrote %s\n", (out / "contact_sheet_rectified.png").string().c_str());

  // View A again, rasterized: the pinhole camera at A's centre of projection (from the GLC
  // classifier) whose pixels map exactly onto the plane's region, compared with A ray cast through
  // the pixel centres (the rasterizer samples pixel centres too).
  mpr::Image<mpr::Rgb8> view_a(width, height);
  mpr::Renderer(plane, renderers[0].selector(), sampler)
      .render(view_a.view(), mpr::Region(0, 0, width, height), options);
  const mpr::glc::Classification<T> a = mpr::glc::classify(plane, renderers[0].selector());
  if (a.type != mpr::glc::Type::pinhole) throw mpr::error("gallery view A is not a pinhole");
  const Vec3 eye = a.centre;
  const T focal = (centre - eye).dot(forward); // distance from the eye to the plane
  mpr::Mat3<T> Rm;
  Rm.row(0) = right.transpose();
  Rm.row(1) = down.transpose();
  Rm.row(2) = forward.transpose();
  mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
  K(0, 0) = focal * static_cast<T>(width) / T(8);
  K(1, 1) = focal * static_cast<T>(height) / T(6);
  K(0, 2) = T(0.5) * static_cast<T>(width) - T(0.5);
  K(1, 2) = T(0.5) * static_cast<T>(height) - T(0.5);
  const mpr::PinholeCamera<T> camera(K, Rm, Vec3(-(Rm * eye)), width, height);
  mpr::scene::RasterOptions raster_options;
  raster_options.threads = threads;
  const mpr::scene::RasterImage raster = mpr::scene::rasterize(*scene, camera, raster_options);
  mpr::write_png(out / "A_perspective_rasterized.png", raster.color);
  std::printf("wrote %s\n", (out / "A_perspective_rasterized.png").string().c_str());
  long identical = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) identical += mpr::to_rgb8(raster.color(x, y)) == view_a(x, y) ? 1 : 0;
  std::printf("view A, rasterized vs ray cast: %ld of %d pixels identical (%.3f%%)\n", identical, width * height,
              100.0 * static_cast<double>(identical) / (width * height));
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "mpr-gallery: %s\n", e.what());
  return 1;
}
