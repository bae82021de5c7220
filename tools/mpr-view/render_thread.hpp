#pragma once
// mpr-view's render thread: renders the latest requested view with mpr-render's own code path
// (framing.hpp's make_camera, samplers.hpp's make_sampler, render_job.hpp's render_view with the
// job's --spp / --filter pixel sampling and --aperture lens), first
// as a preview at quarter resolution (half width, half height; coarser when even that would take
// longer than kPreviewBudgetMs; light fields sampled from frames prefiltered to the preview's
// scale, mpr-render's prefilter.hpp), then at full resolution, in bands of rows
// shared out by a BandPool. Between bands it checks whether a newer view was requested and, if
// so, abandons the frame.
// The thread never waits on the event loop: finished frames are left in a slot that the event
// loop takes, and a callback (an SDL user event) says one is there.

#include "band_pool.hpp"
#include "mpr-render/render_job.hpp"

#include <mpr/core/image.hpp>
#include <mpr/glc.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

namespace mpr_view {

/// One view to render: the job at frame parameters `params`, views of `view_width` x
/// `view_height` pixels (the image is cols x rows of them).
struct RenderRequest {
  mpr_cli::Job job;
  mpr_cli::FrameParams params;
  int view_width = 1, view_height = 1;
  std::uint64_t generation = 0; ///< increases with every request
  std::chrono::steady_clock::time_point submitted{};
};

/// A finished frame (or the reason the view cannot be rendered).
struct RenderedFrame {
  mpr::Image<mpr::Rgb8> image;  ///< a preview or full resolution; empty when `error` is set
  std::uint64_t generation = 0; ///< of the request
  bool full = false;            ///< full resolution (else a preview)
  int scale = 1;                ///< pixels of the view per pixel of the image, across and down
  double milliseconds = 0;      ///< render time of this frame (cameras, sampler and pixels)
  double latency_ms = 0;        ///< from the request's submission to this frame
  std::string type;             ///< GLC type of the first view (mpr::glc::classify), e.g. "cross_slit"
  double focal_depth = 0;       ///< focal depth in use (--raster: the array's)
  std::string error;            ///< why the view cannot be rendered (one line), or empty
};

/// Render time a preview frame aims at, milliseconds (input-to-preview target: 50 ms).
inline constexpr double kPreviewBudgetMs = 20;

/// Rows per band: the unit of work of a pool thread, between two checks of the cancel flag (a
/// multiple of mpr::kTileRows, so tiles fall where mpr-render puts them).
inline constexpr int kBandRows = 8;

template <std::floating_point T>
class RenderThread {
public:
  /// `loaded` must outlive the thread. `notify` is called from the render thread after each
  /// frame is left for `take`.
  RenderThread(const mpr_cli::Loaded<T>& loaded, std::function<void()> notify)
      : loaded_(loaded), notify_(std::move(notify)), thread_([this] { loop(); }) {}
  RenderThread(const RenderThread&) = delete;
  RenderThread& operator=(const RenderThread&) = delete;
  ~RenderThread() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    latest_.fetch_add(1);
    wake_.notify_all();
    thread_.join();
  }

  /// Asks for a new view; a frame in flight for an older one is abandoned.
  void submit(RenderRequest request) {
    {
      const std::lock_guard lock(mutex_);
      latest_.store(request.generation);
      pending_ = std::move(request);
    }
    wake_.notify_all();
  }

  /// The newest finished frame not yet taken, if any.
  [[nodiscard]] std::optional<RenderedFrame> take() {
    const std::lock_guard lock(mutex_);
    std::optional<RenderedFrame> out = std::move(done_);
    done_.reset();
    return out;
  }

private:
  [[nodiscard]] bool cancelled(std::uint64_t generation) const noexcept { return latest_.load() != generation; }

  void publish(RenderedFrame frame) {
    {
      const std::lock_guard lock(mutex_);
      done_ = std::move(frame);
    }
    if (notify_) notify_();
  }

