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
                    normal map on its frame, texel by texel, less its mean within a voxel either
                    way) on steep rock and the beds' normal projected onto the surface; the ridges
                    follow the beds' trace on the face when it is small. lamination_coherence: how
                    directional the detail is (0 none, 1 all one way)
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


def rock_triangles(path):
    """LOD0's rock attributes and its triangles (vertex indices, n × 3)."""
    doc, binary = read_glb(path)
    for mesh in doc["meshes"]:
        if mesh["name"].startswith("rock"):
            prim = mesh["primitives"][0]
            attributes = {name: accessor(doc, binary, index).astype(np.float64)
                          for name, index in prim["attributes"].items()}
            return attributes, accessor(doc, binary, prim["indices"]).astype(np.int64).reshape(-1, 3)
    raise SystemExit(f"{path}: no rock mesh")


def box_mean(image, r):
    """Each texel's mean over the (2r + 1)² texels around it, per channel, edges clamped."""
    c = np.cumsum(np.cumsum(np.pad(image, ((r + 1, r), (r + 1, r), (0, 0)), mode="edge"), 0), 1)
    k = 2 * r + 1
    return (c[k:, k:] - c[:-k, k:] - c[k:, :-k] + c[:-k, :-k]) / (k * k)


def lamination_deg(rock_glb, normal_map, beds, h):
    """The detail's dominant direction on steep rock against the beds' normal on the face, read
    texel by texel: every covered texel of LOD0's atlas gets the normal a client shades with (the
    map on LOD0's interpolated frame, in world space), less its mean over the texels within a
    voxel either way (the detail at the laminae's scale); its component in the surface, against
    the beds' normal projected onto the surface, gives a doubled angle summed over texels weighted
    by the detail's strength. Ridges along the beds' trace tilt the normal across them: 0°."""
    rock, tris = rock_triangles(rock_glb)
    nm = normal_map[..., :3] * 2 - 1
    size = nm.shape[0]
    P, N, UV = rock["POSITION"], rock["NORMAL"], rock["TEXCOORD_0"]
    T, W = rock["TANGENT"][:, :3], rock["TANGENT"][:, 3]
    ea, eb = P[tris[:, 1]] - P[tris[:, 0]], P[tris[:, 2]] - P[tris[:, 0]]
    face = np.cross(ea, eb)
    ua, ub = UV[tris[:, 1]] - UV[tris[:, 0]], UV[tris[:, 2]] - UV[tris[:, 0]]
    uv_area = 0.5 * np.abs(ua[:, 0] * ub[:, 1] - ua[:, 1] * ub[:, 0]) * size * size
    texel = math.sqrt(0.5 * np.linalg.norm(face, axis=1).sum() / uv_area.sum())  # world units a texel
    r = max(1, int(round(h / texel)))
    face /= np.maximum(np.linalg.norm(face, axis=1, keepdims=True), 1e-12)
    shaded = np.zeros((size, size, 3))
    frame_n = np.zeros((size, size, 3))
    steep = np.zeros((size, size), bool)
    for t, (i0, i1, i2) in enumerate(tris):
        q = UV[[i0, i1, i2]] * size
        det = (q[1, 0] - q[0, 0]) * (q[2, 1] - q[0, 1]) - (q[1, 1] - q[0, 1]) * (q[2, 0] - q[0, 0])
        if abs(det) < 1e-12:
            continue
        lo = np.maximum(np.floor(q.min(0)).astype(int), 0)
        hi = np.minimum(np.ceil(q.max(0)).astype(int), size - 1)
        xs, ys = (a.ravel() for a in np.meshgrid(np.arange(lo[0], hi[0] + 1), np.arange(lo[1], hi[1] + 1)))
        px, py = xs + 0.5, ys + 0.5
        w1 = ((px - q[0, 0]) * (q[2, 1] - q[0, 1]) - (py - q[0, 1]) * (q[2, 0] - q[0, 0])) / det
        w2 = ((q[1, 0] - q[0, 0]) * (py - q[0, 1]) - (q[1, 1] - q[0, 1]) * (px - q[0, 0])) / det
        inside = (w1 >= 0) & (w2 >= 0) & (w1 + w2 <= 1)
        if not inside.any():
            continue
        w1, w2, xs, ys = w1[inside], w2[inside], xs[inside], ys[inside]
        w0 = 1 - w1 - w2
        n = w0[:, None] * N[i0] + w1[:, None] * N[i1] + w2[:, None] * N[i2]
        tg = w0[:, None] * T[i0] + w1[:, None] * T[i1] + w2[:, None] * T[i2]
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        tg /= np.linalg.norm(tg, axis=1, keepdims=True)
        bt = np.cross(n, tg) * W[i0]
        m = nm[ys, xs]
        v = m[:, 0:1] * tg + m[:, 1:2] * bt + m[:, 2:3] * n
        shaded[ys, xs] = v / np.linalg.norm(v, axis=1, keepdims=True)
        frame_n[ys, xs] = n
        steep[ys, xs] = abs(face[t, 1]) < math.cos(math.radians(60))
    covered = (np.linalg.norm(frame_n, axis=2) > 0).astype(float)[..., None]
    share = box_mean(covered, r)[..., 0]
    detail = shaded - box_mean(shaded, r) / np.maximum(share, 1e-9)[..., None]
    keep = steep & (share > 0.6)  # texels whose window lies mostly on the atlas's charts
    n, g = frame_n[keep], detail[keep]
    g -= (g * n).sum(1, keepdims=True) * n
    n_world = bed_normal(*beds)
    n_gltf = np.array([n_world[0], n_world[2], -n_world[1]])
    e = n_gltf[None, :] - (n @ n_gltf)[:, None] * n
    length = np.linalg.norm(e, axis=1)
    ok = length > 0.3
    e, g, n = e[ok] / length[ok][:, None], g[ok], n[ok]
    c, s = (g * e).sum(1), (np.cross(e, g) * n).sum(1)
    c2, s2 = (c * c - s * s).sum(), (2 * s * c).sum()
    coherence = math.hypot(c2, s2) / max((c * c + s * s).sum(), 1e-30)
    return float(abs(math.degrees(0.5 * math.atan2(s2, c2)))), float(coherence), int(ok.sum())


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
        out["lamination_deg"], out["lamination_coherence"], out["lamination_texels"] = lamination_deg(
            os.path.join(args.asset, "rock.glb"), read_map(maps[("normal", 0)]), (strike, dip), h)
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
