#!/usr/bin/env python3
"""Mutation run: does the test suite fail when the library is deliberately broken?

Each mutation below is a small source edit (exact text -> replacement, in one or more files).
For each, the script copies the working tree once into build/mutation/src (build/ and .git
left out), applies the edit there, rebuilds only the listed targets in build/mutation/src/build/test
(ccache makes the unchanged translation units cheap) and runs the listed ctest entries, one
test program at a time in the listed order, stopping at the first that fails (--all: run them
all); then restores the file. It prints a table: mutation -> caught by (the failing tests) /
MISSED (every listed test passed).

Focused first pass (unless --no-focus): each mutation is first tested with its test programs built
from only the test files that include an edited file directly or mirror it, or else those of the
headers that include it directly (CMake's MPR_TEST_FILES); a mutation those catch is caught by the suite, which holds them, and the table
names the files. Where they miss it (or there are none), the whole programs are built and run.
This makes a mutation of a widely included header cost minutes instead of a rebuild of every
test file.

A mutation whose text is not found, or that does not compile, is reported as such and counts
as a failure of the run (the list has rotted: fix the pattern). The unmutated copy is built and
tested first; the run stops if it does not pass.

Not part of CI (it rebuilds test programs once per mutation: about 1 to 3 minutes each on two
cores). Usage, from the repository root:

    python3 tests/mutation/run_mutations.py              # every mutation
    python3 tests/mutation/run_mutations.py --list       # names only
    python3 tests/mutation/run_mutations.py --only NAME [NAME ...] [--jobs 2]
    python3 tests/mutation/run_mutations.py --tests lightfield   # only that test program
    python3 tests/mutation/run_mutations.py --levels --only NAME  # at every SIMD level

--levels runs each mutation's tests once per SIMD level the CPU has (MPR_SIMD=portable, avx2,
avx512, avx512vbmi; core/simd.hpp), rebuilding once, and the table has a column per level saying
which test caught the mutation there: a mutation counts as caught only when every level catches
it. A mutation of code that exists only at some levels (an AVX-512 kernel; `levels=` or
LEVELS_OF_FILE) is run at those only, the others marked "not its code's level".

Exit status 0 when every mutation was caught. Python 3.8+, no packages beyond the standard
library; needs cmake, ctest and a compiler (ccache used when installed).
"""

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
WORK = ROOT / "build" / "mutation"
SRC = WORK / "src"
# The scratch build sits at the same place relative to the scratch sources as build/test does to
# the tree, so that ccache (with base_dir at or above the tree) reuses the tree's objects for
# every translation unit the mutation leaves unchanged.
BUILD = SRC / "build" / "test"

# Test program (CMake target) of each ctest entry used below.
TEST_TARGET = {
    "core": "mpr_test_core",
    "render": "mpr_test_render",
    "selector": "mpr_test_selector",
    "glc": "mpr_test_glc",
    "lightfield": "mpr_test_lightfield",
    "scene": "mpr_test_scene",
    "io": "mpr_test_io",
    "tools": "mpr_test_tools",
    "camera": "mpr_test_camera",
    "geometry": "mpr_test_geometry",
    "surface": "mpr_test_surface",
}
CLI_TESTS = ["mpr_render_help", "mpr_render_bad_option", "mpr_render_bad_option_message",
             "mpr_render_bad_value_fails", "mpr_render_impossible_camera", "mpr_render_missing_file",
             "mpr_render_print_camera"]


def M(name, area, edits, tests, why, levels=None, focus=None):
    """A mutation: `edits` is a list of (file, old, new) or (file, old, new, occurrence); without
    an occurrence every occurrence of `old` is replaced, with one only that (0-based) one.
    `levels`: the SIMD levels whose code the edit changes, where it is not every level (a kernel
    that exists only for AVX-512); with --levels the others are not run for it.
    `focus`: test files (under tests/) added to the focused pass, for code the suite tests through
    an umbrella header (which the pass cannot see) rather than through a direct include."""
    return {"name": name, "area": area, "edits": edits, "tests": tests, "why": why, "levels": levels,
            "focus": focus or []}


SA = "include/mpr/lightfield/synthetic_aperture.hpp"
CYL = "include/mpr/lightfield/cylinder_aperture.hpp"
KER = "include/mpr/lightfield/kernels/sampler_rows.hpp"
CYW = "include/mpr/lightfield/kernels/cylinder_weights.hpp"
CYH = "include/mpr/lightfield/kernels/cylinder_weights_hwy.inl"
DWL = "include/mpr/lightfield/kernels/depth_walk_hwy.inl"
DLN = "include/mpr/lightfield/kernels/depth_lane_ops_hwy.inl"
SA_LOOP = "for (const auto& c : table.cameras())"

