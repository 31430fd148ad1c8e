#!/usr/bin/env bash
# The compressed set (docs/delivery.md, "The compressed set") read by other programs than ours:
# every compressed GLB passes the Khronos glTF validator with no errors and declares
# KHR_texture_basisu, KHR_mesh_quantization and EXT_meshopt_compression; its normal map, cut out
# of the GLB and decoded by the encoder's own `basisu -unpack`, reads by glTF's rules within
# tolerance of the full set's PNG (tests/compress/normal_fidelity.py); asset.json's "sets" are
# the files' sizes; a second bake on one thread writes the same bytes.
# Usage: compressed_set_test.sh ROCKBAKE SOURCE_DIR
set -euo pipefail
rockbake=$1
source_dir=$2
validator=$source_dir/scripts/gltf-validator/validate.mjs
for tool in basisu gltfpack oiiotool node; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool is missing; run scripts/setup.sh" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cat > "$work/asset.yaml" <<'YAML'
rockbake: 1
name: packed
seed: 5
grid: {size: [3.0, 3.0, 3.0], resolution: 32}
shape: {box: {size: [1.8, 1.8, 2.2]}}
bubbles: [{up_to: 1.0, bubble: {sphere: {radius: 0.25}}, spheroidal: 0.7, cavernous: 0.3}]
colluvium: {yield: 0.6}
time: 0.5
mesh: {subdivision: 1, lods: [0.5, 0.25], detail: {amplitude: 0.01, period: 0.1, octaves: 2}}
texture: {size: 256, ao_rays: 4, maps: [base_color, normal, orm]}
clasts: {count: 40, size: [1, 4]}
export: [glb]
delivery: {compressed: true}
YAML
"$rockbake" bake "$work/asset.yaml" -o "$work/out" --no-render
asset=$work/out/packed
full=("$asset"/rock*.glb)
packed=("$asset"/compressed/rock*.glb)
[ "${#full[@]}" -eq 3 ] && [ "${#packed[@]}" -eq 3 ] ||
  { echo "FAIL: expected three GLBs in each set, found ${full[*]} and ${packed[*]}" >&2; exit 1; }
for f in "${full[@]}"; do
  [ -f "$asset/compressed/$(basename "$f")" ] || { echo "FAIL: compressed/ has no $(basename "$f")" >&2; exit 1; }
done
[ ! -e "$asset/.compressed.tmp" ] && [ ! -e "$asset/.compress-work" ] ||
  { echo "FAIL: the compressed set's work folders were left behind" >&2; exit 1; }

# The validator, on files that carry their maps inside (nothing beside them to read).
report=$(node "$validator" "${packed[@]}") || { echo "$report"; exit 1; }
echo "$report"

# Extensions, the KTX2 images, asset.json's costs, and the LOD's normal map cut out for basisu.
/usr/bin/python3 - "$asset" "$work/normal.ktx2" <<'PY'
import json, os, struct, sys
asset, ktx_out = sys.argv[1], sys.argv[2]

def glb(path):
    data = open(path, "rb").read()
    size = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + size])
    binary = data[20 + size + 8:] if len(data) > 20 + size else b""
    return doc, binary

def rock_material(doc):
    """The material of the rock's mesh: node rock_lod<k>, or the child gltfpack hangs its mesh on."""
    node = next(n for n in doc["nodes"] if n.get("name", "").startswith("rock_lod"))
    if "mesh" not in node:
        node = doc["nodes"][node["children"][0]]
    return doc["materials"][doc["meshes"][node["mesh"]]["primitives"][0]["material"]]

def fail(message):
    print("FAIL: " + message, file=sys.stderr)
    sys.exit(1)

