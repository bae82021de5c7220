// mpr-gallery: the nine General Linear Cameras of Yu & McMillan (ECCV 2004, fig. 3) -- perspective,
// orthographic, oblique orthographic, pushbroom, twisted orthographic, twisted orthographic
// looking down, cross-slit, pencil and bilinear -- all on ONE image plane, looking at the built-in
// classroom scene, ray cast through a BVH. Writes one PNG per view, a 3 x 3 contact sheet rendered
// in a single multi-view call, and the perspective view rasterized by the software rasterizer
// (identical to view A up to edge pixels).
//
// usage: mpr-gallery [--width N] [--threads N] [OUTPUT_FOLDER]   (defaults: 480, all, mpr-gallery-output)
#include <mpr/mpr.hpp>
#include <mpr/sampler/pinhole_camera.hpp>
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

/// The frame of the shared image plane: centre, unit right / down / forward (into the scene).
struct Frame {
  Vec3 centre, right, down, forward;
};

// ---------------------------------------------------------------------------------------------
// GLC CORNER DIRECTIONS, constructed directly (to be replaced by mpr::glc::gallery_view(id, plane,
// scene_centre, scale) from include/mpr/glc/ when that module is merged).
//
// Every GLC on the plane is d(x, y) = forward + (M (x, y) + c) in the (right, down) basis, with
// (x, y) the offset from the plane centre in world units: the rays meet the line/point where
// det(I + lambda M) = 0 (ECCV 2004, sec. 3, the characteristic equation). The nine types:
//   A perspective         M = I / f                 (all rays through one point)
//   B orthographic        M = 0, c = 0
//   C oblique orthogr.    M = 0, c != 0             (parallel rays, not perpendicular to the plane)
//   D pushbroom           M = diag(0, 1/f)          (parallel in x, through a horizontal slit)
//   E twisted orthogr.    M = [[0, k], [0, 0]]      (nilpotent: no slit, all rays parallel to a plane)
//   F  ... looking down   as E with c pointing down
//   G cross-slit          M = diag(1/fx, 1/fy)      (two slits)
//   H pencil              M = [[1/f, k], [0, 1/f]]  (double root, one slit)
//   I bilinear            M = [[a, -k], [k, a]]     (complex roots: no slit)
mpr::GlcSelector<T> gallery_glc(char id, const mpr::PlanarSurface<T>& plane, const Frame& f) {
  T m00 = 0, m01 = 0, m10 = 0, m11 = 0, cx = 0, cy = 0;
  const T focal = 5;
  switch (id) {
  case 'A': m00 = m11 = 1 / focal; break;
  case 'B': break;
  case 'C': cx = T(0.35); cy = T(0.12); break;
  case 'D': m11 = 1 / focal; break;
  case 'E': m01 = T(0.16); break;
  case 'F': m01 = T(0.16); cy = T(0.45); break;
  case 'G': m00 = T(1) / 3; m11 = T(1) / 14; break;
  case 'H': m00 = m11 = 1 / focal; m01 = T(0.12); break;
  case 'I': m00 = m11 = T(0.12); m01 = T(-0.12); m10 = T(0.12); break;
  default: throw mpr::argument_error("view id", std::string(1, id));
  }
  const auto direction = [&](T u, T v) {
    const Vec3 offset = plane.point_at({u, v}) - f.centre;
    const T x = offset.dot(f.right), y = offset.dot(f.down);
    return Vec3(f.forward + (m00 * x + m01 * y + cx) * f.right + (m10 * x + m11 * y + cy) * f.down);
  };
  return {plane, direction(0, 0), direction(1, 0), direction(0, 1)};
}
// ---------------------------------------------------------------------------------------------

constexpr std::array<std::pair<char, const char*>, 9> kViews = {{{'A', "perspective"},
                                                                 {'B', "orthographic"},
                                                                 {'C', "oblique"},
                                                                 {'D', "pushbroom"},
                                                                 {'E', "twisted_orthographic"},
                                                                 {'F', "twisted_orthographic_down"},
                                                                 {'G', "cross_slit"},
                                                                 {'H', "pencil"},
                                                                 {'I', "bilinear"}}};

} // namespace

