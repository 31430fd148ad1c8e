"""Open a Blender asset library `rockbake blender-library` wrote, headless, as the Asset Browser would.

    blender --background --factory-startup --python-exit-code 1 \
        --python tests/delivery/blender_library_check.py -- LIBRARY EXPECTED.json

EXPECTED.json: {"assets": {NAME: {"catalog": PATH, "dir": ASSET_FOLDER}, ...}, "append": NAME}.

Lists every asset of every .blend in LIBRARY (only IDs marked as assets, as the Asset Browser reads
them) with its catalogue resolved through blender_assets.cats.txt, its tags and its preview, and
checks them against each asset folder's asset.json; checks what each .blend holds besides (the
asset of asset.json's size in metres, the further LODs and the collision hulls hidden and parented
to it, every image packed); then
appends one asset into a new scene, as dragging it from the Asset Browser does, and checks that it
brings one textured object of asset.json's size in metres. Exits 1 listing what failed.
"""
import json
import os
import re
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
library, expected = args[0], json.load(open(args[1]))
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
    return ok


def read_catalogs(path):
    """Blender's catalogue file, strictly: comments, VERSION 1, then UUID:path:simple name lines."""
    catalogs, version = {}, None
    uuid = re.compile(r"^[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}$")
    for line in open(path, encoding="utf-8").read().splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        if version is None:
            version = line
            check(line == "VERSION 1", f"the catalogue file starts {line!r}, not VERSION 1")
            continue
        parts = line.split(":")
        if not check(len(parts) == 3 and uuid.match(parts[0]), f"catalogue line {line!r} is not UUID:path:name"):
            continue
        check(parts[0] not in catalogs, f"catalogue UUID {parts[0]} twice")
        catalogs[parts[0]] = (parts[1], parts[2])
    paths = {p for p, _ in catalogs.values()}
    for path in paths:
        if "/" in path:
            check(path.rsplit("/", 1)[0] in paths, f"catalogue {path} has no parent catalogue")
    return catalogs


def asset_json(name):
    return json.load(open(os.path.join(expected["assets"][name]["dir"], "asset.json")))


def list_assets(catalogs):
    """Every asset of every .blend, linked (read, not copied) as the Asset Browser reads them."""
    found = {}
    for blend in sorted(f for f in os.listdir(library) if f.endswith(".blend")):
        path = os.path.join(library, blend)
        with bpy.data.libraries.load(path, link=True, assets_only=True) as (data_from, data_to):
            check(data_from.objects == [blend[:-6]], f"{blend}: its assets are {data_from.objects}, not one object")
            data_to.objects = data_from.objects
        for obj in data_to.objects:
            meta = obj.asset_data
            catalog = catalogs.get(meta.catalog_id, ("(not in blender_assets.cats.txt)", ""))[0]
            preview = obj.preview
            size = tuple(preview.image_size) if preview else (0, 0)
            lit = preview is not None and size[0] > 0 and any(v > 0 for v in preview.image_pixels_float[:])
            found[obj.name] = {"catalog": catalog, "tags": [t.name for t in meta.tags], "preview": size,
                               "lit": lit, "description": meta.description, "author": meta.author}
            print(f"  {obj.name:24} catalogue {catalog:20} tags {', '.join(t.name for t in meta.tags):32} "
                  f"preview {size[0]}x{size[1]}")
    return found


def check_assets(found):
    check(sorted(found) == sorted(expected["assets"]),
          f"the library's assets are {sorted(found)}, expected {sorted(expected['assets'])}")
    for name, want in expected["assets"].items():
        got = found.get(name)
        if not got:
            continue
        asset = asset_json(name)
        check(got["catalog"] == want["catalog"], f"{name}: catalogue {got['catalog']}, expected {want['catalog']}")
        check(got["tags"] == asset["tags"], f"{name}: tags {got['tags']}, asset.json has {asset['tags']}")
        check(got["lit"], f"{name}: the preview is empty ({got['preview']})")
        size = "{:.2f} × {:.2f} × {:.2f} m".format(*asset["size_m"])
        check(size in got["description"], f"{name}: the description {got['description']!r} lacks the size {size}")
        check(got["author"] == "rockbake", f"{name}: author {got['author']!r}")


