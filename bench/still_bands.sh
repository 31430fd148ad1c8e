#!/usr/bin/env bash
# A lone still rendered the previous build's way (one single-threaded POV-Ray process) against
# this build's (bands of rows, one single-threaded process per core, joined), interleaved in one
# run: wall and CPU seconds (user + system of rockbake and its POV-Ray processes) per render, and
# whether each EXR is byte-identical to the previous build's first.
#   bench/still_bands.sh OLD_ROCKBAKE NEW_ROCKBAKE ASSET_DIR [RUNS] [TEMPLATE (studio)]
# ASSET_DIR is a baked asset (OUT/<name>, with its preset's render block); it is copied, and
# both builds re-render its still with `rockbake render --output` (no turntable).
set -euo pipefail
old=$1 new=$2
runs=${4:-3}
work=$(mktemp -d /tmp/still_bands.XXXXXX)
trap 'rm -rf "$work"' EXIT
cp -r "$3" "$work/asset"
template=${5:-studio}
render() {  # $1 = label, $2 = binary, $3 = run
  local label=$1 bin=$2 run=$3 t0 t1 cpu same
  t0=$(date +%s.%N)
  /usr/bin/time -f '%U %S' -o "$work/cpu.txt" "$bin" render "$work/asset" --template "$template" \
    --output "$label-$run" --threads 2 >/dev/null 2>&1
  t1=$(date +%s.%N)
  cpu=$(awk '{ print $1 + $2 }' "$work/cpu.txt")
  same=first
  if [[ -f "$work/asset/previous-1.exr" && "$label-$run" != previous-1 ]]; then
    if cmp -s "$work/asset/previous-1.exr" "$work/asset/$label-$run.exr"; then same=same-bytes; else same=DIFFERS; fi
  fi
  printf '%-8s run %d  %6.2f s wall  %6.2f s CPU  %s\n' "$label" "$run" "$(echo "$t1 - $t0" | bc)" "$cpu" "$same"
}
for run in $(seq 1 "$runs"); do
  render previous "$old" "$run"
  render bands "$new" "$run"
done