int main(int argc, char** argv) try {
  int width = 480, threads = 0;
  std::filesystem::path out = "mpr-gallery-output";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--width" && i + 1 < argc) {
      width = std::atoi(argv[++i]);
      if (width < 16 || width > 8192) throw mpr::argument_error("--width", "must be between 16 and 8192");
    } else if (arg == "--threads" && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else if (arg == "--help" || arg == "-h") {
      std::puts("usage: mpr-gallery [--width N] [--threads N] [OUTPUT_FOLDER]   (defaults: 480, all, mpr-gallery-output)");
      return 0;
    } else if (!arg.empty() && arg[0] == '-') {
      throw mpr::argument_error(arg, "unknown option (see --help)");
    } else {
      out = arg;
    }
  }
  const int height = width * 3 / 4;
  std::filesystem::create_directories(out);

  const auto start = std::chrono::steady_clock::now();
  const auto scene = std::make_shared<const mpr::scene::Scene<T>>(mpr::scenes::classroom<T>());
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast> sampler(scene);
  std::printf("classroom: %zu triangles, BVH built in %.1f ms\n", scene->size(),
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());

  // One image plane, 8 x 6 m, its lower edge just above the floor, looking slightly down.
  const Vec3 centre(0, 3.1f, 3.0f);
  const Vec3 forward = (Vec3(0, 1.6f, -8) - centre).normalized();
  const Vec3 right = forward.cross(Vec3::UnitY()).normalized();
  const Vec3 down = forward.cross(right);
  const Frame frame{centre, right, down, forward};
  const auto plane = mpr::PlanarSurface<T>::centred(centre, T(8) * right, T(6) * down);

  using R = mpr::Renderer<mpr::PlanarSurface<T>, mpr::GlcSelector<T>, mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast>>;
  std::vector<R> renderers;
  for (const auto& v : kViews) renderers.emplace_back(plane, gallery_glc(v.first, plane, frame), sampler);

  const mpr::RenderOptions options{threads};
  mpr::Image<mpr::Rgb8> view_a;
  for (std::size_t k = 0; k < kViews.size(); ++k) {
    mpr::Image<mpr::Rgb8> image(width, height);
    renderers[k].render(image.view(), mpr::Region(0, 0, width, height), options);
    const auto path = out / (std::string(1, kViews[k].first) + "_" + kViews[k].second + ".png");
    mpr::write_png(path, image);
    std::printf("wrote %s\n", path.string().c_str());
    if (k == 0) view_a = image;
  }

  // The contact sheet: all nine views in one multi-view render call (row-major A..I).
  mpr::Image<mpr::Rgb8> sheet(3 * width, 3 * height);
  const auto region = [&](int k) { return mpr::Region((k % 3) * width, (k / 3) * height, width, height); };
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    mpr::render(sheet.view(), options, mpr::view(region(static_cast<int>(I)), renderers[I])...);
  }(std::make_index_sequence<9>{});
  // Thin separators between the views.
  for (int y = 0; y < sheet.height(); ++y)
    for (int x = 0; x < sheet.width(); ++x)
      if (x % width == 0 || y % height == 0) sheet(x, y) = mpr::Rgb8{255, 255, 255};
  mpr::write_png(out / "contact_sheet.png", sheet);
  std::printf("wrote %s\n", (out / "contact_sheet.png").string().c_str());

  // View A again, rasterized: the pinhole camera at A's centre of projection whose pixels map
  // exactly onto the plane's region.
  const Vec3 eye = centre - T(5) * forward; // A's focal length is 5 (see gallery_glc)
  mpr::Mat3<T> Rm;
  Rm.row(0) = right.transpose();
  Rm.row(1) = down.transpose();
  Rm.row(2) = forward.transpose();
  mpr::Mat3<T> K = mpr::Mat3<T>::Identity();
  K(0, 0) = T(5) * static_cast<T>(width) / T(8);
  K(1, 1) = T(5) * static_cast<T>(height) / T(6);
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
