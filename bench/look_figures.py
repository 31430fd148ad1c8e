#!/usr/bin/env python3
"""The look as a client reads it: from a baked asset's GLBs and maps (docs/textures.md, "The look").

Reads rock.glb, rock_lod<k>.glb and the maps asset.json lists with nothing of rockbake's (the glTF
chunks by hand, the PNGs through oiiotool), and prints one JSON line of figures:

  streak_ratio      on LOD0 rock steeper than 70°, the mean |Δ stain| (History G) between vertex
                    pairs 2–4 voxels apart lying side by side, over that between pairs lying one
                    above the other: streaks run down the fall line when it is well above 1
  scar_brightness   base-colour luminance on fresh rockfall scars (_SCAR ≥ 0.3) over that of the
                    unscarred rock of the same layer (durability within 5 % of the range) within 6
                    voxels, averaged over scar vertices: scars are paler when it is above 1
  varnish_age_rho   Spearman's rho between stain/varnish (History G) and exposure age (History R)
                    over LOD0's rock vertices
  lamination_deg    with --beds STRIKE,DIP (world, z up; the preset's geology fixed): the angle
                    between the dominant direction of the detail a client shades with (LOD0's
                    normal map on its frame, less its mean within two voxels) on steep rock and the
                    beds' normal projected onto the surface; the ridges follow the beds' trace on
                    the face when it is small
  base_vs_vertex    per LOD, the mean absolute difference (linear) between its base-colour map at
                    its vertices and the colour of the nearest vertex of LOD0 in rock.ply

usage: look_figures.py ASSET_DIR [--voxel H] [--beds STRIKE,DIP]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from clast_figures import accessor, read_glb  # noqa: E402


def read_map(path):
    """A PNG's channels as floats 0..1 (8 or 16 bit), through oiiotool to a PNM per channel."""
    info = subprocess.run(["oiiotool", "--info", "-v", path], capture_output=True, text=True, check=True).stdout
    channels = 4 if "4 channel" in info else 3 if "3 channel" in info else 1
    planes = []
    with tempfile.TemporaryDirectory() as tmp:
        for c in range(channels):
            out = os.path.join(tmp, f"c{c}.pgm")
            # The History map's alpha is data (dust), not coverage: read the colour as stored.
            subprocess.run(["oiiotool", "--iconfig", "oiio:UnassociatedAlpha", "1", path, "--ch", str(c), "-o", out],
                           check=True, capture_output=True)
            data = open(out, "rb").read()
            fields, at = [], 0
            while len(fields) < 4:  # P5 width height maxval, then one whitespace
                while data[at : at + 1].isspace():
                    at += 1
                end = at
                while not data[end : end + 1].isspace():
                    end += 1
                fields.append(data[at:end])
                at = end
            at += 1
            w, h, maxval = int(fields[1]), int(fields[2]), int(fields[3])
            dtype = np.dtype(">u2") if maxval > 255 else np.uint8
            planes.append(np.frombuffer(data, dtype=dtype, count=w * h, offset=at).reshape(h, w) / maxval)
    return np.stack(planes, axis=-1)


def sample(image, uv):
    """Nearest texel at glTF uvs ((0, 0) the top-left corner)."""
    h, w = image.shape[:2]
    x = np.clip((uv[:, 0] * w).astype(int), 0, w - 1)
    y = np.clip((uv[:, 1] * h).astype(int), 0, h - 1)
    return image[y, x]