files = ["rock.glb", "rock_lod1.glb", "rock_lod2.glb"]
full_download, seen = 0, set()
packed_download, ktx_gpu, ktx_seen = 0, 0, set()
for name in files:
    doc, _ = glb(os.path.join(asset, name))
    full_download += os.path.getsize(os.path.join(asset, name))
    for image in doc["images"]:
        if image["uri"] not in seen:
            seen.add(image["uri"])
            full_download += os.path.getsize(os.path.join(asset, image["uri"]))
    path = os.path.join(asset, "compressed", name)
    doc, binary = glb(path)
    packed_download += os.path.getsize(path)
    for ext in ("KHR_texture_basisu", "KHR_mesh_quantization", "EXT_meshopt_compression"):
        if ext not in doc.get("extensionsRequired", []):
            fail(f"{name} does not require {ext}")
    if any("source" in t for t in doc["textures"]):
        fail(f"{name} names a KTX2 image as a plain texture source")
    for image in doc["images"]:
        view = doc["bufferViews"][image["bufferView"]]
        data = binary[view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]]
        if image.get("mimeType") != "image/ktx2" or data[:12] != b"\xabKTX 20\xbb\r\n\x1a\n":
            fail(f"{name}: an image that is not KTX2")
        if data in ktx_seen:
            continue
        ktx_seen.add(data)
        w, h = struct.unpack_from("<II", data, 20)
        levels = struct.unpack_from("<I", data, 40)[0]
        if levels < 2 or (w >> (levels - 1)) > 1:
            fail(f"{name}: a KTX2 of {w} x {h} without a full mip chain ({levels} levels)")
        dfd = struct.unpack_from("<I", data, 48)[0]
        model = data[dfd + 12]
        samples = (struct.unpack_from("<H", data, dfd + 10)[0] - 24) // 16
        block = 8 if model == 163 and samples == 1 else 16
        ktx_gpu += sum(((max(1, w >> l) + 3) // 4) * ((max(1, h >> l) + 3) // 4) * block for l in range(levels))
    if name == "rock_lod2.glb":
        material = rock_material(doc)
        texture = doc["textures"][material["normalTexture"]["index"]]
        image = doc["images"][texture["extensions"]["KHR_texture_basisu"]["source"]]
        view = doc["bufferViews"][image["bufferView"]]
        start = view.get("byteOffset", 0)
        open(ktx_out, "wb").write(binary[start:start + view["byteLength"]])
        # The UASTC normal map: colour model 166, linear transfer (1).
        dfd = struct.unpack_from("<I", binary, start + 48)[0]
        if binary[start + dfd + 12] != 166 or binary[start + dfd + 14] != 1:
            fail("rock_lod2.glb's normal map is not linear UASTC")

sets = json.load(open(os.path.join(asset, "asset.json")))["sets"]
if sets["compressed"]["folder"] != "compressed":
    fail(f"asset.json's compressed set is in {sets['compressed']['folder']}")
for key, value in (("full", full_download), ("compressed", packed_download)):
    if sets[key]["download_bytes"] != value:
        fail(f"asset.json's {key} set downloads {sets[key]['download_bytes']} bytes, its files {value}")
if sets["compressed"]["gpu_texture_bytes"] != ktx_gpu:
    fail(f"asset.json's compressed maps take {sets['compressed']['gpu_texture_bytes']} bytes of GPU memory, the KTX2 headers say {ktx_gpu}")
for key in ("full", "compressed"):
    s = sets[key]
    if s["gpu_bytes"] != s["gpu_texture_bytes"] + s["gpu_mesh_bytes"] or s["gpu_mesh_bytes"] <= 0:
        fail(f"asset.json's {key} GPU memory does not add up: {s}")
if not (sets["compressed"]["download_bytes"] < sets["full"]["download_bytes"] and
        sets["compressed"]["gpu_texture_bytes"] * 4 <= sets["full"]["gpu_texture_bytes"] * 1.01):
    fail(f"the compressed set is not smaller: {sets}")
print("sets:", json.dumps(sets))
PY

# The normal map decoded by the encoder itself (its BC7 transcode of mip 0), against the PNG.
mkdir "$work/unpacked"
(cd "$work/unpacked" && basisu -unpack -no_ktx -file ../normal.ktx2 >/dev/null)
decoded=$(ls "$work"/unpacked/*_unpacked_rgb_BC7_RGBA_0_0_0000.png)
normal_png=$(/usr/bin/python3 -c "
import json, struct, sys
data = open(sys.argv[1], 'rb').read(); n = struct.unpack_from('<I', data, 12)[0]; doc = json.loads(data[20:20 + n])
node = next(n for n in doc['nodes'] if n.get('name', '').startswith('rock_lod'))
m = doc['materials'][doc['meshes'][node['mesh']]['primitives'][0]['material']]
print(doc['images'][doc['textures'][m['normalTexture']['index']]['source']]['uri'])" "$asset/rock_lod2.glb")
fidelity=$(/usr/bin/python3 "$source_dir/tests/compress/normal_fidelity.py" "$asset/$normal_png" "$decoded" "$asset/rock_lod2.glb")
echo "LOD2 normals: $fidelity"
/usr/bin/python3 -c "
import json, sys
f = json.loads(sys.argv[1])
# UASTC's floor on a rock's noisy normals is about 2.3° a texel (docs/delivery.md); the mean
# tilt, what shading reads at a distance, within 1.5° of the PNG's.
ok = f['texels'] > 1000 and f['mean_deg'] < 4.0 and abs(f['mean_tilt_deg'] - f['png_mean_tilt_deg']) < 1.5
sys.exit(0 if ok else 1)" "$fidelity" || { echo "FAIL: the decoded normals stray too far: $fidelity" >&2; exit 1; }

# The same bytes on one thread.
"$rockbake" bake "$work/asset.yaml" -o "$work/again" --no-render --threads 1
for f in "${packed[@]}"; do
  cmp "$f" "$work/again/packed/compressed/$(basename "$f")" ||
    { echo "FAIL: $(basename "$f") differs between two thread counts" >&2; exit 1; }
done
echo "PASS: ${#packed[@]} compressed GLBs, no validator errors, normals within tolerance, sizes as the files', the same bytes on one thread"
