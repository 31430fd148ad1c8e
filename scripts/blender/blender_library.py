"""One asset of a Blender asset library, written by Blender for `rockbake blender-library`.

rockbake runs it once per asset (baker/delivery/blender_library.h; docs/libraries.md,
"Blender's asset browser"), as

    blender --background --factory-startup -noaudio --python-exit-code 1 \
        --python blender_library.py -- JOB

JOB is one JSON object: the asset folder, the temporary .blend to save, the LOD files and
collision.glb, the preview, and what rockbake made of asset.json and the manifest (the
catalogue's UUID, path and simple name, the description, the tags, custom properties).
The script imports with Blender's own glTF importer and builds:

    Scene
      <asset>                  collection
        <asset>                LOD0 (rock.glb: rock, colluvium and stones joined), marked as an
                               asset: catalogue, description, author, tags, preview
        <asset> LODs           collection, excluded from the view layer, not rendered:
          <asset>_LOD1 ...     each further LOD joined likewise, parented to LOD0
        <asset> collision      collection, excluded from the view layer, not rendered:
          UCX_<asset>_00 ...   the hulls of collision.glb (Godot: <asset>_00-convcolonly), wire,
                               parented to LOD0

so that dragging the asset from the Asset Browser appends LOD0 alone, and opening the .blend
shows everything. Every image is packed into the .blend (its path set to //textures/<file>, where
File > External Data > Unpack puts it). The preview is the bake's still render (render.png)
loaded as a custom preview; without one, a small Cycles render of LOD0. Nothing is scaled:
glTF positions are metres, and the object's dimensions are checked against asset.json's size_m.

The last line printed is `ROCKBAKE_BLENDER_RESULT {json}`: what was written, and warnings.
Any exception is a failure: the script prints `ROCKBAKE_BLENDER_ERROR <what went wrong>`, which
rockbake reports (the traceback with -v), Blender exits 1 (--python-exit-code), and rockbake
removes the temporary file.
"""
import hashlib
import json
import math
import os
import re
import sys
import tempfile

import bpy
import mathutils
import numpy

# Blender 3.4's glTF importer calls numpy's np.bool, which numpy 1.24 (Debian 12's) removed.
if "bool" not in numpy.__dict__:
    numpy.bool = numpy.bool_

RESULT_PREFIX = "ROCKBAKE_BLENDER_RESULT "
ERROR_PREFIX = "ROCKBAKE_BLENDER_ERROR "
warnings = []


def import_glb(path):
    """The objects Blender's glTF importer makes of `path`, in the scene collection."""
    before = set(bpy.data.objects)
    try:
        result = bpy.ops.import_scene.gltf(filepath=path)
    except RuntimeError as e:
        raise RuntimeError(f"Blender's glTF importer cannot read {path}: {str(e).replace('Error: ', '')}") from e
    if "FINISHED" not in result:
        raise RuntimeError(f"Blender's glTF importer cannot read {path}")
    return [o for o in bpy.data.objects if o not in before]


def join(objects, name):
    """The mesh objects joined into one named `name`, at the origin with no transform; the rest removed."""
    meshes = [o for o in objects if o.type == "MESH"]
    if not meshes:
        raise RuntimeError(f"{name}: the file holds no mesh")
    for o in objects:
        if o.type != "MESH":
            bpy.data.objects.remove(o)
    target = next((o for o in meshes if "rock_lod" in o.name), meshes[0])  # SM_<name>_rock_lod0 in Unreal's
    if len(meshes) > 1:
        with bpy.context.temp_override(active_object=target, object=target, selected_objects=meshes,
                                       selected_editable_objects=meshes):
            bpy.ops.object.join()
    if target.matrix_world != mathutils.Matrix.Identity(4):
        target.data.transform(target.matrix_world)
        target.matrix_world = mathutils.Matrix.Identity(4)
    target.name = name
    target.data.name = name
    if target.name != name:
        warnings.append(f"Blender shortened the object name {name!r} to {target.name!r}")
    return target


def base_name(name):
    """A datablock name without the .001 Blender adds to a second of the same name."""
    return re.sub(r"\.\d{3}$", "", name)


def move_to(obj, collection):
    for c in list(obj.users_collection):
        c.objects.unlink(obj)
    collection.objects.link(obj)


def new_collection(name, parent):
    collection = bpy.data.collections.new(name)
    parent.children.link(collection)
    return collection


def hide_collection(collection):
    """Excluded from the view layer (its Outliner checkbox off) and from renders: there for who opens the file."""
    collection.hide_render = True

    def find(layer):
        if layer.collection == collection:
            return layer
        for child in layer.children:
            found = find(child)
            if found:
                return found
        return None

    find(bpy.context.view_layer.layer_collection).exclude = True


