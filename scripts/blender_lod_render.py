"""Render two LODs of a baked asset side by side in Blender, with their maps, as an artist sees them.

    blender --background --factory-startup --python scripts/blender_lod_render.py -- \
        OUT/goblin OUT.png [LEFT_LOD] [RIGHT_LOD]

Imports LEFT_LOD's and RIGHT_LOD's GLB (default 0 and 3) with their texture sets
(docs/textures.md), places them side by side on the ground, lights them with a sun
and a sky and renders with Cycles on the CPU (48 samples; Debian's build has no denoiser) to OUT.png. Used
for docs/textures-blender-lods.png.
"""
import json
import math
import os
import sys

import bpy
import numpy

# Blender 3.4's glTF importer calls numpy's np.bool, which numpy 1.24 removed (see dcc_import_check.py).
if "bool" not in numpy.__dict__:
    numpy.bool = numpy.bool_

args = sys.argv[sys.argv.index("--") + 1:]
folder, out = args[0], args[1]
levels = [int(a) for a in args[2:4]] or [0, 3]
if len(levels) == 1:
    levels.append(3)
asset = json.load(open(os.path.join(folder, "asset.json")))
lods = {l["level"]: l for l in asset["lods"]}
size = [s * asset["units_per_meter"] for s in asset["size_m"]]
gap = 1.15 * max(size[0], size[1])

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
for i, level in enumerate(levels):
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=os.path.join(folder, lods[level]["file"]), merge_vertices=True)
    for o in set(bpy.data.objects) - before:
        o.location.x += (i - 0.5) * gap

bpy.ops.mesh.primitive_plane_add(size=6 * gap, location=(0, 0, 0))
ground = bpy.context.active_object
ground_material = bpy.data.materials.new("ground")
ground_material.diffuse_color = (0.18, 0.18, 0.18, 1)
ground.data.materials.append(ground_material)

sun = bpy.data.lights.new("sun", "SUN")
sun.energy = 3.5
sun.angle = math.radians(3)
sun_object = bpy.data.objects.new("sun", sun)
sun_object.rotation_euler = (math.radians(50), 0, math.radians(35))
scene.collection.objects.link(sun_object)
world = bpy.data.worlds.new("sky")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.45, 0.5, 0.6, 1)
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.6
scene.world = world

camera = bpy.data.cameras.new("camera")
camera.lens = 50
camera_object = bpy.data.objects.new("camera", camera)
# Far enough back that both fit: the pair's width in the horizontal field of view (about 40°),
# the asset's height in the vertical one (the frame is 16:9).
distance = max(3.4 * gap, 3.4 * size[2])
camera_object.location = (0, -distance, 0.5 * size[2] + 0.3 * distance)
direction = -camera_object.location.copy()
direction.z += 0.45 * size[2]
camera_object.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
scene.collection.objects.link(camera_object)
scene.camera = camera_object

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 48
scene.cycles.use_denoising = False  # Debian's Blender is built without OpenImageDenoise
scene.render.resolution_x, scene.render.resolution_y = 960, 540
scene.render.filepath = out
scene.render.image_settings.file_format = "PNG"
bpy.ops.render.render(write_still=True)
print(f"rendered LOD{levels[0]} and LOD{levels[1]} of {folder} to {out}")
