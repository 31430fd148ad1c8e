"""Import a baked asset into Blender as an artist would, and check what arrives.

    blender --background --factory-startup --python scripts/dcc_import_check.py -- OUT/goblin

A manual release check (Blender is too heavy for CI). It imports rock.glb and
every rock_lodN.glb into one scene, then rock.obj, then rock.ply and
colluvium.ply (each in a fresh scene), and checks, per object, what
README.md promises: the node names, the pivot (footprint centre on the
ground, z up in Blender whatever the file's up axis), closed surfaces,
triangle counts against asset.json, and the colour attributes (glTF's
COLOR_0 and the packed mask COLOR_1). With a texture set (asset.json's
"maps", docs/textures.md) every LOD's material must arrive image-textured:
its base colour map into the Principled BSDF's Base Color, its normal map
through a Normal Map node, its ORM map's G into Roughness and its R into the
importer's occlusion output; the glTF files are imported with their
vertices merged (a UV seam splits them in the file) so that the surfaces are
checked closed. The OBJ's material must bring its base colour and normal
maps. Prints what each importer gives and
exits 1 if any check failed, listing them; zero-area and folded triangles
are counted and shown but do not fail (the bake already warns about the few
it keeps).
"""
import json
import os
import sys

import bmesh
import bpy
import numpy

# Blender 3.4's glTF importer calls numpy's np.bool, which numpy 1.24 (Debian 12's)
# removed: the import fails unless Shading is set to Smooth, which drops the
# file's normals. Restore the alias so the import is the default one.
if "bool" not in numpy.__dict__:
    numpy.bool = numpy.bool_

folder = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "."
asset = json.load(open(os.path.join(folder, "asset.json")))
maps = asset.get("maps", [])  # the texture set; empty: vertex colours only
size = [s * asset["units_per_meter"] for s in asset["size_m"]]  # back to world units
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
    return "ok" if ok else "FAIL"


def fresh_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)


def mesh_objects():
    return sorted((o for o in bpy.data.objects if o.type == "MESH"), key=lambda o: o.name)


def rgba(attribute):
    values = numpy.empty(4 * len(attribute.data), numpy.float32)
    attribute.data.foreach_get("color", values)  # linear, whatever the storage
    return values.reshape(-1, 4)


def world_bbox(objs):
    pts = [o.matrix_world @ v.co for o in objs for v in o.data.vertices]
    return [min(p[a] for p in pts) for a in range(3)], [max(p[a] for p in pts) for a in range(3)]


def inspect(obj):
    """Print one object's topology and attributes; return its triangle count."""
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    boundary = sum(1 for e in bm.edges if e.is_boundary)
    non_manifold = sum(1 for e in bm.edges if not e.is_manifold)  # includes boundary edges
    zero_area = sum(1 for f in bm.faces if f.calc_area() < 1e-12)
    # A fold-over faces against every neighbour across its edges.
    folds = sum(1 for f in bm.faces
                if all(f.normal.dot(g.normal) < 0 for e in f.edges for g in e.link_faces if g is not f))
    tris = sum(len(f.verts) - 2 for f in bm.faces)
    bm.free()
    lo, hi = world_bbox([obj])
    colours = []
    for a in obj.data.color_attributes:
        c = rgba(a)
        ranges = " ".join(f"{lo:.2f}..{hi:.2f}" for lo, hi in zip(c.min(0), c.max(0)))
        colours.append(f"{a.name} ({a.domain.lower()}, {a.data_type.lower()}; RGBA {ranges})")
    others = [a.name for a in obj.data.attributes
              if not a.name.startswith(".") and a.name not in obj.data.color_attributes and a.name != "material_index"]
    print(f"  {obj.name}: {tris} triangles, {len(obj.data.vertices)} vertices; "
          f"bbox x {lo[0]:+.3f}..{hi[0]:+.3f} y {lo[1]:+.3f}..{hi[1]:+.3f} z {lo[2]:+.3f}..{hi[2]:+.3f}")
    print(f"    closed: {check(boundary == 0 and non_manifold == 0, obj.name + ' not closed')} "
          f"({boundary} boundary, {non_manifold} non-manifold edges); "
          f"zero-area faces {zero_area}, fold-overs {folds}")
    print(f"    normals: {'from the file' if obj.data.has_custom_normals else 'recomputed by Blender'}; "
          f"other attributes: {', '.join(others) or 'none'}")
    print("    colour attributes: " + ("; ".join(colours) or "none"))
    return tris