def srgb_to_linear(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def rock_primitive(path):
    doc, binary = read_glb(path)
    for mesh in doc["meshes"]:
        if mesh["name"].startswith("rock"):
            prim = mesh["primitives"][0]
            return {name: accessor(doc, binary, index).astype(np.float64) for name, index in prim["attributes"].items()}
    raise SystemExit(f"{path}: no rock mesh")


def read_ply_colours(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    n = int(header.split("element vertex ")[1].split()[0])
    record = np.dtype([("p", "<f4", 3), ("n", "<f4", 3), ("c", "u1", 3), ("a", "<f4", 3)])
    v = np.frombuffer(data, dtype=record, count=n, offset=end)
    return v["p"].astype(np.float64), srgb_to_linear(v["c"] / 255.0)


def ranks(x):
    order = np.argsort(x, kind="stable")
    r = np.empty(len(x))
    r[order] = np.arange(len(x))
    return r


def spearman(a, b):
    return float(np.corrcoef(ranks(a), ranks(b))[0, 1])


def neighbour_pairs(points, lo, hi, limit, seed=1):
    """Up to `limit` vertex pairs (i, j) lo ≤ |p_i − p_j| ≤ hi, drawn from a cell grid."""
    cell = hi
    keys = np.floor(points / cell).astype(np.int64)
    buckets = {}
    for i, k in enumerate(map(tuple, keys)):
        buckets.setdefault(k, []).append(i)
    rng = np.random.default_rng(seed)
    pairs = []
    for i in rng.permutation(len(points)):
        k = keys[i]
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in buckets.get((k[0] + dx, k[1] + dy, k[2] + dz), ()):
                        if j > i:
                            d = np.linalg.norm(points[j] - points[i])
                            if lo <= d <= hi:
                                pairs.append((i, j))
        if len(pairs) >= limit:
            break
    return np.array(pairs, dtype=np.int64).reshape(-1, 2)


def streak_ratio(rock, history, h):
    steep = np.abs(rock["NORMAL"][:, 1]) < math.cos(math.radians(70))
    idx = np.nonzero(steep)[0]
    p = rock["POSITION"][idx]
    stain = sample(history, rock["TEXCOORD_0"][idx])[:, 1]
    pairs = neighbour_pairs(p, 2 * h, 4 * h, 400000)
    d = p[pairs[:, 1]] - p[pairs[:, 0]]
    length = np.linalg.norm(d, axis=1)
    same_face = np.einsum("ij,ij->i", rock["NORMAL"][idx][pairs[:, 0]], rock["NORMAL"][idx][pairs[:, 1]]) > 0.8
    vertical = np.abs(d[:, 1]) / length
    diff = np.abs(stain[pairs[:, 1]] - stain[pairs[:, 0]])
    side = same_face & (vertical < 0.25)
    above = same_face & (vertical > 0.9)
    return float(diff[side].mean() / max(diff[above].mean(), 1e-9)), int(side.sum()), int(above.sum())


def scar_brightness(rock, base, h):
    if "_SCAR" not in rock:
        return None, 0
    lum = srgb_to_linear(sample(base, rock["TEXCOORD_0"])) @ np.array([0.2126, 0.7152, 0.0722])
    scar = rock["_SCAR"]
    dur = rock["_DURABILITY"]
    span = max(dur.max() - dur.min(), 1e-9)
    fresh = np.nonzero(scar >= 0.3)[0]
    plain = np.nonzero(scar == 0)[0]
    if len(fresh) == 0:
        return None, 0
    p = rock["POSITION"]
    ratios = []
    for i in fresh[:: max(1, len(fresh) // 3000)]:
        near = plain[np.linalg.norm(p[plain] - p[i], axis=1) <= 6 * h]
        near = near[np.abs(dur[near] - dur[i]) <= 0.05 * span]
        if len(near) >= 5:
            ratios.append(lum[i] / max(lum[near].mean(), 1e-6))
    return (float(np.mean(ratios)) if ratios else None), len(ratios)


def bed_normal(strike, dip):
    """The beds' upward normal (world, z up), as docs/model.md §4 defines strike and dip: planes
    striking `strike` degrees clockwise from +y, dipping `dip` degrees towards the strike's right."""
    s, d = math.radians(strike), math.radians(dip)
    right = np.array([math.cos(s), -math.sin(s), 0.0])
    return np.array([math.sin(d) * right[0], math.sin(d) * right[1], math.cos(d)])


def lamination_deg(rock, normal_map, beds, h):
    """The detail's dominant direction on steep rock against the beds' trace. The detail normal is
    what a client shades with, the normal map on LOD0's frame, less its mean within two voxels
    (LOD0 keeps relief coarser than its error bound in its own shape, finer relief is in the map)."""
    n_world = bed_normal(*beds)
    n_gltf = np.array([n_world[0], n_world[2], -n_world[1]])
    N = rock["NORMAL"]
    T = rock["TANGENT"][:, :3]
    B = np.cross(N, T) * rock["TANGENT"][:, 3:4]
    t = sample(normal_map, rock["TEXCOORD_0"]) * 2 - 1
    shaded = t[:, 0:1] * T + t[:, 1:2] * B + t[:, 2:3] * N
    shaded /= np.linalg.norm(shaded, axis=1, keepdims=True)
    p = rock["POSITION"]
    cell = 2 * h
    keys = np.floor(p / cell).astype(np.int64)
    buckets = {}
    for i, k in enumerate(map(tuple, keys)):
        buckets.setdefault(k, []).append(i)
    steep = np.nonzero(np.abs(N[:, 1]) < math.cos(math.radians(60)))[0]
    e_all = n_gltf - np.outer(N @ n_gltf, np.ones(3)) * N
    c_sum = s_sum = 0.0
    used = 0
    for i in steep[:: max(1, len(steep) // 20000)]:
        e = e_all[i]
        if np.linalg.norm(e) < 0.3:
            continue
        k = keys[i]
        near = [j for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                for j in buckets.get((k[0] + dx, k[1] + dy, k[2] + dz), ())]
        near = np.array(near)
        near = near[np.linalg.norm(p[near] - p[i], axis=1) <= cell]
        if len(near) < 6:
            continue
        g = shaded[i] - shaded[near].mean(axis=0)
        g -= N[i] * (g @ N[i])
        e = e / np.linalg.norm(e)
        c, s = g @ e, np.cross(e, g) @ N[i]
        c_sum += c * c - s * s
        s_sum += 2 * s * c
        used += 1
    return float(abs(math.degrees(0.5 * math.atan2(s_sum, c_sum)))), used


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("asset")
    parser.add_argument("--voxel", type=float, help="the grid's h (default: from stats.json and asset.json)")
    parser.add_argument("--beds")
    args = parser.parse_args()
    asset = json.load(open(os.path.join(args.asset, "asset.json")))
    maps = {(m["type"], m["lod"]): os.path.join(args.asset, m["file"]) for m in asset["maps"]}
    stats = json.load(open(os.path.join(args.asset, "stats.json")))
    h = args.voxel or max(asset["individual"]["grid_size"]) / stats["preset"]["grid"]["resolution"]
    rock = rock_primitive(os.path.join(args.asset, "rock.glb"))
    history = read_map(maps[("history", 0)])
    base = read_map(maps[("base_color", 0)])
    out = {}
    out["streak_ratio"], out["streak_pairs_side"], out["streak_pairs_above"] = streak_ratio(rock, history, h)
    out["scar_brightness"], out["scar_vertices"] = scar_brightness(rock, base, h)
    g = sample(history, rock["TEXCOORD_0"])
    out["varnish_age_rho"] = spearman(g[:, 1], g[:, 0])
    if args.beds:
        strike, dip = (float(x) for x in args.beds.split(","))
        out["lamination_deg"], out["lamination_vertices"] = lamination_deg(
            rock, read_map(maps[("normal", 0)]), (strike, dip), h)
    ply = os.path.join(args.asset, "rock.ply")
    if os.path.exists(ply):
        p0, c0 = read_ply_colours(ply)
        p0_gltf = np.stack([p0[:, 0], p0[:, 2], -p0[:, 1]], axis=1)
        cell = 2 * h
        buckets = {}
        for i, k in enumerate(map(tuple, np.floor(p0_gltf / cell).astype(np.int64))):
            buckets.setdefault(k, []).append(i)
        per_lod = []
        for lod in asset["lods"]:
            mesh = rock_primitive(os.path.join(args.asset, lod["file"]))
            colour = srgb_to_linear(sample(read_map(maps[("base_color", lod["level"])]), mesh["TEXCOORD_0"]))
            diffs = []
            for i, q in enumerate(mesh["POSITION"][:: max(1, len(mesh["POSITION"]) // 5000)]):
                k = np.floor(q / cell).astype(np.int64)
                near = [j for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                        for j in buckets.get((k[0] + dx, k[1] + dy, k[2] + dz), ())]
                if near:
                    j = near[int(np.argmin(np.linalg.norm(p0_gltf[near] - q, axis=1)))]
                    diffs.append(np.abs(colour[i * max(1, len(mesh["POSITION"]) // 5000)] - c0[j]).mean())
            per_lod.append(round(float(np.mean(diffs)), 4))
        out["base_vs_vertex"] = per_lod
    print(json.dumps(out))


if __name__ == "__main__":
    main()