MUTATIONS = [
    # --- the eight of issue 19, adapted to the restructured tree ---
    M("region_u_half_pixel_flipped", "core",
      [("include/mpr/core/region.hpp", "return (static_cast<T>(column - x) + T(0.5))",
        "return (static_cast<T>(column - x) - T(0.5))")],
      ["core", "lightfield", "tools"] + CLI_TESTS, "u of a pixel centre off by one pixel"),
    M("glc_u_v_swapped", "selector",
      [("include/mpr/selector/glc_selector.hpp", "const T u = uv.x(), v = uv.y();",
        "const T u = uv.y(), v = uv.x();")],
      ["core", "selector", "glc"], "GLC ray field transposed"),
    M("cylinder_falloff_quadratic_everywhere", "lightfield",
      [(CYL, "static_cast<float>(T(1) - d / r)", "static_cast<float>(T(1) - (d / r) * (d / r))"),
       (CYL, "static_cast<float>(T(1) - std::sqrt(d2) / r)", "static_cast<float>(T(1) - d2 / (r * r))"),
       (CYW, "std::max(T(1) - std::sqrt(d2) * inv_radius, T(0))",
        "std::max(T(1) - d2 * inv_radius * inv_radius, T(0))"),
       (CYH, "hn::NegMulAdd(hn::Sqrt(d2), vinv, one)", "hn::NegMulAdd(hn::Mul(d2, vinv), vinv, one)")],
      ["lightfield", "tools"], "1 - (d/r)^2 instead of 1 - d/r in every path"),
    M("par_t_one_field_early", "io",
      [("include/mpr/io/par_file.hpp", "parse_number(par_file, line, 19 + k)", "parse_number(par_file, line, 18 + k)")],
      ["io", "tools"], "translation read from the wrong columns"),
    M("srgb_thresholds_one_step_low", "core",
      [("include/mpr/core/color.hpp", "      threshold[k] = f;", "      threshold[k] = std::nextafter(f, 0.0f);")],
      ["core"], "8-bit encoding boundaries one float too low"),
    M("sa_tile_drops_last_camera", "lightfield",
      [(SA, SA_LOOP + " {", SA_LOOP + " {\n      if (&c == &table.cameras().back()) continue;")],
      ["lightfield", "tools"], "tile path of the synthetic aperture forgets the last camera"),
    M("sa_drops_last_camera_every_path", "lightfield",
      [(SA, SA_LOOP, SA_LOOP + " if (&c != &table.cameras().back())")],
      ["lightfield", "tools"], "per-ray, batch and tile paths all forget the last camera"),
    M("sa_drops_middle_camera_every_path", "lightfield",
      [(SA, SA_LOOP,
        SA_LOOP + " if (table.size() < 2 || &c != &table.cameras()[table.size() / 2])")],
      ["lightfield", "tools"], "every path forgets the middle camera (invisible with symmetric fixtures)"),
    M("cylinder_group_keeps_stale_weights", "lightfield",
      [(CYL, "std::fill(ray_weight + span_lo, ray_weight + s.lo[q], 0.0f);", "")],
      ["lightfield"], "a camera's span in a row group keeps another camera's weights left of the row's own rays"),
    M("grid_row_points_half_step", "lightfield",
      [("include/mpr/lightfield/plane_rows.hpp", "row.point_step = (table.point_of(last) - row.point) * inv;",
        "row.point_step = (table.point_of(last) - row.point) * (inv * T(0.5));")],
      ["lightfield"], "a grid row's points step half as far as its exact end rays say"),
    M("run_edges_skip_seen_pixels", "lightfield",
      [("include/mpr/lightfield/frame_runs.hpp", "const T lo = T(-0.51), hi = static_cast<T>(c.width) - T(0.49);",
        "const T lo = T(-0.3), hi = static_cast<T>(c.width) - T(0.7);")],
      ["lightfield"], "a run's edge pixels that the camera still sees (its outer 0.2 pixel) are skipped"),
    M("simd_limit_ignored", "core",
      [("include/mpr/core/simd.hpp", "return asked && *asked < best ? *asked : best;", "return best;")],
      ["core"], "MPR_SIMD no longer lowers the level: every run takes the widest kernels"),
    M("renderer_grid_v_step_of_u", "render",
      [("include/mpr/render/renderer.hpp", "Vec3<T>(sv * field.origin.dv),", "Vec3<T>(su * field.origin.dv),")],
      ["render", "lightfield"], "the renderer's RayGrid steps its rows by the column spacing"),
    M("srgb_split_one_step_late", "core",
      [("include/mpr/core/color.hpp", "static_cast<std::uint32_t>(code) | (split << 8)",
        "static_cast<std::uint32_t>(code) | ((split + 1) << 8)")],
      ["core"], "the one-gather sRGB encoder's in-bin threshold one 2^-23 step late",
      levels=["avx2", "avx512", "avx512vbmi"]),
    M("srgb_avx2_compares_one_late", "core",
      [("include/mpr/core/kernels/srgb_encode.hpp", "_mm256_cmpgt_epi32(_mm256_srli_epi32(entry, 8), at)",
        "_mm256_cmpgt_epi32(_mm256_srli_epi32(entry, 8), _mm256_add_epi32(at, one))")],
      ["core"], "the AVX2 sRGB step rounds up one 2^-23 step early within a bin",
      levels=["avx2"]),
    M("srgb_poly_band_narrow", "core",
      [("include/mpr/core/kernels/srgb_encode.hpp", "_mm512_set1_ps(0.5f - 0x1p-10f)",
        "_mm512_set1_ps(0.5f - 0x1p-16f)")],
      ["core"], "the AVX-512 sRGB step trusts its polynomial within 2^-16 of k + 1/2, inside its error",
      levels=["avx512", "avx512vbmi"]),
    M("shift_tile_blend_weights_swapped", "lightfield",
      [("include/mpr/lightfield/kernels/decode_vbmi.hpp",
        "const __m512 v0 = _mm512_set1_ps(wy0), v1 = _mm512_set1_ps(wy1);",
        "const __m512 v0 = _mm512_set1_ps(wy1), v1 = _mm512_set1_ps(wy0);")],
      ["lightfield"], "the fused row pass of the 2-D shift-and-add blends its two rows with each other's weight"),
    M("tile_weight_steps_one_short", "lightfield",
      [("include/mpr/lightfield/frame_tiles.hpp",
        "weight_steps[static_cast<std::size_t>(r) * (n + 1) + static_cast<std::size_t>(b.last)] -= 1.0f;\n  }",
        "weight_steps[static_cast<std::size_t>(r) * (n + 1) + static_cast<std::size_t>(b.last) - 1] -= 1.0f;\n  }")],
      ["lightfield"], "a tile's per-pixel weights stop one pixel before the last pixel it adds"),
    M("resample_tile_rows_swapped", "lightfield",
      [("include/mpr/lightfield/kernels/resample_tile.hpp",
        "const __m512 w0 = _mm512_set1_ps((1 - ay) * scale), w1 = _mm512_set1_ps(ay * scale);",
        "const __m512 w1 = _mm512_set1_ps((1 - ay) * scale), w0 = _mm512_set1_ps(ay * scale);")],
      ["lightfield"], "the resampled block weighs each output row's upper camera row with the lower one's fraction",
      levels=["avx512vbmi"]),
    M("shift_tile_add_reads_next_block", "lightfield",
      [("include/mpr/lightfield/kernels/decode_vbmi.hpp",
        "__m512 sum = _mm512_fmadd_ps(w0, cur[k], _mm512_maskz_loadu_ps(keep, acc + at));",
        "__m512 sum = _mm512_fmadd_ps(w0, cur[(k + 1) % 4], _mm512_maskz_loadu_ps(keep, acc + at));")],
      ["lightfield"], "a row added at a vertical offset of 0 takes its texels 16 channels too far right"),
    M("tile_snap_keeps_texel", "lightfield",
      [("include/mpr/lightfield/accumulation/affine_block.hpp", "  if (a > 1 - kSnap) ++i;", "  if (a > 1 - kSnap) i += 0;")],
      ["lightfield"], "an offset just below a texel is snapped to 0 without moving to that texel (the tile's "
      "2-D shift and the row path share the snap)"),
    M("texel_snap_ignores_rounding", "lightfield",
      [("include/mpr/lightfield/accumulation/affine_block.hpp",
        "return std::max(T(1e-4), 4 * std::numeric_limits<T>::epsilon() * std::abs(x));", "return T(1e-4);")],
      ["lightfield"], "a float coordinate a few units in the last place off a texel is not taken as on it",
      focus=["lightfield/accumulation/affine_block_test.cpp"]),
    M("finish_all_background_ignored", "lightfield",
      [("include/mpr/lightfield/frame_table.hpp", "if (!(weight[i] > 0)) out[i] = config_.background;",
        "if (!(weight[i] > 0)) (void)out;")],
      ["lightfield"], "the batch and tile averages leave points nobody sees black instead of the background",
      focus=["lightfield/frame_sampler_test.cpp"]),
    M("tile_reads_pairs_past_the_edge", "lightfield",
      [("include/mpr/lightfield/frame_tiles.hpp", "right = ax == 0 && ay == 0 ? 0 : 1;", "right = 0;")],
      ["lightfield"], "a 2-D shift takes the image's last column into the block where it interpolates past it"),
    M("magnified_plan_period_drifts", "lightfield",
      [("include/mpr/lightfield/kernels/magnified_plan.hpp", "advance = 3 * static_cast<std::size_t>(p) * (pixels / q);",
        "advance = 3 * static_cast<std::size_t>(p) * (pixels / q) + 3;")],
      ["lightfield"], "a magnified row's next period starts one texel too far on",
      focus=["lightfield/accumulation/magnified_tile_test.cpp"]),
    M("magnified_blend_weights_swapped", "lightfield",
      [("include/mpr/lightfield/kernels/resample_row_hwy.inl", "const auto a0 = hn::Set(df, w0), a1 = hn::Set(df, w1);",
        "const auto a0 = hn::Set(df, w1), a1 = hn::Set(df, w0);")],
      ["lightfield"], "a magnified block blends a new bottom row into its output row with the top row's weight",
      focus=["lightfield/accumulation/magnified_tile_test.cpp"]),
    M("resample_groups_serve_other_positions", "lightfield",
      [("include/mpr/lightfield/kernels/resample_tile.hpp", "!groups.empty() && std::abs(x1 - x) <= 1e-4 &&",
        "!groups.empty() &&")],
      ["lightfield"], "a resampled run reuses the kept groups of a row at other positions",
      levels=["avx512vbmi"]),
    M("cylinder_span_drops_last_weight", "lightfield",
      [("include/mpr/lightfield/kernels/cylinder_weights.hpp",
        "last = i + static_cast<std::size_t>(32 - __builtin_clz(positive));",
        "last = i + static_cast<std::size_t>(31 - __builtin_clz(positive));")],
      ["lightfield"], "the SIMD weights kernels end the cylinder's span before its last positive weight"),
    M("weighted_row_spreads_one_phase", "lightfield",
      [("include/mpr/lightfield/kernels/decode_vbmi.hpp", "spread[at % 3]", "spread[0]")],
      ["lightfield"], "the one-pass weighted row gives 16 channels the weights of the wrong pixels"),
    M("shift_batch_rows_from_tile_start", "lightfield",
      [("include/mpr/lightfield/kernels/shift_batch.hpp",
        "b.texels + static_cast<std::ptrdiff_t>(r - b.r_begin) * b.stride;",
        "b.texels + static_cast<std::ptrdiff_t>(r) * b.stride;")],
      ["lightfield"], "a block starting below the tile's first row reads its camera rows from the wrong one"),
    M("shift_batch_sum_drops_a_camera", "lightfield",
      [("include/mpr/lightfield/kernels/shift_batch.hpp",
        "for (std::size_t c = c0; c < std::min(k, c0 + kShiftSumCameras); ++c) {",
        "for (std::size_t c = c0; c + 1 < std::min(k, c0 + kShiftSumCameras); ++c) {")],
      ["lightfield"], "the register sum of the cameras' whole-pixel shifts leaves out the last camera of each pass",
      levels=["avx512vbmi"]),
    M("weight_steps_scan_half_vector", "lightfield",
      [("include/mpr/lightfield/kernels/running_sums.hpp", "plus_shifted<8>(plus_shifted<4>(", "(plus_shifted<4>(")],
      ["lightfield"], "the vectorised running count of a tile's weights sums only within each half vector",
      levels=["avx512", "avx512vbmi"]),
    M("border_row_reads_second_row", "lightfield",
      [("include/mpr/lightfield/frame_runs.hpp", "const int row_a = std::clamp(iy, 0, c.height - 1)",
        "const int row_a = std::clamp(iy, 1, c.height - 1)")],
      ["lightfield"], "a run in the top half-pixel border blends the second row into the clamped first"),
    # --- more, across the library ---
    M("nearest_tie_to_highest_index", "lightfield",
      [("include/mpr/lightfield/camera_index.hpp", "(d2 == best && i < best_index)", "(d2 == best && i > best_index)")],
      ["lightfield"], "documented tie rule (lowest index) broken"),
    M("sa_background_ignored", "lightfield",
      [("include/mpr/lightfield/frame_table.hpp", "if (!(weight > 0)) return config_.background;",
        "if (!(weight > 0)) return Color::Zero();")],
      ["lightfield"], "points nobody sees are black instead of the configured background",
      focus=["lightfield/frame_sampler_test.cpp"]),
    M("glc_type_names_swapped", "glc",
      [("include/mpr/glc/classify.hpp", 'return "pencil";', 'return "pushbroom";')],
      ["glc"], "to_string of one GLC type wrong"),
    M("scene_barycentric_weights_swapped", "scene",
      [("include/mpr/scene/scene.hpp",
        "const float w1 = static_cast<float>(b1), w2 = static_cast<float>(b2), w0 = 1.0f - w1 - w2;",
        "const float w2 = static_cast<float>(b1), w1 = static_cast<float>(b2), w0 = 1.0f - w1 - w2;")],
      ["scene"], "vertex colours/uv of p[1] and p[2] exchanged"),
    M("texture_v_not_flipped", "scene",
      [("include/mpr/scene/texture.hpp", "image_.height() - 1 - index(v, height_, image_.height())",
        "index(v, height_, image_.height())")],
      ["scene"], "texture rows read upside down"),
    M("ssim_constant_c2_wrong", "core",
      [("include/mpr/core/image_metrics.hpp", "c2 = (0.03 * 255) * (0.03 * 255)", "c2 = (0.3 * 255) * (0.3 * 255)")],
      ["core"], "SSIM stabilising constant K2 = 0.3 instead of 0.03"),
    M("bvh_keeps_farther_hit", "scene",
      [("include/mpr/scene/bvh/watertight.hpp", "triangle < hit.triangle))) return;\n  hit.t = t;",
        "triangle < hit.triangle))) return;\n  if (hit.valid()) return;\n  hit.t = t;")],
      ["scene"], "the first triangle found is kept, not the nearest"),
    M("cli_size_width_height_swapped", "tools",
      [("tools/mpr-render/cli_args.hpp",
        "return {parse_int(parts[0], option, 1, 16384), parse_int(parts[1], option, 1, 16384)};",
        "return {parse_int(parts[1], option, 1, 16384), parse_int(parts[0], option, 1, 16384)};")],
      ["tools"] + CLI_TESTS, "--size WxH read as HxW"),
    M("renderer_tile_u_one_column_late", "render",
      [("include/mpr/render/renderer.hpp",
        "u_of_column[static_cast<std::size_t>(x - x_begin)] = region.column_to_u<scalar_type>(x);",
        "u_of_column[static_cast<std::size_t>(x - x_begin)] = region.column_to_u<scalar_type>(x + 1);")],
      ["render", "lightfield"], "the tile path shifts every ray by one column"),
    M("bilinear_convergence_sign", "glc",
      [("include/mpr/glc/cameras.hpp", "K << convergence, -twist, twist, convergence;",
        "K << -convergence, -twist, twist, -convergence;")],
      ["glc"], "bilinear camera spreads the other way (still classified bilinear)"),
    M("twisted_orthographic_axes_swapped", "glc",
      [("include/mpr/glc/cameras.hpp", "K = twist * w * w_perp.transpose();", "K = twist * w_perp * w.transpose();")],
      ["glc"], "twisted orthographic rays turn about the wrong axis (still classified twisted orthographic)"),
    M("tool_reference_camera_first", "tools",
      [("tools/mpr-render/loading.hpp", ": l.frames->size() / 2);", ": 0);")],
      ["tools"], "mpr-render views a _par.txt light field from the first camera, not the middle one"),
    # --- DepthProxy's sixteen-lane batch path (issue 12) ---
    M("depth_lanes_refine_coarser", "lightfield",
      [(DWL, "set(1.0f / 256)", "set(1.0f / 128)")],
      ["lightfield"], "the lanes narrow the crossing to 1/128 of a step, the per-ray walk to 1/256"),
    M("depth_lanes_visibility_search_tolerance", "lightfield",
      [("include/mpr/lightfield/depth_proxy/depth_proxy_lanes.hpp", "slots,\n                            static_cast<T>(p.visibility_tolerance),",
        "slots,\n                            static_cast<T>(p.tolerance),")],
      ["lightfield"], "the batch path tests visibility with the surface search's tolerance, not the blend's"),
    M("depth_proxy_box_exit_ignored", "lightfield",
      [("include/mpr/lightfield/depth_proxy.hpp", "w == detail::DepthWalk::escaped || search.t >= stretch[1]",
        "w == detail::DepthWalk::escaped")],
      ["lightfield"], "a ray the walks see free through the box of the maps' points takes the focal point, not the background"),
    M("depth_lanes_box_exit_ignored", "lightfield",
      [("include/mpr/lightfield/depth_proxy/depth_proxy_lanes.hpp", "((w.passed >> l & 1u) != 0 && w.t[l] >= leave[l])",
        "false")],
      ["lightfield"], "the batch path forgets where a ray leaves the box of the maps' points"),
    M("depth_bounds_without_margin", "lightfield",
      [("include/mpr/lightfield/frame_set.hpp", "const double margin = 2 * far /", "const double margin = 0 * far /")],
      ["lightfield"], "the box of the maps' points is not widened for points between pixel centres"),
    M("affine_sight_ignores_perspective", "lightfield",
      [("include/mpr/lightfield/accumulation/affine_block.hpp",
        "if (!(perspective + off <= tolerance)) return false;", "if (!(off <= tolerance)) return false;")],
      ["lightfield"], "a camera that sees a block at varying depth is taken as seeing it at one"),
    M("affine_sight_ignores_row_deviation", "lightfield",
      [("include/mpr/lightfield/accumulation/affine_block.hpp",
        "if (!(perspective + off <= tolerance)) return false;", "if (!(perspective <= tolerance)) return false;")],
      ["lightfield"], "rows off the grid by what affine_grid lets through are placed as if on it"),
    M("affine_grid_rows_unchecked", "lightfield",
      [("include/mpr/lightfield/accumulation/affine_block.hpp",
        "if (!(off <= tolerance)) return false;", "(void)tolerance;")],
      ["lightfield"], "rows are taken as one grid from three end points without checking the others"),
    M("cylinder_sight_next_row", "lightfield",
      [(CYL, "const double dq = static_cast<double>(q),", "const double dq = static_cast<double>(q + 1),")],
      ["lightfield"], "the cylinder's runs are placed one output row off in each camera",
      focus=["lightfield/frame_sampler_test.cpp"]),
    M("cylinder_rows_outer_last_row_skipped", "lightfield",
      [(CYL, "for (std::size_t q = 0; q < nrows; ++q)\n        for (std::size_t j = 0; j < ncam; ++j) {",
        "for (std::size_t q = 0; q + 1 < nrows; ++q)\n        for (std::size_t j = 0; j < ncam; ++j) {")],
      ["lightfield"], "rows outer, the cylinder adds no camera to a group's last row",
      focus=["lightfield/frame_sampler_test.cpp"]),
    M("cylinder_weigh_last_segment_dropped", "lightfield",
      [(CYL, "last = std::min(w, g1 * kSegment);", "last = std::min(w, (g1 - 1) * kSegment);")],
      ["lightfield"], "the cylinder weighs a camera on every segment within reach but the last",
      focus=["lightfield/frame_sampler_test.cpp"]),
    M("weighted_codes_weights_one_channel_off", "lightfield",
      [("include/mpr/lightfield/kernels/decode_vbmi.hpp", "s.index[o][l] = (16 * o + l) / 3;",
        "s.index[o][l] = (16 * o + l + 1) / 3 % 16;")],
      ["lightfield"], "the one-pass weighted row spreads each pixel's weight one channel early"),
    M("projective_tile_box_ignores_ray_weights", "lightfield",
      [("include/mpr/lightfield/kernels/projective_tile.hpp",
        "_mm512_maskz_mul_ps(p.m, p.wt, _mm512_set1_ps(scale))", "_mm512_maskz_mov_ps(p.m, _mm512_set1_ps(scale))")],
      ["lightfield"], "the projective tile's box step adds every seen point at weight 1, whatever its ray weight",
      levels=["avx512vbmi"]),
    M("projective_tile_rows_from_first_output", "lightfield",
      [("include/mpr/lightfield/kernels/projective_tile.hpp", "      float* acc_row = out[r].acc;",
        "      float* acc_row = out[0].acc + 3 * n * r;")],
      ["lightfield"], "the projective tile places row r's sums after row 0's instead of at its own outputs",
      levels=["avx512vbmi"]),
    M("projective_linear_blue_word_late", "lightfield",
      [("include/mpr/lightfield/kernels/projective_row_hwy.inl", "hn::Add(at, hn::Set(di, 4))",
        "hn::Add(at, hn::Set(di, 6))")],
      ["lightfield"], "the Highway projective row reads blue from its 16-bit linear copy one texel late"),
    M("shift_add_linear_row_one_texel_late", "lightfield",
      [("include/mpr/lightfield/frame_runs.hpp", "cam->linear + (code - cam->texels->c)",
        "cam->linear + (code - cam->texels->c) + 3")],
      ["lightfield"], "the separable shift-and-add reads each camera row's 16-bit linear copy one texel late",
      levels=["portable", "avx2"]),
    M("cylinder_tile_last_row_dropped", "lightfield",
      [("include/mpr/lightfield/cylinder_aperture.hpp",
        "std::span<const Vec3<T>* const>(points, rows),\n                               std::span<const detail::TileRowOut>(out, rows)",
        "std::span<const Vec3<T>* const>(points, rows - 1),\n                               std::span<const detail::TileRowOut>(out, rows - 1)")],
      ["lightfield"], "a camera added to a tilted group's rows at once skips the last row it weighs",
      focus=["lightfield/frame_sampler_test.cpp"]),
    M("shared_weights_linear_drops_a_camera", "lightfield",
      [("include/mpr/lightfield/accumulation/shared_weights_batch.hpp",
        "kernels::sum_linear_rows_hwy(batch.rows16.data(), k, scale",
        "kernels::sum_linear_rows_hwy(batch.rows16.data(), k - 1, scale")],
      ["lightfield"], "a magnified whole-pixel plane sums the 16-bit linear values of every camera but the last",
      levels=["portable", "avx2", "avx512"]),
    M("linear_rows_fourth_vector_reread", "lightfield",
      [("include/mpr/lightfield/kernels/linear_rows_hwy.inl",
        "s3 = hn::Add(s3, hn::PromoteTo(du, hn::LoadU(d16, p + 3 * lanes)));",
        "s3 = hn::Add(s3, hn::PromoteTo(du, hn::LoadU(d16, p + 2 * lanes)));")],
      ["lightfield"], "the 16-bit row sum adds the third vector of each step where the fourth belongs"),
    M("sweep_code_weights_sum_uncorrected", "lightfield",
      [("include/mpr/lightfield/kernels/sweep_code_kernels.hpp", "w[static_cast<std::size_t>(largest)] += 128 - sum;",
        "w[static_cast<std::size_t>(largest)] += 0 * (128 - sum);")],
      ["lightfield"], "the 16-bit sweep's rounded bilinear weights are not corrected to sum to 128"),
    M("sweep_code_cost_coarser", "lightfield",
      [("include/mpr/lightfield/kernels/sweep_code_kernels.hpp", "    s += (d < 0 ? -d : d) >> 2;",
        "    s += (d < 0 ? -d : d) >> 3;")],
      ["lightfield"], "the 16-bit sweep's vector body counts a channel's difference in 1/16 code, not 1/32"),
    M("sweep_code_whole_tap_unsplit", "lightfield",
      [("include/mpr/lightfield/kernels/sweep_code_kernels.hpp", "if (w[static_cast<std::size_t>(i)] < 128) continue;",
        "if (w[static_cast<std::size_t>(i)] < 129) continue;")],
      ["lightfield"], "a whole-pixel shift keeps its weight of 128, which the byte multiply-add reads as -128"),
    M("sweep_code_pairs_bottom_row_top_weights", "lightfield",
      [("include/mpr/lightfield/kernels/sweep_code_pairs.hpp", "_mm512_maddubs_epi16(_mm512_loadu_si512(bottom), wb)",
        "_mm512_maddubs_epi16(_mm512_loadu_si512(bottom), wt)")],
      ["lightfield"], "the AVX-512 pair-word blend weighs the bottom row with the top row's weights",
      levels=["avx512", "avx512vbmi"]),
    M("sweep_code_plain_right_tap_low_byte", "lightfield",
      [("include/mpr/lightfield/kernels/sweep_code_kernels.hpp", "(a >> 8) * k.w[1]", "(a & lo) * k.w[1]")],
      ["lightfield"], "the plain pair-word blend takes the pixel's own code for its right tap",
      levels=["portable"]),
    M("sweep_code_peel_lands_wrong", "lightfield",
      [("include/mpr/lightfield/kernels/sweep_code_kernels.hpp", "    sel[j] = v;\n", "    sel[0] = v;\n")],
      ["lightfield"], "the first neighbours of the 16-bit sweep's selection all land at its first place"),
    M("median_avx2_table_bits_swapped", "lightfield",
      [("include/mpr/lightfield/kernels/depth_median_lanes.hpp", "_mm256_slli_epi32(k, 28)", "_mm256_slli_epi32(k, 27)")],
      ["lightfield"], "the AVX2 median reads the colour tables' quarters by bit 4 twice instead of bits 3 and 4",
      levels=["avx2"]),
    M("median_lanes_half_weight_high", "lightfield",
      [("include/mpr/lightfield/kernels/depth_median_lanes.hpp", "const V half = total * 0.5f;",
        "const V half = total * 0.55f;")],
      ["lightfield"], "the lane median looks for 55% of the window's weight instead of half"),
    M("frame_set_images_overlap", "lightfield",
      [("include/mpr/lightfield/frame_set.hpp", "      offsets[i] = total;", "      offsets[i] = 0;")],
      ["lightfield"], "every image is decoded into the same place of the shared buffer"),
    M("frame_set_cast_decodes_again", "lightfield",
      [("include/mpr/lightfield/frame_set.hpp", "out.texels_ = texels_;\n    out.texel_data_ = texel_data_;",
        "out.texels_ = decode(images_, out.texel_data_);")],
      ["lightfield"], "a scalar cast decodes every image again instead of sharing the texels"),
    M("frame_prefilter_principal_point_unshifted", "lightfield",
      [("include/mpr/lightfield/frame_prefilter.hpp", "  A(0, 2) = shift;", "  A(0, 2) = T(0);")],
      ["lightfield"], "a downsampled camera keeps the principal point's scaling but not the half-block shift"),
    M("depth_weigh_lanes_threshold_always_largest", "lightfield",
      [("include/mpr/lightfield/kernels/depth_weigh_hwy.inl", "    if (k < slots) threshold", "    if (k < 0) threshold")],
      ["lightfield"], "the lanes take twice the largest penalty as the threshold even when k + 1 cameras see the point"),
    M("depth_lanes_agreement_looser", "lightfield",
      [(DWL, "set(tol * detail::kDepthAgreement)", "set(tol * detail::kDepthAgreement * 2)")],
      ["lightfield"], "the lanes stop narrowing where the depths agree within twice what the per-ray walk asks"),
    M("depth_lanes_pass_forgets_skip", "lightfield",
      [(DWL, "skip_end = hn::IfThenElse(record, end, hn::IfThenElse(used, inf, se));",
        "skip_end = hn::IfThenElse(used, inf, se);")],
      ["lightfield"], "a lane passed on records no end of the stretch it saw free"),
    M("depth_lanes_step_into_stretch", "lightfield",
      [(DWL, "hn::And(hn::Lt(s, search.skip_begin), hn::Gt(next, search.skip_begin))",
        "hn::And(hn::Lt(s, search.skip_begin), hn::Gt(search.skip_begin, search.skip_begin))")],
      ["lightfield"], "a lane's step runs into the stretch seen free instead of stopping at its start"),
    M("depth_lanes_bracket_start_value", "lightfield",
      [(DWL, "b.f0 = hn::IfThenElse(found, fs, b.f0);", "b.f0 = hn::IfThenElse(found, fn, b.f0);")],
      ["lightfield"], "a lane keeps f at the bracket's end as the value at its start"),
    M("depth_lanes_equal_cosines_by_index", "lightfield",
      [(DLN, "hn::And(hn::Eq(cs, s.cosine[j]), nearer)", "hn::And(hn::Eq(cs, s.cosine[j]), hn::Not(hn::Or(nearer, hn::Not(nearer))))")],
      ["lightfield"], "equal cosines kept in the order of the cameras, not of their distance"),
    M("virtual_array_depth_off_centre", "scene",
      [("include/mpr/scene/rasterized_sampler.hpp", "half = (n - 1) / 2;", "half = 0;")],
      ["scene"], "a supersampled frame's depth taken at a corner point, not the pixel centre"),
    M("virtual_array_subpixels_not_centred", "scene",
      [("include/mpr/scene/rasterized_sampler.hpp", "scale(0, 2) = scale(1, 2) = T(0.5) * static_cast<T>(n - 1);",
        "scale(0, 2) = scale(1, 2) = T(0);")],
      ["scene"], "a supersampled frame's points spread from the pixel centre instead of about it"),
]


