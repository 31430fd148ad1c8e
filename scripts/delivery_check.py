"""Check a delivery profile's GLBs the way Blender reads them (docs/delivery.md).

    blender --background --factory-startup --python-exit-code 1 \
        --python scripts/delivery_check.py -- ASSET_DIR [ASSET_DIR ...]

Imports each asset's rock.glb into one scene, as an artist gathering rocks would, and checks:
- the rock's surfaces (every mesh object but the stones) measure asset.json's size_m in metres,
  whatever units_per_meter the preset gave: glTF is metres, and so is Blender's import;
- each asset's objects keep their own materials (named after the asset, as the profile names
  them), none shared with another asset's or renamed by Blender for a clash;
- a textured material has its base colour and normal images, loaded with pixels (embedded
  images included).
Prints what it finds and exits 1 listing the failures.
"""
import json
import os
import sys

import bpy
import numpy

# Blender 3.4's glTF importer calls numpy's np.bool, which numpy 1.24 (Debian 12's) removed.
if "bool" not in numpy.__dict__:
    numpy.bool = numpy.bool_

folders = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
    return "ok" if ok else "FAIL"


bpy.ops.wm.read_factory_settings(use_empty=True)
seen_materials = {}
for folder in folders:
    asset = json.load(open(os.path.join(folder, "asset.json")))
    name = asset["name"]
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=os.path.join(folder, "rock.glb"))
    bpy.context.view_layer.update()
    objects = [o for o in bpy.data.objects if o not in before and o.type == "MESH"]
    surfaces = [o for o in objects if "clast" not in o.name]
    lo = numpy.full(3, numpy.inf)
    hi = numpy.full(3, -numpy.inf)
    for o in surfaces:
        for corner in o.bound_box:
            p = numpy.array(o.matrix_world @ __import__("mathutils").Vector(corner))
            lo, hi = numpy.minimum(lo, p), numpy.maximum(hi, p)
    size = hi - lo
    expected = numpy.array(asset["size_m"])
    ok = bool(numpy.all(numpy.abs(size - expected) <= 0.01 * expected.max()))
    print(f"{name}: {len(surfaces)} surfaces, {len(objects) - len(surfaces)} stones, size "
          f"{numpy.round(size, 4).tolist()} m, asset.json {expected.tolist()} m "
          f"(units_per_meter {asset['units_per_meter']}): {check(ok, name + ' size in metres')}")
    materials = {slot.material for o in objects for slot in o.material_slots if slot.material}
    names = sorted(m.name for m in materials)
    own = all(name in m for m in names)
    shared = [m.name for m in materials if m in seen_materials and seen_materials[m] != name]
    print(f"{name}: materials {names}: {check(own and names, name + ' materials named after the asset')}, "
          f"{check(not shared, name + ' materials not shared')}")
    for m in materials:
        seen_materials.setdefault(m, name)
        if not m.use_nodes:
            continue
        images = [n.image for n in m.node_tree.nodes if n.type == "TEX_IMAGE" and n.image]
        loaded = [i for i in images if i.size[0] > 0 and i.size[1] > 0]
        if images:
            print(f"  {m.name}: {len(loaded)} of {len(images)} images with pixels "
                  f"({', '.join(i.name for i in images)}): {check(len(loaded) == len(images), m.name + ' images')}")
rocks = [m for m in seen_materials if m.name.endswith("_rock")]
print(f"{len(rocks)} rock materials for {len(folders)} assets: "
      f"{check(len(rocks) == len(folders), 'one rock material per asset')}")
if failures:
    print("FAILED: " + "; ".join(failures))
    sys.exit(1)
print("all delivery checks passed")
