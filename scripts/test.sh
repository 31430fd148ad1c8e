#!/usr/bin/env bash
# Installs what is missing (everything), builds with the tests and benchmarks, and runs every
# test with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh -DROCKBAKE_BUILD_TESTS=ON -DROCKBAKE_BUILD_BENCH=ON
ctest --test-dir build --output-on-failure --parallel "$(nproc)"
