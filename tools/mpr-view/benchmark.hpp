#pragma once
// mpr-view --benchmark: the viewer's render thread without a window. Measures full-resolution
// and preview frame times of the job's view, and the time from an input event (a new request
// arriving while a full-resolution frame is being rendered) to the first preview frame of the
// new view (quarter resolution or coarser, render_thread.hpp), which includes abandoning the
// frame in flight.

#include "render_thread.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace mpr_view {

namespace detail {

inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// The 1-minute load average, or -1 when /proc/loadavg cannot be read.
inline double load_average() {
  std::ifstream in("/proc/loadavg");
  double load = -1;
  in >> load;
  return in ? load : -1;
}

} // namespace detail

/// Runs the benchmark and prints its figures; returns the exit status.
template <std::floating_point T>
int run_benchmark(const mpr_cli::Job& job, const mpr_cli::Loaded<T>& l, int frames) {
  using Clock = std::chrono::steady_clock;
  std::mutex mutex;
  std::condition_variable arrived;
  std::vector<RenderedFrame> received;
  RenderThread<T>* thread = nullptr;
  RenderThread<T> render_thread(l, [&] {
    // Called on the render thread: collect every frame, so no preview is missed.
    const std::lock_guard lock(mutex);
    if (thread == nullptr) return;
    if (std::optional<RenderedFrame> f = thread->take()) {
      f->image = mpr::Image<mpr::Rgb8>();
      received.push_back(std::move(*f));
    }
    arrived.notify_all();
  });
  {
    const std::lock_guard lock(mutex);
    thread = &render_thread;
  }
  const std::pair<int, int> view_size = mpr_cli::view_size(job, l); // not a structured binding: Clang 14
  const int view_w = view_size.first, view_h = view_size.second;    // captures none
  std::uint64_t generation = 0;
  const auto submit = [&] {
    RenderRequest r;
    r.job = job;
    r.params = mpr_cli::frame_params(job, l.default_focal_depth, 0);
    r.view_width = view_w;
    r.view_height = view_h;
    r.generation = ++generation;
    r.submitted = Clock::now();
    render_thread.submit(std::move(r));
  };
  // Waits for the full frame of the current generation (full), or for its first frame, the
  // preview unless the render thread skips it (!full); or for an error frame.
  const auto wait_for = [&](bool full) -> RenderedFrame {
    std::unique_lock lock(mutex);
    for (;;) {
      for (const RenderedFrame& f : received)
        if (f.generation == generation && (f.full || !full || !f.error.empty())) return f;
      arrived.wait(lock);
    }
  };

  std::vector<double> full_ms, preview_ms, latency_ms;
  int preview_scale = 2;
  submit(); // warm-up: loads caches, builds the sampler
  if (const RenderedFrame f = wait_for(true); !f.error.empty()) {
    std::fprintf(stderr, "mpr-view: %s\n", f.error.c_str());
    return 1;
  }
  const Clock::time_point start = Clock::now();
  for (int i = 0; i < frames; ++i) {
    submit();
    const RenderedFrame preview = wait_for(false);
    if (!preview.full) {
      preview_ms.push_back(preview.milliseconds);
      preview_scale = preview.scale;
    }
    full_ms.push_back(wait_for(true).milliseconds);
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  // Input events while a full-resolution frame is in flight: after a preview arrives, the
  // next request comes at a different point of the full frame each time.
  const double full = detail::median(full_ms);
  for (int i = 0; i < frames; ++i) {
    submit();
    (void)wait_for(false);
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(full * (i % 8 + 0.5) / 8));
    submit();
    latency_ms.push_back(wait_for(false).latency_ms);
    (void)wait_for(true);
  }
  const std::string interp(mpr_cli::interpolation_name(job.interpolation));
  const bool focus = job.raster || mpr_cli::is_light_field(job.sampler);
  std::printf("mpr-view benchmark: %dx%d, %d view(s), %s, threads %d, %s%s, load average %.2f\n", view_w * job.cols,
              view_h * job.rows, job.cols * job.rows, sizeof(T) == 4 ? "float" : "double", job.threads,
              job.sampler == mpr_cli::SamplerKind::scene ? "scene" : job.input.filename().string().c_str(),
              focus ? (std::string(" ") + interp).c_str() : "", detail::load_average());
  std::printf("full resolution:    median %.2f ms = %.1f frames/s (%d frames)\n", full, 1000 / std::max(full, 1e-9),
              frames);
  if (preview_ms.empty())
    std::printf("preview: skipped (no faster than the full frame)\n");
  else
    std::printf("preview (1/%d of the pixels): median %.2f ms = %.1f frames/s (%zu frames)\n",
                preview_scale * preview_scale, detail::median(preview_ms),
                1000 / std::max(detail::median(preview_ms), 1e-9), preview_ms.size());
  std::printf("preview then full per view change: %.1f changes/s\n", frames / std::max(seconds, 1e-9));
  std::printf(
      "input event -> first frame (preview or full): median %.2f ms, max %.2f ms (%d events during full frames)\n",
      detail::median(latency_ms), *std::max_element(latency_ms.begin(), latency_ms.end()), frames);
  return 0;
}

} // namespace mpr_view
