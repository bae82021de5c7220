// lightfield_glc_gallery: the nine gallery GLCs (Yu & McMillan 2004: A perspective ... I bilinear)
// rendered from camera arrays, as the 2004 system's "students" animation did.
//
// 1. Stanford Chess (7 x 7 cameras). Each gallery view is mapped into the array in two-plane
//    terms (mpr::fit_to_array: its rays cross the camera plane inside the array and the focal
//    plane z = 820 inside the view) and answered by a cylinder aperture of the camera spacing.
//    Writes chess_glc.png (labelled 3 x 3 sheet) and chess_glc_difference.png (each view minus
//    view A, amplified 8x). The effect is small because the array is narrow: seen from the
//    focal plane the whole array spans about 2.6 degrees, so the views differ by parallax within
//    that cone (printed per view as the mean difference against A).
// 2. The classroom through a virtual array of 8 x 6 rasterized cameras of 320 x 240 spread over
//    the 8 m image plane (wide, so the multi-perspective effects are strong), with the
//    rasterizer's exact depth maps and anti-aliased frames (3 x 3 points a pixel, averaged):
//    classroom_array_glc.png, the nine views answered from the array with a cylinder aperture
//    of the spacing (one focal plane: ghosts off it),
//    classroom_depth_glc.png, the same from the depth proxy (mpr::DepthProxy: the surface from
//    the depth maps, the cameras that see it blended by angle), and classroom_raycast_glc.png,
//    the nine GLCs ray cast; PSNR of each against the ray cast printed, and against the ray cast
//    at 16 samples a pixel, classroom_raycast16_glc.png (anti-aliased: a point-sampled ray cast
//    has staircase edges that no image resampled from frames reproduces, docs/accuracy.md).
//
// usage: lightfield_glc_gallery [DATA_DIR] [OUTPUT_FOLDER]
#include "lightfield_common.hpp"

#include <mpr/core/image_metrics.hpp>
#include <mpr/core/label.hpp>
#include <mpr/glc.hpp>
#include <mpr/lightfield/array_view.hpp>
#include <mpr/sampling.hpp>
#include <mpr/scene.hpp>
#include <mpr/scene/rasterized_sampler.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <string>

using namespace lf_example;

