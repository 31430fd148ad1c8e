#!/usr/bin/env bash
# Configures and builds rockbake (Release, Ninja) into build/.
# Usage: scripts/build.sh [-Doption=value]... [--target TARGET]
#   -D options go to CMake's configure (they stay in build/CMakeCache.txt for later builds);
#   --target builds one target instead of everything configured.
set -euo pipefail
cd "$(dirname "$0")/.."
configure=() targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --target)
      if [ $# -lt 2 ]; then
        echo "build: --target needs a target name" >&2
        exit 2
      fi
      targets+=(--target "$2")
      shift 2
      ;;
    *)
      configure+=("$1")
      shift
      ;;
  esac
done
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${configure[@]}" > build.configure.log 2>&1 || {
  cat build.configure.log
  echo "build: cmake configure failed (log above)" >&2
  exit 1
}
rm -f build.configure.log
cmake --build build --parallel "$(nproc)" "${targets[@]}"
