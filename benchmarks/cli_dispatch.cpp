// The cost of mpr-render's run-time choice: the same classroom view (gallery view G, cross-slit,
// float) rendered (1) directly from C++ with a fully typed mpr::Renderer, (2) through the tool's
// render_view, i.e. a std::variant of cameras x a std::variant of samplers and ONE std::visit per
// render, and (3) through the tool's whole per-frame path (camera and sampler built from the Job,
// then render_view). Prints median (min-max) ms and Mrays/s, and checks the three images are
// identical.
//
// usage: cli_dispatch [--quick]
#include "bench_common.hpp"

#include "../tools/mpr-render/render_job.hpp"
#include "../tools/options/make_job.hpp"

#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
  using T = float;
  const bool quick = mpr_bench::quick_mode(argc, argv);
  const int w = quick ? 64 : 800, h = quick ? 48 : 600;
  const int repeats = quick ? 1 : 9;
  std::printf("%s\n", mpr_bench::machine_description().c_str());

  const std::string size = std::to_string(w) + "x" + std::to_string(h);
  const char* args[] = {"mpr-render", "--view", "G", "--size", size.c_str()};
  mpr_cli::Job job = mpr_cli::parse_job(5, args);
  const mpr_cli::Loaded<T> loaded = mpr_cli::load<T>(job);
  const mpr_cli::FrameParams params = mpr_cli::frame_params(job, loaded.default_focal_depth, 0);

  // (1) Direct C++: the classroom plane of the tool's defaults and gallery view G.
  const mpr::Vec3<T> centre(0, 3.1f, 3.0f), look(0, 1.6f, -8);
  const mpr::Vec3<T> forward = (look - centre).normalized();
  const mpr::Vec3<T> right = forward.cross(mpr::Vec3<T>::UnitY()).normalized();
  const mpr::Vec3<T> down = forward.cross(right);
  const auto plane = mpr::PlanarSurface<T>::centred(centre, T(8) * right, (T(8) * T(h) / T(w)) * down);
  const mpr::Renderer direct(plane, mpr::glc::gallery_view('G', plane, look, T(14)), *loaded.scene_sampler);

  const mpr_cli::CameraVariant<T> camera = mpr_cli::make_camera(job, loaded, params, 0, w, h);
  const mpr_cli::SamplerVariant<T> sampler = mpr_cli::make_sampler(job, loaded, params, w, h);

  std::printf("classroom, gallery view G (cross-slit), %dx%d, float, median of %d runs (min-max)\n\n", w, h, repeats);
  std::printf("| path | threads | ms | Mrays/s |\n|---|---|---|---|\n");
  const double rays = double(w) * h;
  mpr::Image<mpr::Rgb8> a(w, h), b(w, h), c(w, h);
  const mpr::Region region(0, 0, w, h);
  for (const int threads : {1, 2}) {
    const mpr::RenderOptions options{threads};
    const auto row = [&](const char* name, const mpr_bench::Timing& t) {
      std::printf("| %-44s | %d | %7.2f (%.2f-%.2f) | %6.2f |\n", name, threads, t.median * 1e3, t.min * 1e3,
                  t.max * 1e3, rays / t.median * 1e-6);
    };
    row("C++ Renderer<Planar, Glc, SceneSampler>",
        mpr_bench::time_repeated(repeats, [&] { direct.render(a.view(), region, options); }));
    row("mpr-render: one std::visit (render_view)",
        mpr_bench::time_repeated(repeats, [&] { mpr_cli::render_view(camera, sampler, b.view(), region, options); }));
    row("mpr-render: whole frame (Job -> camera, sampler)", mpr_bench::time_repeated(repeats, [&] {
          const mpr_cli::CameraVariant<T> cam = mpr_cli::make_camera(job, loaded, params, 0, w, h);
          const mpr_cli::SamplerVariant<T> smp = mpr_cli::make_sampler(job, loaded, params, w, h);
          mpr_cli::render_view(cam, smp, c.view(), region, options);
        }));
  }
  const bool same = std::memcmp(a.data(), b.data(), sizeof(mpr::Rgb8) * a.width() * a.height()) == 0 &&
                    std::memcmp(a.data(), c.data(), sizeof(mpr::Rgb8) * a.width() * a.height()) == 0;
  std::printf("\nimages identical: %s\n", same ? "yes" : "NO");
  return same ? 0 : 1;
}
