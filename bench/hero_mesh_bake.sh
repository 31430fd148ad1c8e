#!/usr/bin/env bash
# MESHES: the hero bake with its meshes and LODs (`bench/hero_bake.sh --meshes`):
# goblin as shipped, `--no-render`, stage seconds (stats.json) and peak memory
# (GNU time), a baseline build and this one in the same run; whether this
# build's rock.vdb and meshes are byte-identical at 1 and 2 threads; the house
# bake (goblin at 96) both ways and whether its files are the baseline's;
# goblin at a larger resolution end to end (render included) with its peak.
# Figures: bench/README.md.
#
# Usage: bench/hero_bake.sh --meshes BASELINE_ROCKBAKE [RESOLUTION=384] [OUT=/tmp/hero-mesh-bake] [LARGE=512]
# RUNS (environment): which parts, in this order (default all):
#   hero     baseline and this build at 2 threads, RESOLUTION
#   house    both at 96, 2 threads, files compared
#   large    this build at LARGE, 2 threads, end to end
#   scaling  this build and the baseline at 1 thread, RESOLUTION; this build's files at 1 and 2 threads compared
#   pair     two copies of this build at 1 thread at once (the machine's ceiling for two workers)
# BASELINE_PRESET (environment): the goblin preset the baseline reads, for a baseline that
#   predates keys of this one (say, the baseline's own checkout's presets/goblin.yaml)
# PREVIOUS_ROCKBAKE (environment): a second build to compare against (say, the previous
#   commit's), baked after the baseline in the hero and house runs
# Texture maps are left out (`--no-textures`, for builds that make them): their cost is
# measured on its own (bench/texture_cost.sh).
# Run it alone on the machine; the previous runs' folders are replaced.
set -euo pipefail
cd "$(dirname "$0")/.."
baseline=${1:?usage: bench/hero_bake.sh --meshes BASELINE_ROCKBAKE [RESOLUTION] [OUT] [LARGE]}
resolution=${2:-384}
out=${3:-/tmp/hero-mesh-bake}
large=${4:-512}
runs=${RUNS:-hero house large scaling pair}
current=build/baker/rockbake
preset=presets/goblin.yaml
mkdir -p "$out"

# bake NAME EXECUTABLE THREADS RESOLUTION [render]: one bake, verbose log, peak memory (GNU time).
bake() {
  local flags=(--no-render) input=$preset
  [ "${5:-}" = render ] && flags=()
  "$2" bake --help | grep -q -- --no-textures && flags+=(--no-textures)
  [ "$2" = "$baseline" ] && [ -n "${BASELINE_PRESET:-}" ] && input=$BASELINE_PRESET
  rm -rf "${out:?}/$1"
  /usr/bin/time -f '%e %M' -o "$out/$1.time" "$2" -v bake "$input" --resolution "$4" "${flags[@]}" \
    --threads "$3" -o "$out/$1" > "$out/$1.log" 2>&1
}

# One line of figures for a finished bake: wall seconds and peak, stage seconds, triangles.
report() {
  python3 - "$out/$1" "$(cat "$out/$1.time")" "$1" <<'PY'
import json, re, sys
folder, (wall, rss_kb), name = sys.argv[1], sys.argv[2].split(), sys.argv[3]
s = json.load(open(folder + "/goblin/stats.json"))["stages"]
mesh = sum(s.get(k, 0) for k in ("mesh_extract", "mesh_subdivide", "mesh_attributes", "mesh_simplify", "export"))
log = open(folder + ".log").read()
refined = re.search(r"refined (\d+) triangles; LOD0 rock \d+ vertices, (\d+) triangles; colluvium \d+ vertices, (\d+)", log)
tri = f", refined {int(refined[1]) / 1e6:.2f} M → LOD0 {(int(refined[2]) + int(refined[3])) / 1e3:.0f} k triangles" if refined else ""
print(f"{name:>12}: wall {float(wall):6.1f} s, peak {int(rss_kb) / 1024:6.0f} MiB; shape {s.get('shape', 0):5.1f}, "
      f"simulate {s['simulate']:6.1f}, mesh {mesh:6.1f} (extract {s.get('mesh_extract', 0):5.1f}, "
      f"subdivide {s.get('mesh_subdivide', 0):5.1f}, attributes {s.get('mesh_attributes', 0):4.1f}, "
      f"simplify {s.get('mesh_simplify', 0):5.1f}, export {s.get('export', 0):4.1f}), write_vdb {s.get('write_vdb', 0):4.1f}, "
      f"collision {s.get('collision', 0):4.1f} (beside the meshes where the build overlaps them), "
      f"render {s.get('render', 0):5.1f}{tri}")
PY
}

# same A B: whether two bakes' rock.vdb and mesh files are byte-identical.
same() {
  local differ=()
  for f in "$out/$1/goblin/"*.{vdb,ply,glb}; do
    cmp -s "$f" "$out/$2/goblin/$(basename "$f")" || differ+=("$(basename "$f")")
  done
  if [ ${#differ[@]} -eq 0 ]; then echo "$1 / $2: rock.vdb and meshes byte-identical"; else echo "$1 / $2: differ: ${differ[*]}"; fi
}

for run in $runs; do
  case $run in
    hero)
      bake baseline "$baseline" 2 "$resolution"; report baseline
      if [ -n "${PREVIOUS_ROCKBAKE:-}" ]; then bake previous "$PREVIOUS_ROCKBAKE" 2 "$resolution"; report previous; fi
      bake current "$current" 2 "$resolution"; report current ;;
    house)
      bake house-baseline "$baseline" 2 96; report house-baseline
      if [ -n "${PREVIOUS_ROCKBAKE:-}" ]; then bake house-previous "$PREVIOUS_ROCKBAKE" 2 96; report house-previous; fi
      bake house-current "$current" 2 96; report house-current
      same house-baseline house-current ;;
    large)
      bake large "$current" 2 "$large" render; report large ;;
    scaling)
      bake current-1 "$current" 1 "$resolution"; report current-1
      [ -d "$out/current" ] && same current current-1
      bake baseline-1 "$baseline" 1 "$resolution"; report baseline-1 ;;
    pair)
      bake pair-a "$current" 1 "$resolution" &
      bake pair-b "$current" 1 "$resolution" &
      wait
      report pair-a; report pair-b ;;
    *) echo "unknown run: $run" >&2; exit 2 ;;
  esac
done