def check_blend(name):
    """What the .blend holds for who opens it: LODs and hulls hidden beside the asset, images packed."""
    bpy.ops.wm.open_mainfile(filepath=os.path.join(library, name + ".blend"))
    asset = asset_json(name)
    lod0 = bpy.data.objects[name]
    lods = sorted(o.name for o in bpy.data.objects if o.name.startswith(name + "_LOD"))
    check(lods == [f"{name}_LOD{lod['level']}" for lod in asset["lods"][1:]], f"{name}: LOD objects {lods}")
    hulls = sorted(o.name for o in bpy.data.objects if o.name.startswith("UCX_"))
    want = asset.get("collision", {}).get("hull_count", 0)
    check(hulls == [f"UCX_{name}_{i:02d}" for i in range(want)], f"{name}: hulls {hulls}, expected {want}")
    for child in lods + hulls:
        obj = bpy.data.objects[child]
        check(obj.parent == lod0, f"{name}: {child} is not parented to the asset")
        check(obj.asset_data is None, f"{name}: {child} is marked as an asset")
        check(not obj.visible_get() and all(c.hide_render for c in obj.users_collection),
              f"{name}: {child} is visible or renders")
    check(lod0.visible_get(), f"{name}: the asset object is hidden")
    size, want_size = list(lod0.dimensions), asset["size_m"]
    check(all(abs(a - b) <= 1e-3 + 1e-4 * max(want_size) for a, b in zip(size, want_size)),
          f"{name}: the asset measures {size} m, asset.json says {want_size} (units_per_meter "
          f"{asset['units_per_meter']})")
    images = [i for i in bpy.data.images if i.source == "FILE"]
    check(len(images) == len(bpy.data.images), f"{name}: images that are no files: {list(bpy.data.images)}")
    check(all(i.packed_file for i in images), f"{name}: images not packed: "
          f"{[i.name for i in images if not i.packed_file]}")
    print(f"  {name}.blend: {size[0]:.3f} x {size[1]:.3f} x {size[2]:.3f} m, {len(lods)} LODs, {len(hulls)} hulls, "
          f"{len(images)} packed images, "
          f"collections {sorted(c.name for c in bpy.data.collections)}")


def images_into(socket, seen):
    """The images whose texture nodes feed `socket`, through any nodes between (glTF's COLOR_0 multiply)."""
    images = []
    for link in socket.links:
        node = link.from_node
        if node in seen:
            continue
        seen.add(node)
        if node.type == "TEX_IMAGE" and node.image is not None:
            images.append(node.image)
        for upstream in node.inputs:
            images += images_into(upstream, seen)
    return images


def image_textured(obj):
    """A material of the object feeds an image holding pixels into its Principled BSDF's base colour."""
    for slot in obj.material_slots:
        material = slot.material
        if not material or not material.use_nodes:
            continue
        bsdf = next((n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
        if bsdf and any(i.packed_file and i.size[0] > 0 for i in images_into(bsdf.inputs["Base Color"], set())):
            return True
    return False


def check_append(name):
    """Appended into a new scene as the Asset Browser appends: one textured object of size_m metres."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    before = set(bpy.data.objects)
    path = os.path.join(library, name + ".blend")
    bpy.ops.wm.append(filepath=os.path.join(path, "Object", name), directory=os.path.join(path, "Object"),
                      filename=name)
    new = [o for o in bpy.data.objects if o not in before]
    if not check(len(new) == 1 and new[0].type == "MESH", f"appending {name} brought {[o.name for o in new]}"):
        return
    obj = new[0]
    bpy.context.view_layer.update()
    size = list(obj.dimensions)
    want = asset_json(name)["size_m"]
    check(obj.name in bpy.context.scene.objects, f"{name}: the appended object is not in the scene")
    check(image_textured(obj), f"{name}: the appended object has no image-textured material")
    check(all(abs(a - b) <= 1e-3 + 1e-4 * max(want) for a, b in zip(size, want)),
          f"{name}: the appended object measures {size} m, asset.json says {want}")
    check(bpy.context.scene.unit_settings.scale_length == 1.0, "the scene's unit scale is not 1")
    print(f"  appended {obj.name}: {len(obj.data.polygons)} faces, "
          f"{sorted(s.material.name for s in obj.material_slots)}, "
          f"{size[0]:.4f} x {size[1]:.4f} x {size[2]:.4f} m (asset.json {want})")


catalogs = read_catalogs(os.path.join(library, "blender_assets.cats.txt"))
print(f"{library}: {len(catalogs)} catalogues")
check_assets(list_assets(catalogs))
for asset_name in sorted(expected["assets"]):
    check_blend(asset_name)
check_append(expected["append"])
if failures:
    print("FAIL:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("ok")
