#!/usr/bin/env python3
"""python_render: the cost of calling mpr from Python.

Renders the same 640x480 job (a refocus view of a 7x7 synthetic array of 640x480 frames, each
interpolation without depth maps, one thread) timed inside C++ (`mpr._mpr._render_seconds`: the
same dispatch and typed renderer, no Python in the loop), through `mpr.render` into a new array,
and through `mpr.render(..., out=)`; the C++ render and `out=` write the same array (where the
output lies relative to the frames moves a render's time by a few percent). The three
are interleaved in a shuffled order, many times, and each is timed twice: wall clock and the
calling thread's CPU time (with one thread the render runs on the calling thread, so its CPU time
is the render's and the call's, whatever else the machine runs). The overhead of a call is
reported from the minima (the run least disturbed) and as the median of the per-round
differences, and measured directly on a 1x1 render, where the render itself is next to nothing. Then builds a frame set from 49 uint8 arrays and
prints the time and the memory it adds (the set reads the arrays in place).

usage: PYTHONPATH=<build>/python python3 benchmarks/python_render.py [--quick]
"""

import os
import platform
import random
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


def timed_runs(frames, view, w, h, interpolation, repeats):
    """{kind: [(wall ms, thread CPU ms)]} for kind in cpp, new, out, interleaved in shuffled order."""
    out = np.empty((h, w, 3), np.uint8)
    runs = {"cpp": [], "new": [], "out": []}

    def python_call(kind):
        wall, cpu = time.perf_counter(), time.thread_time()
        if kind == "new":
            mpr.render(frames, view, w, h, interpolation=interpolation, threads=1)
        else:
            mpr.render(frames, view, w, h, interpolation=interpolation, threads=1, out=out)
        return 1e3 * (time.perf_counter() - wall), 1e3 * (time.thread_time() - cpu)

    order = random.Random(11)
    for _ in range(repeats):
        kinds = list(runs)
        order.shuffle(kinds)
        for kind in kinds:
            if kind == "cpp":
                wall, cpu = mpr._mpr._render_seconds(frames, view, w, h, interpolation, 1, 1, out)
                runs[kind].append((1e3 * wall, 1e3 * cpu))
            else:
                runs[kind].append(python_call(kind))
    return runs


def main():
    quick = "--quick" in sys.argv
    n_side, w, h = (3, 160, 120) if quick else (7, 640, 480)
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
    shared = sum(frames.shares(i) for i in range(len(frames)))

    print(f"machine: {platform.node()} {platform.machine()}, {os.cpu_count()} cpus, load "
          f"{os.getloadavg()[0]:.2f}; Python {platform.python_version()}, numpy {np.__version__}")
    print(f"frame_set from {len(images)} uint8 arrays of {w}x{h}: {build_ms:.2f} ms, resident memory "
          f"+{added / 2**20:.2f} MiB for {array_bytes / 2**20:.1f} MiB of arrays ({shared} of {len(images)} read "
          f"in place)")
    view = mpr.View.pinhole(frames.camera(len(cams) // 2), 3.0)

    # The call alone: a 1x1 render, where the render itself costs next to nothing.
    tiny = timed_runs(frames, view, 1, 1, "nearest", 50 if quick else 2000)
    call_us = {k: 1e3 * min(c for _, c in v) for k, v in tiny.items()}
    print(f"1x1 render, thread CPU min: C++ {call_us['cpp']:.1f} us, mpr.render {call_us['new']:.1f} us, "
          f"mpr.render(out=) {call_us['out']:.1f} us")

    print("| job | output | C++ ms, thread CPU min / median (wall min) | mpr.render ms | overhead | "
          "mpr.render(out=) ms | overhead |")
    print("|---|---|---|---|---|---|---|")
    for interpolation in mpr.interpolations:
        if interpolation == "depth":  # needs depth maps, which this array has not
            continue
        repeats = 1 if quick else (5 if interpolation == "cylinder" else 40)
        mpr.render(frames, view, w, h, interpolation=interpolation, threads=1)  # warm-up (tables, pages)
        runs = timed_runs(frames, view, w, h, interpolation, repeats)
        cell, cpu_min = {}, {}
        for kind, values in runs.items():
            cpu = [c for _, c in values]
            cpu_min[kind] = min(cpu)
            cell[kind] = f"{min(cpu):.2f} / {statistics.median(cpu):.2f} ({min(wl for wl, _ in values):.2f})"
        c = cpu_min["cpp"]
        cpp_median = statistics.median(cpu for _, cpu in runs["cpp"])

        def overhead(kind):  # from the minima, and the median of the per-round differences (paired)
            paired = statistics.median(p[1] - q[1] for p, q in zip(runs[kind], runs["cpp"]))
            return f"{100 * (cpu_min[kind] - c) / c:+.2f}% (paired {100 * paired / cpp_median:+.2f}%)"

        print(f"| {interpolation}, {len(cams)} cameras, 1 thread, {repeats} runs | {w}x{h} 8-bit | {cell['cpp']} | "
              f"{cell['new']} | {overhead('new')} | {cell['out']} | {overhead('out')} |")
    print("python_render: done")
    return 0


if __name__ == "__main__":
    sys.exit(main())
