#!/usr/bin/env python3
"""How much of LOD0's atlas is spent on surface no one sees (docs/textures.md, "Hidden surface").

Reads an asset folder as a client would: rock.glb's LOD0 uvs (both surfaces, TEXCOORD_0) and the
ORM map it names (R: ambient occlusion), decoded here with zlib and numpy. A texel is covered when
its centre lies in a uv triangle; prints one JSON line: the share of the map covered, the share of
covered texels whose occlusion is below 0.05 (surface that almost no ray from outside reaches:
under the apron, the ground caps), and asset.json's LOD0 texel density.

usage: hidden_texels.py ASSET_DIR
"""
import json
import os
import struct
import sys
import zlib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clast_figures import accessor, read_glb  # noqa: E402


def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    offset, idat = 8, b""
    while offset < len(data):
        length, kind = struct.unpack_from(">I4s", data, offset)
        body = data[offset + 8 : offset + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        offset += 12 + length
    assert depth == 8 and interlace == 0, "8-bit, non-interlaced PNGs only"
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8)
    stride = width * channels
    rows = raw.reshape(height, stride + 1)
    out = np.zeros((height, stride), dtype=np.int32)
    prev = np.zeros(stride, dtype=np.int32)
    for y in range(height):
        kind, line = rows[y, 0], rows[y, 1:].astype(np.int32)
        if kind == 0:
            cur = line
        elif kind == 2:
            cur = (line + prev) & 255
        else:  # Sub, Average, Paeth: left-dependent, done per pixel
            cur = np.zeros(stride, dtype=np.int32)
            for x in range(stride):
                a = cur[x - channels] if x >= channels else 0
                b = prev[x]
                c = prev[x - channels] if x >= channels else 0
                if kind == 1:
                    p = a
                elif kind == 3:
                    p = (a + b) // 2
                else:
                    pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                    p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                cur[x] = (line[x] + p) & 255
        out[y] = cur
        prev = cur
    return out.reshape(height, width, channels)


def covered(uv_triangles, size):
    mask = np.zeros((size, size), dtype=bool)
    for tri in uv_triangles:
        p = tri * size - 0.5  # texel centres at integers
        lo = np.maximum(np.floor(p.min(axis=0)).astype(int), 0)
        hi = np.minimum(np.ceil(p.max(axis=0)).astype(int), size - 1)
        if np.any(hi < lo):
            continue
        xs, ys = np.meshgrid(np.arange(lo[0], hi[0] + 1), np.arange(lo[1], hi[1] + 1))
        a, b, c = p
        d = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        if abs(d) < 1e-12:
            continue
        u = ((xs - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (ys - a[1])) / d
        v = ((b[0] - a[0]) * (ys - a[1]) - (xs - a[0]) * (b[1] - a[1])) / d
        inside = (u >= 0) & (v >= 0) & (u + v <= 1)
        mask[ys[inside], xs[inside]] = True
    return mask


def main():
    folder = sys.argv[1]
    doc, binary = read_glb(os.path.join(folder, "rock.glb"))
    asset = json.load(open(os.path.join(folder, "asset.json")))
    orm_file = next(m["file"] for m in asset["maps"] if m["type"] == "orm" and m["lod"] == 0)
    orm = read_png(os.path.join(folder, orm_file))
    size = orm.shape[0]
    triangles = []
    for node in doc["nodes"]:
        if node["name"] not in ("rock_lod0", "colluvium_lod0"):
            continue
        prim = doc["meshes"][node["mesh"]]["primitives"][0]
        uv = accessor(doc, binary, prim["attributes"]["TEXCOORD_0"]).astype(np.float64)
        idx = accessor(doc, binary, prim["indices"]).reshape(-1, 3)
        triangles.append(uv[idx])
    mask = covered(np.concatenate(triangles), size)
    occlusion = orm[:, :, 0] / 255.0
    hidden = np.count_nonzero(mask & (occlusion < 0.05))
    print(json.dumps({
        "map_size": size,
        "covered": round(float(mask.mean()), 4),
        "covered_below_0.05_occlusion": round(hidden / max(1, np.count_nonzero(mask)), 4),
        "texel_density_lod0": asset["lods"][0].get("texel_density"),
    }))


if __name__ == "__main__":
    main()
