#!/usr/bin/env bash
# What the texture set adds to a bake (docs/textures.md; figures in bench/README.md):
# the previous build, this build with --no-textures and this build with the house
# style's texture set, each baking PRESET with --no-render at 2 threads, RUNS times
# in turn (so load changes hit all three alike). Prints wall and CPU seconds and peak
# memory per run, and this build's stats.json texture time.
# BASELINE_PRESETS: the previous build's presets folder (its house style has no texture:
# key, which it would refuse).
# Usage: bench/texture_cost.sh BASELINE_ROCKBAKE BASELINE_PRESETS [ROCKBAKE] [PRESET] [RUNS] [EXTRA ARGS…]
set -euo pipefail
baseline=$1
baseline_presets=$2
rockbake=${3:-build/baker/rockbake}
preset=${4:-presets/goblin.yaml}
runs=${5:-3}
shift $(( $# < 5 ? $# : 5 ))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
name=$(basename "$preset" .yaml)
printf '%-12s %-4s %8s %8s %10s %10s\n' build run wall_s cpu_s peak_MiB texture_s
for run in $(seq "$runs"); do
  for build in baseline no-textures textures; do
    case $build in
      baseline) cmd=("$baseline" bake "$baseline_presets/$(basename "$preset")") ;;
      no-textures) cmd=("$rockbake" bake "$preset" --no-textures) ;;
      textures) cmd=("$rockbake" bake "$preset") ;;
    esac
    out=$work/$build
    rm -rf "$out"
    /usr/bin/time -f '%e %U %S %M' -o "$work/time" "${cmd[@]}" --no-render --threads 2 -o "$out" "$@" >/dev/null 2>&1
    read -r wall user sys peak < "$work/time"
    texture=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['stages'].get('texture', 0))" \
      "$out/$name/stats.json")
    printf '%-12s %-4s %8.2f %8.2f %10.0f %10.2f\n' "$build" "$run" "$wall" "$(echo "$user + $sys" | bc)" \
      "$(echo "$peak / 1024" | bc)" "$texture"
  done
done
