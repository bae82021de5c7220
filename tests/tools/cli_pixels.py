#!/usr/bin/env python3
"""Pixel checks of mpr-render's output against answers worked out here (ctest mpr_render_pixels).

  tests/tools/cli_pixels.py MPR_RENDER SCRATCH_FOLDER

1. A _par.txt light field of three 8x6 cameras (R = I, centres 0.1 apart on the x axis), each
   image one flat colour: (200, 60, 20), (10, 120, 240), (90, 250, 0). Rendered at its own
   size with --focal-depth 2, every output pixel sees every camera, so:
   * --interp synthetic: each pixel is the mean of the three colours in linear light, encoded
     to sRGB, (131, 169, 147), computed here from the sRGB formula (the mean of the codes,
     (100, 143, 87), and any channel swap fail);
   * --interp nearest: the reference (middle) camera's colour, and with --camera 0 the first's.
2. --lens-distance's default is the image plane's width: --plane-size 8,6 with no
   --lens-distance gives the same bytes as --lens-distance 8, and other bytes than 8.5.
3. An 8-bit output renders each view in bands of rows of linear pixels (at most 16 MiB of them):
   a PNG of 1200x1500 pixels (bands of 16 MiB / (12 x 1200) = 1165 rows) with --spp 2 and a
   Mitchell filter reaching across the band border holds the codes of the same render written
   as PFM (the linear image of the whole frame), each within 1 of the sRGB formula here: every
   pixel of the rows around the border, every tenth row elsewhere.
Prints "cli pixels: ok" when every check holds; else names the check and exits 1.
"""

import array
import filecmp
import os
import struct
import subprocess
import sys
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "compare-renders"))
import png_diff  # noqa: E402  (the one PNG decoder of the tests and tools)


def flat_png(w, h, rgb):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    rows = b"".join(b"\0" + bytes(rgb) * w for _ in range(h))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def read_png(path):
    """(width, height, rows of (r, g, b)) of an 8-bit RGB or RGBA PNG (png_diff.decode's pixels)."""
    w, h, channels, pixels = png_diff.decode(path)
    if channels not in (3, 4):
        raise ValueError(path + ": not 8-bit RGB(A)")
    stride = w * channels
    return w, h, [[tuple(pixels[y * stride + x * channels:y * stride + x * channels + 3]) for x in range(w)]
                  for y in range(h)]


def read_pfm(path):
    """(width, height, rows of (r, g, b) floats, top row first) of an RGB PFM."""
    data = open(path, "rb").read()
    header, p = [], 0
    while len(header) < 4:  # "PF", width, height, scale (whitespace-separated)
        while data[p:p + 1].isspace():
            p += 1
        q = p
        while not data[q:q + 1].isspace():
            q += 1
        header.append(data[p:q].decode())
        p = q
    p += 1
    if header[0] != "PF":
        raise ValueError(path + " is not an RGB PFM")
    w, h, scale = int(header[1]), int(header[2]), float(header[3])
    values = array.array("f")
    values.frombytes(data[p:p + 12 * w * h])
    if (scale < 0) != (sys.byteorder == "little"):
        values.byteswap()
    rows = [values[(h - 1 - y) * 3 * w:(h - y) * 3 * w] for y in range(h)]  # stored bottom row first
    return w, h, rows


def to_linear(code):
    c = code / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def to_code(linear):
    v = 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055
    return int(round(255 * v))


def main():
    tool, out = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(out, exist_ok=True)
    failures = []

    def render(name, *args):
        path = os.path.join(out, name)
        if os.path.exists(path):
            os.remove(path)
        r = subprocess.run([tool, *args, "--output", path], capture_output=True, text=True, timeout=120)
        if r.returncode != 0:
            raise SystemExit("cli pixels: %s failed (%d): %s" % (name, r.returncode, r.stderr.strip()))
        return path

    def expect_all(name, path, size, colour):
        w, h, rows = read_png(path)
        if (w, h) != size:
            failures.append("%s: %dx%d, expected %dx%d" % (name, w, h, *size))
            return
        wrong = [(x, y, rows[y][x]) for y in range(h) for x in range(w) if rows[y][x] != colour]
        if wrong:
            failures.append("%s: %d pixels differ from %s, e.g. %s" % (name, len(wrong), colour, wrong[:3]))

    colours = [(200, 60, 20), (10, 120, 240), (90, 250, 0)]
    par = os.path.join(out, "flat_par.txt")
    with open(par, "w") as f:
        f.write("3\n")
        for i, c in enumerate(colours):
            with open(os.path.join(out, "flat%d.png" % i), "wb") as img:
                img.write(flat_png(8, 6, c))
            f.write("flat%d.png 8 0 3.5 0 8 2.5 0 0 1  1 0 0 0 1 0 0 0 1  %g 0 0\n" % (i, -0.1 * (i - 1)))
    lf = ["--par", par, "--size", "8x6", "--focal-depth", "2"]
    mean = tuple(to_code(sum(to_linear(c[k]) for c in colours) / 3) for k in range(3))
    assert mean == (131, 169, 147), mean  # the hand computation itself
    expect_all("synthetic", render("flat_synthetic.png", *lf, "--interp", "synthetic"), (8, 6), mean)
    expect_all("nearest", render("flat_nearest.png", *lf, "--interp", "nearest"), (8, 6), colours[1])
    expect_all("nearest --camera 0", render("flat_camera0.png", *lf, "--interp", "nearest", "--camera", "0"), (8, 6),
               colours[0])

    lens = ["--size", "32x24", "--spp", "4", "--aperture", "disc:0.3", "--focus", "9", "--plane-centre", "0,3.1,3",
            "--look-at", "0,1.6,-8", "--plane-size", "8,6"]
    default = render("lens_default.png", *lens)
    if not filecmp.cmp(default, render("lens_8.png", *lens, "--lens-distance", "8"), shallow=False):
        failures.append("--lens-distance: the default differs from the plane's width (8)")
    if filecmp.cmp(default, render("lens_8.5.png", *lens, "--lens-distance", "8.5"), shallow=False):
        failures.append("--lens-distance: 8.5 gives the default's bytes (the option is ignored)")

    banded = ["--view", "G", "--size", "1200x1500", "--spp", "2", "--filter", "mitchell:2"]
    w, h, codes = read_png(render("banded.png", *banded))
    pw, ph, linear = read_pfm(render("banded.pfm", *banded))
    if (w, h) != (1200, 1500) or (pw, ph) != (1200, 1500):
        failures.append("banded: %dx%d PNG, %dx%d PFM, expected 1200x1500" % (w, h, pw, ph))
    else:
        rows = [y for y in range(h) if 1100 <= y < 1230 or y % 10 == 0]
        off = [(x, y) for y in rows for x in range(w)
               if any(abs(codes[y][x][k] - to_code(min(max(linear[y][3 * x + k], 0.0), 1.0))) > 1 for k in range(3))]
        if off:
            failures.append("banded: %d pixels of the 8-bit PNG differ from the PFM's codes, e.g. %s" % (len(off), off[:3]))

    for f in failures:
        print("cli pixels: FAIL " + f)
    if failures:
        return 1
    print("cli pixels: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
