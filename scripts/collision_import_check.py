"""Import collision.glb into Blender as an artist would, and check what arrives.

    blender --background --factory-startup --python-exit-code 1 \\
        --python scripts/collision_import_check.py -- EXPECTED.json [ASSET_FOLDER]

EXPECTED.json (written by tests/collision/write_collision_sample.cpp) lists
the files beside it and, per file, every hull node: name, vertices,
triangles and bounds in the asset's frame (z up, about the pivot). Each
file is imported into a fresh scene with Blender's glTF importer; the
check fails (exit 1, naming what failed) unless the objects are exactly
the nodes, by name (no .001), each a closed, convex mesh with its normals
outward and its vertices and triangles, standing where the file put it
(z up in Blender, origin at the pivot).

ASSET_FOLDER, a baked asset: its rock.glb and collision.glb are imported into
one scene, as an artist pairs them; every hull asset.json lists must arrive
under its name, closed and convex, with asset.json's vertex count and volume
(m³ times units_per_meter³), beside the rock.glb object its name pairs with
(UCX_<mesh>_NN, <mesh>_NN-convcolonly).
"""
import json
import os
import re
import sys

import bmesh
import bpy
import numpy

# Blender 3.4's glTF importer calls numpy's np.bool, which numpy 1.24 removed
# (see scripts/dcc_import_check.py).
if "bool" not in numpy.__dict__:
    numpy.bool = numpy.bool_

arguments = sys.argv[sys.argv.index("--") + 1:]
expected_file = arguments[0]
asset_folder = arguments[1] if len(arguments) > 1 else None
folder = os.path.dirname(os.path.abspath(expected_file))
expected = json.load(open(expected_file))
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
    return "ok" if ok else "FAIL"


def inspect(obj, node):
    name = obj.name
    mesh = obj.data
    bm = bmesh.new()
    bm.from_mesh(mesh)
    bm.normal_update()
    boundary = sum(1 for e in bm.edges if e.is_boundary)
    non_manifold = sum(1 for e in bm.edges if not e.is_manifold)
    triangles = sum(len(f.verts) - 2 for f in bm.faces)
    # Convex and outward: every vertex on the inner side of every face's plane.
    size = max(h - l for l, h in zip(node["min"], node["max"]))
    worst = max((f.normal.dot(v.co - f.verts[0].co) for f in bm.faces for v in bm.verts), default=0.0)
    bm.free()
    pts = [obj.matrix_world @ v.co for v in mesh.vertices]
    lo = [min(p[a] for p in pts) for a in range(3)]
    hi = [max(p[a] for p in pts) for a in range(3)]
    off = max(max(abs(lo[a] - node["min"][a]), abs(hi[a] - node["max"][a])) for a in range(3))
    print(f"  {name}: {len(mesh.vertices)} vertices, {triangles} triangles; "
          f"bbox x {lo[0]:+.3f}..{hi[0]:+.3f} y {lo[1]:+.3f}..{hi[1]:+.3f} z {lo[2]:+.3f}..{hi[2]:+.3f}")
    print(f"    closed {check(boundary == 0 and non_manifold == 0, name + ' not closed')} "
          f"({boundary} boundary, {non_manifold} non-manifold edges); "
          f"convex and outward {check(worst <= 1e-4 * size, name + ' not convex or not outward')} "
          f"(farthest vertex outside a face {worst:.2g}); "
          f"counts {check(len(mesh.vertices) == node['vertices'] and triangles == node['triangles'], name + ' counts')} "
          f"(file: {node['vertices']}, {node['triangles']}); "
          f"in place {check(off <= 1e-4 * size and obj.matrix_world.translation.length < 1e-9, name + ' not in place')} "
          f"(bounds off by {off:.2g})")
    check(len(mesh.vertices) <= expected["max_vertices"], name + " over the vertex cap")


for entry in expected["files"]:
    path = os.path.join(folder, entry["file"])
    print(f"== {entry['file']}")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=path)
    objects = {o.name: o for o in bpy.data.objects}
    names = sorted(objects)
    wanted = sorted(n["name"] for n in entry["nodes"])
    print(f"  names: {check(names == wanted, entry['file'] + ': object names ' + str(names))} "
          f"({len(names)} objects: {' '.join(names[:3])} …)")
    for node in entry["nodes"]:
        obj = objects.get(node["name"])
        if check(obj is not None and obj.type == "MESH", f"{entry['file']}: no mesh object {node['name']}") == "ok":
            inspect(obj, node)



def check_asset(folder):
    asset = json.load(open(os.path.join(folder, "asset.json")))
    collision = asset["collision"]
    units3 = asset["units_per_meter"] ** 3
    print(f"== {folder}: rock.glb and {collision['file']} ({collision['naming']} names)")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=os.path.join(folder, "rock.glb"))
    render_objects = sorted(o.name for o in bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=os.path.join(folder, collision["file"]))
    objects = {o.name: o for o in bpy.data.objects}
    hull_names = sorted(h["node"] for h in collision["hulls"])
    names = sorted(n for n in objects if n not in render_objects)
    print(f"  names: {check(names == hull_names, 'hull objects ' + str(names))} "
          f"({len(names)} hulls beside {' '.join(render_objects)})")
    pattern = r"UCX_(.+)_\d\d" if collision["naming"] == "unreal" else r"(.+)_\d\d-convcolonly"
    for hull in collision["hulls"]:
        name = hull["node"]
        obj = objects.get(name)
        if check(obj is not None and obj.type == "MESH", f"no mesh object {name}") != "ok":
            continue
        paired = re.fullmatch(pattern, name)
        check(paired is not None and paired.group(1) in render_objects, f"{name} pairs with no object of rock.glb")
        bm = bmesh.new()
        bm.from_mesh(obj.data)
        closed = all(e.is_manifold for e in bm.edges)
        volume = bm.calc_volume(signed=True)
        bm.free()
        wanted = hull["volume_m3"] * units3
        print(f"  {name}: pairs with {paired.group(1) if paired else None}; {len(obj.data.vertices)} vertices "
              f"{check(len(obj.data.vertices) == hull['vertices'], name + ' vertices')}; closed "
              f"{check(closed, name + ' not closed')}; volume {volume:.6g} "
              f"{check(abs(volume - wanted) <= 1e-4 * wanted + 1e-9, name + ' volume')} (asset.json {wanted:.6g})")


if asset_folder:
    check_asset(asset_folder)

if failures:
    print(f"FAIL: {len(failures)} checks: " + "; ".join(failures))
    sys.exit(1)
print("PASS: every hull node arrives with its name, closed, convex, in place")
