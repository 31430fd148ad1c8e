#!/usr/bin/env bash
# POV-Ray's antialiasing jitter against the same render without it (-J), on one
# scene at two threads, interleaved in one run: wall seconds and CPU seconds
# (user + system: the work done, less sensitive to a shared machine's load) per
# render, and whether each image is pixel-identical to the first of its kind
# (idiff -fail 0).
#   bench/render_threads.sh SCENE_DIR [RUNS]   (SCENE_DIR holds scene.pov and rock_mesh.inc)
set -euo pipefail
scene_dir=$(cd "$1" && pwd)
runs=${2:-5}
work=$(mktemp -d /tmp/render_threads.XXXXXX)
trap 'rm -rf "$work"' EXIT
cp "$scene_dir/scene.pov" "$scene_dir/rock_mesh.inc" "$work/"
cd "$work"
render() {  # $1 = label, $2 = run, $3.. = extra POV-Ray options
  local label=$1 run=$2
  shift 2
  local t0 t1 cpu
  t0=$(date +%s.%N)
  /usr/bin/time -f '%U %S' -o cpu.txt povray -D -V -P +Iscene.pov "+O$label-$run.exr" +FE +W640 +H480 +Q9 +A0.3 "$@" +WT2 \
    >/dev/null 2>&1
  t1=$(date +%s.%N)
  cpu=$(awk '{ print $1 + $2 }' cpu.txt)
  local same=first
  if [[ $run -gt 1 ]]; then
    if idiff -fail 0 -warn 0 "$label-1.exr" "$label-$run.exr" >/dev/null 2>&1; then same=same; else same=DIFFERS; fi
  fi
  printf '%-9s run %d  %6.2f s wall  %6.2f s CPU  %s\n' "$label" "$run" "$(echo "$t1 - $t0" | bc)" "$cpu" "$same"
}
for run in $(seq 1 "$runs"); do
  render jitter "$run"
  render no-jitter "$run" -J
done
