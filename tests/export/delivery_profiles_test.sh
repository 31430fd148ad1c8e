#!/usr/bin/env bash
# Delivery profiles through the clients that read them (docs/delivery.md):
# - units_per_meter: 100 gives GLBs in metres: Blender measures asset.json's size_m;
# - two assets imported into one Blender scene keep their own materials;
# - the Unreal profile's normal maps, read by oiiotool, are the generic ones with green flipped
#   (and are wrong read as they are); its GLBs embed their images and pass the Khronos validator;
#   its names carry Unreal's prefixes;
# - an unknown profile is refused, exit 2, nothing written.
# Usage: delivery_profiles_test.sh ROCKBAKE SOURCE_DIR
set -euo pipefail
rockbake=$1
source_dir=$2
for tool in blender oiiotool node; do
  if ! command -v "$tool" >/dev/null; then
    echo "FAIL: $tool is missing; run scripts/setup.sh" >&2
    exit 1
  fi
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/rock.yaml" <<'YAML'
rockbake: 1
name: profile-check
seed: 5
grid: {size: [3.0, 3.0, 3.0], resolution: 28}
shape: {box: {size: [1.8, 1.8, 2.2]}}
durability: {points: [[0.0, 1.0], [0.5, 0.4], [1.0, 1.5]]}
bubbles: [{up_to: 1.0, bubble: {sphere: {radius: 0.25}}, spheroidal: 0.7, cavernous: 0.3}]
colluvium: {yield: 0.6}
time: 0.5
mesh: {subdivision: 1, lods: [0.5], detail: {amplitude: 0.01, period: 0.1, octaves: 2}}
export: [glb, collision]
texture: {size: 256, ao_rays: 4}
clasts: {count: 20, size: [1, 4]}
YAML
bake() {  # NAME OUT [--set ...]
  local name=$1 out=$2
  shift 2
  "$rockbake" bake "$work/rock.yaml" -o "$out" --no-render --set "name=$name" "$@" >"$work/$name.log" 2>&1 ||
    { cat "$work/$name.log"; echo "FAIL: the $name bake failed" >&2; exit 1; }
}
bake generic "$work/out"
bake centimetres "$work/out" --set units_per_meter=100
bake unreal "$work/out" --set delivery.profile=unreal

# GLB bounds in metres, and each asset's own materials, as Blender imports them.
blender --background --factory-startup --python-exit-code 1 \
  --python "$source_dir/scripts/delivery_check.py" -- "$work/out/generic" "$work/out/centimetres" "$work/out/unreal"

# The Unreal profile's files: prefixes, DirectX normals, embedded images.
/usr/bin/python3 - "$work/out" "$source_dir" <<'PY'
import json, os, subprocess, sys, tempfile
import numpy
out = sys.argv[1]
sys.path.insert(0, os.path.join(sys.argv[2], "bench"))
from clast_figures import read_glb  # glTF's chunks, by the spec's layout
failures = []
def check(ok, what):
    if not ok: failures.append(what)
    return "ok" if ok else "FAIL"
def pixels(path):  # oiiotool decodes, as any client's loader would
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-o", tmp + "/map.ppm"],  # 8-bit maps: no conversion
                       capture_output=True, check=True)
        raw = open(tmp + "/map.ppm", "rb").read()
    header = raw.split(b"\n", 3)
    w, h = map(int, header[1].split())
    return numpy.frombuffer(header[3], numpy.uint8)[: w * h * 3].reshape(h, w, 3).astype(int)
unreal = json.load(open(os.path.join(out, "unreal", "asset.json")))
generic = json.load(open(os.path.join(out, "generic", "asset.json")))
print("unreal delivery:", unreal.get("delivery"), check(unreal.get("delivery", {}).get("normal_map") == "directx", "asset.json says directx"))
print("generic delivery:", generic.get("delivery"), check(generic.get("delivery", {}).get("normal_map") == "opengl", "asset.json says opengl"))
g, binary = read_glb(os.path.join(out, "unreal", "rock.glb"))
meshes = [m["name"] for m in g["meshes"]]
materials = [m["name"] for m in g["materials"]]
print("unreal meshes", meshes[:3], check(all(m.startswith("SM_unreal_") for m in meshes), "SM_ prefix"))
print("unreal materials", materials, check(all(m.startswith("M_unreal_") for m in materials), "M_ prefix"))
print("unreal images embedded", check(g.get("images") and all("bufferView" in i and "uri" not in i for i in g["images"]), "embedded images"))
c, _ = read_glb(os.path.join(out, "unreal", "collision.glb"))
hulls = [n["name"] for n in c["nodes"]]
print("unreal hulls", hulls[:2], check(all(h.startswith("UCX_SM_unreal_") for h in hulls), "UCX_ on the SM_ names"))
maps = [m for m in unreal["maps"] if m["type"] == "normal"]
print("unreal normal maps", [m["file"] for m in maps], check(maps and all(os.path.basename(m["file"]).startswith("T_unreal_") for m in maps), "T_ prefix"))
for m in maps:
    dx = pixels(os.path.join(out, "unreal", m["file"]))
    gl_file = os.path.join(out, "generic", m["file"].replace("T_unreal_", "generic_"))
    gl = pixels(gl_file)
    flipped = dx.copy(); flipped[..., 1] = 255 - flipped[..., 1]
    right = numpy.abs(flipped - gl).mean()
    wrong = numpy.abs(dx[..., 1] - gl[..., 1]).mean()
    print(f"  {m['file']}: green flipped vs generic {right:.3f} levels, as is {wrong:.2f} levels: "
          f"{check(right < 0.05, 'flipped matches')} {check(wrong > 5, 'unflipped differs')}")
# The GLB's own normal map, as glTF reads it (OpenGL's), is the generic one.
material = next(m for m in g["materials"] if m["name"] == "M_unreal_rock")
image = g["images"][g["textures"][material["normalTexture"]["index"]]["source"]]
view = g["bufferViews"][image["bufferView"]]
with tempfile.TemporaryDirectory() as tmp:
    open(tmp + "/embedded.png", "wb").write(binary[view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]])
    embedded = pixels(tmp + "/embedded.png")
gl = pixels(os.path.join(out, "generic", "textures", "generic_Normal_LOD0.png"))
d = numpy.abs(embedded - gl).mean()
print(f"unreal rock.glb's embedded normal map vs generic: {d:.3f} levels: {check(d < 0.05, 'embedded normal map is OpenGL')}")
if failures:
    print("FAILED: " + "; ".join(failures)); sys.exit(1)
PY

# The Unreal GLB (embedded images) passes the Khronos validator.
node "$source_dir/scripts/gltf-validator/validate.mjs" "$work/out/unreal/rock.glb" "$work/out/unreal/rock_lod1.glb"

# An unknown profile: exit 2, the key named, nothing written.
set +e
"$rockbake" bake "$work/rock.yaml" -o "$work/bad" --no-render --set delivery.profile=unrael >"$work/bad.log" 2>&1
status=$?
set -e
cat "$work/bad.log"
[ "$status" -eq 2 ] || { echo "FAIL: an unknown profile gave exit $status, not 2" >&2; exit 1; }
grep -q "delivery.profile" "$work/bad.log" || { echo "FAIL: the message does not name delivery.profile" >&2; exit 1; }
[ ! -e "$work/bad" ] || { echo "FAIL: an unknown profile left $work/bad behind" >&2; exit 1; }
echo "delivery profiles: all checks passed"
