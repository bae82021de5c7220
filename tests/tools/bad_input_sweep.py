#!/usr/bin/env python3
"""The scripted bad-input sweep of mpr-render and mpr-view (docs/reliability.md).

Runs each tool on several hundred command lines that must be refused (bad option values,
values out of range, missing, garbage and hostile files, impossible jobs, unwritable outputs)
and checks every case:

  * exit status 1 and exactly one line on stderr, "<tool>: ..." (no "std::", no "terminate");
    stdout (progress such as "estimated the depth maps ...") never says a file was written;
  * no file created, changed or removed in the case's folder (which holds the fixtures, an
    existing --output and an earlier run's frames), in TMPDIR (pointed into the folder), or in
    /dev/shm;
  * peak resident memory (the child's ru_maxrss) at most --max-rss-mib (default 256 MiB);
  * wall time at most --max-seconds (default 30 s; the run is killed there).

Usage (Debian's python3 is enough; nothing outside the standard library):

  tests/tools/bad_input_sweep.py --render build/test/tools/mpr-render \
      [--view build/test/tools/mpr-view] [--sample N] [--only REGEX] [--list] [--verbose]

--sample N runs N cases spread evenly over the list (the ctest entry runs 40). Prints one line
per failed case and a summary ("sweep: N cases, N passed, ..."); exit status 0 when every case
passed.
"""

import argparse
import hashlib
import os
import re
import resource
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import threading
import time
import zlib

# ---------------------------------------------------------------------------------------------
# Fixtures


def png_bytes(w, h, seed=1):
    """An 8-bit RGB PNG of w x h pixels with a deterministic pattern."""
    rows = bytearray()
    for y in range(h):
        rows.append(0)
        for x in range(w):
            rows += bytes(((x * 37 + y * 11 + seed * 5) % 256, (x * 3 + y * 29 + seed) % 256, (seed * 71 + x * y) % 256))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(bytes(rows))) + chunk(b"IEND", b""))


def png_header_only(w, h):
    """A PNG signature and IHDR of w x h, and nothing after it."""
    ihdr = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + b"IHDR" + ihdr +
            struct.pack(">I", zlib.crc32(b"IHDR" + ihdr) & 0xFFFFFFFF))


def pfm_bytes(w, h, value, header=None):
    data = struct.pack("<%df" % (w * h), *([value] * (w * h)))
    return (header if header is not None else ("Pf\n%d %d\n-1\n" % (w, h)).encode()) + data


def write(path, data, mode=0o644):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())
    os.chmod(path, mode)


def sparse(path, size, head=b""):
    with open(path, "wb") as f:
        f.write(head)
        f.truncate(size)


PAR_LINE = "view{i}.png 8 0 3.5 0 8 2.5 0 0 1  1 0 0 0 1 0 0 0 1  {t} 0 0\n"


def par_text(n=3, lines=None):
    body = lines if lines is not None else "".join(PAR_LINE.format(i=i, t=-0.1 * (i - 1)) for i in range(n))
    return "%d\n" % n + body