# The SIMD levels (MPR_SIMD names, narrowest first) and the x86 CPU flags each needs on top of
# the one before it, as core/simd.hpp detects them.
SIMD_LEVELS = [("portable", []), ("avx2", ["avx2", "fma"]),
               ("avx512", ["avx512f", "avx512bw", "avx512vl", "avx512dq"]), ("avx512vbmi", ["avx512vbmi"])]


def cpu_simd_levels():
    """The levels this CPU runs (from /proc/cpuinfo's flags; portable only where it is absent)."""
    flags = set()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("flags"):
                flags = set(line.split(":", 1)[1].split())
                break
    except OSError:
        pass
    out = []
    for name, needs in SIMD_LEVELS:
        if not all(f in flags for f in needs):
            break
        out.append(name)
    return out

# Files whose code runs only at some SIMD levels: a mutation that edits only these is run (with
# --levels) at those levels, unless it names its own.
_AVX512_UP = ["avx512", "avx512vbmi"]
LEVELS_OF_FILE = {
    "include/mpr/lightfield/kernels/decode_vbmi.hpp": ["avx512vbmi"],
}
for _m in MUTATIONS:
    _files = {e[0] for e in _m["edits"]}
    if _m["levels"] is None and all(f in LEVELS_OF_FILE for f in _files):
        _m["levels"] = sorted({lv for f in _files for lv in LEVELS_OF_FILE[f]}, key=_AVX512_UP.index)


