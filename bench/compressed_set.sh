#!/usr/bin/env bash
# The compressed set against the full set (docs/delivery.md, "The compressed set"): bakes a
# preset with delivery.compressed at the default threads and at --threads 1, and prints asset.json's
# "sets" with the ratios, the seconds the set took (the bake's log), whether both bakes wrote the
# same compressed bytes, and LOD2's normal map decoded by `basisu -unpack` against the PNG
# (tests/compress/normal_fidelity.py).
# Usage: bench/compressed_set.sh ROCKBAKE PRESET [--set KEY=VALUE ...]
set -euo pipefail
rockbake=$1
preset=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for threads in 0 1; do
  args=(bake "$preset" -o "$work/t$threads" --no-render --set delivery.compressed=true "$@")
  [ "$threads" -eq 0 ] || args+=(--threads "$threads")
  /usr/bin/time -f "bake at threads=${threads/#0/all}: %e s wall, %U s user" "$rockbake" "${args[@]}" 2>&1 |
    grep -E "compressed set in|s wall"
done
asset=$(ls -d "$work"/t0/*/)
same=yes
for f in "$asset"/compressed/*.glb; do
  cmp -s "$f" "$work/t1/$(basename "$asset")/compressed/$(basename "$f")" || same=no
done
echo "the same compressed bytes at both thread counts: $same"
/usr/bin/python3 - "$asset/asset.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["sets"]
for key in ("download_bytes", "gpu_texture_bytes", "gpu_mesh_bytes", "gpu_bytes"):
    print(f"{key}: full {s['full'][key]:,}  compressed {s['compressed'][key]:,}  "
          f"{s['full'][key] / s['compressed'][key]:.2f}x smaller")
PY
/usr/bin/python3 - "$asset" "$work/normal.ktx2" <<'PY'
import json, struct, sys
asset, out = sys.argv[1:3]
def glb(path):
    data = open(path, "rb").read(); n = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + n]), data[20 + n + 8:]
doc, binary = glb(asset + "/compressed/rock_lod2.glb")
node = next(x for x in doc["nodes"] if x.get("name", "").startswith("rock_lod"))
node = node if "mesh" in node else doc["nodes"][node["children"][0]]
m = doc["materials"][doc["meshes"][node["mesh"]]["primitives"][0]["material"]]
image = doc["images"][doc["textures"][m["normalTexture"]["index"]]["extensions"]["KHR_texture_basisu"]["source"]]
view = doc["bufferViews"][image["bufferView"]]
open(out, "wb").write(binary[view.get("byteOffset", 0):view.get("byteOffset", 0) + view["byteLength"]])
PY
normal=$(/usr/bin/python3 -c "
import json, struct, sys
data = open(sys.argv[1], 'rb').read(); n = struct.unpack_from('<I', data, 12)[0]; doc = json.loads(data[20:20 + n])
node = next(x for x in doc['nodes'] if x.get('name', '').startswith('rock_lod'))
m = doc['materials'][doc['meshes'][node['mesh']]['primitives'][0]['material']]
print(doc['images'][doc['textures'][m['normalTexture']['index']]['source']]['uri'])" "$asset/rock_lod2.glb")
mkdir "$work/unpacked"
(cd "$work/unpacked" && basisu -unpack -no_ktx -file ../normal.ktx2 >/dev/null)
echo "LOD2 normals (BC7 transcode of mip 0 against $normal): $(/usr/bin/python3 "$here/../tests/compress/normal_fidelity.py" \
  "$asset/$normal" "$work"/unpacked/*_unpacked_rgb_BC7_RGBA_0_0_0000.png "$asset/rock_lod2.glb")"