def make_fixtures(fx):
    """Valid inputs (so that one thing at a time can be broken) and hostile files, under fx."""
    # A _par.txt light field: three 8x6 cameras with depth maps of the plane z = 2.
    for i in range(3):
        write(f"{fx}/par/view{i}.png", png_bytes(8, 6, i))
        write(f"{fx}/par/view{i}.pfm", pfm_bytes(8, 6, 2.0))
    write(f"{fx}/par/tiny_par.txt", par_text())
    # Depth-map folders with one broken map each.
    broken_maps = {
        "truncated": pfm_bytes(8, 6, 2.0)[:-5],
        "wrong_size": pfm_bytes(4, 3, 2.0),
        "bad_magic": pfm_bytes(8, 6, 2.0, b"PX\n8 6\n-1\n"),
        "nan_scale": pfm_bytes(8, 6, 2.0, b"Pf\n8 6\nnan\n"),
        "zero_scale": pfm_bytes(8, 6, 2.0, b"Pf\n8 6\n0\n"),
        "negative_size": pfm_bytes(8, 6, 2.0, b"Pf\n-8 6\n-1\n"),
        "huge_size": pfm_bytes(8, 6, 2.0, b"Pf\n99999999 99999999\n-1\n"),
        "long_token": pfm_bytes(8, 6, 2.0, b"Pf\n" + b"8" * 40 + b" 6\n-1\n"),
        "text": b"this is not a depth map\n",
        "empty": b"",
        "extra_bytes": pfm_bytes(8, 6, 2.0) + b"tail",
        "header_only": b"Pf\n8 6\n-1\n",
        "colour": b"PF\n8 6\n-1\n" + b"\0" * (8 * 6 * 4),
        "header_4097": b"Pf\n" + b" " * 4097 + b"8 6\n-1\n" + b"\0" * (8 * 6 * 4),
    }
    for name, data in broken_maps.items():
        for i in range(3):
            write(f"{fx}/maps_{name}/view{i}.pfm", data if i == 1 else pfm_bytes(8, 6, 2.0))
    os.makedirs(f"{fx}/maps_missing", exist_ok=True)
    write(f"{fx}/maps_missing/view0.pfm", pfm_bytes(8, 6, 2.0))
    # Broken _par.txt files (the images of par/ beside them).
    good = [PAR_LINE.format(i=i, t=-0.1 * (i - 1)) for i in range(3)]
    bad_par = {
        "count_high": "5\n" + "".join(good),
        "count_low": "2\n" + "".join(good),
        "count_negative": "-3\n" + "".join(good),
        "count_huge": "99999999999999999999\n" + "".join(good),
        "count_text": "three\n" + "".join(good),
        "count_zero": "0\n",
        "empty": "",
        "fields_short": "3\n" + good[0] + good[1] + "view2.png 8 0 3.5 0 8 2.5 0 0 1 1 0 0 0 1 0 0 0 1 0.1 0\n",
        "fields_long": "3\n" + good[0] + good[1] + good[2].rstrip("\n") + " 7\n",
        "nan_k": "3\n" + good[0] + good[1] + good[2].replace("8 0 3.5", "nan 0 3.5", 1),
        "inf_t": "3\n" + good[0] + good[1] + good[2].replace("  0.1 0 0", "  inf 0 0"),
        "overflow": "3\n" + good[0] + good[1] + good[2].replace("8 0 3.5", "1e999 0 3.5", 1),
        "singular_k": "3\n" + good[0] + good[1] + good[2].replace("8 0 3.5 0 8 2.5 0 0 1", "0 0 0 0 0 0 0 0 0"),
        "not_rotation": "3\n" + good[0] + good[1] + good[2].replace("1 0 0 0 1 0 0 0 1", "2 0 0 0 1 0 0 0 1"),
        "missing_image": "3\n" + good[0] + good[1] + good[2].replace("view2.png", "absent.png"),
        "image_is_folder": "3\n" + good[0] + good[1] + good[2].replace("view2.png", "folder.png"),
        "image_garbage": "3\n" + good[0] + good[1] + good[2].replace("view2.png", "garbage.png"),
        "image_other_size": "3\n" + good[0] + good[1] + good[2].replace("view2.png", "big.png"),
        "image_huge_header": "3\n" + good[0] + good[1] + good[2].replace("view2.png", "huge_header.png"),
        "image_sparse": "3\n" + good[0] + good[1] + good[2].replace("view2.png", "sparse.png"),
        "image_dev_zero": "3\n" + good[0] + good[1] + good[2].replace("view2.png", "/dev/zero"),
        "image_empty": "3\n" + good[0] + good[1] + good[2].replace("view2.png", "empty.png"),
        "binary": "3\n\0\0\0\x01\x02" + good[0],
        "control_chars": "3\n" + good[0] + good[1] + good[2].replace(" 0 0\n", " 0 0\x07\n"),
        "long_line": "3\n" + good[0] + good[1] + "x" * (2 << 20) + "\n",
        "comma_numbers": "3\n" + good[0] + good[1] + good[2].replace("8 0 3.5", "8,0,3.5", 1),
    }
    for name, text in bad_par.items():
        write(f"{fx}/par/bad_{name}_par.txt", text)
    os.makedirs(f"{fx}/par/folder.png", exist_ok=True)
    write(f"{fx}/par/garbage.png", bytes((i * 7919) % 251 for i in range(4096)))
    write(f"{fx}/par/big.png", png_bytes(10, 6, 3))
    write(f"{fx}/par/huge_header.png", png_header_only(100000, 100000))
    sparse(f"{fx}/par/sparse.png", 1000 << 20, png_header_only(8, 6))
    write(f"{fx}/par/empty.png", b"")
    sparse(f"{fx}/par/huge_par.txt", (1 << 30) + 10, b"3\n")

    # A Stanford folder (2x2) and broken ones.
    def stanford(folder, names, img=None):
        os.makedirs(folder, exist_ok=True)
        for k, name in enumerate(names):
            write(f"{folder}/{name}", img if img is not None else png_bytes(8, 6, k))

    grid = ["out_00_00_-10.0_-10.0.png", "out_00_01_-10.0_10.0.png", "out_01_00_10.0_-10.0.png",
            "out_01_01_10.0_10.0.png"]
    stanford(f"{fx}/stanford/good", grid)
    stanford(f"{fx}/stanford/empty", [])
    stanford(f"{fx}/stanford/bad_name", grid[:3] + ["out_01_xx_10.0_10.0.png"])
    stanford(f"{fx}/stanford/duplicate", grid + ["out_01_01_11.0_11.0.png"])
    stanford(f"{fx}/stanford/garbage", grid, bytes(range(256)) * 4)
    stanford(f"{fx}/stanford/mixed_size", grid[:3])
    write(f"{fx}/stanford/mixed_size/{grid[3]}", png_bytes(9, 6, 3))
    stanford(f"{fx}/stanford/huge_header", grid[:3])
    write(f"{fx}/stanford/huge_header/{grid[3]}", png_header_only(70000, 70000))
    stanford(f"{fx}/stanford/nan_position", grid[:3] + ["out_01_01_nan_10.0.png"])
    stanford(f"{fx}/stanford/overflow_position", grid[:3] + ["out_01_01_1e999_10.0.png"])
    stanford(f"{fx}/stanford/link_loop", grid[:3])
    os.symlink("out_01_01_10.0_10.0.png", f"{fx}/stanford/link_loop/out_01_01_10.0_10.0.png.tmp")
    os.rename(f"{fx}/stanford/link_loop/out_01_01_10.0_10.0.png.tmp", f"{fx}/stanford/link_loop/x")
    os.symlink("out_01_01_10.0_10.0.png", f"{fx}/stanford/link_loop/out_01_01_10.0_10.0.png")
    stanford(f"{fx}/stanford/dangling", grid[:3])
    os.symlink("nowhere.png", f"{fx}/stanford/dangling/{grid[3]}")

    # LFCA: positions and homographies.
    def lfca(folder, positions, homographies, images=("a", "b", "c")):
        write(f"{folder}/positions.txt", positions)
        for k, cam in enumerate(images):
            write(f"{folder}/{cam}.png", png_bytes(8, 6, k))
        for cam, text in homographies.items():
            write(f"{folder}/{cam}.homography.txt", text)

    ident = "1 0 0\n0 1 0\n0 0 1\n"
    good_h = {"a": ident, "b": ident, "c": ident}
    lfca(f"{fx}/lfca/good", "a 0 0\nb 1 0\nc 0 1\n", good_h)
    lfca(f"{fx}/lfca/duplicate", "a 0 0\nb 1 0\na 0 1\n", good_h)
    lfca(f"{fx}/lfca/nan", "a 0 0\nb nan 0\nc 0 1\n", good_h)
    lfca(f"{fx}/lfca/fields", "a 0 0\nb 1\nc 0 1\n", good_h)
    lfca(f"{fx}/lfca/overflow", "a 0 0\nb 1e400 0\nc 0 1\n", good_h)
    lfca(f"{fx}/lfca/singular", "a 0 0\nb 1 0\nc 0 1\n", dict(good_h, b="0 0 0\n0 0 0\n0 0 0\n"))
    lfca(f"{fx}/lfca/eight_numbers", "a 0 0\nb 1 0\nc 0 1\n", dict(good_h, b="1 0 0\n0 1 0\n0 0\n"))
    lfca(f"{fx}/lfca/nan_h", "a 0 0\nb 1 0\nc 0 1\n", dict(good_h, b="1 0 0\n0 nan 0\n0 0 1\n"))
    lfca(f"{fx}/lfca/missing_h", "a 0 0\nb 1 0\nc 0 1\n", {"a": ident, "c": ident})
    lfca(f"{fx}/lfca/missing_image", "a 0 0\nb 1 0\nc 0 1\n", good_h, images=("a", "c"))
    lfca(f"{fx}/lfca/empty", "", {})
    lfca(f"{fx}/lfca/garbage", "\x00\x01\x02\x03 garbage\n", good_h)

    # HCI: a 3x3 subset of the 9x9 grid around the centre view 40, and broken ones.
    views = [30, 31, 32, 39, 40, 41, 48, 49, 50]

    def hci(folder, nums, cfg=None, extra=None):
        os.makedirs(folder, exist_ok=True)
        for k, n in enumerate(nums):
            write(f"{folder}/input_Cam{n:03d}.png", png_bytes(8, 8, k))
        if cfg is not None:
            write(f"{folder}/parameters.cfg", cfg)
        for name, data in (extra or {}).items():
            write(f"{folder}/{name}", data)

    cfg = ("[intrinsics]\nfocal_length_mm = 100\nsensor_size_mm = 35\nimage_resolution_x_px = 8\n"
           "image_resolution_y_px = 8\n[extrinsics]\nbaseline_mm = 90\nfocus_distance_m = 8\n"
           "num_cams_x = 9\nnum_cams_y = 9\n")
    hci(f"{fx}/hci/good", views, cfg)
    hci(f"{fx}/hci/no_centre", [v for v in views if v != 40])
    hci(f"{fx}/hci/out_of_grid", views + [81])
    hci(f"{fx}/hci/bad_name", views, extra={"input_Cam04x.png": png_bytes(8, 8)})
    hci(f"{fx}/hci/mixed_size", views[:-1], extra={"input_Cam050.png": png_bytes(9, 8)})
    hci(f"{fx}/hci/cfg_resolution", views, cfg.replace("image_resolution_x_px = 8", "image_resolution_x_px = 9"))
    hci(f"{fx}/hci/cfg_nan", views, cfg.replace("baseline_mm = 90", "baseline_mm = nan"))
    hci(f"{fx}/hci/cfg_zero_focal", views, cfg.replace("focal_length_mm = 100", "focal_length_mm = 0"))
    hci(f"{fx}/hci/cfg_garbage", views, "\x00\x01garbage = = =\n[[[\n")
    hci(f"{fx}/hci/cfg_missing_key", views, cfg.replace("baseline_mm = 90\n", ""))
    hci(f"{fx}/hci/cfg_cams", views, cfg.replace("num_cams_x = 9", "num_cams_x = -9"))
    hci(f"{fx}/hci/gt_wrong_size", views, cfg, {"gt_disp_lowres.pfm": pfm_bytes(4, 4, 0.5)})
    hci(f"{fx}/hci/gt_garbage", views, cfg, {"gt_disp_lowres.pfm": b"Pf\n8 8\n-1\nshort"})
    hci(f"{fx}/hci/garbage_view", views[:-1], extra={"input_Cam050.png": b"\x89PNG garbage"})
    hci(f"{fx}/hci/empty", [])

    # COLMAP text models.
    cams = "1 PINHOLE 8 6 8 8 3.5 2.5\n"
    imgs = ("1 1 0 0 0 0 0 0 1 view0.png\n\n2 1 0 0 0 0.1 0 0 1 view1.png\n\n"
            "3 1 0 0 0 -0.1 0 0 1 view2.png\n\n")

    def colmap(folder, cameras, images):
        write(f"{folder}/cameras.txt", cameras)
        write(f"{folder}/images.txt", images)
        for i in range(3):
            write(f"{folder}/images/view{i}.png", png_bytes(8, 6, i))

    colmap(f"{fx}/colmap/good", cams, imgs)
    colmap(f"{fx}/colmap/bad_model", "1 FISHEYE 8 6 8 8 3.5 2.5\n", imgs)
    colmap(f"{fx}/colmap/unknown_camera", cams, imgs.replace("0.1 0 0 1 view1", "0.1 0 0 7 view1"))
    colmap(f"{fx}/colmap/zero_quaternion", cams, imgs.replace("1 1 0 0 0 0 0 0 1 view0", "1 0 0 0 0 0 0 0 1 view0"))
    colmap(f"{fx}/colmap/nan", cams.replace("8 8 3.5", "nan 8 3.5"), imgs)
    colmap(f"{fx}/colmap/size_mismatch", cams.replace("8 6 8", "16 12 8"), imgs)
    colmap(f"{fx}/colmap/missing_image", cams, imgs.replace("view2.png", "absent.png"))
    colmap(f"{fx}/colmap/short_line", cams, "1 1 0 0 0 0 0 view0.png\n\n")
    colmap(f"{fx}/colmap/empty", "", "")

    # OBJ meshes.
    tri = "v 0 0 -5\nv 1 0 -5\nv 0 1 -5\n"
    bad_obj = {
        "index_high": tri + "f 1 2 9\n",
        "index_zero": tri + "f 0 1 2\n",
        "index_negative": tri + "f -1 -2 -9\n",
        "index_text": tri + "f a b c\n",
        "nan_vertex": "v nan 0 -5\nv 1 0 -5\nv 0 1 -5\nf 1 2 3\n",
        "inf_vertex": "v 1e999 0 -5\nv 1 0 -5\nv 0 1 -5\nf 1 2 3\n",
        "bare_cr": tri.replace("\n", "\r") + "f 1 2 900000\r",
        "control": tri + "f 1 2 3\x01\n",
        "binary": bytes(range(256)).decode("latin-1"),
        "long_line": tri + "# " + "x" * (2 << 20) + "\n",
        "no_faces": tri,
        "empty": "",
        "vw_overflow": tri + "vw 1 99999999999 0.5\nf 1 2 3\n",
        "missing_mtl": "mtllib absent.mtl\nusemtl m\n" + tri + "f 1 2 3\n",
        "missing_texture": "mtllib tex.mtl\nusemtl m\n" + tri + "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
        "garbage_texture": "mtllib garbage_tex.mtl\nusemtl m\n" + tri + "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
    }
    for name, text in bad_obj.items():
        write(f"{fx}/obj/{name}.obj", text)
    write(f"{fx}/obj/good.obj", tri + "f 1 2 3\n")
    write(f"{fx}/obj/tex.mtl", "newmtl m\nKd 1 1 1\nmap_Kd absent_texture.png\n")
    write(f"{fx}/obj/garbage_tex.mtl", "newmtl m\nKd 1 1 1\nmap_Kd garbage_texture.png\n")
    write(f"{fx}/obj/garbage_texture.png", b"\x89PNG\r\n\x1a\nnot really")
    sparse(f"{fx}/obj/huge.obj", (1 << 30) + 100, tri.encode())
    os.makedirs(f"{fx}/obj/folder.obj", exist_ok=True)

    # mpr-view scripts.
    bad_scripts = {
        "unknown_command": "jump 3\n",
        "wait_negative": "wait -5\n",
        "wait_text": "wait soon\n",
        "wait_huge": "wait 99999999999999999999\n",
        "key_unknown": "key NoSuchKey\n",
        "drag_short": "drag 1,2\n",
        "drag_outside": "drag 1,2 99999,3\n",
        "drag_button": "drag 1,2 3,4 fourth\n",
        "wheel_text": "wheel many\n",
        "wheel_huge": "wheel 1e30\n",
        "click_negative": "click -1,5\n",
        "click_nan": "click nan,5\n",
        "screenshot_none": "screenshot\n",
        "binary": "\x00\x01\x02\x03\n",
        "long_line": "wait " + "1" * (70000) + "\n",
        "long_word": "x" * (3 << 20),
        "extra_field": "wait 5 6\n",
    }
    for name, text in bad_scripts.items():
        write(f"{fx}/scripts/{name}.txt", text)
    sparse(f"{fx}/scripts/huge.txt", 300 << 20, b"wait 1\n")

    # Other hostile files.
    write(f"{fx}/empty", b"")
    write(f"{fx}/garbage.bin", bytes((i * 104729) % 256 for i in range(65536)))
    os.makedirs(f"{fx}/a_folder", exist_ok=True)
    os.mkfifo(f"{fx}/fifo")
    os.symlink("loop_b", f"{fx}/loop_a")
    os.symlink("loop_a", f"{fx}/loop_b")
    os.symlink("/dev/zero", f"{fx}/zero_link")
    os.symlink("/dev/full", f"{fx}/full_link.png")
    os.symlink("/dev/full", f"{fx}/full_link.pfm")
    write(f"{fx}/readonly/keep.txt", b"x")
    os.makedirs(f"{fx}/out_is_folder.png", exist_ok=True)
    os.makedirs(f"{fx}/d_preview.png", exist_ok=True)
    write(f"{fx}/plain_file", b"a file where a folder is expected")


