// The option table's ANIMATION, OUTPUT AND RUN and VIEWER sections (table_sections.hpp).
#include "table_sections.hpp"

#include <array>
#include <string>
#include <string_view>

namespace mpr_cli::table {

namespace {

constexpr std::array<std::string_view, 2> kBitDepths{"8", "16"};
constexpr std::array<std::string_view, 2> kExrPixels{"half", "float"};

// mpr-render's defaults are those of Job (job.hpp); the save command writes the options in
// this order.
constexpr std::array kOptions = {
    // Animation (one frame, the one on screen, in the save command).
    Option{.name = "frames",
           .value = "N",
           .help = "Render an animation of N frames (numbered PNGs; an MP4 too when ffmpeg is on PATH). mpr-view: the "
                   "frames ',' and '.' step through.",
           .example = "--frames 24 --tilt-x 0:30",
           .kind = integer,
           .group = anim,
           .lo = 1,
           .hi = 100000},
    Option{.name = "morph-to",
           .value = "VIEW",
           .help = "Animation: morph from the view to this VIEW by interpolating corner directions.",
           .example = "--view A --morph-to G --frames 24",
           .group = anim,
           .save =
               [](const SaveContext& c) {
                 return c.job.morph_to && c.job.morph.at(c.time) != 0 ? Saved(*c.job.morph_to) : kOmit;
               }},
    Option{.name = "morph",
           .value = "A:B|T=V,...",
           .help = "Morph weight over the animation.",
           .default_text = "0:1",
           .example = "--view A --morph-to G --morph 0=0,0.5=1,1=0 --frames 24",
           .kind = track,
           .group = anim,
           .save =
               [](const SaveContext& c) {
                 return c.job.morph_to && c.job.morph.at(c.time) != 0 ? Saved(num(c.job.morph.at(c.time))) : kOmit;
               }},
    Option{.name = "fps",
           .value = "F",
           .help = "Animation: frame rate of the MP4 in frames per second.",
           .default_text = "12",
           .example = "--tilt-x 0:30 --frames 3 --fps 24",
           .kind = number,
           .group = anim,
           .lo = 0,
           .hi = 1000,
           .lo_open = true,
           .bound_text = "must lie in (0, 1000] frames per second"},
    Option{.name = "shard",
           .value = "K/N",
           .help = "Render only the frames f (counted from 0) with f % N == K of an animation; they keep their global "
                   "numbers, so N processes (a Slurm job array: --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT) "
                   "write the frames of one run between them. No MP4 and no stale-frame removal (no shard sees every "
                   "frame).",
           .example = "--tilt-y -20:20 --frames 6 --shard 0/3 --no-video",
           .group = anim,
           .in_view_help = false},
    Option{.name = "no-video",
           .help = "Do not write an MP4 even when ffmpeg is available.",
           .example = "--tilt-y -20:20 --frames 24 --no-video",
           .kind = flag,
           .group = anim,
           .in_view_help = false},

    // Output and run.
    Option{
        .name = "threads",
        .value = "N",
        .help = "Worker threads, 0 = all. Images are identical for any N.",
        .default_text = "0",
        .example = "--threads 2",
        .kind = integer,
        .group = run,
        .lo = 0,
        .hi = 1024,
        .save = [](const SaveContext& c) { return c.job.threads != 0 ? Saved(std::to_string(c.job.threads)) : kOmit; }},
    Option{.name = "double",
           .help = "Render in double precision.",
           .default_text = "float",
           .example = "--double",
           .kind = flag,
           .group = run,
           .save = [](const SaveContext& c) { return c.job.use_double ? Saved("") : kOmit; }},
    Option{.name = "no-budget",
           .help = "Lift the documented limits that refuse a job before it starts (an image over 2^28 pixels, over "
                   "2^34 rays in all, a --raster array over 1 GiB or 30 minutes): for a machine that can afford it.",
           .example = "--size 320x240 --spp 64 --no-budget",
           .kind = flag,
           .group = run,
           .save = [](const SaveContext& c) { return c.job.no_budget ? Saved("") : kOmit; }},
    Option{.name = "bit-depth",
           .value = "8|16",
           .help = "Bits per channel of a .png output: 16 writes 16-bit sRGB-encoded PNG (libpng).",
           .default_text = "8",
           .example = "--bit-depth 16 --output view16.png",
           .kind = choice,
           .group = run,
           .choices = kBitDepths,
           .in_view_help = false},
    Option{.name = "exr-pixel",
           .value = "half|float",
           .help = "Sample type of an .exr output: half (16-bit floats) or float (the render's 32-bit values "
                   "exactly).",
           .default_text = "half",
           .example = "--exr-pixel float --output linear.exr",
           .kind = choice,
           .group = run,
           .choices = kExrPixels,
           .in_view_help = false},
    Option{.name = "output",
           .value = "FILE.png|FILE.jpg|FILE.pfm|FILE.exr",
           .help = "Output image by the extension: .png (8-bit sRGB; 16-bit with --bit-depth 16), .jpg or .jpeg "
                   "(JPEG, quality 95), or the linear render as floats: .pfm (RGB PFM, 32-bit) or .exr (OpenEXR, half "
                   "floats; --exr-pixel float). With --frames N: FILE_0001.png ... FILE_NNNN.png (stale frames "
                   "FILE_NNNN.png beyond N of an earlier run are removed; the MP4 only from .png or .jpg frames). "
                   "mpr-view: the base name of the PNGs that S saves (default mpr-view.png).",
           .default_text = "mpr-render.png",
           .example = "--output out/cross.png",
           .group = run,
           .save = [](const SaveContext& c) { return Saved(c.output.string()); }},
    Option{.name = "help",
           .help = "Print this help and exit.",
           .example = "mpr-render --help",
           .kind = flag,
           .group = run,
           .in_view_help = false},

    // mpr-view only.
    Option{.name = "script",
           .value = "FILE",
           .help = "Drive the window from a script of timed events (wait MS, key NAME, drag X0,Y0 X1,Y1 [BUTTON], "
                   "wheel N, click X,Y, screenshot PATH) and exit when it ends; errors are reported before the window "
                   "opens.",
           .example = "--script tests/view.txt",
           .group = viewer,
           .tools = Tools::view},
    Option{.name = "benchmark",
           .help = "Open no window: render the view repeatedly through the viewer's render thread and print "
                   "frames/s and the time from an input event to the first quarter-resolution frame.",
           .example = "--benchmark --size 960x540 --threads 2",
           .kind = flag,
           .group = viewer,
           .tools = Tools::view},
    Option{.name = "benchmark-frames",
           .value = "N",
           .help = "With --benchmark: frames per benchmark measurement.",
           .default_text = "30",
           .example = "--benchmark --benchmark-frames 10",
           .kind = integer,
           .group = viewer,
           .tools = Tools::view,
           .lo = 1,
           .hi = 10000},
};

} // namespace

std::span<const Option> run_options() noexcept { return kOptions; }

} // namespace mpr_cli::table