def images_into(socket, seen=None):
    """The file names of the images whose texture nodes feed `socket`, through any nodes between."""
    seen = set() if seen is None else seen
    names = set()
    for link in socket.links:
        node = link.from_node
        if node in seen:
            continue
        seen.add(node)
        if node.type == "TEX_IMAGE" and node.image is not None:
            names.add(os.path.basename(node.image.filepath))
        for s in node.inputs:
            names |= images_into(s, seen)
    return names


def map_file(kind, level):
    files = [m["file"] for m in maps if m["type"] == kind and m["lod"] == level]
    return os.path.basename(files[0]) if files else None


def check_material(obj, level, orm=True):
    """The object's material brings LOD `level`'s maps, wired as an engine reads them."""
    material = obj.active_material
    if check(material is not None and material.use_nodes, f"{obj.name}: no node material") != "ok":
        return
    nodes = material.node_tree.nodes
    bsdf = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
    if check(bsdf is not None, f"{obj.name}: no Principled BSDF") != "ok":
        return
    wired = {"base colour": (images_into(bsdf.inputs["Base Color"]), map_file("base_color", level)),
             "normal": (images_into(bsdf.inputs["Normal"]), map_file("normal", level))}
    normal_map = [l.from_node.type for l in bsdf.inputs["Normal"].links]
    check(normal_map == ["NORMAL_MAP"], f"{obj.name}: the normal map does not go through a Normal Map node")
    if orm:
        wired["roughness (ORM)"] = (images_into(bsdf.inputs["Roughness"]), map_file("orm", level))
        # Blender keeps glTF's occlusion in a group node of its own (Cycles and EEVEE ignore it;
        # it is there for the round trip back to glTF).
        occlusion = set()
        for n in nodes:
            if n.type == "GROUP" and "Occlusion" in n.inputs:
                occlusion |= images_into(n.inputs["Occlusion"])
        wired["occlusion (ORM)"] = (occlusion, map_file("orm", level))
    for what, (got, want) in wired.items():
        check(want is not None and want in got, f"{obj.name}: {what} map {want} not wired (got {sorted(got)})")
    print(f"    material {material.name}: " +
          "; ".join(f"{what} {'ok' if want in got else 'FAIL'} ({', '.join(sorted(got)) or 'none'})"
                    for what, (got, want) in wired.items()))


def check_asset(objs, label, triangles, pivot=True):
    """Size and pivot of what one file (or one LOD) holds, taken together."""
    lo, hi = world_bbox(objs)
    centre = [(lo[a] + hi[a]) / 2 for a in range(2)]
    height = hi[2] - lo[2]
    # The pivot is the centre of the voxels' footprint, the bbox's centre that of
    # the smoothed surface: allow 2 % of the footprint. A LOD may lose a little height.
    # A coarse LOD shares LOD0's frame but not its footprint (a colluvium apron
    # simplified to a few triangles shrinks): there only the ground and the
    # objects' origins are checked. (The OBJ importer turns y up into z up with
    # a rotation on the object, so its transform is not the identity.)
    centred = max(map(abs, centre)) < 0.02 * max(size[0], size[1]) or not pivot
    grounded = abs(lo[2]) < 1e-4 and all(o.matrix_world.translation.length < 1e-6 for o in objs)
    print(f"  {label}: upright {check(abs(height - size[2]) < 0.02 * size[2], label + ' height')} "
          f"(height along Z {height:.4f}, asset.json {size[2]:.4f}); "
          f"pivot {check(centred and grounded, label + ' pivot')} "
          f"(footprint centre {centre[0]:+.4f} {centre[1]:+.4f}{'' if pivot else ', not checked'}; min Z {lo[2]:+.5f})")
    tris = sum(inspect(o) for o in objs)
    print(f"    triangles {check(tris == triangles, f'{label} has {tris} triangles, asset.json {triangles}')} "
          f"({tris}, asset.json {triangles})")


# glTF: every LOD into one scene, as an artist lines a LOD chain up.
print(f"== glTF: {', '.join(l['file'] for l in asset['lods'])} in one scene")
fresh_scene()
for lod in asset["lods"]:
    # A textured LOD's vertices are split along its UV seams; merged, its surfaces are closed again.
    bpy.ops.import_scene.gltf(filepath=os.path.join(folder, lod["file"]), merge_vertices=bool(maps))