# ---------------------------------------------------------------------------------------------
# Cases: (name, tool, args); `fx` stands for the fixtures folder.

EXISTING = "existing.png"  # an existing --output every render case names; it must stay untouched
SMALL = ["--size", "16x12"]


def render_cases():
    cases = []

    def add(name, *args, out=True):
        argv = list(args)
        if out:
            argv += ["--output", EXISTING]
        cases.append((name, "render", argv))

    # Option syntax.
    add("unknown_option", "--no-such-option")
    add("unknown_option_value", "--colour", "red")
    add("typo", "--veiw", "G")
    add("positional", "scene.obj")
    add("single_dash", "-size", "16x12")
    add("empty_option", "--")
    add("empty_word", "")
    add("missing_value_last", "--size", out=False)
    for opt in ["--size", "--view", "--spp", "--focal-depth", "--par", "--write-depth", "--frames", "--aperture"]:
        add("missing_value_before" + opt, opt, "--double")
    add("flag_with_value", "--double=yes")

    # W x H options.
    bad_wh = ["", "x", "16", "16x", "x12", "0x12", "16x0", "-16x12", "16x-12", "16x12x2", "axb", "16.5x12",
              "1e3x12", "99999999999x12", "16x99999999999", "2147483648x1", "16384x16385", "16385x16384",
              "nanxnan", "16 x12", " 16x12", "16x12 ", "0x0", "16X12", "16*12", "0x10", "+16x+12", "16x12,",
              "0016x0012x", "١٦x12"]
    for v in bad_wh:
        add("size=" + v, "--size", v)
    for v in ["", "0x1", "1x0", "-1x1", "3", "axb", "65536x1", "1x65536", "2x2x2", "nanx1", "1.5x1"]:
        add("layout=" + v, "--layout", v)
    for v in ["", "0x4", "4x0", "-1x4", "axb", "100000x1", "4", "1e9x1e9"]:
        add("raster=" + v, "--raster", v)

    # Integer options.
    ints = {
        "--threads": ["", "two", "-1", "1.5", "99999999999", "1e3", "0x4", "nan", "100000"],
        "--spp": ["", "0", "-1", "4097", "100000", "1.5", "x", "nan", "99999999999999999999"],
        "--raster-samples": ["0", "2", "4", "17", "-1", "x", "1.0", "99"],
        "--camera": ["-1", "x", "1.5", "99999999999"],
        "--frames": ["", "0", "-1", "x", "1.5", "100000001", "99999999999"],
        "--prefilter": ["0", "9", "-1", "x", "1.5", "autox", "AUTO"],
        "--fps": ["0", "-1", "x", "nan", "inf", "1e999"],
    }
    for opt, values in ints.items():
        for v in values:
            extra = []
            if opt == "--raster-samples":
                extra = ["--raster", "2x2"]
            add(opt[2:] + "=" + v, opt, v, *extra, *SMALL)

    # Scalar options.
    bad_scalar = ["", "x", "nan", "inf", "-inf", "1e999", "-1e999", "1,2", "1.0.0", "0x", "--1"]
    for opt, extra in {
        "--lens-distance": ["--spp", "4", "--aperture", "disc:0.2"],
        "--obj-scale": ["--obj", "fx/obj/good.obj"],
        "--reference-depth": ["--stanford", "fx/stanford/good"],
        "--position-scale": ["--stanford", "fx/stanford/good"],
        "--zoom": ["--par", "fx/par/tiny_par.txt", "--focal-depth", "2"],
        "--scene-scale": [],
    }.items():
        for v in bad_scalar + ["0", "-1"]:
            add(opt[2:] + "=" + v, opt, v, *extra, *SMALL)
    add("lens-distance_without_aperture", "--lens-distance", "2", *SMALL)
    add("lens-distance=1e-39", "--lens-distance", "1e-39", "--spp", "4", "--aperture", "disc:0.2", *SMALL)
    add("obj-scale=1e300", "--obj-scale", "1e300", "--obj", "fx/obj/good.obj", *SMALL)
    add("position-scale=1e300", "--position-scale", "1e300", "--stanford", "fx/stanford/good", *SMALL)
    add("zoom=1e-30", "--zoom", "1e-30", "--par", "fx/par/tiny_par.txt", "--focal-depth", "2", *SMALL)
    add("zoom=1e30", "--zoom", "1e30", "--par", "fx/par/tiny_par.txt", "--focal-depth", "2", *SMALL)

    # Animatable values.
    bad_anim = ["", "x", "nan", "inf", "1:", ":1", "1:2:3:4", "0=1", "0=1,0=2", "2=1,3=1", "-1=0,1=1", "0=1,x=2",
                "t=1", "0=1,1=", "1e999", "0=nan,1=1", "1:nan", "0=1;1=2", "1=0,0=1"]
    for opt in ["--focal-depth", "--radius"]:
        for v in bad_anim:
            add(opt[2:] + "=" + v, opt, v, "--par", "fx/par/tiny_par.txt", "--interp", "cylinder", "--frames", "2",
                *SMALL)
    for opt in ["--tilt-x", "--tilt-y"]:
        for v in bad_anim + ["90", "-90", "1e6", "180"]:
            add(opt[2:] + "=" + v, opt, v, "--frames", "2", *SMALL)
    for v in ["x", "nan", "1:", "0=nan,1=1", "0=1,0=0"]:
        add("morph=" + v, "--morph-to", "G", "--morph", v, "--frames", "2", *SMALL)
    add("morph_without_morph_to", "--morph", "0:1", "--frames", "2", *SMALL)
    add("tilt_animated_without_frames", "--tilt-x", "0:30", *SMALL)
    add("frames_without_animation", "--frames", "3", *SMALL)
    add("focal_depth_scene", "--focal-depth", "5", *SMALL)
    add("focal_depth=1e39", "--focal-depth", "1e39", "--par", "fx/par/tiny_par.txt", *SMALL)
    add("focal_depth=1e39_save_maps", "--focal-depth", "1e39", "--par", "fx/par/tiny_par.txt", "--depth-maps",
        "estimate:1:3:4", "--save-depth-maps", "saved_maps", *SMALL)
    add("focal_depth=1e-308_float", "--focal-depth", "1e-308", "--par", "fx/par/tiny_par.txt", *SMALL)
    add("radius_scene", "--radius", "1", *SMALL)

    # Vectors.
    bad_vec3 = ["", "1,2", "1,2,3,4", "a,b,c", "nan,0,0", "0,inf,0", "1e999,0,0", ",,", "1;2;3", "1 2 3", "0,0,0,"]
    for opt in ["--plane-centre", "--look-at", "--up", "--scene-centre"]:
        for v in bad_vec3:
            add(opt[2:] + "=" + v, opt, v, *SMALL)
    add("up=0,0,0", "--up", "0,0,0", *SMALL)
    add("up_along_normal", "--plane-centre", "0,0,0", "--look-at", "0,1,0", "--up", "0,1,0", *SMALL)
    add("look_at_centre", "--plane-centre", "1,2,3", "--look-at", "1,2,3", *SMALL)
    for v in ["", "1", "1,2,3", "0,1", "1,0", "-1,1", "nan,1", "inf,1", "1e-30,1e-30", "a,b"]:
        add("plane-size=" + v, "--plane-size", v, *SMALL)
    for v in ["", "1", "x,y", "-1,0", "0,-1", "16,0", "0,12", "1e9,1", "nan,1", "1.5,2"]:
        add("focus-at=" + v, "--focus-at", v, "--raster", "2x2", *SMALL)

    # Views.
    bad_views = ["", "J", "Z", "pinhole:", "pinhole:1,2", "pinhole:nan,0,0", "orthographic:0,0,0",
                 "orthographic:1,0,0", "oblique:90,0", "oblique:x,0", "pushbroom:0,0,0", "pushbroom:0,1.6,10:0,0,0",
                 "cross_slit:0,1.6,10:1,0,0", "cross_slit:0,1.6,10:1,0,0:0,1.6,10:1,0,0", "pencil:0,1.6,10:1,0,0",
                 "pencil:0,1.6,10:1,0,0:nan", "twisted:0,0,-1:1,0,0", "bilinear:0,0,-1:x:0.05",
                 "corners:1,0,0:1,0,0:1,0,0", "corners:0,0,0:0,0,0:0,0,0", "corners:-0.3,-0.1,-1:0.3,-0.1,-1",
                 "pinhole:1e999,0,0", "G:extra", "unknown:1"]
    for v in bad_views:
        add("view=" + v, "--view", v, *SMALL)
    add("views_count_low", "--layout", "3x1", "--views", "A,B", *SMALL)
    add("views_count_high", "--layout", "2x1", "--views", "A,B,C", *SMALL)
    add("views_bad_entry", "--layout", "2x1", "--views", "A,pinhole:1;2", *SMALL)
    add("views_empty_entry", "--layout", "2x1", "--views", "A,", *SMALL)
    add("views_without_layout", "--views", "A,B", *SMALL)
    add("view_and_views", "--layout", "2x1", "--views", "A,B", "--view", "G", *SMALL)
    add("morph_to_bad", "--morph-to", "Q", "--frames", "2", *SMALL)

    # Pixel sampling, aperture and focus.
    for v in ["", "sinc", "box:", "box:-1", "box:0", "box:nan", "box:inf", "tent:1e9", "gaussian:x", "box:1:2"]:
        add("filter=" + v, "--filter", v, "--spp", "4", *SMALL)
    add("filter_without_spp", "--filter", "box", *SMALL)
    for v in ["", "disc", "disc:", "disc:-0.2", "disc:nan", "disc:inf", "ellipse:0.2", "polygon:0.2", "polygon2:0.2",
              "polygon1000000:0.2", "square:x", "disc:0.2:", "disc:1e999", "gaussian:-1", "disc:0=0.1,0=0.2"]:
        add("aperture=" + v, "--aperture", v, "--spp", "4", *SMALL)
    add("aperture_without_spp", "--aperture", "disc:0.2", *SMALL)
    add("aperture_animated_without_frames", "--aperture", "disc:0:0.5", "--spp", "4", *SMALL)
    for v in ["", "x", "nan", "inf", "-3", "1,2,3", "1,", ",1", "-1", "1e999"]:
        add("focus=" + v, "--focus", v, "--spp", "4", "--aperture", "disc:0.2", "--lens-distance", "1", *SMALL)
    add("focus_without_aperture", "--focus", "3", "--spp", "4", *SMALL)
    add("focus_parallel_rays", "--double", "--view", "corners:1,0,-1e-8:0.3,-0.1,-1:-0.3,-0.5,-1", "--spp", "4",
        "--aperture", "disc:0.1", "--focus", "3", *SMALL)

    # Light-field options without (or with the wrong) light field.
    for opt, val in [("--interp", "cylinder"), ("--depth-maps", "fx/par"), ("--all-in-focus", None),
                     ("--camera", "0"), ("--zoom", "2"), ("--prefilter", "2"), ("--reference-depth", "10"),
                     ("--position-scale", "2"), ("--sweep", "best=2"), ("--proxy", "k=2"),
                     ("--save-depth-maps", "maps_out"), ("--colmap-images", "fx/colmap/good/images")]:
        add("scene_with" + opt, opt, *([val] if val else []), *SMALL)
    for v in ["", "bilinear", "NEAREST", "depth2", "cylinder,depth"]:
        add("interp=" + v, "--interp", v, "--par", "fx/par/tiny_par.txt", "--focal-depth", "2", *SMALL)
    add("interp_depth_without_maps", "--interp", "depth", "--par", "fx/par/tiny_par.txt", *SMALL)
    add("all_in_focus_without_maps", "--all-in-focus", "--par", "fx/par/tiny_par.txt", *SMALL)
    add("camera=3_of_3", "--camera", "3", "--par", "fx/par/tiny_par.txt", "--focal-depth", "2", *SMALL)
    add("camera=-1_par", "--camera", "-1", "--par", "fx/par/tiny_par.txt", "--focal-depth", "2", *SMALL)
    add("two_samplers", "--par", "fx/par/tiny_par.txt", "--stanford", "fx/stanford/good", *SMALL)
    add("scene_and_obj", "--scene", "classroom", "--obj", "fx/obj/good.obj", *SMALL)
    add("scene=other", "--scene", "kitchen", *SMALL)
    add("raster_with_par", "--raster", "2x2", "--par", "fx/par/tiny_par.txt", *SMALL)
    add("raster_samples_without_raster", "--raster-samples", "3", *SMALL)

    # Depth maps: folders and estimates.
    lf = ["--par", "fx/par/tiny_par.txt", "--focal-depth", "2", "--interp", "depth", *SMALL]
    for d in sorted(os.listdir("fx")) if os.path.isdir("fx") else []:
        if d.startswith("maps_"):
            add("depth_maps_" + d[5:], "--depth-maps", "fx/" + d, *lf)
    add("depth_maps_absent_folder", "--depth-maps", "fx/no_such_maps", *lf)
    add("depth_maps_file", "--depth-maps", "fx/plain_file", *lf)
    add("depth_maps_fifo", "--depth-maps", "fx/fifo", *lf)
    for v in ["estimate:", "estimate:1", "estimate:3:1", "estimate:0:1", "estimate:-1:2", "estimate:1:2:0",
              "estimate:1:2:1", "estimate:1:2:x", "estimate:nan:2", "estimate:1:inf", "estimate:1:2:100000000",
              "estimate:1:2:4:5", "estimate:1e-39:2", "guess:1:2"]:
        add("depth_maps=" + v, "--depth-maps", v, *lf)
    for v in ["", "best", "best=", "best=0", "best=99", "neighbours=0", "neighbours=-1", "neighbours=x", "truncation=-1",
              "truncation=nan", "spatial=-1", "range=-1", "selection=random", "unknown=1", "best=2,best=3"]:
        add("sweep=" + v, "--sweep", v, "--depth-maps", "estimate:1:3:4", *lf)
    add("sweep_without_estimate", "--sweep", "best=2", "--depth-maps", "fx/par", *lf)
    for v in ["", "k", "k=0", "k=-1", "k=x", "k=1000", "tolerance=-1", "tolerance=nan", "visibility_tolerance=-1",
              "march_cameras=0", "whole_line=2", "radius=1", "unknown=1"]:
        add("proxy=" + v, "--proxy", v, "--depth-maps", "fx/par", *lf)
    add("save_depth_maps_without_estimate", "--save-depth-maps", "maps_out", "--depth-maps", "fx/par", *lf)
    add("save_depth_maps_into_file", "--save-depth-maps", "fx/plain_file", "--depth-maps", "estimate:1:3:4", *lf)
    add("save_depth_maps_proc", "--save-depth-maps", "/proc/mpr-maps", "--depth-maps", "estimate:1:3:4", *lf)
    add("save_depth_maps_then_write_depth_fails", "--save-depth-maps", "maps_out", "--depth-maps", "estimate:1:3:4",
        "--write-depth", "fx/full_link.pfm", *lf)
    add("save_depth_maps_then_output_fails", "--save-depth-maps", "maps_out", "--depth-maps", "estimate:1:3:4",
        *lf[:-2], "--size", "16x12", "--output", "fx/full_link.png", out=False)
    add("save_depth_maps_deep", "--save-depth-maps", "no/such/folder", "--depth-maps", "estimate:1:3:4", *lf)

    # Input files: every loader with missing, wrong-type and hostile files.
    hostile = ["fx/absent", "fx/empty", "fx/garbage.bin", "fx/a_folder", "fx/fifo", "fx/loop_a", "fx/zero_link",
               "/dev/zero", "/dev/null", "/proc/self/mem", ""]
    for opt in ["--obj", "--par", "--lfca"]:
        for f in hostile:
            add(opt[2:] + "=" + f, opt, f, *SMALL)
    for opt in ["--stanford", "--hci", "--colmap"]:
        for f in ["fx/absent", "fx/empty", "fx/plain_file", "fx/loop_a", "/dev/null", "/proc/self", ""]:
            add(opt[2:] + "=" + f, opt, f, *SMALL)
    for name in sorted(os.listdir("fx/obj")) if os.path.isdir("fx/obj") else []:
        if name.endswith(".obj") and name != "good.obj":
            add("obj_" + name, "--obj", "fx/obj/" + name, *SMALL)
    for name in sorted(os.listdir("fx/par")) if os.path.isdir("fx/par") else []:
        if name.startswith("bad_") or name == "huge_par.txt":
            add("par_" + name, "--par", "fx/par/" + name, *SMALL)
    for name in sorted(os.listdir("fx/stanford")) if os.path.isdir("fx/stanford") else []:
        if name != "good":
            add("stanford_" + name, "--stanford", "fx/stanford/" + name, *SMALL)
    for name in sorted(os.listdir("fx/lfca")) if os.path.isdir("fx/lfca") else []:
        if name != "good":
            add("lfca_" + name, "--lfca", f"fx/lfca/{name}/positions.txt", *SMALL)
    for name in sorted(os.listdir("fx/hci")) if os.path.isdir("fx/hci") else []:
        if name != "good":
            add("hci_" + name, "--hci", "fx/hci/" + name, *SMALL)
    for name in sorted(os.listdir("fx/colmap")) if os.path.isdir("fx/colmap") else []:
        if name != "good":
            add("colmap_" + name, "--colmap", "fx/colmap/" + name, *SMALL)
    add("colmap_images_absent", "--colmap", "fx/colmap/good", "--colmap-images", "fx/absent", *SMALL)
    add("colmap_images_file", "--colmap", "fx/colmap/good", "--colmap-images", "fx/plain_file", *SMALL)
    add("colmap_images_without_colmap", "--par", "fx/par/tiny_par.txt", "--colmap-images", "fx/a_folder", *SMALL)

    # Outputs that cannot be written (and an existing file that must stay as it was).
    for o in ["/proc/mpr-x.png", "fx/absent_dir/deeper/x.png", "fx/out_is_folder.png", "fx/plain_file/x.png",
              "/dev/full", "fx/full_link.png", "x.bmp", "", "x.PNG.txt", "/", "fx/a_folder/", "x.jpg/"]:
        add("output=" + o, "--output", o, *SMALL, out=False)
    add("output_proc_frames", "--output", "/proc/mpr-x.png", "--tilt-x", "0:5", "--frames", "2", "--no-video",
        *SMALL, out=False)
    for o in ["/proc/d.pfm", "fx/full_link.pfm", "fx/a_folder", "fx/absent_dir/deeper/d.pfm", "d.txt", "",
              "fx/d.pfm", "fx/plain_file/d.pfm"]:
        add("write_depth=" + o, "--write-depth", o, *SMALL)
    add("write_depth_with_frames", "--write-depth", "d.pfm", "--tilt-x", "0:5", "--frames", "2", *SMALL)
    add("write_depth_light_field_without_maps", "--write-depth", "d.pfm", "--par", "fx/par/tiny_par.txt", "--focal-depth", "2", *SMALL)
    add("write_depth_same_as_output", "--write-depth", EXISTING, *SMALL)

    # Budgets: jobs whose memory or time exceeds the documented limits.
    add("budget_layout", "--layout", "8x8", "--size", "16384x16384")
    add("budget_pixels_spp", "--size", "16384x16384", "--spp", "4096")
    add("budget_rays_frames", "--size", "4096x4096", "--spp", "1024", "--tilt-x", "0:1", "--frames", "100")
    add("budget_raster", "--raster", "64x48", "--raster-samples", "15")
    add("budget_raster_cameras", "--raster", "1000x1000")
    add("budget_raster_frames", "--raster", "32x32", "--raster-samples", "5", "--tilt-x", "0:1", "--frames", "50")
    add("budget_sweep_memory", "--par", "fx/par/tiny_par.txt", "--size", "16384x16384", "--depth-maps",
        "estimate:1:3:100000", "--interp", "depth")

    # Animation and shards.
    for v in ["", "0/0", "1/1", "3/2", "-1/2", "x/2", "1", "1/2/3", "0/-2"]:
        add("shard=" + v, "--shard", v, "--tilt-x", "0:5", "--frames", "2", "--no-video", *SMALL)
    add("shard_without_frames", "--shard", "0/2", *SMALL)
    add("rectify_bad", "--rectify", "1,2,3", *SMALL)
    add("rectify_nan", "--rectify", "nan,0,0;1,0,0;1,1,0;0,1,0", *SMALL)
    add("rectify_degenerate", "--rectify", "0,0,-5;0,0,-5;0,0,-5;0,0,-5", *SMALL)
    add("rectify_five", "--rectify", "0,0,-5;1,0,-5;1,1,-5;0,1,-5;2,2,-5", *SMALL)
    return cases


