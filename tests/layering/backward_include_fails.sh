#!/usr/bin/env bash
# The build enforces the pipeline's order: a stage that includes a header of a
# later stage fails to compile, one that includes an earlier stage's builds.
# Usage: backward_include_fails.sh CMAKE BUILD_DIR
set -uo pipefail
cmake=$1 build=$2

if ! out=$("$cmake" --build "$build" --target layering_probe_mesh_includes_sim 2>&1); then
  echo "$out"
  echo "FAIL: mesh/ could not include sim/weathering.h, an earlier stage's header"
  exit 1
fi
if out=$("$cmake" --build "$build" --target layering_probe_mesh_includes_render 2>&1); then
  echo "FAIL: mesh/ compiled with render/scene.h, a later stage's header"
  exit 1
fi
if ! grep -q 'render/scene.h: No such file or directory' <<<"$out"; then
  echo "$out"
  echo "FAIL: the probe failed to build, but not because render/scene.h was out of reach"
  exit 1
fi
grep -m1 'render/scene.h' <<<"$out"
echo "ok: a backward include does not compile; a forward one does"