names = sorted(o.name for o in bpy.data.objects if not o.name.startswith("clast_"))
expected = sorted(f"{s}_lod{l['level']}" for l in asset["lods"] for s in ("rock", "colluvium"))
print(f"  names: {check(names == expected, f'glTF names {names}, expected {expected}')} ({' '.join(names)})")
for lod in asset["lods"]:
    objs = [bpy.data.objects[n] for n in (f"rock_lod{lod['level']}", f"colluvium_lod{lod['level']}") if n in names]
    check_asset(objs, f"LOD{lod['level']} ({lod['file']})", lod["triangles"], pivot=lod["level"] == 0)
    for o in objs:
        # COLOR_0 and COLOR_1 arrive as the first two colour attributes (COLOR_0 white with a
        # base colour map, which glTF multiplies by it); the mask's G is colluvium coverage, 1 all
        # over the colluvium surface.
        colours = o.data.color_attributes
        if check(len(colours) >= 2, f"{o.name}: COLOR_0 and COLOR_1 not both imported") == "ok":
            mask = rgba(colours[1])
            if maps:
                check(rgba(colours[0])[:, :3].min() > 0.999, f"{o.name}: COLOR_0 is not white beside the maps")
            if o.name.startswith("colluvium"):
                check(mask[:, 1].min() > 0.99, f"{o.name}: the mask's G is not 1 on the colluvium surface")
        if maps:
            check(len(o.data.uv_layers) >= 1, f"{o.name}: no UV map")
            check_material(o, lod["level"])
lod0 = asset["lods"][0]["triangles"]

clasts = asset.get("clasts")
if clasts:
    # Stones: glTF nodes sharing a mesh arrive as linked duplicates (objects sharing one mesh
    # datablock), each with the stones' material and, with a texture set, their base colour map.
    print("== glTF: rock.glb's stones")
    fresh_scene()
    bpy.ops.import_scene.gltf(filepath=os.path.join(folder, asset["lods"][0]["file"]))
    stones = [o for o in bpy.data.objects if o.name.startswith("clast_")]
    shared = {o.data.name for o in stones}
    count = clasts["lods"][0]["stones"]
    print(f"  stones {check(len(stones) == count, f'{len(stones)} stone objects, asset.json {count}')} ({len(stones)}); "
          f"linked duplicates {check(len(shared) <= clasts['shapes'] and len(shared) < len(stones), f'{len(shared)} meshes for {len(stones)} stones')} "
          f"({len(shared)} meshes)")
    for o in stones:
        check(len(o.material_slots) == 1 and o.material_slots[0].material is not None, f"{o.name}: no material")
        if maps:
            images = images_into(o.material_slots[0].material.node_tree.nodes["Principled BSDF"].inputs["Base Color"])
            check(any("Clasts_BaseColor" in i for i in images), f"{o.name}: no stone base colour map ({images})")

if os.path.exists(os.path.join(folder, "rock.obj")):  # OBJ is exported on request only
    print("== OBJ: rock.obj (y up in the file; Blender's importer turns it z up)")
    fresh_scene()
    bpy.ops.wm.obj_import(filepath=os.path.join(folder, "rock.obj"))
    objs = mesh_objects()
    print(f"  names: {' '.join(o.name for o in objs)}")
    check_asset(objs, "rock.obj", lod0)
    if maps:
        for o in objs:
            check(len(o.data.uv_layers) >= 1, f"{o.name} (OBJ): no UV map")
            check_material(o, 0, orm=False)
else:
    print("== OBJ: no rock.obj (add obj to the preset's export: list to check it)")

print("== PLY: rock.ply + colluvium.ply (z up)")
fresh_scene()
for f in ("rock.ply", "colluvium.ply"):
    if os.path.exists(os.path.join(folder, f)):
        bpy.ops.import_mesh.ply(filepath=os.path.join(folder, f))
objs = mesh_objects()
print(f"  names: {' '.join(o.name for o in objs)}")
check_asset(objs, "rock.ply + colluvium.ply", lod0)

if failures:
    print(f"FAILED: {len(failures)} check(s):\n  " + "\n  ".join(failures))
    sys.exit(1)
print("all checks passed")