def view_cases():
    cases = []

    def add(name, *args, out=True):
        cases.append((name, "view", list(args) + (["--output", EXISTING] if out else [])))

    add("unknown_option", "--no-such-option")
    add("typo", "--scirpt", "x.txt")
    add("positional", "file.txt")
    for v in ["", "0", "-1", "x", "1.5", "99999999999", "1e9"]:
        add("benchmark-frames=" + v, "--benchmark", "--benchmark-frames", v, *SMALL)
    add("benchmark_frames_without_benchmark", "--benchmark-frames", "3", *SMALL)
    for f in ["fx/absent", "fx/a_folder", "fx/fifo", "fx/loop_a", "/dev/zero", "fx/zero_link", "fx/garbage.bin", ""]:
        add("script=" + f, "--script", f, *SMALL)
    for name in sorted(os.listdir("fx/scripts")) if os.path.isdir("fx/scripts") else []:
        add("script_" + name, "--script", "fx/scripts/" + name, *SMALL)
    add("script_and_benchmark", "--script", "fx/scripts/unknown_command.txt", "--benchmark", *SMALL)
    # The shared options: a selection of those above.
    for v in ["0x12", "16x0", "x", "16384x16385", "nanxnan"]:
        add("size=" + v, "--size", v)
    for opt, v in [("--spp", "0"), ("--spp", "4097"), ("--threads", "-1"), ("--frames", "0"), ("--view", "J"),
                   ("--view", "pinhole:1,2"), ("--filter", "sinc"), ("--aperture", "disc:-1"), ("--layout", "0x1"),
                   ("--focal-depth", "nan"), ("--tilt-x", "x"), ("--up", "0,0,0"), ("--plane-size", "0,1"),
                   ("--interp", "bilinear"), ("--prefilter", "9"), ("--zoom", "0"), ("--raster", "0x4"),
                   ("--lens-distance", "0"), ("--fps", "0"), ("--shard", "3/2"), ("--morph", "x")]:
        add(opt[2:] + "=" + v, opt, v, *SMALL)
    for opt in ["--obj", "--par", "--lfca"]:
        for f in ["fx/absent", "fx/garbage.bin", "fx/a_folder", "/dev/zero"]:
            add(opt[2:] + "=" + f, opt, f, *SMALL)
    for opt in ["--stanford", "--hci", "--colmap"]:
        for f in ["fx/absent", "fx/plain_file"]:
            add(opt[2:] + "=" + f, opt, f, *SMALL)
    add("par_count_high", "--par", "fx/par/bad_count_high_par.txt", *SMALL)
    add("par_image_sparse", "--par", "fx/par/bad_image_sparse_par.txt", *SMALL)
    add("stanford_mixed_size", "--stanford", "fx/stanford/mixed_size", *SMALL)
    add("depth_maps_truncated", "--par", "fx/par/tiny_par.txt", "--depth-maps", "fx/maps_truncated", "--interp",
        "depth", *SMALL)
    add("budget_layout", "--layout", "8x8", "--size", "16384x16384")
    add("budget_raster", "--raster", "64x48", "--raster-samples", "15")
    add("output_bad_extension", "--output", "x.bmp", *SMALL, out=False)
    return cases


