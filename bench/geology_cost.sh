#!/usr/bin/env bash
# What the geology (shape variation, strata, joints, rind) costs a
# bake, against a baseline build in the same run:
#   bench/geology_cost.sh BASELINE_ROCKBAKE [OUT]
# For every shipped preset at its own resolution, `--no-mesh`, 2 threads:
# the baseline with the preset's geology, this build with it, and this build
# with the geology keys removed (`--set KEY=null`). Prints the shape stage
# (the initial rock, its distance field and the durability field), the
# simulation, and peak memory. Run it alone on the machine.
set -euo pipefail
cd "$(dirname "$0")/.."
baseline=${1:?usage: bench/geology_cost.sh BASELINE_ROCKBAKE [OUT]}
out=${2:-$(mktemp -d)}
mkdir -p "$out"
current=build/baker/rockbake
no_geology=(--set shape.variation=null --set durability.strata=null --set durability.joints=null
            --set durability.rind=null)

# run NAME PRESET EXECUTABLE [ARGS...]: one bake, then its figures on one line.
run() {
  local name=$1 preset=$2 exe=$3
  shift 3
  /usr/bin/time -f '%M' -o "$out/$name.rss" "$exe" bake "$preset" --no-mesh --threads 2 -o "$out/$name" "$@" \
    > "$out/$name.log" 2>&1
  python3 - "$out/$name" "$(basename "$preset" .yaml)" "$(cat "$out/$name.rss")" "$name" <<'PY'
import json, sys
folder, preset, rss_kb, name = sys.argv[1:]
s = json.load(open(f"{folder}/{preset}/stats.json"))["stages"]
print(f"  {name.split('.')[0]:>10}: shape {s['shape']:6.2f} s, simulate {s['simulate']:6.2f} s, "
      f"peak {int(rss_kb) / 1024:6.1f} MiB")
PY
}

for preset in presets/*.yaml; do
  name=$(basename "$preset" .yaml)
  [ "$name" = base ] || [ "$name" = library ] && continue
  echo "$name"
  run "baseline.$name" "$preset" "$baseline"
  run "current.$name" "$preset" "$current"
  run "nogeology.$name" "$preset" "$current" "${no_geology[@]}"
done