def import_lod0(job, folder):
    lod0 = join(import_glb(os.path.join(folder, job["lods"][0]["file"])), job["name"])
    lod0.data.name = job["name"]
    return lod0


def import_lods(job, folder, lod0, collection):
    lods = []
    for lod in job["lods"][1:]:
        level = lod["level"]
        obj = join(import_glb(os.path.join(folder, lod["file"])), f"{job['name']}_LOD{level}")
        for slot in obj.material_slots:
            if slot.material:
                slot.material.name = f"{base_name(slot.material.name)}_LOD{level}"
        obj["rockbake_lod"] = level
        obj.parent = lod0
        move_to(obj, collection)
        lods.append(obj.name)
    return lods


def import_hulls(job, folder, lod0, collection):
    """collision.glb's hulls, renamed after the LOD0 object as Unreal pairs UCX_ hulls with a mesh."""
    collision = job.get("collision")
    if not collision:
        return []
    objects = sorted((o for o in import_glb(os.path.join(folder, collision["file"])) if o.type == "MESH"),
                     key=lambda o: o.name)
    names = []
    for i, obj in enumerate(objects):
        obj.name = (f"{job['name']}_{i:02d}-convcolonly" if collision.get("naming") == "godot"
                    else f"UCX_{job['name']}_{i:02d}")
        obj.data.name = obj.name
        obj.display_type = "WIRE"
        obj.hide_render = True
        obj.parent = lod0
        move_to(obj, collection)
        names.append(obj.name)
    return names


def pack_images():
    """One image per map, packed into the .blend. A map two LODs share is imported twice: kept once. A GLB
    that names its maps (the generic profile) has them read from textures/ and packed; one that embeds
    them (the engine profiles, docs/delivery.md) has them packed by the importer already."""
    kept = {}
    for image in list(bpy.data.images):
        if image.source != "FILE":
            continue
        if image.packed_file:
            key = hashlib.sha256(image.packed_file.data).hexdigest()
            name = base_name(image.name)
            if not os.path.splitext(name)[1]:
                name += "." + image.file_format.lower().replace("jpeg", "jpg")
        else:
            key = os.path.realpath(bpy.path.abspath(image.filepath))
            name = os.path.basename(key)
            if not os.path.isfile(key):
                raise RuntimeError(f"the map {key} is missing")
        if key in kept:
            image.user_remap(kept[key])
            bpy.data.images.remove(image)
            continue
        kept[key] = image
        if not image.packed_file:
            image.pack()
        image.filepath_raw = "//textures/" + name
    return sorted(kept.values(), key=lambda i: i.name)