def run(cmd, cwd, log, timeout=None, env=None):
    with open(log, "a") as out:
        out.write("\n$ " + "".join(k + "=" + v + " " for k, v in (env or {}).items()) + " ".join(map(str, cmd)) + "\n")
        out.flush()
        try:
            return subprocess.run(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT, timeout=timeout,
                                  env=dict(os.environ, **env) if env else None).returncode
        except subprocess.TimeoutExpired:
            out.write("timed out\n")
            return 124


def _copy_if_changed(src, dst):
    """Leaves dst alone when it already holds src's bytes; else copies with a fresh time stamp, so
    that the build redoes what depends on it (a file restored after the last run's final
    mutation is newer than the objects built from the mutated text; copying the tree's older
    time stamp over it would leave those objects, and the mutation, in the baseline)."""
    try:
        if Path(dst).read_bytes() == Path(src).read_bytes():
            return dst
    except OSError:
        pass
    return shutil.copy(src, dst)


def copy_tree():
    """Copies the working tree (without .git and build/) over SRC, keeping SRC/build and the
    time stamps of unchanged files; files gone from the tree are removed."""
    ignore = shutil.ignore_patterns(".git", "build")
    if SRC.exists():
        for path in sorted(SRC.rglob("*"), reverse=True):
            rel = path.relative_to(SRC)
            if rel.parts[0] == "build":
                continue
            if not (ROOT / rel).exists() and not (ROOT / rel).is_symlink():
                if path.is_dir() and not path.is_symlink():
                    shutil.rmtree(path)
                else:
                    path.unlink()
    shutil.copytree(ROOT, SRC, ignore=ignore, symlinks=True, dirs_exist_ok=True, copy_function=_copy_if_changed)