# Open findings: cases that fail today, each with the reason. They are run and reported as
# "known" (not counted as failures); one that passes is reported, so the entry can go.
KNOWN = {}

# ---------------------------------------------------------------------------------------------
# Running and checking


def snapshot(roots):
    """Every entry under roots: path -> (kind, size, mtime_ns, content digest for small files)."""
    state = {}
    for root in roots:
        for top, dirs, files in os.walk(root, followlinks=False):
            for name in dirs + files:
                p = os.path.join(top, name)
                st = os.lstat(p)
                digest = None
                if os.path.isfile(p) and not os.path.islink(p) and st.st_size <= (4 << 20):
                    with open(p, "rb") as f:
                        digest = hashlib.sha1(f.read()).hexdigest()
                kind = "link" if os.path.islink(p) else "dir" if os.path.isdir(p) else "file"
                state[p] = (kind, st.st_size, st.st_mtime_ns if kind == "file" else 0, digest,
                            os.readlink(p) if kind == "link" else None)
    return state


def run_case(tool_path, args, cwd, env, max_seconds):
    start = time.monotonic()
    proc = subprocess.Popen([tool_path] + args, cwd=cwd, env=env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, start_new_session=True)
    killed = []

    def kill():
        killed.append(True)
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass

    timer = threading.Timer(max_seconds, kill)
    timer.start()
    out_chunks, err_chunks = [], []
    readers = [threading.Thread(target=lambda s=s, c=c: c.append(s.read())) for s, c in
               ((proc.stdout, out_chunks), (proc.stderr, err_chunks))]
    for r in readers:
        r.start()
    _, status, usage = os.wait4(proc.pid, 0)
    timer.cancel()
    for r in readers:
        r.join()
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.monotonic() - start
    return (proc.returncode, b"".join(out_chunks).decode(errors="replace"),
            b"".join(err_chunks).decode(errors="replace"), usage.ru_maxrss / 1024.0, wall, bool(killed))


