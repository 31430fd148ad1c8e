#!/usr/bin/env bash
# Blender's glTF importer reads collision.glb's hull nodes with their names
# (scripts/collision_import_check.py; Debian's blender, installed by scripts/setup.sh).
# Usage: blender_import_test.sh ROCKBAKE_COLLISION_SAMPLE SOURCE_DIR
set -euo pipefail
sample=$1
source_dir=$2
if ! command -v blender >/dev/null; then
  echo "FAIL: blender is missing; run scripts/setup.sh" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$sample" "$work"
# Blender exits 0 even when the script fails: the script's own exit status is what counts.
blender --background --factory-startup --python-exit-code 1 \
  --python "$source_dir/scripts/collision_import_check.py" -- "$work/expected.json"
