#!/usr/bin/env bash
# The whole suite in an ASan + UBSan build (CMake preset `asan`, build-asan/).
# Run before each release (README, "Bad input"); any sanitizer report fails
# the test it happens in.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset asan > build-asan.configure.log 2>&1 || {
  cat build-asan.configure.log
  echo "test-sanitizers: cmake configure failed (log above)" >&2
  exit 1
}
rm -f build-asan.configure.log
cmake --build --preset asan
# The fuzzers have their own build (scripts/fuzz.sh); here only the suite.
ctest --preset asan --parallel "$(nproc)" -LE fuzz "$@"
