#!/usr/bin/env bash
# The collision phase in a whole bake (docs/collision.md, "In a bake";
# bench/README.md, "The collision phase in a bake"): bakes a few shipped
# presets at their house settings without the render, with this build and
# with a previous one in the same run, and prints per preset each build's
# wall time (each with its own presets), this build's `collision` stage seconds (stats.json), the
# hulls and size of collision.glb, and whether it is byte-identical at 1 and
# 2 threads. Run it from the checkout, after building.
#   bench/collision_phase.sh PREVIOUS_ROOT [PRESET...]
# PREVIOUS_ROOT holds the previous build's build/baker/rockbake and its presets/.
set -euo pipefail
previous_root=$1
shift
presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=(goblin hoodoo-cap talus-cliff sea-cave-corner)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
wall() { /usr/bin/time -f %e "$@" 2>&1 >/dev/null | tail -1; }
echo "| preset | previous build | this build | collision stage | hulls (vertices) | collision.glb | 1 vs 2 threads |"
echo "|---|---|---|---|---|---|---|"
for name in "${presets[@]}"; do
  preset=presets/$name.yaml
  before=$(wall "$previous_root/build/baker/rockbake" bake "$previous_root/$preset" --no-render -o "$work/previous")
  now=$(wall ./build/baker/rockbake bake "$preset" --no-render -o "$work/two" --threads 2)
  ./build/baker/rockbake bake "$preset" --no-render -o "$work/one" --threads 1 >/dev/null 2>&1
  same=$(cmp -s "$work/one/$name/collision.glb" "$work/two/$name/collision.glb" && echo identical || echo DIFFER)
  read -r stage hulls vertices < <(python3 -c "
import json
s = json.load(open('$work/two/$name/stats.json'))['stages']
c = json.load(open('$work/two/$name/asset.json'))['collision']
print(f\"{s['collision']:.2f} {c['hull_count']} {c['vertex_count']}\")")
  size=$(($(stat -c %s "$work/two/$name/collision.glb") / 1024))
  echo "| $name | ${before} s | ${now} s | ${stage} s | $hulls ($vertices) | ${size} KiB | $same |"
done
