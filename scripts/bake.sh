#!/usr/bin/env bash
# The main job: installs what a bake needs when it is missing, builds the rockbake executable,
# and bakes the default preset (presets/goblin.yaml) into out/goblin/. Extra arguments go to
# `rockbake bake`, e.g. scripts/bake.sh --resolution 64.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh bake
# A first build leaves the tests and benchmarks out (their packages are the test command's);
# a build folder configured before keeps its settings, and only the executable is built.
if [ -f build/CMakeCache.txt ]; then
  bash scripts/build.sh --target rockbake
else
  bash scripts/build.sh -DROCKBAKE_BUILD_TESTS=OFF -DROCKBAKE_BUILD_BENCH=OFF --target rockbake
fi
./build/baker/rockbake bake presets/goblin.yaml -o out "$@"
echo "bake: wrote $(pwd)/out/goblin/"
ls -l out/goblin/
