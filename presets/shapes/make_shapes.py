#!/usr/bin/env python3
"""Writes the catalogue's generated blockouts and footprints (standard library only).

  arch.obj          an arch: a slab with a round-headed opening, extruded along y
  sea-cave.png      an L footprint whose inside corner opens towards -y +x (the camera)
  mesa.png          a lobed, irregular mesa footprint

Run from anywhere: python3 presets/shapes/make_shapes.py (writes next to itself).
"""
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write_png(path, width, height, inside):
    """1-bit-looking greyscale PNG: white (rock) where inside(x, y) with y up."""
    rows = b""
    for row in range(height):
        y = (height - 1 - row + 0.5) / height  # top row is +y
        line = bytes(255 if inside((col + 0.5) / width, y) else 0 for col in range(width))
        rows += b"\x00" + line

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def arch_obj(path, span=4.0, height=3.0, depth=1.2, opening=2.2, opening_height=1.9, n=24):
    """Closed, outward-facing prism of an arch in x-z, extruded along y.

    Outer outline: a half-superellipse from (-span/2, 0) over the top to (span/2, 0);
    inner outline: an opening of width `opening` with steep sides and a round
    head whose crown is at `opening_height`. Point i of the outer curve pairs with point i of the inner
    one, so each cap is a strip of quads between them."""
    outer, inner = [], []
    for i in range(n + 1):
        t = math.pi * (1 - i / n)  # pi .. 0: left foot to right foot
        c, s = math.cos(t), math.sin(t)
        # superellipse (exponent 0.6) keeps the shoulders full
        ox = span / 2 * math.copysign(abs(c) ** 0.6, c)
        oz = height * abs(s) ** 0.6
        # the opening: steep sides and a round head (exponent 0.45 on the height)
        ix = opening / 2 * c
        iz = opening_height * abs(s) ** 0.45
        outer.append((ox, oz))
        inner.append((ix, iz))
    verts = []
    for y in (-depth / 2, depth / 2):
        for (x, z) in outer:
            verts.append((x, y, z))
        for (x, z) in inner:
            verts.append((x, y, z))
    m = n + 1
    O = lambda side, i: side * 2 * m + i + 1       # outer vertex (1-based)
    I = lambda side, i: side * 2 * m + m + i + 1   # inner vertex
    faces = []
    for i in range(n):
        # caps: front (y = -depth/2, normal -y) and back (normal +y)
        faces.append((O(0, i), I(0, i), I(0, i + 1), O(0, i + 1)))
        faces.append((O(1, i), O(1, i + 1), I(1, i + 1), I(1, i)))
        # outer skin (normal away from the opening) and inner skin (normal into the opening)
        faces.append((O(0, i), O(0, i + 1), O(1, i + 1), O(1, i)))
        faces.append((I(0, i), I(1, i), I(1, i + 1), I(0, i + 1)))
    # the two feet, facing down
    for i in (0, n):
        a, b, c, d = O(0, i), I(0, i), I(1, i), O(1, i)
        faces.append((a, d, c, b) if i == 0 else (a, b, c, d))
    with open(path, "w") as f:
        f.write("# arch blockout written by make_shapes.py\n")
        for v in verts:
            f.write("v %.5f %.5f %.5f\n" % v)
        for face in faces:
            f.write("f " + " ".join(str(k) for k in face) + "\n")


def sea_cave(x, y):
    # Walls 0.38 of the footprint thick along the back (+y) and the left (-x).
    return y > 0.62 or x < 0.38


def mesa(x, y):
    dx, dy = x - 0.5, y - 0.5
    r = math.hypot(dx, dy)
    a = math.atan2(dy, dx)
    edge = 0.36 + 0.05 * math.sin(3 * a + 0.7) + 0.035 * math.sin(5 * a + 2.1) + 0.02 * math.sin(9 * a)
    return r < edge


if __name__ == "__main__":
    arch_obj(os.path.join(HERE, "arch.obj"))
    write_png(os.path.join(HERE, "sea-cave.png"), 64, 64, sea_cave)
    write_png(os.path.join(HERE, "mesa.png"), 128, 128, mesa)
