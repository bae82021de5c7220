#!/usr/bin/env python3
"""Compares the PNGs of two folders (same relative paths) pixel by pixel.

Usage: png_diff.py BASE_DIR NEW_DIR
Prints one line per image: identical bytes, identical pixels, or the number of differing pixels
and the largest channel difference; images only in one folder are listed too. Exits 1 when any
image differs or is missing, 0 otherwise. Decodes 8-bit greyscale/RGB/RGBA PNGs with the
standard library only (zlib), which is all mpr writes.
"""
import os
import struct
import sys
import zlib


def decode(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, idat, width = 8, [], None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or interlace != 0 or colour not in (0, 2, 4, 6):
                raise ValueError(f"{path}: unsupported PNG (depth {depth}, colour {colour})")
            channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    raw = zlib.decompress(b"".join(idat))
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, channels, b"".join(rows)


def pngs(folder):
    out = set()
    for root, _, files in os.walk(folder):
        for f in files:
            if f.endswith(".png"):
                out.add(os.path.relpath(os.path.join(root, f), folder))
    return out


def main():
    if len(sys.argv) != 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    base, new = sys.argv[1], sys.argv[2]
    a, b = pngs(base), pngs(new)
    bad = 0
    for name in sorted(a | b):
        if name not in b or name not in a:
            print(f"MISSING   {name} (only in {'base' if name in a else 'new'})")
            bad += 1
            continue
        pa, pb = os.path.join(base, name), os.path.join(new, name)
        if open(pa, "rb").read() == open(pb, "rb").read():
            print(f"identical {name}")
            continue
        wa, ha, ca, da = decode(pa)
        wb, hb, cb, db = decode(pb)
        if (wa, ha, ca) != (wb, hb, cb):
            print(f"DIFFERENT {name}: size {wa}x{ha}x{ca} vs {wb}x{hb}x{cb}")
            bad += 1
            continue
        if da == db:
            print(f"identical {name} (pixels; file bytes differ)")
            continue
        pixels, worst = 0, 0
        for p in range(wa * ha):
            s = slice(p * ca, (p + 1) * ca)
            if da[s] != db[s]:
                pixels += 1
                worst = max(worst, max(abs(x - y) for x, y in zip(da[s], db[s])))
        print(f"DIFFERENT {name}: {pixels} of {wa * ha} pixels, largest difference {worst}/255")
        bad += 1
    print(f"{len(a | b) - bad} of {len(a | b)} images identical")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
