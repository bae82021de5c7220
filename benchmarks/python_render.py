#!/usr/bin/env python3
"""python_render: the cost of calling mpr from Python.

Renders the same 640x480 job (a refocus view of a 7x7 synthetic array of 640x480 frames, each
interpolation without depth maps) timed inside C++ (`mpr._mpr._render_seconds`: the same dispatch
and typed renderer into one reused image, no Python in the loop), through `mpr.render` into a new
array, and through `mpr.render(..., out=)` into a reused one, interleaved in one run, and prints
the overhead of each Python call from the minima (on a shared machine the medians carry the other
jobs' noise). Then times building a frame set from 49 uint8 arrays and the memory it adds (the
set copies the pixels: its images plus the texels its samplers read).

usage: PYTHONPATH=<build>/python python3 benchmarks/python_render.py [--quick]
"""

import os
import platform
import statistics
import sys
import time

import numpy as np

import mpr


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def synthetic_array(n_side, w, h):
    rng = np.random.default_rng(3)
    cams = [mpr.Camera.look_at([0.05 * (i - n_side // 2), 0.05 * (j - n_side // 2), -3], [0, 0, 0], [0, -1, 0],
                               0.6, w, h) for j in range(n_side) for i in range(n_side)]
    base = rng.integers(0, 256, (h // 8 + 1, w // 8 + 1, 3), dtype=np.uint8)
    images = [np.ascontiguousarray(np.roll(np.kron(base, np.ones((8, 8, 1), np.uint8))[:h, :w], k, axis=1))
              for k in range(len(cams))]
    return cams, images


def main():
    quick = "--quick" in sys.argv
    n_side, w, h = (3, 160, 120) if quick else (7, 640, 480)
    repeats = 1 if quick else 9
    cams, images = synthetic_array(n_side, w, h)
    K = np.stack([c.K for c in cams])
    R = np.stack([c.R for c in cams])
    t = np.stack([c.t for c in cams])

    before = rss_bytes()
    start = time.perf_counter()
    frames = mpr.frame_set(images, K, R, t)
    build_ms = 1e3 * (time.perf_counter() - start)
    added = rss_bytes() - before
    array_bytes = sum(im.nbytes for im in images)

    print(f"machine: {platform.node()} {platform.machine()}, {os.cpu_count()} cpus, load "
          f"{os.getloadavg()[0]:.2f}; Python {platform.python_version()}, numpy {np.__version__}")
    print(f"frame_set from {len(images)} uint8 arrays of {w}x{h}: {build_ms:.1f} ms, resident memory "
          f"+{added / 2**20:.1f} MiB for {array_bytes / 2**20:.1f} MiB of arrays (copied: images + texels)")
    view = mpr.View.pinhole(frames.camera(len(cams) // 2), 3.0)
    print("| job | output | C++ ms (min / median) | Python ms, new array (min / median) | overhead | "
          "Python ms, out= (min / median) | overhead |")
    print("|---|---|---|---|---|---|---|")
    out = np.empty((h, w, 3), np.uint8)
    for interpolation in mpr.interpolations:
        if interpolation == "depth":  # needs depth maps, which this array has not
            continue
        cpp, py, into = [], [], []
        mpr.render(frames, view, w, h, interpolation=interpolation)  # warm-up (tables, pages)
        for _ in range(repeats):
            cpp.append(1e3 * mpr._mpr._render_seconds(frames, view, w, h, interpolation, 1))
            start = time.perf_counter()
            mpr.render(frames, view, w, h, interpolation=interpolation)
            py.append(1e3 * (time.perf_counter() - start))
            start = time.perf_counter()
            mpr.render(frames, view, w, h, interpolation=interpolation, out=out)
            into.append(1e3 * (time.perf_counter() - start))
        c, p, o = min(cpp), min(py), min(into)
        print(f"| {interpolation}, {len(cams)} cameras | {w}x{h} 8-bit | {c:.2f} / {statistics.median(cpp):.2f} | "
              f"{p:.2f} / {statistics.median(py):.2f} | {100 * (p - c) / c:+.1f}% | "
              f"{o:.2f} / {statistics.median(into):.2f} | {100 * (o - c) / c:+.1f}% |")
    print("python_render: done")
    return 0


if __name__ == "__main__":
    sys.exit(main())
