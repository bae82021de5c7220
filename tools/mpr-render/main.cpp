// mpr-render: multi-perspective rendering from the shell. Chooses the image surface, the GLC
// ray selector and the sampler (classroom scene, OBJ mesh, light field) at run time, renders to
// PNG, JPEG or the linear PFM and OpenEXR, and renders animations (tilt, aperture, focal-depth
// sweeps, GLC morphs) as numbered images plus an MP4 when ffmpeg is on PATH. See
// `mpr-render --help` and docs/mpr-render.md.
#include "encode_output.hpp"
#include "error_line.hpp"
#include "render_job.hpp"

#include "options/help.hpp"
#include "options/make_job.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <unistd.h>

namespace {

/// The progress of an animation on stderr: a bar on a terminal; otherwise (a batch job's log)
/// one line a frame with the time so far and the estimated time left.
class Progress {
public:
  explicit Progress(int frames) : frames_(frames), terminal_(isatty(STDERR_FILENO) != 0) {}

  /// Frame `index` (from 0, of the whole animation) is rendered; `done` of this run's `count`.
  void frame(int index, int done, int count) const {
    if (!terminal_) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      std::fprintf(stderr, "frame %d of %d rendered (%d/%d of this run), %.1f s, ETA %.0f s\n", index + 1, frames_,
                   done, count, s, s / done * (count - done));
      std::fflush(stderr);
      return;
    }
    constexpr int width = 40;
    const int filled = done * width / count;
    std::fprintf(stderr, "\r[%s%s] %d/%d", std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(width - filled), ' ').c_str(), done, count);
    if (done == count) std::fputc('\n', stderr);
    std::fflush(stderr);
  }

private:
  int frames_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// The progress of loading a light field's images on stderr, drawn only when stderr is a terminal.
void loading_progress(std::size_t done, std::size_t count) {
  std::fprintf(stderr, "\rloading images %zu/%zu", done, count);
  if (done == count) std::fprintf(stderr, "\r%*s\r", 40, "");
  std::fflush(stderr);
}

/// The progress of a depth estimation (--depth-maps estimate): on a terminal a bar for each stage
/// on stderr, replaced in place, as Progress draws an animation's, ending in the stage's line;
/// otherwise (a batch job's log) one line a stage when it ends, with its time, in the same form
/// as an animation's frame lines but on stdout, beside the estimate's summary line, so that a
/// run that fails after the estimate (a full disk) still ends in exactly one line on stderr.
void depth_progress_terminal(const mpr::DepthProgress& p) {
  constexpr std::size_t width = 40;
  const std::size_t filled = p.total > 0 ? p.done * width / p.total : width;
  std::fprintf(stderr, "\rdepth %-8s [%s%s] %zu/%zu, %.1f s", p.stage, std::string(filled, '#').c_str(),
               std::string(width - filled, ' ').c_str(), p.done, p.total, p.seconds);
  if (p.done == p.total) std::fputc('\n', stderr);
  std::fflush(stderr);
}

void depth_progress_lines(const mpr::DepthProgress& p) {
  if (p.done != p.total) return;
  std::printf("depth stage %s done (%zu/%zu), %.1f s\n", p.stage, p.done, p.total, p.seconds);
  std::fflush(stdout);
}

/// The frames of this run (all, or those of --shard K/N).
int frames_of_run(const mpr_cli::Job& job) {
  if (!job.shard) return job.frames;
  const auto [k, n] = *job.shard;
  return job.frames > k ? (job.frames - 1 - k) / n + 1 : 0;
}

/// After the frames of an animation are published: stale frames of an earlier run and the MP4
/// (neither for a shard, which sees only some frames).
void finish_animation(const mpr_cli::Job& job) {
  if (job.shard) return;
  // Frames beyond N of an earlier, longer run with the same name would mix with this one.
  if (const int removed = mpr_cli::remove_stale_frames(job.output, job.frames); removed > 0)
    std::printf("removed %d stale frame%s of an earlier run (%s onwards)\n", removed, removed == 1 ? "" : "s",
                mpr_cli::frame_path(job.output, job.frames).filename().string().c_str());
  if (!job.video || mpr_cli::is_linear(mpr_cli::image_format(job.output))) return; // no MP4 of linear frames
  const std::filesystem::path mp4 = mpr_cli::video_path(job.output);
  if (!mpr_cli::ffmpeg_available()) {
    std::fprintf(stderr,
                 "mpr-render: skipped %s: ffmpeg is not on PATH (the frames are complete; --no-video "
                 "silences this)\n",
                 mp4.string().c_str());
  } else if (std::system(mpr_cli::ffmpeg_command(job.output, job.frames, job.fps).c_str()) == 0) {
    std::printf("wrote %s\n", mp4.string().c_str());
  } else {
    std::fprintf(stderr, "mpr-render: ffmpeg failed; the frames are complete\n");
  }
}

} // namespace

int main(int argc, char** argv) try {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
      std::fputs(mpr_cli::render_help().c_str(), stdout);
      return 0;
    }
  mpr_cli::Job job = mpr_cli::parse_job(argc, argv);
  if (isatty(STDERR_FILENO)) job.load_progress = loading_progress;
  job.depth_progress = isatty(STDERR_FILENO) ? depth_progress_terminal : depth_progress_lines;
  mpr_cli::check_output_folder(job.output, "--output");
  if (job.write_depth) mpr_cli::check_output_folder(*job.write_depth, "--write-depth");
  // Before the plane sweep, not after it: a folder that cannot be made or written costs no estimate.
  if (job.save_depth_maps) mpr_cli::probe_output_folder(*job.save_depth_maps, "--save-depth-maps");
  const bool animation = job.frames >= 1;
  const int run_frames = frames_of_run(job);
  const Progress progress(job.frames);
  // Every file is staged as it is rendered and published only when all are (publish.hpp): a run
  // that fails leaves every existing file as it was and writes none.
  mpr_cli::Publication files;
  int done = 0, first = -1, last = -1;
  mpr_cli::run_linear(
      job,
      mpr_cli::frame_sinks(job.output, job.encoding,
                           [&](int index, int, const auto& image) { // 8-bit outputs: sRGB codes, else linear
                             const std::filesystem::path path =
                                 animation ? mpr_cli::frame_path(job.output, index) : job.output;
                             files.stage(path, mpr_cli::encode_output(path, image, job.encoding));
                             if (first < 0) first = index;
                             last = index;
                             if (animation) progress.frame(index, ++done, run_frames);
                           }),
      &std::cout, &std::cerr, &files);
  files.commit();
  if (!animation) {
    std::printf("wrote %s\n", job.output.string().c_str());
  } else if (done > 0) {
    std::printf("wrote %s ... %s%s\n", mpr_cli::frame_path(job.output, first).string().c_str(),
                mpr_cli::frame_path(job.output, last).string().c_str(),
                job.shard ? (" (" + std::to_string(done) + " frames of shard " + std::to_string(job.shard->first) +
                             "/" + std::to_string(job.shard->second) + ")")
                                .c_str()
                          : "");
    finish_animation(job);
  }
  return 0;
} catch (const std::exception& e) {
  // One line: "mpr-render: invalid --size: ...", "mpr-render: /path: no such folder".
  std::fprintf(stderr, "mpr-render: %s\n", mpr_cli::error_line(e.what()).c_str());
  return 1;
}