  void loop() {
    for (;;) {
      RenderRequest request;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || pending_.has_value(); });
        if (stop_) return;
        request = std::move(*pending_);
        pending_.reset();
      }
      for (const bool full : {false, true}) {
        if (cancelled(request.generation)) break;
        if (!full && preview_no_faster()) continue;
        std::optional<RenderedFrame> frame = render(request, full);
        if (!frame) break; // abandoned
        const bool failed = !frame->error.empty();
        publish(std::move(*frame));
        if (failed) break;
      }
    }
  }

  /// The data a render of request `r` at `scale` (view pixels per image pixel) samples: the
  /// loaded frames prefiltered as --prefilter says (mpr-render's prefilter.hpp; auto: by the
  /// footprint of the image's pixels at the request's parameters, so a preview reads frames at
  /// its own scale), each factor's frames built once, on first use.
  const mpr_cli::Loaded<T>& loaded_for(const RenderRequest& r, int w, int h) {
    const int factor = mpr_cli::prefilter_factor(r.job, loaded_, [&] {
      // View pixels per image pixel (a preview of an odd size is ceil(size / scale) wide).
      const double scale = std::min(static_cast<double>(r.view_width) / w, static_cast<double>(r.view_height) / h);
      return scale * mpr_cli::footprint_at(r.job, loaded_, r.params, r.view_width, r.view_height);
    });
    if (factor <= 1 || !loaded_.frames) return loaded_;
    if (const auto it = prefiltered_.find(factor); it != prefiltered_.end()) return it->second;
    mpr_cli::Loaded<T> l = loaded_;
    const auto start = std::chrono::steady_clock::now();
    l.frames = mpr_cli::prefiltered_frames(loaded_.frames, factor, r.job.threads);
    prefilter_ms_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return prefiltered_.emplace(factor, std::move(l)).first->second;
  }

  /// The sampler of a request over `l` (`loaded_for`), one kept for previews and one for full
  /// frames (the same one when their settings agree): rebuilt only when its settings change (a
  /// rasterized array costs milliseconds per camera to build).
  const mpr_cli::SamplerVariant<T>& sampler_for(const RenderRequest& r, const mpr_cli::Loaded<T>& l, bool full) {
    std::string key = std::to_string(static_cast<int>(r.job.interpolation)) + " " + std::to_string(r.params.radius) +
                      " " + std::to_string(reinterpret_cast<std::uintptr_t>(l.frames.get()));
    if (r.job.raster) {
      const mpr::PlanarSurface<T> plane = mpr_cli::base_plane(r.job, loaded_, r.params, r.view_width, r.view_height);
      // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on `" " + std::to_string(...)`.
      for (const mpr::Vec3<T>& v : {plane.centre(), plane.width_vector(), plane.height_vector()})
        key.append(" ")
            .append(std::to_string(v.x()))
            .append(",")
            .append(std::to_string(v.y()))
            .append(",")
            .append(std::to_string(v.z()));
      key.append(" ").append(std::to_string(r.job.focal_depth ? r.params.focal_depth : -1.0));
    }
    std::shared_ptr<const mpr_cli::SamplerVariant<T>>& sampler = sampler_[full ? 1 : 0];
    std::string& sampler_key = sampler_key_[full ? 1 : 0];
    if (!sampler || key != sampler_key) {
      sampler.reset();
      if (sampler_[full ? 0 : 1] && sampler_key_[full ? 0 : 1] == key)
        sampler = sampler_[full ? 0 : 1];
      else
        sampler = std::make_shared<const mpr_cli::SamplerVariant<T>>(
            mpr_cli::make_sampler(r.job, l, r.params, r.view_width, r.view_height));
      sampler_key = key;
    }
    return *sampler;
  }

  std::optional<RenderedFrame> render(const RenderRequest& r, bool full) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    prefilter_ms_ = 0;
    RenderedFrame frame;
    frame.generation = r.generation;
    frame.full = full;
    frame.focal_depth = r.params.focal_depth;
    const int scale = full ? 1 : preview_scale();
    frame.scale = scale;
    const int w = (r.view_width + scale - 1) / scale, h = (r.view_height + scale - 1) / scale;
    std::vector<mpr_cli::CameraVariant<T>> cameras;
    const mpr_cli::SamplerVariant<T>* sampler = nullptr;
    try {
      for (std::size_t k = 0; k < r.job.views.size(); ++k)
        cameras.push_back(mpr_cli::make_camera(r.job, loaded_, r.params, k, r.view_width, r.view_height));
      sampler = &sampler_for(r, loaded_for(r, w, h), full);
    } catch (const std::exception& e) {
      frame.error = one_line(e.what());
      frame.latency_ms = std::chrono::duration<double, std::milli>(Clock::now() - r.submitted).count();
      return frame;
    }
    if (const auto* raster =
            std::get_if<mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::NearestCamera>>>(sampler))
      frame.focal_depth = static_cast<double>(raster->focal_depth());
    else if (const auto* rs =
                 std::get_if<mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::SyntheticAperture>>>(sampler))
      frame.focal_depth = static_cast<double>(rs->focal_depth());
    else if (const auto* rc =
                 std::get_if<mpr::SceneSampler<mpr::scene::Scene<T>, mpr::Rasterized<mpr::CylinderAperture>>>(sampler))
      frame.focal_depth = static_cast<double>(rc->focal_depth());
    frame.type = type_of(cameras.front());
    frame.image = mpr::Image<mpr::Rgb8>(w * r.job.cols, h * r.job.rows);
    const int threads = mpr::detail::resolve_thread_count(r.job.threads, 1 << 20);
    if (!pool_ || pool_->threads() != threads) {
      pool_.reset();
      pool_.emplace(threads);
    }
    const mpr::RenderOptions one_thread{1}; // the pool spreads the bands
    // --spp / --filter and --aperture as mpr-render renders them (the same pixels: each view's
    // region is the tile mpr-render renders, shifted into the band).
    const mpr_cli::PixelSamplingVariant sampling = mpr_cli::make_pixel_sampling(r.job.spp, r.job.filter);
    const mpr_cli::ApertureSpec* aperture = r.job.aperture ? &*r.job.aperture : nullptr;
    const int height = frame.image.height(), bands = (height + kBandRows - 1) / kBandRows;
    std::atomic<bool> abandoned{false};
    pool_->run(bands, [&](int b) {
      if (abandoned.load(std::memory_order_relaxed)) return;
      if (cancelled(r.generation)) {
        abandoned.store(true, std::memory_order_relaxed);
        return;
      }
      const int y0 = b * kBandRows, rows = std::min(kBandRows, height - y0);
      const mpr::ImageView<mpr::Rgb8> band = frame.image.view().subview(0, y0, frame.image.width(), rows);
      for (std::size_t k = 0; k < cameras.size(); ++k) {
        const int col = static_cast<int>(k) % r.job.cols, row = static_cast<int>(k) / r.job.cols;
        mpr_cli::render_view(cameras[k], *sampler, sampling, band, mpr::Region(col * w, row * h - y0, w, h), one_thread,
                             aperture, r.params.aperture_size);
      }
    });
    if (abandoned.load()) return std::nullopt;
    const Clock::time_point end = Clock::now();
    // The frames' one-off prefiltering is not what the next frames will take.
    (full ? last_full_ms_ : last_preview_ms_) =
        std::chrono::duration<double, std::milli>(end - start).count() - prefilter_ms_;
    frame.milliseconds = std::chrono::duration<double, std::milli>(end - start).count();
    frame.latency_ms = std::chrono::duration<double, std::milli>(end - r.submitted).count();
    return frame;
  }

  /// The preview's scale: 2 (a quarter of the pixels), coarser when the last full frame took so
  /// long that a quarter-resolution preview would exceed kPreviewBudgetMs.
  [[nodiscard]] int preview_scale() const noexcept {
    const double ratio = std::sqrt(std::max(last_full_ms_, 0.0) / kPreviewBudgetMs);
    return std::clamp(static_cast<int>(std::ceil(ratio)), 2, 8);
  }

  /// Whether the last preview took nearly as long as the last full frame: then the full frame
  /// comes first. (Before previews sampled prefiltered frames, a light field at its cameras' own
  /// resolution, on a fast path, rendered faster than a preview grid on the full frames.) A
  /// slower full frame later brings the preview back.
  [[nodiscard]] bool preview_no_faster() const noexcept {
    return last_preview_ms_ > 0 && last_full_ms_ > 0 && last_preview_ms_ >= 0.8 * last_full_ms_;
  }

  static std::string type_of(const mpr_cli::CameraVariant<T>& camera) {
    const bool rectified = std::holds_alternative<mpr::glc::Rectified<T>>(camera);
    const mpr::PlanarSurface<T>& plane = rectified ? std::get<mpr::glc::Rectified<T>>(camera).surface.plane()
                                                   : std::get<mpr_cli::PlanarCamera<T>>(camera).surface;
    const mpr::GlcSelector<T>& glc = rectified ? std::get<mpr::glc::Rectified<T>>(camera).selector.selector()
                                               : std::get<mpr_cli::PlanarCamera<T>>(camera).selector;
    try {
      std::string type(mpr::glc::to_string(mpr::glc::classify(plane, glc).type));
      return rectified ? type + " rectified" : type;
    } catch (const std::exception&) {
      return "unclassified";
    }
  }

  static std::string one_line(std::string what) {
    if (what.rfind("mpr: ", 0) == 0) what.erase(0, 5);
    for (char& c : what)
      if (c == '\n') c = ' ';
    return what;
  }

  const mpr_cli::Loaded<T>& loaded_;
  std::function<void()> notify_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::optional<RenderRequest> pending_;
  std::optional<RenderedFrame> done_;
  std::atomic<std::uint64_t> latest_{0};
  std::map<int, mpr_cli::Loaded<T>> prefiltered_;                // render thread only: by factor
  std::shared_ptr<const mpr_cli::SamplerVariant<T>> sampler_[2]; // render thread only: preview, full
  std::string sampler_key_[2];                                   // render thread only
  std::optional<BandPool> pool_;
  double last_full_ms_ = 0, last_preview_ms_ = 0; // render thread only
  double prefilter_ms_ = 0;                       // render thread only: spent prefiltering this frame
  std::thread thread_;                            // last: starts after the members above
};

} // namespace mpr_view