def configure(log, test_files=""):
    """Configures the scratch build; `test_files`: the MPR_TEST_FILES regular expression (empty:
    every test file)."""
    env_launcher = ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"] if shutil.which("ccache") else []
    # The same spelling as the tree's default (a compile definition: part of ccache's hash).
    data = os.environ.get("MPR_DATA_DIR", str(ROOT) + "/../shared/data")
    return run(["cmake", "-S", SRC, "-B", BUILD, "-DCMAKE_BUILD_TYPE=Release", "-DMPR_DATA_DIR=" + data,
                "-DMPR_BUILD_EXAMPLES=OFF", "-DMPR_BUILD_BENCHMARKS=OFF", "-DMPR_INSTALL=OFF",
                "-DMPR_TEST_FILES=" + test_files] + env_launcher,
               ROOT, log)


def _tests_of(headers, areas):
    """Test files (paths under tests/) in `areas` that mirror one of `headers` (paths under
    include/) or include one directly."""
    out = set()
    for area in areas:
        for test in sorted((ROOT / "tests" / area).rglob("*_test.cpp")):
            rel = test.relative_to(ROOT / "tests").as_posix()
            text = test.read_text(errors="replace")
            for path in headers:
                header = path[len("include/"):] if path.startswith("include/") else path
                mirror = Path(header).with_suffix("").as_posix()[len("mpr/"):] + "_test.cpp"
                if rel == mirror or ("<" + header + ">") in text or ('"' + header + '"') in text:
                    out.add(rel)
    return out


