#!/usr/bin/env python3
"""The full set's weight and fidelity, one asset folder against another (bench/README.md,
"A lighter full set"): the same preset and seed baked by two builds.

    python3 bench/full_set_figures.py BEFORE_ASSET_DIR AFTER_ASSET_DIR

Prints each folder's size (all files, and without the render's files), the biggest files, and,
read by oiiotool as a client reads them:
- LOD0's normal-map fidelity: the mean and 99th-percentile angle between the two maps' normals
  (each decoded as glTF does, n = 2c − 1, normalised), over every texel;
- the base colour's mean absolute difference in linear RGB (sRGB decoded), LOD0 and every LOD,
  and the other colour maps' (ORM, mask, History; linear), over every texel and over the texels
  LOD0's uvs cover. A map the two folders hold at different sizes is compared as a renderer
  reads it: the smaller sampled bilinearly (glTF's linear filter, uv at each larger texel's
  centre, clamped at the edges) at every texel of the larger;
- the height map's largest difference, world units.
"""
import os
import subprocess
import struct
import sys
import zlib
import tempfile

import numpy

RENDER_FILES = ("render.exr", "render.png", "scene.pov", "rock_mesh.inc", "turntable", "turntable_sheet",
                "turntable.mp4")


def folder_bytes(folder, skip_render=False):
    total = 0
    for root, _, files in os.walk(folder):
        rel = os.path.relpath(root, folder)
        if skip_render and rel.split(os.sep)[0].startswith(RENDER_FILES):
            continue
        for f in files:
            if skip_render and rel == "." and f.startswith(RENDER_FILES):
                continue
            total += os.path.getsize(os.path.join(root, f))
    return total


def pixels(path):
    """RGB samples in [0, 1] of one of rockbake's PNGs, decoded here: zlib and PNG's Up filter, the
    only one texture/png_encoder.h writes (oiiotool 2.4's 16-bit PPM output is not usable)."""
    data = open(path, "rb").read()
    at, idat = 8, b""
    while at < len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        if kind == b"IHDR":
            w, h, bits, colour = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
    step = bits // 8
    rows = numpy.frombuffer(zlib.decompress(idat), numpy.uint8).reshape(h, w * channels * step + 1)
    if not (rows[:, 0] == 2).all():
        raise SystemExit(f"{path}: not written by rockbake's encoder (a filter other than Up)")
    raw = numpy.cumsum(rows[:, 1:].astype(numpy.uint64), axis=0).astype(numpy.uint8)
    if step == 2:
        values = raw.reshape(h, -1, 2).astype(numpy.uint32)
        samples = (values[..., 0] << 8 | values[..., 1]) / 65535.0
    else:
        samples = raw / 255.0
    return samples.reshape(h, w, channels)[..., :4]


def resampled(small, size):
    """`small` (h, w, c) sampled bilinearly at the texel centres of a size × size map."""
    def along(a, axis):
        n = a.shape[axis]
        x = (numpy.arange(size) + 0.5) * n / size - 0.5
        x0 = numpy.floor(x).astype(int)
        t = (x - x0).reshape([-1 if d == axis else 1 for d in range(a.ndim)])
        return numpy.take(a, numpy.clip(x0, 0, n - 1), axis) * (1 - t) + numpy.take(a, numpy.clip(x0 + 1, 0, n - 1), axis) * t
    return along(along(small, 0), 1)


def same_size(a, b):
    """Both maps at the larger's size (the smaller resampled)."""
    size = max(a.shape[0], b.shape[0])
    return tuple(m if m.shape[0] == size else resampled(m, size) for m in (a, b))


def covered_texels(asset, size):
    """Texels whose centre LOD0's rock or colluvium uvs cover (tests/compress/normal_fidelity.py)."""
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, os.path.join(here, "..", "tests", "compress"))
    from normal_fidelity import covered  # noqa: E402
    from clast_figures import read_glb  # noqa: E402
    doc, binary = read_glb(os.path.join(asset, "rock.glb"))
    return covered(doc, binary, size)


def normals(path):
    c = pixels(path)[..., :3].astype(numpy.float64)
    n = 2 * c - 1
    return n / numpy.maximum(numpy.linalg.norm(n, axis=2, keepdims=True), 1e-12)


def linear(srgb):
    return numpy.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)


def main():
    before, after = sys.argv[1], sys.argv[2]
    for label, folder in (("before", before), ("after", after)):
        print(f"{label}: {folder_bytes(folder) / 1e6:.1f} MB in all, "
              f"{folder_bytes(folder, skip_render=True) / 1e6:.1f} MB without the render's files")
        sizes = []
        for root, _, files in os.walk(folder):
            for f in files:
                p = os.path.join(root, f)
                sizes.append((os.path.getsize(p), os.path.relpath(p, folder)))
        print("   largest: " + ", ".join(f"{n} {s / 1e6:.2f}" for s, n in sorted(sizes, reverse=True)[:8]))
    tex_b, tex_a = os.path.join(before, "textures"), os.path.join(after, "textures")
    name = os.path.basename(os.path.normpath(before))
    nb, na = normals(os.path.join(tex_b, f"{name}_Normal_LOD0.png")), normals(os.path.join(tex_a, f"{name}_Normal_LOD0.png"))
    angle = numpy.degrees(numpy.arccos(numpy.clip((nb * na).sum(axis=2), -1, 1)))
    print(f"LOD0 normals: mean {angle.mean():.3f}°, 99th percentile {numpy.percentile(angle, 99):.3f}°, "
          f"largest {angle.max():.3f}°")
    mask = covered_texels(after, nb.shape[0])
    for f in sorted(os.listdir(tex_b)):
        kind = next((k for k in ("_BaseColor", "_ORM", "_Mask", "_History") if k in f), None)
        if kind is None or "_Clasts" in f or not os.path.exists(os.path.join(tex_a, f)):
            continue
        a, b = pixels(os.path.join(tex_b, f)), pixels(os.path.join(tex_a, f))
        if kind == "_BaseColor":
            a, b = linear(a[..., :3]), linear(b[..., :3])
        sizes = f"{a.shape[0]} → {b.shape[0]}"
        a, b = same_size(a, b)
        d = numpy.abs(a - b)
        line = f"{f} ({sizes}): mean |Δ| {d.mean():.5f} linear"
        if a.shape[0] == mask.shape[0]:
            line += f", {d[mask].mean():.5f} on LOD0's covered texels (99th percentile {numpy.percentile(d[mask], 99):.4f})"
        print(line)
    hb, ha = os.path.join(tex_b, f"{name}_Height.exr"), os.path.join(tex_a, f"{name}_Height.exr")
    if os.path.exists(hb) and os.path.exists(ha):
        diff = subprocess.run(["oiiotool", hb, ha, "--diff"], capture_output=True, text=True).stdout
        print("height, oiiotool --diff: " + "; ".join(l.strip() for l in diff.splitlines() if "error" in l.lower()))


if __name__ == "__main__":
    main()
