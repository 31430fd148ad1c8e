#!/usr/bin/env bash
# Clean-build wall time of two commits, one after the other on this machine: each checked out
# into a scratch worktree, configured (Release, Ninja) and built with every default target at
# --parallel N with ccache off. Compare within one run, never against old figures.
# Usage: bench/clean_build_time.sh OLD_REV NEW_REV [JOBS]
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 OLD_REV NEW_REV [JOBS]" >&2; exit 2; }
repo=$(cd "$(dirname "$0")/.." && pwd)
jobs=${3:-$(nproc)}
scratch=$(mktemp -d)
trap 'for w in "$scratch"/old "$scratch"/new; do git -C "$repo" worktree remove --force "$w" 2>/dev/null || true; done; rm -rf "$scratch"' EXIT
for which in old new; do
  rev=$([ $which = old ] && echo "$1" || echo "$2")
  git -C "$repo" worktree add -q --detach "$scratch/$which" "$rev"
  cmake -S "$scratch/$which" -B "$scratch/$which/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >"$scratch/$which.cfg" 2>&1
  start=$(date +%s.%N)
  CCACHE_DISABLE=1 cmake --build "$scratch/$which/build" --parallel "$jobs" >"$scratch/$which.log" 2>&1
  end=$(date +%s.%N)
  printf '%s (%s): %.1f s, %d compiles\n' "$which" "$rev" "$(echo "$end - $start" | bc)" \
    "$(grep -c 'Building CXX' "$scratch/$which.log")"
done
