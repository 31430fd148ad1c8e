#!/usr/bin/env bash
# The mesh stage of one preset, a baseline build against this one in the same
# run: RUNS bakes each, alternating, `--no-render`, every mesh export on; the
# median and the fastest of each stage's seconds (stats.json "stages"), and
# whether the two builds' meshes and rock.vdb are byte-identical.
# Figures: bench/README.md.
#
# Usage: bench/mesh_stage_compare.sh BASELINE_ROCKBAKE [PRESET=presets/goblin.yaml] [RUNS=5] [OUT]
set -euo pipefail
cd "$(dirname "$0")/.."
baseline=${1:?usage: bench/mesh_stage_compare.sh BASELINE_ROCKBAKE [PRESET] [RUNS] [OUT]}
preset=${2:-presets/goblin.yaml}
runs=${3:-5}
out=${4:-$(mktemp -d)}
current=build/baker/rockbake
name=$(basename "$preset" .yaml)
mkdir -p "$out"

for run in $(seq 1 "$runs"); do
  for build in baseline current; do
    exe=$current
    [ "$build" = baseline ] && exe=$baseline
    rm -rf "$out/$build"
    "$exe" bake "$preset" --set 'export=[ply, obj, glb, vdb]' --no-render -o "$out/$build" > /dev/null 2>&1
    cp "$out/$build/$name/stats.json" "$out/$build-$run.json"
  done
done

python3 - "$out" "$runs" <<'PY'
import json, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
keys = ["mesh_extract", "mesh_attributes", "mesh_subdivide", "mesh_simplify", "export"]
print(f"{'stage':>16}  {'baseline median':>15}  {'this median':>11}  {'baseline min':>12}  {'this min':>8}")
totals = {}
for key in keys + ["mesh stage"]:
    row = {}
    for build in ("baseline", "current"):
        values = []
        for run in range(1, runs + 1):
            stages = json.load(open(f"{out}/{build}-{run}.json"))["stages"]
            values.append(sum(stages[k] for k in keys) if key == "mesh stage" else stages[key])
        row[build] = (statistics.median(values), min(values))
    print(f"{key:>16}  {row['baseline'][0]:14.3f}s  {row['current'][0]:10.3f}s  {row['baseline'][1]:11.3f}s  "
          f"{row['current'][1]:7.3f}s")
PY

same=1
for f in "$out/current/$name"/rock.vdb "$out/current/$name"/*.ply "$out/current/$name"/rock.obj "$out/current/$name"/*.glb; do
  cmp -s "$f" "$out/baseline/$name/$(basename "$f")" || { echo "$(basename "$f"): DIFFERS"; same=0; }
done
[ $same = 1 ] && echo "meshes and rock.vdb: byte-identical to the baseline's"