def focus_files(mutation, most=8):
    """The test files (paths under tests/) of a mutation's focused pass: in the areas of its test
    programs, the mirror test of each edited file and every test file that includes one directly;
    where there are none, the same for the headers that include an edited file directly (at most
    `most` files, else none). A mutation these catch is caught by the suite, which holds them; one
    they miss runs the full programs."""
    areas = [t for t in mutation["tests"] if t in TEST_TARGET]
    edited = sorted({e[0] for e in mutation["edits"]})
    out = _tests_of(edited, areas) | set(mutation["focus"])
    if not out:
        names = ["<" + e[len("include/"):] + ">" for e in edited if e.startswith("include/")]
        includers = [h.relative_to(ROOT).as_posix() for h in sorted((ROOT / "include").rglob("*.hpp"))
                     if any(n in h.read_text(errors="replace") for n in names)]
        out = _tests_of(includers, areas)
        if len(out) > most:
            out = set()
    return sorted(out)


_configured = [None]  # the MPR_TEST_FILES of the scratch build's last configure


def filter_to(test_files, log):
    """Configures the scratch build for these test files (a regular expression; empty: all), when
    it is not already."""
    if _configured[0] != test_files:
        if configure(log, test_files) != 0:
            raise SystemExit("configure failed; see " + str(log))
        _configured[0] = test_files


