#!/usr/bin/env bash
# Every stage links exactly the stages its files include (baker/CMakeLists.txt,
# docs/architecture.md): a stage that includes another's header without linking it,
# or links one whose headers it never includes, fails; so does any include circle,
# between files or between stages.
# Usage: links_match_includes.sh BAKER_DIR STAGE_LINKS_DIR
#   STAGE_LINKS_DIR holds <stage>.txt, the rockbake_* targets the build links each
#   stage to, one a line (written at generate time from the targets themselves).
#        links_match_includes.sh --self-test
#   plants each kind of fault in a scratch tree and checks that it is caught.
set -uo pipefail

check() {
  local baker=$1 links=$2 problems=0 stage dep
  local -a stages=()
  for f in "$links"/*.txt; do stages+=("$(basename "$f" .txt)"); done
  is_stage() { local s; for s in "${stages[@]}"; do [ "$s" = "$1" ] && return 0; done; return 1; }

  for stage in "${stages[@]}"; do
    [ -d "$baker/$stage" ] || { echo "FAIL: $stage is linked as a stage but $baker/$stage is no folder"; problems=1; continue; }
    local included linked
    included=$(grep -rhoE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"[a-z_]+/' "$baker/$stage" |
      sed -E 's/.*"([a-z_]+)\//\1/' | sort -u | while read -r d; do
        [ "$d" != "$stage" ] && is_stage "$d" && echo "$d"; done)
    linked=$(sed -E 's/^rockbake_//' "$links/$stage.txt" | grep -v '^$' | grep -vx "$stage" | sort -u)
    for dep in $included; do
      if ! grep -qx "$dep" <<<"$linked"; then
        local where
        where=$(grep -rnE "^[[:space:]]*#[[:space:]]*include[[:space:]]*\"$dep/" "$baker/$stage" | head -1 | cut -d: -f1,2)
        echo "FAIL: $stage includes $dep ($where) but does not link rockbake_$dep"
        problems=1
      fi
    done
    for dep in $linked; do
      if ! grep -qx "$dep" <<<"$included"; then
        echo "FAIL: $stage links rockbake_$dep but none of its files includes a $dep/ header"
        problems=1
      fi
    done
  done

  # Circles: between files (an include that resolves to a file in baker/), and between stages.
  local file_edges stage_edges
  file_edges=$(cd "$baker" && grep -rnoE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"[a-z_]+/[A-Za-z0-9_./]+"' --include='*.h' --include='*.cpp' . |
    sed -E 's#^\./([^:]+):[0-9]+:.*"([^"]+)"#\1 \2#' | while read -r from to; do [ -f "$to" ] && echo "$from $to"; done)
  if ! out=$(tsort <<<"$file_edges" 2>&1 >/dev/null) || [ -n "$out" ]; then
    echo "FAIL: an include circle between files:"
    grep -v 'input contains a loop' <<<"$out" | sed 's/^tsort: /  /'
    problems=1
  fi
  stage_edges=$(for stage in "${stages[@]}"; do sed -E 's/^rockbake_//' "$links/$stage.txt" | grep -v '^$' |
    while read -r dep; do echo "$stage $dep"; done; done)
  if ! out=$(tsort <<<"$stage_edges" 2>&1 >/dev/null) || [ -n "$out" ]; then
    echo "FAIL: a circle of stage links:"
    grep -v 'input contains a loop' <<<"$out" | sed 's/^tsort: /  /'
    problems=1
  fi
  return $problems
}

self_test() {
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
  plant() {  # a tree where a links b, b links nothing; a.h includes b.h
    rm -rf "$scratch/baker" "$scratch/links"
    mkdir -p "$scratch/baker/a" "$scratch/baker/b" "$scratch/baker/c" "$scratch/links"
    printf '#include "b/b.h"\n' >"$scratch/baker/a/a.h"
    printf '#include "a/a.h"\n' >"$scratch/baker/a/a.cpp"
    printf '#pragma once\n' >"$scratch/baker/b/b.h"
    printf '#pragma once\n' >"$scratch/baker/c/c.h"
    printf 'rockbake_b\n' >"$scratch/links/a.txt"
    printf '\n' >"$scratch/links/b.txt"
    printf '\n' >"$scratch/links/c.txt"
  }
  expect_fail() {  # $1: what was planted, $2: the message that must name it
    local out
    if out=$(check "$scratch/baker" "$scratch/links"); then
      echo "FAIL (self-test): $1 was not caught"
      exit 1
    fi
    grep -q "$2" <<<"$out" || { echo "$out"; echo "FAIL (self-test): $1 was caught, but not as \"$2\""; exit 1; }
    echo "ok: $1 is caught: $(grep -m1 "$2" <<<"$out")"
  }
  plant
  check "$scratch/baker" "$scratch/links" >/dev/null || { echo "FAIL (self-test): the clean tree was refused"; exit 1; }
  plant; printf '#include "c/c.h"\n' >>"$scratch/baker/a/a.cpp"
  expect_fail "an include of a stage not linked" "a includes c (.*a.cpp:2) but does not link rockbake_c"
  plant; printf 'rockbake_c\n' >>"$scratch/links/a.txt"
  expect_fail "a link to a stage never included" "a links rockbake_c but none of its files includes"
  plant; printf '#include "b/b2.h"\n' >"$scratch/baker/b/b.h"; printf '#include "b/b.h"\n' >"$scratch/baker/b/b2.h"
  expect_fail "an include circle between files" "an include circle between files"
  plant; printf 'rockbake_a\n' >"$scratch/links/b.txt"; printf '#include "a/a.h"\n' >>"$scratch/baker/b/b.h"
  expect_fail "a circle of stage links" "a circle of stage links"
  echo "ok: the check catches every planted fault"
}

if [ "${1:-}" = "--self-test" ]; then
  self_test
  exit 0
fi
if [ $# -ne 2 ]; then
  echo "usage: $0 BAKER_DIR STAGE_LINKS_DIR | --self-test" >&2
  exit 2
fi
if check "$1" "$2"; then
  echo "ok: $(ls "$2" | wc -l) stages each link exactly the stages they include; no include circle"
else
  exit 1
fi
