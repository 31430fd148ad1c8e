"""Import collision.glb into Blender as an artist would, and check what arrives.

    blender --background --factory-startup --python-exit-code 1 \\
        --python scripts/collision_import_check.py -- EXPECTED.json

EXPECTED.json (written by tests/collision/write_collision_sample.cpp) lists
the files beside it and, per file, every hull node: name, vertices,
triangles and bounds in the asset's frame (z up, about the pivot). Each
file is imported into a fresh scene with Blender's glTF importer; the
check fails (exit 1, naming what failed) unless the objects are exactly
the nodes, by name (no .001), each a closed, convex mesh with its normals
outward and its vertices and triangles, standing where the file put it
(z up in Blender, origin at the pivot).
"""
import json
import os
import sys

import bmesh
import bpy
import numpy

# Blender 3.4's glTF importer calls numpy's np.bool, which numpy 1.24 removed
# (see scripts/dcc_import_check.py).
if "bool" not in numpy.__dict__:
    numpy.bool = numpy.bool_

expected_file = sys.argv[sys.argv.index("--") + 1]
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

if failures:
    print(f"FAIL: {len(failures)} checks: " + "; ".join(failures))
    sys.exit(1)
print("PASS: every hull node arrives with its name, closed, convex, in place")
