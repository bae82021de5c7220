// mpr-render: multi-perspective rendering from the shell. Chooses the image surface, the GLC
// ray selector and the sampler (classroom scene, OBJ mesh, light field) at run time, renders to
// PNG, and renders animations (tilt, aperture, focal-depth sweeps, GLC morphs) as numbered PNGs
// plus an MP4 when ffmpeg is on PATH. See `mpr-render --help` and docs/mpr-render.md.
#include "render_job.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <unistd.h>

namespace {

void print_help() {
  std::printf("usage: mpr-render [OPTIONS]\n\nRenders General Linear Camera views of a scene or a light field to PNG "
              "or JPEG.\n\n");
  for (const mpr_cli::OptionSpec& s : mpr_cli::options()) {
    std::string head = "--" + s.name + (s.value.empty() ? "" : " " + s.value);
    std::printf("  %s\n      %s\n      e.g. %s\n", head.c_str(), s.help.c_str(), s.example.c_str());
  }
  std::printf("\n%s", mpr_cli::view_help());
}

/// A progress bar on stderr, drawn only when stderr is a terminal.
void progress(int done, int count) {
  if (!isatty(STDERR_FILENO)) return;
  constexpr int width = 40;
  const int filled = done * width / count;
  std::fprintf(stderr, "\r[%s%s] %d/%d", std::string(static_cast<std::size_t>(filled), '#').c_str(),
               std::string(static_cast<std::size_t>(width - filled), ' ').c_str(), done, count);
  if (done == count) std::fputc('\n', stderr);
  std::fflush(stderr);
}

/// The progress of loading a light field's images on stderr, drawn only when stderr is a terminal.
void loading_progress(std::size_t done, std::size_t count) {
  std::fprintf(stderr, "\rloading images %zu/%zu", done, count);
  if (done == count) std::fprintf(stderr, "\r%*s\r", 40, "");
  std::fflush(stderr);
}

} // namespace

int main(int argc, char** argv) try {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
      print_help();
      return 0;
    }
  mpr_cli::Job job = mpr_cli::parse_job(argc, argv);
  if (isatty(STDERR_FILENO)) job.load_progress = loading_progress;
  if (const auto parent = job.output.parent_path(); !parent.empty()) std::filesystem::create_directories(parent);
  const bool animation = job.frames >= 1;
  mpr_cli::run(
      job,
      [&](int index, int count, const mpr::Image<mpr::Rgb8>& image) {
        const std::filesystem::path path = animation ? mpr_cli::frame_path(job.output, index) : job.output;
        mpr_cli::write_image(path, image);
        if (animation)
          progress(index + 1, count);
        else
          std::printf("wrote %s\n", path.string().c_str());
      },
      &std::cout, &std::cerr);
  if (animation) {
    std::printf("wrote %s ... %s\n", mpr_cli::frame_path(job.output, 0).string().c_str(),
                mpr_cli::frame_path(job.output, job.frames - 1).string().c_str());
    // Frames beyond N of an earlier, longer run with the same name would mix with this one.
    if (const int removed = mpr_cli::remove_stale_frames(job.output, job.frames); removed > 0)
      std::printf("removed %d stale frame%s of an earlier run (%s onwards)\n", removed, removed == 1 ? "" : "s",
                  mpr_cli::frame_path(job.output, job.frames).filename().string().c_str());
    if (job.video) {
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
  }
  return 0;
} catch (const std::exception& e) {
  // One line: "mpr-render: invalid --size: ...", "mpr-render: /path: no such folder".
  std::string what = e.what();
  if (what.rfind("mpr: ", 0) == 0) what.erase(0, 5);
  for (char& c : what)
    if (c == '\n') c = ' ';
  std::fprintf(stderr, "mpr-render: %s\n", what.c_str());
  return 1;
}
