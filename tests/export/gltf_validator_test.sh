#!/usr/bin/env bash
# The .glb exports (the asset and its LODs) pass the Khronos glTF validator
# (npm package gltf-validator, installed by scripts/setup.sh).
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
files=("$work"/out/glb-check/*.glb "$work"/counts/glb-counts/*.glb)
[ "${#files[@]}" -eq 6 ] || { echo "FAIL: expected rock.glb and two LODs twice, found ${files[*]}" >&2; exit 1; }
node "$validator" "${files[@]}"
echo "PASS: ${#files[@]} files, no validator errors"
