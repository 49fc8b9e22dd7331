"""Writes the images of the texture and light scenes: scenes/textures/plaid.png, tiles.png,
goniometric.png and dimples.png.

Usage: python3 scripts/make_textures.py [out_dir]   (default: scenes/textures)
Deterministic, standard library only (PNG through zlib), so rerunning it reproduces the files.

plaid.png: a 200 x 200 8-bit sRGB tartan of red, navy and gold bands with thin white lines, made
from one stripe sequence across and down. 200 is not a power of two on purpose: pbrt-v4 (and
pbrt_ext) resample such an image up to 256 x 256 before building its MIP pyramid.
tiles.png: a 256 x 256 8-bit gray image of 8 x 8 light tiles with dark 2-texel grout lines, the
high-contrast, high-frequency pattern that a floor seen at a grazing angle aliases.
goniometric.png: a 64 x 64 8-bit gray goniometric diagram in pbrt's equal-area octahedral
square: |u - 1/2| + |v - 1/2| grows from the pole at the centre to the opposite pole at the
corners, so bands of it are bands of latitude; bright bands alternate with dim ones, brightest
around the pole, and one quadrant (an azimuth range) is dimmed.
dimples.png: a 128 x 128 8-bit tangent-space normal map (rgb = (n + 1) / 2, read linearly, as
pbrt-v4 reads normal maps) of 4 x 4 round dimples, each the bottom of a sphere half a cell in
radius cut 0.4 cells wide: normals tilt toward each dimple's centre, up to 53 degrees at its rim,
and are flat between the dimples.
"""
import math
import os
import struct
import sys
import zlib


def write_png(path, width, height, channels, pixel):
    """pixel(x, y) -> tuple of `channels` bytes; 8-bit gray (1) or RGB (3), top row first."""
    rows = b"".join(b"\0" + bytes(v for x in range(width) for v in pixel(x, y)) for y in range(height))
    color_type = {1: 0, 3: 2}[channels]

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, 8, color_type, 0, 0, 0)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


# The tartan's sett: (colour, width in texels), repeated across 200 texels.
RED, NAVY, GOLD, WHITE = (170, 20, 30), (20, 30, 80), (210, 170, 60), (235, 235, 230)
SETT = [(RED, 24), (NAVY, 12), (RED, 4), (WHITE, 2), (RED, 4), (NAVY, 12), (GOLD, 6), (NAVY, 12), (RED, 16), (GOLD, 4), (RED, 4)]


def band(i):
    i %= sum(w for _, w in SETT)
    for colour, w in SETT:
        if i < w:
            return colour
        i -= w
    return SETT[-1][0]


def plaid(x, y):
    # A twill: warp and weft alternate diagonally, so each texel shows one band's colour.
    return band(x) if (x + y) % 4 < 2 else band(y)


def tiles(x, y):
    grout = x % 32 < 2 or y % 32 < 2
    return (40,) if grout else (215,)


def goniometric(x, y):
    u, v = (x + 0.5) / 64 - 0.5, (y + 0.5) / 64 - 0.5
    latitude = abs(u) + abs(v)  # 0 at the pole, 1 at the opposite one
    band = 1.0 if int(latitude * 8) % 2 == 0 else 0.25
    level = band * (1 - 0.6 * latitude) * (0.3 if u > 0 and v > 0 else 1.0)
    return (int(round(255 * level)),)


def dimples(x, y):
    # Offsets from the cell's centre in cells; inside the rim the surface is z = -sqrt(R^2 - d^2).
    dx, dy = (x % 32 + 0.5) / 32 - 0.5, (y % 32 + 0.5) / 32 - 0.5
    sphere, rim = 0.5, 0.4
    n = (0.0, 0.0, 1.0)
    if dx * dx + dy * dy < rim * rim:
        n = (-dx / sphere, -dy / sphere, math.sqrt(sphere * sphere - dx * dx - dy * dy) / sphere)
    return tuple(int(round(255 * (c + 1) / 2)) for c in n)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes", "textures")
    write_png(os.path.join(out, "plaid.png"), 200, 200, 3, plaid)
    write_png(os.path.join(out, "tiles.png"), 256, 256, 1, tiles)
    write_png(os.path.join(out, "goniometric.png"), 64, 64, 1, goniometric)
    write_png(os.path.join(out, "dimples.png"), 128, 128, 3, dimples)


if __name__ == "__main__":
    main()
