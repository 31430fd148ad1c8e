#!/usr/bin/env bash
# collision.glb passes the Khronos glTF validator (npm package gltf-validator,
# installed by scripts/setup.sh): the sample's, named for Unreal and for Godot,
# and the ones rockbake bakes beside a shipped preset's meshes (goblin at a test
# resolution, each naming, the colluvium hulled too).
# Usage: gltf_validator_test.sh ROCKBAKE_COLLISION_SAMPLE SOURCE_DIR ROCKBAKE
set -euo pipefail
sample=$1
source_dir=$2
rockbake=$3
validator=$source_dir/scripts/gltf-validator/validate.mjs
if ! command -v node >/dev/null || [ ! -d "$source_dir/scripts/gltf-validator/node_modules/gltf-validator" ]; then
  echo "FAIL: node or the gltf-validator package is missing; run scripts/setup.sh" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$sample" "$work"
for naming in unreal godot; do
  "$rockbake" bake "$source_dir/presets/goblin.yaml" --resolution 32 --no-render -o "$work/$naming" \
    --set 'export=[collision]' --set collision.colluvium=true --set "collision.naming=$naming" >/dev/null
done
node "$validator" "$work/collision.glb" "$work/collision_godot.glb" "$work/unreal/goblin/collision.glb" \
  "$work/godot/goblin/collision.glb"
echo "PASS: the sample's and the baked collision.glb files, no validator errors"