def frame_camera(scene, obj):
    """A camera 20 degrees above the horizon from the front right, as the bake's: the bounding sphere fills
    the (square) frame, or every corner of the bounding box lies within 92 % of it, whichever is nearer."""
    corners = [obj.matrix_world @ mathutils.Vector(c) for c in obj.bound_box]
    centre = sum(corners, mathutils.Vector()) / 8
    radius = max(max((c - centre).length for c in corners), 1e-3)
    camera = bpy.data.objects.new("rockbake preview camera", bpy.data.cameras.new("rockbake preview camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    azimuth, elevation = math.radians(-60), math.radians(20)
    direction = mathutils.Vector(
        (math.cos(elevation) * math.cos(azimuth), math.cos(elevation) * math.sin(azimuth), math.sin(elevation)))
    rotation = (-direction).to_track_quat("-Z", "Y")
    right, up = rotation @ mathutils.Vector((1, 0, 0)), rotation @ mathutils.Vector((0, 1, 0))
    half = camera.data.angle / 2
    # A corner q (from the centre) is in frame when max(|q.right|, |q.up|) <= t (distance - q.direction).
    t = 0.92 * math.tan(half)
    box = max((c - centre).dot(direction) + max(abs((c - centre).dot(right)), abs((c - centre).dot(up))) / t
              for c in corners)
    distance = min(radius / math.sin(half), box)
    camera.location = centre + distance * direction
    camera.rotation_euler = rotation.to_euler()
    camera.data.clip_start = max(1e-3, 0.01 * radius)
    camera.data.clip_end = distance + 4 * radius
    return camera


def render_preview(obj, path):
    """A 256 x 256 Cycles render of `obj` to `path`, in a scene of its own removed afterwards."""
    scene = bpy.data.scenes.new("rockbake preview")
    scene.collection.objects.link(obj)
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 16
    scene.cycles.use_denoising = False
    scene.render.resolution_x = scene.render.resolution_y = 256
    scene.render.film_transparent = True
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = path
    world = bpy.data.worlds.new("rockbake preview")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs[0].default_value = (0.5, 0.5, 0.5, 1.0)
    world.node_tree.nodes["Background"].inputs[1].default_value = 0.6
    scene.world = world
    sun = bpy.data.objects.new("rockbake preview sun", bpy.data.lights.new("rockbake preview sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (math.radians(40), 0.0, math.radians(30))
    scene.collection.objects.link(sun)
    camera = frame_camera(scene, obj)
    try:
        bpy.ops.render.render(write_still=True, scene=scene.name)
    finally:
        camera_data, sun_data = camera.data, sun.data
        bpy.data.objects.remove(camera)
        bpy.data.objects.remove(sun)
        bpy.data.cameras.remove(camera_data)
        bpy.data.lights.remove(sun_data)
        bpy.data.worlds.remove(world)
        bpy.data.scenes.remove(scene)
        for image in [i for i in bpy.data.images if i.type == "RENDER_RESULT"]:
            bpy.data.images.remove(image)


def set_preview(job, folder, obj):
    """The still render as the asset's preview, or a Cycles render of LOD0 when the bake has none."""
    with tempfile.TemporaryDirectory(prefix="rockbake-preview-") as scratch:
        if job.get("preview"):
            path, source = os.path.join(folder, job["preview"]), job["preview"]
        else:
            path, source = os.path.join(scratch, "preview.png"), "generated"
            render_preview(obj, path)
        with bpy.context.temp_override(id=obj):
            result = bpy.ops.ed.lib_id_load_custom_preview(filepath=path)
    if "FINISHED" not in result or obj.preview is None or obj.preview.image_size[0] == 0:
        raise RuntimeError(f"Blender could not load the preview {path}")
    return source


def mark_asset(job, obj):
    obj.asset_mark()
    data = obj.asset_data
    data.catalog_id = job["catalog"]["id"]
    try:  # read-only in some versions; Blender fills it from the catalogue file then
        data.catalog_simple_name = job["catalog"]["simple_name"]
    except (AttributeError, TypeError):
        pass
    data.description = job["description"]
    data.author = job["author"]
    for tag in job["tags"]:
        data.tags.new(tag, skip_if_exists=True)
    for key, value in job["properties"].items():
        obj[key] = value


def check_size(job, obj):
    """The object measures asset.json's size_m (glTF positions are metres: nothing is scaled)."""
    size = list(obj.dimensions)
    off = [abs(a - b) for a, b in zip(size, job["size_m"])]
    if max(off) > 1e-3 + 1e-4 * max(job["size_m"]):
        warnings.append("the object measures {:.4f} x {:.4f} x {:.4f} m, asset.json says size_m {}".format(
            *size, job["size_m"]))
    return size


def main():
    job = json.loads(sys.argv[sys.argv.index("--") + 1])
    folder = job["asset_dir"]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.unit_settings.system = "METRIC"
    scene.unit_settings.scale_length = 1.0

    lod0 = import_lod0(job, folder)
    main_collection = new_collection(job["name"], scene.collection)
    move_to(lod0, main_collection)
    lod_collection = new_collection(f"{job['name']} LODs", main_collection)
    hull_collection = new_collection(f"{job['name']} collision", main_collection)
    lods = import_lods(job, folder, lod0, lod_collection)
    hulls = import_hulls(job, folder, lod0, hull_collection)
    for collection, objects in ((lod_collection, lods), (hull_collection, hulls)):
        if objects:
            hide_collection(collection)
        else:
            bpy.data.collections.remove(collection)
    for slot in lod0.material_slots:
        if slot.material:
            slot.material.name = base_name(slot.material.name)

    images = pack_images()
    size = check_size(job, lod0)
    mark_asset(job, lod0)
    preview = set_preview(job, folder, lod0)
    bpy.ops.wm.save_as_mainfile(filepath=job["output"], compress=True, relative_remap=False)
    print(RESULT_PREFIX + json.dumps({
        "object": lod0.name, "lods": lods, "hulls": hulls, "images": [i.name for i in images],
        "materials": [s.material.name for s in lod0.material_slots if s.material],
        "size_m": [round(s, 6) for s in size], "preview": preview, "warnings": warnings}))


try:
    main()
except Exception as e:
    # rockbake's message is this line; the traceback follows for `rockbake -v`. Re-raised: Blender's exit
    # status 1 (--python-exit-code).
    print(ERROR_PREFIX + " ".join(str(e).split()), flush=True)
    raise
