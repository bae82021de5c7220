// mpr_python_golden OUT_DIR [PAR_FILE]: the C++ side of the Python module's pixel-for-pixel tests
// (python/tests/test_render.py). Writes a synthetic 3x3 array as OUT_DIR/synth_par.txt + PNGs, then
// renders fixed jobs with typed mpr::Renderers written by hand (no dispatch) and writes each image
// as raw bytes (OUT_DIR/<job>.bin: rows top to bottom, RGB, uint8 or float32). With PAR_FILE, the
// same for a view of its first camera (real data). The tests render the same jobs through the
// module and compare every byte.

#include <mpr/glc/finite_aperture.hpp>
#include <mpr/glc/gallery.hpp>
#include <mpr/lightfield.hpp>
#include <mpr/mpr.hpp>
#include <mpr/sampling.hpp>
#include <mpr/scene.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

namespace {

using T = float;
using Set = mpr::CameraFrameSet<T>;

template <class Px>
void write_raw(const std::filesystem::path& path, const mpr::Image<Px>& image) {
  std::ofstream out(path, std::ios::binary);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      if constexpr (std::is_same_v<Px, mpr::Rgb8>) {
        out.write(reinterpret_cast<const char*>(&image(x, y)), 3);
      } else {
        const float c[3] = {image(x, y)[0], image(x, y)[1], image(x, y)[2]};
        out.write(reinterpret_cast<const char*>(c), sizeof c);
      }
    }
}

/// A 3x3 array of 40x30 cameras looking at a textured scene, the frames drawn procedurally.
std::filesystem::path write_synthetic(const std::filesystem::path& dir) {
  std::vector<mpr::PinholeCamera<T>> cameras;
  std::vector<mpr::Image<mpr::Rgb8>> images;
  std::vector<std::string> names;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      cameras.push_back(
          mpr::PinholeCamera<T>::look_at({0.2f * (i - 1), 0.2f * (j - 1), -4}, {0, 0, 0}, {0, -1, 0}, 0.6f, 40, 30));
      mpr::Image<mpr::Rgb8> image(40, 30);
      for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x)
          image(x, y) = mpr::Rgb8{static_cast<std::uint8_t>((x * 37 + i * 50) % 256),
                                  static_cast<std::uint8_t>((y * 53 + j * 70) % 256),
                                  static_cast<std::uint8_t>(((x / 4 + y / 4) % 2) * 200 + 20)};
      images.push_back(std::move(image));
      names.push_back("synth_" + std::to_string(3 * j + i) + ".png");
    }
  return mpr::write_frame_set(dir, "synth", Set(std::move(cameras), std::move(images), std::move(names)));
}

template <class Sampler, class Sampling, class Px, class Selector>
void render_job(const std::filesystem::path& path, const mpr::PlanarSurface<T>& plane, const Selector& glc,
                const Sampler& sampler, const Sampling& sampling, int w, int h) {
  mpr::Image<Px> image(w, h);
  mpr::Renderer(plane, glc, sampler, sampling).render(image.view(), mpr::Region(0, 0, w, h));
  write_raw(path, image);
}

void render_jobs(const std::filesystem::path& dir, const std::string& prefix, const std::filesystem::path& par, T depth,
                 int w, int h) {
  const auto frames = std::make_shared<const Set>(mpr::read_par_file<T>(par));
  const mpr::PinholeCamera<T>& c = frames->camera(frames->size() / 2);
  const mpr::PlanarSurface<T> plane = c.image_plane(depth);
  const mpr::GlcSelector<T> glc = mpr::pinhole_glc(c, plane);
  const mpr::CameraFrameSampler<mpr::SyntheticAperture, T> full(frames);
  const mpr::CameraFrameSampler<mpr::NearestCamera, T> nearest(frames);
  const mpr::CameraFrameSampler<mpr::CylinderAperture, T> cylinder(frames, mpr::CylinderAperture{0.25});
  const mpr::Supersample<mpr::OwenSobol, mpr::AnyFilter> tent(mpr::OwenSobol(4), mpr::AnyFilter(mpr::TentFilter(2)));
  render_job<decltype(full), mpr::PixelCentre, mpr::Rgb8>(dir / (prefix + "synthetic8.bin"), plane, glc, full, {}, w,
                                                          h);
  render_job<decltype(nearest), mpr::PixelCentre, mpr::Color>(dir / (prefix + "nearest_linear.bin"), plane, glc,
                                                              nearest, {}, w, h);
  render_job<decltype(cylinder), decltype(tent), mpr::Rgb8>(dir / (prefix + "cylinder_tent4.bin"), plane, glc, cylinder,
                                                            tent, w, h);
  // A disc aperture of radius depth / 40 around the pinhole, lens plane one plane width behind the
  // image plane, focused depth / 4 in front of it; 8 samples, box filter.
  const mpr::Supersample<mpr::OwenSobol, mpr::AnyFilter> box8(mpr::OwenSobol(8), mpr::AnyFilter(mpr::BoxFilter(0.5)));
  const T lens_distance = plane.width_vector().norm();
  const mpr::glc::FiniteAperture lens(plane, glc, mpr::glc::DiscAperture{}, depth / 40, lens_distance,
                                      mpr::glc::focus_at_depth(lens_distance, depth / 4));
  render_job<decltype(full), decltype(box8), mpr::Rgb8>(dir / (prefix + "disc_aperture8.bin"), plane, lens, full, box8,
                                                        w, h);
  // Gallery view G (cross-slit) on the same plane, looking at the point 2 depths along the axis.
  const mpr::Vec3<T> target = c.centre() + 2 * depth * c.forward();
  const mpr::GlcSelector<T> g = mpr::glc::gallery_view('G', plane, target, depth);
  render_job<decltype(full), mpr::PixelCentre, mpr::Rgb8>(dir / (prefix + "gallery_g.bin"), plane, g, full, {}, w, h);
}

/// The classroom through a pinhole at the back of the room, 64x48, pixel centres (8-bit) and 4
/// Gaussian-filtered samples (linear).
void render_classroom(const std::filesystem::path& dir) {
  const mpr::SceneSampler<mpr::scene::Scene<T>, mpr::RayCast> sampler(mpr::scene::classroom<T>());
  const auto camera = mpr::PinholeCamera<T>::look_at({0.5f, 1.6f, 8}, {0, 1.2f, -14}, {0, 1, 0}, 1.0f, 64, 48);
  const mpr::PlanarSurface<T> plane = camera.image_plane(10);
  const mpr::GlcSelector<T> glc = mpr::pinhole_glc(camera, plane);
  const mpr::Supersample<mpr::OwenSobol, mpr::AnyFilter> gauss(mpr::OwenSobol(4),
                                                               mpr::AnyFilter(mpr::GaussianFilter(1.5)));
  render_job<decltype(sampler), mpr::PixelCentre, mpr::Rgb8>(dir / "classroom8.bin", plane, glc, sampler, {}, 64, 48);
  render_job<decltype(sampler), decltype(gauss), mpr::Color>(dir / "classroom_gauss4_linear.bin", plane, glc, sampler,
                                                             gauss, 64, 48);
}

} // namespace

int main(int argc, char** argv) try {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: mpr_python_golden OUT_DIR [PAR_FILE]\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  render_jobs(dir, "synth_", write_synthetic(dir), 4, 40, 30);
  render_classroom(dir);
  if (argc == 3) render_jobs(dir, "real_", argv[2], 0.6f, 160, 120);
  std::printf("mpr_python_golden: wrote %s\n", dir.string().c_str());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "mpr_python_golden: %s\n", e.what());
  return 1;
}
