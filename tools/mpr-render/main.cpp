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
  std::printf(
      "usage: mpr-render [OPTIONS]\n\nRenders General Linear Camera views of a scene or a light field to PNG.\n\n");
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

bool ffmpeg_available() { return std::system("command -v ffmpeg >/dev/null 2>&1") == 0; }

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

} // namespace

int main(int argc, char** argv) try {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
      print_help();
      return 0;
    }
  const mpr_cli::Job job = mpr_cli::parse_job(argc, argv);
  if (const auto parent = job.output.parent_path(); !parent.empty()) std::filesystem::create_directories(parent);
  const bool animation = job.frames >= 1;
  mpr_cli::run(
      job,
      [&](int index, int count, const mpr::Image<mpr::Rgb8>& image) {
        const std::filesystem::path path = animation ? mpr_cli::frame_path(job.output, index) : job.output;
        mpr::write_png(path, image);
        if (animation)
          progress(index + 1, count);
        else
          std::printf("wrote %s\n", path.string().c_str());
      },
      &std::cout, &std::cerr);
  if (animation) {
    std::printf("wrote %s ... %s\n", mpr_cli::frame_path(job.output, 0).string().c_str(),
                mpr_cli::frame_path(job.output, job.frames - 1).string().c_str());
    if (job.video && ffmpeg_available()) {
      std::filesystem::path mp4 = job.output;
      mp4.replace_extension(".mp4");
      std::filesystem::path pattern = job.output;
      pattern.replace_filename(job.output.stem().string() + "_%04d.png");
      const std::string cmd = "ffmpeg -loglevel error -y -framerate 12 -i " + quoted(pattern.string()) +
                              " -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' " + quoted(mp4.string());
      if (std::system(cmd.c_str()) == 0)
        std::printf("wrote %s\n", mp4.string().c_str());
      else
        std::fprintf(stderr, "mpr-render: ffmpeg failed; the PNG frames are complete\n");
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