def files_regex(files):
    return "(" + "|".join("/tests/" + f.replace(".", "\\.") for f in files) + ")$"


def targets_of(tests):
    out = []
    for t in tests:
        tgt = TEST_TARGET.get(t, "mpr-render" if t.startswith("mpr_render") else None)
        if tgt is None:
            raise SystemExit("no target known for test " + t)
        if tgt not in out:
            out.append(tgt)
        if t == "tools" and "mpr-render" not in out:
            out.append("mpr-render")
    return out


def groups_of(tests):
    """The tests in order, grouped by the target that builds them (one build per group)."""
    groups = []
    for t in tests:
        tgt = tuple(targets_of([t]))
        if groups and groups[-1][0] == tgt:
            groups[-1][1].append(t)
        else:
            groups.append((tgt, [t]))
    return groups


def build_and_test(tests, jobs, log, stop_at_first=True, level=None):
    """(build ok, failing tests). Builds and runs one group of tests at a time, in the listed
    order; with stop_at_first, stops at the first group with a failing test. With a level, the
    tests run with MPR_SIMD set to it."""
    failed = []
    for targets, group in groups_of(tests):
        if run(["cmake", "--build", BUILD, "-j", str(jobs), "--target"] + list(targets), ROOT, log) != 0:
            return False, failed
        regex = "^(" + "|".join(group) + ")$"
        fail_log = BUILD / "Testing" / "Temporary" / "LastTestsFailed.log"
        if fail_log.exists():
            fail_log.unlink()
        rc = run(["ctest", "--test-dir", BUILD, "-R", regex, "-j", str(jobs), "--timeout", "300"], ROOT, log,
                 env={"MPR_SIMD": level} if level else None)
        now = []
        if fail_log.exists():
            now = [line.split(":", 1)[1].strip() for line in fail_log.read_text().splitlines() if ":" in line]
        if rc != 0 and not now:
            now = ["ctest exit %d" % rc]
        failed += now
        if failed and stop_at_first:
            break
    return True, failed


