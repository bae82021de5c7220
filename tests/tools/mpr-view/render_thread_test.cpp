#include "mpr-view/render_thread.hpp"
#include "tools/tools_test_support.hpp"

#include <catch2/catch.hpp>

#include <condition_variable>
#include <cstring>
#include <mutex>
#include <vector>

namespace {
mpr_cli::Job job_of(std::vector<std::string> args) {
  std::vector<const char*> argv{"mpr-render"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  return mpr_cli::parse_job(static_cast<int>(argv.size()), argv.data());
}

bool identical(const mpr::Image<mpr::Rgb8>& a, const mpr::Image<mpr::Rgb8>& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.data(), b.data(), sizeof(mpr::Rgb8) * static_cast<std::size_t>(a.width() * a.height())) == 0;
}

/// Collects every frame the thread publishes.
struct Collector {
  std::mutex mutex;
  std::condition_variable arrived;
  std::vector<mpr_view::RenderedFrame> frames;
  mpr_view::RenderThread<float>* thread = nullptr;

  void on_frame() {
    const std::lock_guard lock(mutex);
    if (thread == nullptr) return;
    if (std::optional<mpr_view::RenderedFrame> f = thread->take()) frames.push_back(std::move(*f));
    arrived.notify_all();
  }
  mpr_view::RenderedFrame wait_full(std::uint64_t generation) {
    std::unique_lock lock(mutex);
    for (;;) {
      for (const mpr_view::RenderedFrame& f : frames)
        if (f.generation == generation && (f.full || !f.error.empty())) return f;
      arrived.wait(lock);
    }
  }
};

/// Every frame a render thread publishes for `job` (first request: a preview, then the full
/// frame), and that full frame.
struct Published {
  std::vector<mpr_view::RenderedFrame> frames;
  mpr_view::RenderedFrame full;
};
Published render_once(const mpr_cli::Job& job, const mpr_cli::Loaded<float>& l);

mpr_view::RenderRequest request_of(const mpr_cli::Job& job, const mpr_cli::Loaded<float>& l, std::uint64_t gen) {
  mpr_view::RenderRequest r;
  r.job = job;
  r.params = mpr_cli::frame_params(job, l.default_focal_depth, 0);
  r.view_width = job.width;
  r.view_height = job.height;
  r.generation = gen;
  return r;
}
Published render_once(const mpr_cli::Job& job, const mpr_cli::Loaded<float>& l) {
  Collector c;
  mpr_view::RenderThread<float> thread(l, [&] { c.on_frame(); });
  {
    const std::lock_guard lock(c.mutex);
    c.thread = &thread;
  }
  thread.submit(request_of(job, l, 1));
  Published p;
  p.full = c.wait_full(1);
  const std::lock_guard lock(c.mutex);
  p.frames = c.frames;
  return p;
}
} // namespace

TEST_CASE("RenderThread renders a preview, then exactly mpr-render's image", "[view]") {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--view", "G", "--size", "61x37", "--threads", "2"},
        std::vector<std::string>{"--layout", "2x2", "--views", "A,D,G,I", "--size", "30x21", "--threads", "3"},
        std::vector<std::string>{"--raster", "3x2", "--interp", "cylinder", "--radius", "2", "--size", "40x30",
                                 "--tilt-x", "10", "--rectify", "plane", "--threads", "2"}}) {
    const mpr_cli::Job job = job_of(args);
    const mpr_cli::Loaded<float> l = mpr_cli::load<float>(job);
    const Published c = render_once(job, l);
    REQUIRE(c.full.error.empty());
    const std::vector<mpr::Image<mpr::Rgb8>> expected = mpr_cli::render_frames(job);
    CHECK(identical(c.full.image, expected.at(0)));
    REQUIRE(c.frames.size() >= 1);
    if (c.frames.size() == 2) { // the preview was taken before the full frame replaced it
      CHECK_FALSE(c.frames[0].full);
      CHECK(c.frames[0].scale == 2);
      CHECK(c.frames[0].image.width() == job.cols * ((job.width + 1) / 2));
    }
  }
}

TEST_CASE("RenderThread samples a light field prefiltered to each frame's scale, as mpr-render does", "[view]") {
  // Three 8 x 6 cameras of random codes 0.1 apart, focal length 8: on the plane z = 2 the side
  // cameras' texels lie 0.4 pixel off the middle one's, so bilinear sampling of the full frames
  // and of frames prefiltered to half scale give different images.
  const std::filesystem::path dir = mpr_tools_test::plane_light_field("view_prefilter", 2.0f);
  const std::string par = (dir / "tiny_par.txt").string();
  const auto job_at = [&](const char* size) {
    return job_of({"--par", par, "--focal-depth", "2", "--interp", "synthetic", "--size", size, "--threads", "2"});
  };
  const mpr::Image<mpr::Rgb8> half = mpr_cli::render_frames(job_at("4x3")).at(0); // prefiltered by 2 (auto)
  CHECK_FALSE(identical(half, mpr_cli::render_frames(job_of({"--par", par, "--focal-depth", "2", "--interp",
                                                             "synthetic", "--size", "4x3", "--prefilter", "1"}))
                                  .at(0)));
  for (const char* size : {"8x6", "4x3"}) {
    INFO(size);
    const mpr_cli::Job job = job_at(size);
    const Published c = render_once(job, mpr_cli::load<float>(job));
    REQUIRE(c.full.error.empty());
    CHECK(identical(c.full.image, mpr_cli::render_frames(job).at(0)));
    REQUIRE(c.frames.size() == 2); // the first request's preview is never skipped
    CHECK_FALSE(c.frames[0].full);
    // The 4x3 preview of the 8x6 view is mpr-render's 4x3 image: the frames prefiltered to its scale.
    if (job.width == 8) CHECK(identical(c.frames[0].image, half));
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("RenderThread reports an impossible view as one line and keeps going", "[view]") {
  mpr_cli::Job job = job_of({"--view", "A", "--size", "32x24", "--threads", "1"});
  const mpr_cli::Loaded<float> l = mpr_cli::load<float>(job);
  Collector c;
  mpr_view::RenderThread<float> thread(l, [&] { c.on_frame(); });
  {
    const std::lock_guard lock(c.mutex);
    c.thread = &thread;
  }
  mpr_cli::Job bad = job;
  bad.views = {"orthographic:1,0,0"}; // rays parallel to the image plane
  thread.submit(request_of(bad, l, 1));
  const mpr_view::RenderedFrame failed = c.wait_full(1);
  CHECK_THAT(failed.error, Catch::Contains("impossible camera"));
  CHECK(failed.error.find('\n') == std::string::npos);
  CHECK(failed.image.width() == 0);
  thread.submit(request_of(job, l, 2));
  const mpr_view::RenderedFrame good = c.wait_full(2);
  CHECK(good.error.empty());
  CHECK(good.type == "pinhole");
}
