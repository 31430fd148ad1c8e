#!/usr/bin/env bash
# The main job: installs what is missing, builds, and bakes the default
# preset (presets/goblin.yaml) into out/goblin/. Extra arguments go to
# `rockbake bake`, e.g. scripts/bake.sh --resolution 64.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/baker/rockbake bake presets/goblin.yaml -o out "$@"
echo "bake: wrote $(pwd)/out/goblin/"
ls -l out/goblin/
