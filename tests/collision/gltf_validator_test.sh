#!/usr/bin/env bash
# collision.glb, named for Unreal and for Godot, passes the Khronos glTF
# validator (npm package gltf-validator, installed by scripts/setup.sh).
# Usage: gltf_validator_test.sh ROCKBAKE_COLLISION_SAMPLE SOURCE_DIR
set -euo pipefail
sample=$1
source_dir=$2
validator=$source_dir/scripts/gltf-validator/validate.mjs
if ! command -v node >/dev/null || [ ! -d "$source_dir/scripts/gltf-validator/node_modules/gltf-validator" ]; then
  echo "FAIL: node or the gltf-validator package is missing; run scripts/setup.sh" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$sample" "$work"
node "$validator" "$work/collision.glb" "$work/collision_godot.glb"
echo "PASS: collision.glb and collision_godot.glb, no validator errors"
