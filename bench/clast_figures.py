#!/usr/bin/env python3
"""The apron's stones as a client reads them: from a baked GLB (docs/model.md §13).

Reads rock.glb with nothing of rockbake's: the glTF JSON and binary chunks, node transforms
(translation, rotation, scale) applied to each clast_<k> node's mesh. Prints one JSON line:
the stone count, the sizes' 5th and 95th percentiles and their ratio, the Spearman correlation
between a stone's size and its distance from the rock's foot, the largest gap between a stone's
lowest point and the apron or ground under it, the largest overlap between two stones (share of
the smaller's volume, voxelized), and how many stones reach into the rock.

usage: clast_figures.py ASSET_DIR [VOXEL_SIZE]   (default: asset.json's clasts.voxel_size_m)
"""
import json
import math
import struct
import sys

import numpy as np


def read_glb(path):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67 and version == 2, "not a glTF 2.0 binary"
    offset, doc, binary = 12, None, b""
    while offset < length:
        size, kind = struct.unpack_from("<II", data, offset)
        chunk = data[offset + 8 : offset + 8 + size]
        if kind == 0x4E4F534A:
            doc = json.loads(chunk)
        elif kind == 0x004E4942:
            binary = chunk
        offset += 8 + size
    return doc, binary


def accessor(doc, binary, index):
    a = doc["accessors"][index]
    view = doc["bufferViews"][a["bufferView"]]
    comps = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[a["type"]]
    dtype = {5126: np.float32, 5125: np.uint32, 5123: np.uint16, 5121: np.uint8}[a["componentType"]]
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    values = np.frombuffer(binary, dtype=dtype, count=a["count"] * comps, offset=start)
    if a.get("normalized"):  # unsigned integers read as [0, 1], as glTF clients read them
        values = values / np.float64(np.iinfo(dtype).max)
    return values.reshape(a["count"], comps) if comps > 1 else values


def quat_matrix(q):
    x, y, z, w = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def mesh_triangles(doc, binary, mesh_index):
    prim = doc["meshes"][mesh_index]["primitives"][0]
    pos = accessor(doc, binary, prim["attributes"]["POSITION"]).astype(np.float64)
    idx = accessor(doc, binary, prim["indices"]).reshape(-1, 3)
    return pos, idx


def surface_height(pos, idx, points_xz):
    """Highest point of a triangle soup (y up) above each (x, z), -inf where none."""
    out = np.full(len(points_xz), -np.inf)
    a, b, c = pos[idx[:, 0]], pos[idx[:, 1]], pos[idx[:, 2]]
    lo = np.minimum(np.minimum(a, b), c)
    hi = np.maximum(np.maximum(a, b), c)
    for n, (x, z) in enumerate(points_xz):
        near = np.nonzero((lo[:, 0] <= x) & (hi[:, 0] >= x) & (lo[:, 2] <= z) & (hi[:, 2] >= z))[0]
        for t in near:
            p0, p1, p2 = a[t], b[t], c[t]
            d = (p1[0] - p0[0]) * (p2[2] - p0[2]) - (p2[0] - p0[0]) * (p1[2] - p0[2])
            if abs(d) < 1e-14:
                continue
            u = ((x - p0[0]) * (p2[2] - p0[2]) - (p2[0] - p0[0]) * (z - p0[2])) / d
            v = ((p1[0] - p0[0]) * (z - p0[2]) - (x - p0[0]) * (p1[2] - p0[2])) / d
            if u >= -1e-9 and v >= -1e-9 and u + v <= 1 + 1e-9:
                out[n] = max(out[n], p0[1] + u * (p1[1] - p0[1]) + v * (p2[1] - p0[1]))
    return out


def volume(pos, idx):
    a, b, c = pos[idx[:, 0]], pos[idx[:, 1]], pos[idx[:, 2]]
    return abs(float(np.sum(np.einsum("ij,ij->i", a, np.cross(b, c))) / 6.0))


def inside_mesh(pos, idx, pts):
    """Whether each point is inside the closed mesh: upward (+y) ray crossings are odd."""
    a, b, c = pos[idx[:, 0]], pos[idx[:, 1]], pos[idx[:, 2]]
    x, z = pts[:, 0:1], pts[:, 2:3]
    d = (b[:, 0] - a[:, 0]) * (c[:, 2] - a[:, 2]) - (c[:, 0] - a[:, 0]) * (b[:, 2] - a[:, 2])
    d = np.where(np.abs(d) < 1e-18, np.nan, d)
    u = ((x - a[:, 0]) * (c[:, 2] - a[:, 2]) - (c[:, 0] - a[:, 0]) * (z - a[:, 2])) / d
    v = ((b[:, 0] - a[:, 0]) * (z - a[:, 2]) - (x - a[:, 0]) * (b[:, 2] - a[:, 2])) / d
    y = a[:, 1] + u * (b[:, 1] - a[:, 1]) + v * (c[:, 1] - a[:, 1])
    hit = (u >= 0) & (v >= 0) & (u + v <= 1) & (y > pts[:, 1:2])
    return (np.sum(hit, axis=1) % 2) == 1


def spearman(a, b):
    ra = np.argsort(np.argsort(a)).astype(float)
    rb = np.argsort(np.argsort(b)).astype(float)
    return float(np.corrcoef(ra, rb)[0, 1])


