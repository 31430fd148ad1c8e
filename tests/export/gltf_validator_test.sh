#!/usr/bin/env bash
# The .glb exports (the asset and its LODs) pass the Khronos glTF validator
# (npm package gltf-validator, installed by scripts/setup.sh), untextured and
# textured: with a texture set the validator reads every map each GLB names
# from textures/ beside it (scripts/gltf-validator/validate.mjs).
# Usage: gltf_validator_test.sh ROCKBAKE SOURCE_DIR
set -euo pipefail
rockbake=$1
source_dir=$2
validator=$source_dir/scripts/gltf-validator/validate.mjs
if ! command -v node >/dev/null || [ ! -d "$source_dir/scripts/gltf-validator/node_modules/gltf-validator" ]; then
  echo "FAIL: node or the gltf-validator package is missing; run scripts/setup.sh" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# A weathered rock on the ground with colluvium: both surfaces, two LODs.
cat > "$work/asset.yaml" <<'YAML'
rockbake: 1
name: glb-check
seed: 5
grid: {size: [3.0, 3.0, 3.0], resolution: 32}
shape: {box: {size: [1.8, 1.8, 2.2]}}
durability: {points: [[0.0, 1.0], [0.5, 0.4], [1.0, 1.5]]}
bubbles: [{up_to: 1.0, bubble: {sphere: {radius: 0.25}}, spheroidal: 0.7, cavernous: 0.3}]
colluvium: {yield: 0.6}
time: 0.5
mesh: {subdivision: 1, lods: [0.5, 0.25], detail: {amplitude: 0.01, period: 0.1, octaves: 2}}
export: [glb]
YAML
"$rockbake" bake "$work/asset.yaml" -o "$work/out" --no-render
# The house chain: LODs as triangle counts.
"$rockbake" bake "$work/asset.yaml" -o "$work/counts" --no-render --set name=glb-counts --set 'mesh.lods=[900, 300]'
# With a texture set (docs/textures.md): TEXCOORD_0, TANGENT and the maps by relative URI; and
# stones on the apron, nodes instancing shared meshes with their own maps (docs/model.md §13).
"$rockbake" bake "$work/asset.yaml" -o "$work/textured" --no-render --set name=glb-textured \
  --set 'texture={size: 256, ao_rays: 4}' --set 'clasts={count: 40, size: [1, 4]}'
files=("$work"/out/glb-check/*.glb "$work"/counts/glb-counts/*.glb "$work"/textured/glb-textured/*.glb)
[ "${#files[@]}" -eq 9 ] || { echo "FAIL: expected rock.glb and two LODs thrice, found ${files[*]}" >&2; exit 1; }
report=$(node "$validator" "${files[@]}") || { echo "$report"; exit 1; }
echo "$report"
# The validator read the maps: a textured GLB that names an image it cannot load fails above,
# and one whose maps went missing is caught here too.
for glb in "$work"/textured/glb-textured/*.glb; do
  grep -qa '"TANGENT"' "$glb" || { echo "FAIL: $glb has no TANGENT" >&2; exit 1; }
  grep -qa 'textures/glb-textured_BaseColor' "$glb" || { echo "FAIL: $glb names no base colour map" >&2; exit 1; }
done
grep -qa '"clast_0"' "$work/textured/glb-textured/rock.glb" || { echo "FAIL: rock.glb has no stones" >&2; exit 1; }
mv "$work/textured/glb-textured/textures" "$work/textured/glb-textured/maps-moved"
if node "$validator" "$work/textured/glb-textured/rock.glb" >/dev/null; then
  echo "FAIL: the validator passed a GLB whose maps are missing" >&2
  exit 1
fi
echo "PASS: ${#files[@]} files, no validator errors"