int main(int argc, char** argv) try {
  const auto [out, frames, centre] = open_chess(argc, argv);
  const T zf = 820;
  const mpr::PlanarSurface<T> plane = centre.image_plane(zf);
  const mpr::ArrayFootprint<T> array = mpr::array_footprint(*frames, centre);
  const mpr::CameraFrameSampler<mpr::CylinderAperture, T> sampler(frames, mpr::CylinderAperture{array.spacing});
  const int w = centre.width() / 4, h = centre.height() / 4;

  // The angle the array subtends from the focal-plane centre (its diagonal).
  const mpr::Vec3<T> a0 = array.point({-array.half_u, -array.half_v}) - plane.centre();
  const mpr::Vec3<T> a1 = array.point({array.half_u, array.half_v}) - plane.centre();
  const double cone = std::acos(static_cast<double>(a0.normalized().dot(a1.normalized()))) * 180 / std::numbers::pi;
  std::printf("Chess: %zu cameras over %.1f x %.1f units, spacing %.2f; from the focal plane z = %.0f the array "
              "spans %.2f degrees\n",
              array.cameras, 2.0 * array.half_u, 2.0 * array.half_v, double(array.spacing), double(zf), cone);

  mpr::Image<mpr::Rgb8> sheet(3 * w, 3 * h);
  std::array<std::string, 9> labels;
  const auto seconds_taken = seconds([&] {
    for (int k = 0; k < 9; ++k) {
      const mpr::glc::GalleryEntry& e = mpr::glc::gallery[static_cast<std::size_t>(k)];
      const mpr::GlcSelector<T> glc = mpr::fit_to_array(
          plane,
          mpr::glc::gallery_view(e.id, plane, mpr::Vec3<T>(plane.centre() + T(0.1) * zf * plane.normal()),
                                 plane.width_vector().norm()),
          array);
      const mpr::glc::Type type = mpr::glc::classify(plane, glc).type;
      labels[k] = std::string(1, e.id) + " " + std::string(e.name);
      if (type != e.type) labels[k] += ": now " + std::string(mpr::glc::to_string(type));
      mpr::Renderer(plane, glc, sampler).render(sheet.view(), mpr::Region((k % 3) * w, (k / 3) * h, w, h));
    }
  });
  std::printf("nine views of %dx%d rendered in %.0f ms\n", w, h, 1000 * seconds_taken);

  mpr::Image<mpr::Rgb8> diff(3 * w, 3 * h);
  std::array<std::string, 9> diff_labels;
  for (int k = 0; k < 9; ++k) {
    double sum = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const mpr::Rgb8 p = sheet((k % 3) * w + x, (k / 3) * h + y), q = sheet(x, y);
        const auto amplified = [&](std::uint8_t u, std::uint8_t v) {
          const int delta = std::abs(int(u) - int(v));
          sum += delta;
          return static_cast<std::uint8_t>(std::min(255, 8 * delta));
        };
        diff((k % 3) * w + x, (k / 3) * h + y) =
            mpr::Rgb8{amplified(p.r, q.r), amplified(p.g, q.g), amplified(p.b, q.b)};
      }
    const double mean = sum / (3.0 * w * h);
    char text[64];
    std::snprintf(text, sizeof text, "%c - A x8: mean %.1f", 'A' + k, mean);
    diff_labels[static_cast<std::size_t>(k)] = text;
    std::printf("view %s: mean |view - A| = %.2f of 255\n", labels[k].c_str(), mean);
  }
  mpr::label_tiles(sheet.view(), w, h, labels, mpr::LabelStyle{1});
  mpr::write_png(out / "chess_glc.png", sheet);
  report(out / "chess_glc.png");
  mpr::label_tiles(diff.view(), w, h, diff_labels, mpr::LabelStyle{1});
  mpr::write_png(out / "chess_glc_difference.png", diff);
  report(out / "chess_glc_difference.png");

  // The classroom through a wide virtual array, against the ray cast of the same GLCs.
  using Scene = mpr::scene::Scene<T>;
  const auto scene = std::make_shared<const Scene>(mpr::scene::classroom<T>());
  const mpr::Vec3<T> eye(0, 3.1f, 3.0f), target(0, 1.6f, -8);
  const mpr::Vec3<T> forward = (target - eye).normalized();
  const mpr::Vec3<T> right = forward.cross(mpr::Vec3<T>::UnitY()).normalized();
  const mpr::Vec3<T> down = forward.cross(right);
  const auto room = mpr::PlanarSurface<T>::centred(eye, T(8) * right, T(6) * down);
  mpr::scene::VirtualArrayConfig<T> config;
  config.columns = 8;
  config.rows = 6;
  config.width = 320;
  config.height = 240;
  config.depth_maps = true;
  config.samples = 3; // anti-aliased frames: 3 x 3 points a pixel, as a sensor integrates its area
  const T spacing = T(8) / T(config.columns);
  const int cw = 320, ch = 240;
  mpr::Image<mpr::Rgb8> from_array(3 * cw, 3 * ch), from_depth(3 * cw, 3 * ch), cast(3 * cw, 3 * ch),
      cast16(3 * cw, 3 * ch);
  const mpr::Supersample<mpr::OwenSobol> sixteen{mpr::OwenSobol(16)};
  double cylinder_s = 0, depth_s = 0;
  const double build = seconds([&] {
    const mpr::scene::VirtualArray<T, mpr::Rgb8> array = mpr::scene::rasterize_virtual_array(*scene, room, config);
    const mpr::SceneSampler<Scene, mpr::Rasterized<mpr::CylinderAperture>> raster(
        array, scene->background(), config.filter,
        mpr::Rasterized<mpr::CylinderAperture>{mpr::CylinderAperture{spacing}});
    const mpr::SceneSampler<Scene, mpr::Rasterized<mpr::DepthProxy>> depth(
        array, scene->background(), config.filter, mpr::Rasterized<mpr::DepthProxy>{mpr::DepthProxy{2 * spacing}});
    const mpr::SceneSampler<Scene, mpr::RayCast> ray_cast(scene);
    std::array<std::string, 9> names;
    for (int k = 0; k < 9; ++k) {
      const mpr::glc::GalleryEntry& e = mpr::glc::gallery[static_cast<std::size_t>(k)];
      const mpr::GlcSelector<T> glc = mpr::glc::gallery_view(e.id, room, target, T(14));
      const mpr::Region region((k % 3) * cw, (k / 3) * ch, cw, ch);
      cylinder_s += seconds([&] { mpr::Renderer(room, glc, raster).render(from_array.view(), region); });
      depth_s += seconds([&] { mpr::Renderer(room, glc, depth).render(from_depth.view(), region); });
      mpr::Renderer(room, glc, ray_cast).render(cast.view(), region);
      mpr::Renderer(room, glc, ray_cast, sixteen).render(cast16.view(), region);
      names[k] = std::string(1, e.id) + " " + std::string(e.name);
      const auto tile = [&](const mpr::Image<mpr::Rgb8>& image) {
        return image.view().subview(region.x, region.y, cw, ch);
      };
      std::printf("classroom view %s: vs ray cast PSNR cylinder %.1f dB, depth proxy %.1f dB; vs the 16-sample "
                  "ray cast %.1f, %.1f dB\n",
                  names[k].c_str(), mpr::compare_images(tile(from_array), tile(cast)).psnr,
                  mpr::compare_images(tile(from_depth), tile(cast)).psnr,
                  mpr::compare_images(tile(from_array), tile(cast16)).psnr,
                  mpr::compare_images(tile(from_depth), tile(cast16)).psnr);
    }
    mpr::label_tiles(from_array.view(), cw, ch, names, mpr::LabelStyle{1});
    mpr::label_tiles(from_depth.view(), cw, ch, names, mpr::LabelStyle{1});
    mpr::label_tiles(cast.view(), cw, ch, names, mpr::LabelStyle{1});
    mpr::label_tiles(cast16.view(), cw, ch, names, mpr::LabelStyle{1});
  });
  std::printf("classroom: %dx%d array of %dx%d cameras (%dx%d points a pixel), rasterized and nine views each of four "
              "ways in %.1f s; whole sheet vs ray cast: cylinder %.2f dB (%.2f s), depth proxy %.2f dB (%.2f s); vs "
              "the 16-sample ray cast: %.2f, %.2f dB\n",
              config.columns, config.rows, config.width, config.height, config.samples, config.samples, build,
              mpr::compare_images(from_array.view(), cast.view()).psnr, cylinder_s,
              mpr::compare_images(from_depth.view(), cast.view()).psnr, depth_s,
              mpr::compare_images(from_array.view(), cast16.view()).psnr,
              mpr::compare_images(from_depth.view(), cast16.view()).psnr);
  std::printf("  (the cylinder blends the cameras near each ray at one focal surface: whatever lies off it shows\n"
              "   once per camera blended, the doubled wall text of classroom_array_glc.png; the depth proxy takes\n"
              "   the surface from each camera's depth map instead)\n");
  mpr::write_png(out / "classroom_array_glc.png", from_array);
  report(out / "classroom_array_glc.png");
  mpr::write_png(out / "classroom_depth_glc.png", from_depth);
  report(out / "classroom_depth_glc.png");
  mpr::write_png(out / "classroom_raycast_glc.png", cast);
  report(out / "classroom_raycast_glc.png");
  mpr::write_png(out / "classroom_raycast16_glc.png", cast16);
  report(out / "classroom_raycast16_glc.png");
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "lightfield_glc_gallery: %s\n", e.what());
  return 1;
}