def check(tool, rc, out, err, rss_mib, wall, killed, before, after, args, limits):
    problems = []
    if killed:
        problems.append("killed after %.0f s" % wall)
    if rc != 1:
        problems.append("exit status %d" % rc)
    lines = err.split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    if len(lines) != 1:
        problems.append("%d lines on stderr" % len(lines))
    elif not lines[0].startswith("mpr-%s: " % tool):
        problems.append("the line does not start with 'mpr-%s: '" % tool)
    if re.search(r"std::|terminate|bad_alloc|Assertion|Sanitizer|runtime error", err):
        problems.append("an internal error reached the user")
    if len(err) > 2000:
        problems.append("a message of %d bytes" % len(err))
    if re.search(r"\bwrote\b", out):
        problems.append("stdout reports a file as written")
    if rss_mib > limits.max_rss_mib:
        problems.append("peak memory %.0f MiB" % rss_mib)
    if wall > limits.max_seconds:
        problems.append("%.1f s" % wall)
    for p in sorted(set(before) | set(after)):
        if p not in after:
            problems.append("removed " + p)
        elif p not in before:
            problems.append("created " + p)
        elif before[p] != after[p]:
            problems.append("changed " + p)
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--render", required=True, help="the mpr-render program")
    ap.add_argument("--view", help="the mpr-view program (its cases are skipped without it)")
    ap.add_argument("--sample", type=int, default=0, help="run N cases spread over the list (0: all)")
    ap.add_argument("--only", help="run the cases whose name matches this regular expression")
    ap.add_argument("--max-rss-mib", type=float, default=256.0)
    ap.add_argument("--max-seconds", type=float, default=30.0)
    ap.add_argument("--list", action="store_true", help="print the cases and exit")
    ap.add_argument("--verbose", action="store_true", help="print every case with its message and figures")
    ap.add_argument("--keep", action="store_true", help="keep the scratch folder")
    a = ap.parse_args()
    tools = {"render": os.path.abspath(a.render)}
    if a.view:
        tools["view"] = os.path.abspath(a.view)

    # A sweep stopped with SIGTERM (or Ctrl-C) still removes its scratch folder.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(130))
    scratch = tempfile.mkdtemp(prefix="mpr-sweep-")
    base = os.path.join(scratch, "fixtures")
    os.makedirs(base)
    cwd0 = os.getcwd()
    try:
        os.chdir(base)
        make_fixtures("fx")
        cases = [(n, t, args) for n, t, args in render_cases() + view_cases() if t in tools]
        os.chdir(cwd0)
        if a.only:
            cases = [c for c in cases if re.search(a.only, c[1] + ":" + c[0])]
        if a.sample and a.sample < len(cases):
            step = len(cases) / a.sample
            cases = [cases[int(i * step)] for i in range(a.sample)]
        if a.list:
            for n, t, args in cases:
                print("%s:%s  %s" % (t, n, " ".join(repr(x) if (not x or " " in x) else x for x in args)))
            return 0

        work = os.path.join(scratch, "case")
        tmp = os.path.join(scratch, "tmp")
        env = dict(os.environ, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy", TMPDIR=tmp)
        env.pop("DISPLAY", None)
        env.pop("WAYLAND_DISPLAY", None)
        failed, known, rss_max, wall_max, slowest, counts = [], [], 0.0, 0.0, "", {}
        t0 = time.monotonic()
        for name, tool, args in cases:
            # A fresh case folder: the fixtures (moved, not copied: the sparse files stay sparse),
            # an existing --output and an earlier animation's frames beside it.
            os.makedirs(work)
            os.makedirs(tmp)
            os.rename(os.path.join(base, "fx"), os.path.join(work, "fx"))
            with open(os.path.join(work, EXISTING), "wb") as f:
                f.write(b"the user's existing file")
            with open(os.path.join(work, "existing_0001.png"), "wb") as f:
                f.write(b"an earlier frame")
            with open(os.path.join(work, "existing_0042.png"), "wb") as f:
                f.write(b"a camera's own file")
            roots = [work, tmp]
            shm0 = set(os.listdir("/dev/shm")) if os.path.isdir("/dev/shm") else set()
            before = snapshot(roots)
            label = "%s:%s" % (tool, name)
            # An open finding that hangs need not cost the whole time limit.
            limit = min(a.max_seconds, 5.0) if label in KNOWN else a.max_seconds
            rc, out, err, rss, wall, killed = run_case(tools[tool], args, work, env, limit)
            after = snapshot(roots)
            shm1 = set(os.listdir("/dev/shm")) if os.path.isdir("/dev/shm") else set()
            problems = check(tool, rc, out, err, rss, wall, killed, before, after, args, a)
            problems += ["created /dev/shm/" + s for s in sorted(shm1 - shm0) if "mpr" in s]
            counts[tool] = counts.get(tool, 0) + 1
            if label not in KNOWN:
                rss_max = max(rss_max, rss)
                if wall > wall_max:
                    wall_max, slowest = wall, label
            message = err.strip().replace("\n", " | ")
            if label in KNOWN:
                known.append(label)
                print("%s %s: %s (%s)" % ("KNOWN" if problems else "FIXED", label, KNOWN[label],
                                          "; ".join(problems) if problems else "now passes: remove it from KNOWN"))
            elif problems:
                failed.append(label)
                print("FAIL %s: %s\n     args: %s\n     stderr: %s" % (label, "; ".join(problems), args, message[:400]))
            elif a.verbose:
                print("ok   %s (%.2f s, %.0f MiB): %s" % (label, wall, rss, message[:300]))
            sys.stdout.flush()
            # Put the fixtures back and clear the rest (even what a failed case left).
            os.rename(os.path.join(work, "fx"), os.path.join(base, "fx"))
            shutil.rmtree(work)
            shutil.rmtree(tmp)
        total = time.monotonic() - t0
        print("cases per tool: " + ", ".join("mpr-%s %d" % kv for kv in sorted(counts.items())))
        print("sweep: %d cases, %d passed, %d failed, %d known; peak memory %.1f MiB (limit %.0f), slowest %.2f s (%s, limit "
              "%.0f s; known cases not counted), %.0f s in all" % (len(cases), len(cases) - len(failed) - len(known), len(failed), len(known), rss_max, a.max_rss_mib,
                                         wall_max, slowest, a.max_seconds, total))
        return 0 if not failed else 1
    finally:
        os.chdir(cwd0)
        if not a.keep:
            shutil.rmtree(scratch, ignore_errors=True)
        else:
            print("scratch kept: " + scratch)


if __name__ == "__main__":
    sys.exit(main())