def main():
    asset = sys.argv[1]
    doc, binary = read_glb(asset + "/rock.glb")
    meta = json.load(open(asset + "/asset.json"))
    h = float(sys.argv[2]) if len(sys.argv) > 2 else meta["clasts"]["voxel_size_m"] * meta["units_per_meter"]
    # Heights are from the ground plane: a sunk asset's is at the sink depth.
    sink = meta.get("ground", {}).get("sink_m", 0.0) * meta["units_per_meter"]
    nodes = {n["name"]: n for n in doc["nodes"]}
    rock_pos, rock_idx = mesh_triangles(doc, binary, nodes["rock_lod0"]["mesh"])
    col_pos, col_idx = mesh_triangles(doc, binary, nodes["colluvium_lod0"]["mesh"])
    rock_pos[:, 1] += sink
    col_pos[:, 1] += sink
    stones = []
    for name, node in nodes.items():
        if not name.startswith("clast_"):
            continue
        pos, idx = mesh_triangles(doc, binary, node["mesh"])
        r = quat_matrix(node.get("rotation", [0, 0, 0, 1]))
        s = np.array(node.get("scale", [1, 1, 1]))
        t = np.array(node.get("translation", [0, 0, 0]))
        world = (r @ (pos * s).T).T + t + np.array([0.0, sink, 0.0])
        stones.append({"name": name, "world": world, "idx": idx, "size": float(np.max(np.ptp(pos * s, axis=0)))})
    # The apron's toe: the colluvium's upward-facing triangles whose centre is within a voxel of
    # the ground (not the ground cap), their mean slope weighted by area.
    a, b, c = col_pos[col_idx[:, 0]], col_pos[col_idx[:, 1]], col_pos[col_idx[:, 2]]
    n = np.cross(b - a, c - a)
    area = np.linalg.norm(n, axis=1)
    centre_y = (a[:, 1] + b[:, 1] + c[:, 1]) / 3
    toe = (area > 0) & (n[:, 1] > 0) & (centre_y < h) & (np.maximum(np.maximum(a[:, 1], b[:, 1]), c[:, 1]) > 1e-6)
    slope = np.degrees(np.arccos(np.clip(n[toe, 1] / area[toe], -1, 1)))
    toe_slope = float(np.sum(slope * area[toe]) / np.sum(area[toe])) if np.any(toe) else 0.0
    if not stones:
        print(json.dumps({"stones": 0, "toe_slope_deg": round(toe_slope, 2)}))
        return
    # The rock's foot: its LOD0 vertices within a voxel of the ground, projected on the ground.
    foot = rock_pos[rock_pos[:, 1] < rock_pos[:, 1].min() + h][:, [0, 2]]
    sizes, dist, gaps, inside = [], [], [], 0
    for st in stones:
        w = st["world"]
        low = w[np.argmin(w[:, 1])]
        under = max(0.0, surface_height(col_pos, col_idx, [(low[0], low[2])])[0])
        gaps.append(abs(low[1] - under) / h)
        centre = w.mean(axis=0)
        sizes.append(st["size"])
        dist.append(float(np.min(np.hypot(foot[:, 0] - centre[0], foot[:, 1] - centre[2]))))
        # Into the rock: a stone vertex under the rock's surface where the rock stands above it.
        top = surface_height(rock_pos, rock_idx, [(v[0], v[2]) for v in w[:: max(1, len(w) // 16)]])
        inside += int(np.any((top > -np.inf) & (w[:: max(1, len(w) // 16), 1] < top - h)))
    # Overlap: points on a grid of h/6 in the boxes' intersection, inside both stones (a vertical
    # ray's crossings), over the smaller stone's volume (divergence theorem).
    worst = 0.0
    boxes = [(st["world"].min(axis=0), st["world"].max(axis=0)) for st in stones]
    for i in range(len(stones)):
        for j in range(i + 1, len(stones)):
            lo = np.maximum(boxes[i][0], boxes[j][0])
            hi = np.minimum(boxes[i][1], boxes[j][1])
            if np.any(lo >= hi):
                continue
            step = h / 6
            axes = [np.arange(lo[a] + step / 2, hi[a], step) for a in range(3)]
            if any(len(x) == 0 for x in axes):
                continue
            pts = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
            both = inside_mesh(stones[i]["world"], stones[i]["idx"], pts) & inside_mesh(
                stones[j]["world"], stones[j]["idx"], pts)
            shared = both.sum() * step**3
            smaller = min(volume(stones[i]["world"], stones[i]["idx"]), volume(stones[j]["world"], stones[j]["idx"]))
            worst = max(worst, float(shared / smaller))
    sizes, dist = np.array(sizes), np.array(dist)
    p5, p95 = np.percentile(sizes, 5), np.percentile(sizes, 95)
    print(json.dumps({
        "stones": len(stones),
        "size_p5_voxels": round(p5 / h, 3),
        "size_p95_voxels": round(p95 / h, 3),
        "size_ratio": round(p95 / p5, 2),
        "spearman_size_distance": round(spearman(sizes, dist), 3),
        "largest_gap_voxels": round(max(gaps), 3),
        "largest_overlap": round(worst, 3),
        "into_rock": inside,
        "toe_slope_deg": round(toe_slope, 2),
    }))


if __name__ == "__main__":
    main()
