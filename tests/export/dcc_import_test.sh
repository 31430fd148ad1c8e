#!/usr/bin/env bash
# Blender 3.4 (Debian's blender, installed by scripts/setup.sh) imports a textured
# bake as an artist would (scripts/dcc_import_check.py): every LOD's GLB with its
# image-textured material (base colour, normal map, ORM's occlusion and
# roughness), the OBJ with its MTL's maps, the PLYs; names, pivot, closedness
# and triangle counts against asset.json.
# Usage: dcc_import_test.sh ROCKBAKE SOURCE_DIR
set -euo pipefail
rockbake=$1
source_dir=$2
if ! command -v blender >/dev/null; then
  echo "FAIL: blender is missing; run scripts/setup.sh" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/asset.yaml" <<'YAML'
rockbake: 1
name: dcc-check
seed: 5
grid: {size: [3.0, 3.0, 3.0], resolution: 32}
shape: {box: {size: [1.8, 1.8, 2.2]}}
durability: {points: [[0.0, 1.0], [0.5, 0.4], [1.0, 1.5]]}
bubbles: [{up_to: 1.0, bubble: {sphere: {radius: 0.25}}, spheroidal: 0.7, cavernous: 0.3}]
colluvium: {yield: 0.6}
time: 0.5
mesh: {subdivision: 1, lods: [0.5, 0.25], detail: {amplitude: 0.01, period: 0.1, octaves: 2}}
export: [ply, obj, glb]
texture: {size: 256, ao_rays: 4}
clasts: {count: 40, size: [1, 4]}
YAML
"$rockbake" bake "$work/asset.yaml" -o "$work/out" --no-render
# Blender exits 0 even when the script fails: the script's own exit status is what counts.
blender --background --factory-startup --python-exit-code 1 \
  --python "$source_dir/scripts/dcc_import_check.py" -- "$work/out/dcc-check"
