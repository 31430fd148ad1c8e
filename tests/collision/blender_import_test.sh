#!/usr/bin/env bash
# Blender's glTF importer reads collision.glb's hull nodes with their names
# (scripts/collision_import_check.py; Debian's blender, installed by scripts/setup.sh):
# the sample's files, and a baked asset's (goblin at a test resolution, its
# colluvium hulled too) beside its rock.glb, against its asset.json.
# Usage: blender_import_test.sh ROCKBAKE_COLLISION_SAMPLE SOURCE_DIR ROCKBAKE
set -euo pipefail
sample=$1
source_dir=$2
rockbake=$3
if ! command -v blender >/dev/null; then
  echo "FAIL: blender is missing; run scripts/setup.sh" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$sample" "$work"
"$rockbake" bake "$source_dir/presets/goblin.yaml" --resolution 32 --no-render -o "$work/baked" \
  --set 'export=[glb, collision]' --set collision.colluvium=true >/dev/null
# Blender exits 0 even when the script fails: the script's own exit status is what counts.
blender --background --factory-startup --python-exit-code 1 \
  --python "$source_dir/scripts/collision_import_check.py" -- "$work/expected.json" "$work/baked/goblin"
