#!/usr/bin/env bash
# Collision hulls on every shipped preset (bench/README.md, "Collision hulls"):
# bakes each at its house resolution with --no-mesh (this build; and the
# previous build, when given, for the bake's time beside the hulls' and to
# check that both simulate the same rock), then runs rockbake_collision_bench
# on the rocks. Run it from the checkout, after building.
#   bench/collision_bench.sh [PREVIOUS_ROCKBAKE]
set -euo pipefail
previous=${1:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
presets=()
for p in presets/*.yaml; do
  case $(basename "$p") in base.yaml | library.yaml) ;; *) presets+=("$p") ;; esac
done
echo "| preset | bake --no-mesh, this build | previous build | same rock.vdb |"
echo "|---|---|---|---|"
seconds() { printf '%d.%02d s' $(($1 / 1000000000)) $(($1 % 1000000000 / 10000000)); }
for p in "${presets[@]}"; do
  name=$(basename "$p" .yaml)
  start=$(date +%s%N)
  ./build/baker/rockbake bake "$p" -o "$work/current" --no-mesh >/dev/null 2>&1
  now=$(seconds $(($(date +%s%N) - start)))
  before=- same=-
  if [ -n "$previous" ]; then
    start=$(date +%s%N)
    "$previous" bake "$p" -o "$work/previous" --no-mesh >/dev/null 2>&1
    before=$(seconds $(($(date +%s%N) - start)))
    same=$(cmp -s "$work/current/$name/rock.vdb" "$work/previous/$name/rock.vdb" && echo yes || echo NO)
  fi
  printf '| %s | %s | %s | %s |\n' "$name" "$now" "$before" "$same"
done
echo
./build/bench/rockbake_collision_bench "$work/current" "${presets[@]}"
