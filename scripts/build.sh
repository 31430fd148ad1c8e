#!/usr/bin/env bash
# Configures and builds rockbake (Release, Ninja) into build/.
# Usage: scripts/build.sh [extra cmake -D options]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" > build.configure.log 2>&1 || {
  cat build.configure.log
  echo "build: cmake configure failed (log above)" >&2
  exit 1
}
rm -f build.configure.log
cmake --build build --parallel "$(nproc)"
