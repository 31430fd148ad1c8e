#!/usr/bin/env bash
# Asset budgets, against a baseline build in the same run:
#   bench/asset_bench.sh BASELINE_ROOT [OUT]
# BASELINE_ROOT holds the baseline's build/baker/rockbake and its presets/.
# Prints the goblin bake's wall time and folder size for both builds, LOD0's
# triangles and its distance from the field (detail off), and the folder size
# of every shipped preset with the house settings.
set -euo pipefail
cd "$(dirname "$0")/.."
baseline=$1
out=${2:-$(mktemp -d)}
new=build/baker/rockbake
wall() { /usr/bin/time -f %e "$@" 2>&1 >/dev/null | tail -1; }
size_mb() { du -sm "$1" | cut -f1; }

echo "== goblin, whole bake (render included), baseline then new"
tb=$(wall "$baseline/build/baker/rockbake" bake "$baseline/presets/goblin.yaml" -o "$out/baseline")
tn=$(wall "$new" bake presets/goblin.yaml -o "$out/new")
echo "baseline: ${tb} s, $(size_mb "$out/baseline/goblin") MB"
echo "new:      ${tn} s, $(size_mb "$out/new/goblin") MB"
python3 -c "import json; a = json.load(open('$out/new/goblin/asset.json')); print('LODs:', [(l['file'], l['triangles']) for l in a['lods']])"

echo "== every shipped preset, house settings (MB)"
for preset in presets/*.yaml; do
  [ "$(basename "$preset")" = base.yaml ] || [ "$(basename "$preset")" = library.yaml ] && continue
  name=$(basename "$preset" .yaml)
  "$new" bake "$preset" -o "$out/presets" >/dev/null 2>&1
  echo "$name $(size_mb "$out/presets/$name")"
done

echo "== goblin LOD0 against rock_sdf, detail off"
"$new" bake presets/goblin.yaml -o "$out/nodetail" --no-render --set mesh.detail=null >/dev/null 2>&1
build/bench/rockbake_lod0_error "$out/nodetail/goblin"