def apply(mutation):
    """Applies the edits in SRC; returns {path: original text} or raises ValueError."""
    originals = {}
    for edit in mutation["edits"]:
        path, old, new = edit[0], edit[1], edit[2]
        occurrence = edit[3] if len(edit) > 3 else None
        p = SRC / path
        text = p.read_text()
        originals.setdefault(p, text)
        count = text.count(old)
        if count == 0:
            raise ValueError("pattern not found in " + path + ": " + old)
        if occurrence is None:
            text = text.replace(old, new)
        else:
            if occurrence >= count:
                raise ValueError("occurrence %d of %d in %s" % (occurrence, count, path))
            at = -1
            for _ in range(occurrence + 1):
                at = text.index(old, at + 1)
            text = text[:at] + new + text[at + len(old):]
        p.write_text(text)
    return originals


def restore(originals):
    for p, text in originals.items():
        p.write_text(text)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--only", nargs="*", help="names of the mutations to run")
    parser.add_argument("--list", action="store_true", help="list the mutations and exit")
    parser.add_argument("--jobs", type=int, default=1, help="parallel build and test jobs (default 1)")
    parser.add_argument("--all", action="store_true",
                        help="run every listed test of a mutation (default: stop at the first test program that fails)")
    parser.add_argument("--tests", nargs="*", help="run only these of each mutation's ctest entries")
    parser.add_argument("--no-focus", action="store_true",
                        help="no focused first pass: build and run each mutation's whole test programs")
    parser.add_argument("--no-baseline", action="store_true", help="skip the unmutated build and test")
    parser.add_argument("--levels", nargs="*", metavar="LEVEL",
                        help="run each mutation's tests at every SIMD level the CPU has (or at the LEVELs named: "
                        "portable avx2 avx512 avx512vbmi); the table shows which level caught it")
    args = parser.parse_args()
    by_name = {m["name"]: m for m in MUTATIONS}
    chosen = [by_name[n] for n in args.only if n in by_name] if args.only else list(MUTATIONS)  # --only: that order
    if args.tests:
        chosen = [dict(m, tests=[t for t in m["tests"] if t in args.tests]) for m in chosen]
        chosen = [m for m in chosen if m["tests"]]
    if args.list:
        for m in MUTATIONS:
            print("%-40s %-10s %s" % (m["name"], m["area"], m["why"]))
        return 0
    if args.only and len(chosen) != len(args.only):
        raise SystemExit("unknown mutation among " + " ".join(args.only))
    levels = [None]
    if args.levels is not None:
        levels = args.levels or cpu_simd_levels()
        unknown = [lv for lv in levels if lv not in [name for name, _ in SIMD_LEVELS]]
        if unknown:
            raise SystemExit("unknown SIMD level " + " ".join(unknown))
        print("SIMD levels:", " ".join(levels), flush=True)
    WORK.mkdir(parents=True, exist_ok=True)
    log = WORK / "log.txt"
    log.write_text("")
    print("copying the tree to", SRC, flush=True)
    copy_tree()
    filter_to("", log)
    if not args.no_baseline:
        all_tests = sorted({t for m in chosen for t in m["tests"]})
        print("baseline: building and testing the unmutated copy ...", flush=True)
        for level in levels:
            ok, failed = build_and_test(all_tests, args.jobs, log, stop_at_first=False, level=level)
            if not ok or failed:
                raise SystemExit("baseline does not pass%s (%s); see %s" % (
                    " at " + level if level else "", "build" if not ok else ", ".join(failed), log))
    rows = []
    for m in chosen:
        start = time.time()
        print("%-40s ..." % m["name"], end=" ", flush=True)
        try:
            originals = apply(m)
        except ValueError as e:
            rows.append((m, [("PATTERN NOT FOUND: %s" % e, False)] * len(levels), False, 0))
            print("pattern not found", flush=True)
            continue
        cells = []  # (text, caught) per level
        focus = [] if args.no_focus else focus_files(m)
        focus_tests = [t for t in m["tests"] if any(f.startswith(t + "/") for f in focus)]
        try:
            for level in levels:
                if level and m["levels"] and level not in m["levels"]:
                    cells.append(("not its code's level", True))
                    continue
                if focus_tests:
                    filter_to(files_regex(focus), log)
                    ok, failed = build_and_test(focus_tests, args.jobs, log, stop_at_first=True, level=level)
                    if ok and failed:
                        names = ", ".join(Path(f).name for f in focus)
                        cells.append(("caught by " + ", ".join(failed) + " (" + names + ")", True))
                        continue
                filter_to("", log)
                ok, failed = build_and_test(m["tests"], args.jobs, log, stop_at_first=not args.all, level=level)
                if not ok:
                    cells = [("DOES NOT COMPILE", False)] * len(levels)
                    break
                if failed:
                    cells.append(("caught by " + ", ".join(failed), True))
                else:
                    cells.append(("MISSED (ran " + ", ".join(m["tests"]) + ")", False))
        finally:
            restore(originals)
        seconds = time.time() - start
        rows.append((m, cells, all(c[1] for c in cells), seconds))
        print("; ".join((lv + ": " if lv else "") + c[0] for lv, c in zip(levels, cells)), "(%.0f s)" % seconds,
              flush=True)
    print()
    heads = ["result"] if levels == [None] else ["at " + lv for lv in levels]
    print("| mutation | area | " + " | ".join(heads) + " | s |")
    print("|---|---|" + "---|" * len(heads) + "---|")
    for m, cells, _, seconds in rows:
        print("| `%s` | %s | %s | %.0f |" % (m["name"], m["area"], " | ".join(c[0] for c in cells), seconds))
    caught = sum(1 for r in rows if r[2])
    print("\n%d of %d mutations caught%s (log: %s)" % (caught, len(rows), " at every level" if levels != [None] else "",
                                                      log.relative_to(ROOT)))
    return 0 if caught == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
