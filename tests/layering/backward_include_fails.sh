#!/usr/bin/env bash
# The build enforces what a stage may include (baker/CMakeLists.txt): a header of a
# stage it does not link fails to compile, whether that stage comes later (render) or
# earlier (sim, whose results reach the mesh stage as plain data); a header of a stage
# it links compiles.
# Usage: backward_include_fails.sh CMAKE BUILD_DIR
set -uo pipefail
cmake=$1 build=$2

if ! out=$("$cmake" --build "$build" --target layering_probe_mesh_includes_geometry 2>&1); then
  echo "$out"
  echo "FAIL: mesh/ could not include geometry/edge_table.h, a header of a stage it links"
  exit 1
fi
for probe in render/scene.h sim/weathering.h; do
  target=layering_probe_mesh_includes_${probe%%/*}
  if out=$("$cmake" --build "$build" --target "$target" 2>&1); then
    echo "FAIL: mesh/ compiled with $probe, a header of a stage it does not link"
    exit 1
  fi
  if ! grep -q "$probe: No such file or directory" <<<"$out"; then
    echo "$out"
    echo "FAIL: the probe $target failed to build, but not because $probe was out of reach"
    exit 1
  fi
  grep -m1 "$probe" <<<"$out"
done
echo "ok: a header of a stage not linked does not compile; one of a linked stage does"
