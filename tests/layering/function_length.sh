#!/usr/bin/env bash
# No function in baker/ runs over 100 lines (docs/architecture.md): a longer one is split
# at its own steps. Lengths come from Universal Ctags (the `end:` field), first line to
# closing brace.
# Usage: function_length.sh BAKER_DIR [LIMIT]
#        function_length.sh --self-test   plants a long function and checks it is caught
set -uo pipefail

lengths() {  # "<lines> <file> <function>", longest first
  ctags --languages=C++ --kinds-C++=f --fields=+ne -R -f - "$1" |
    awk -F'\t' '{l = 0; e = 0
      for (i = 4; i <= NF; i++) { if ($i ~ /^line:/) l = substr($i, 6) + 0; if ($i ~ /^end:/) e = substr($i, 5) + 0 }
      if (l > 0 && e >= l) print e - l + 1, $2 ":" l, $1}' | sort -rn
}

check() {
  local dir=$1 limit=$2 all long
  command -v ctags >/dev/null || { echo "FAIL: ctags not found: install universal-ctags (scripts/setup.sh)"; return 1; }
  all=$(lengths "$dir")
  [ -n "$all" ] || { echo "FAIL: ctags found no function in $dir"; return 1; }
  long=$(awk -v limit="$limit" '$1 > limit' <<<"$all")
  if [ -n "$long" ]; then
    echo "FAIL: functions over $limit lines (split them at their own steps):"
    sed 's/^/  /' <<<"$long"
    return 1
  fi
  echo "ok: $(wc -l <<<"$all") functions, the longest $(head -1 <<<"$all")"
}

if [ "${1:-}" = "--self-test" ]; then
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' EXIT
  { echo "int shortOne() { return 1; }"; echo "int longOne() {"; echo "  int x = 0;"
    for i in $(seq 1 101); do echo "  x += $i;"; done; echo "  return x;"; echo "}"; } >"$scratch/long.cpp"
  if out=$(check "$scratch" 100); then echo "$out"; echo "FAIL (self-test): a 105-line function passed"; exit 1; fi
  grep -q '105 .*long.cpp:2 longOne' <<<"$out" || { echo "$out"; echo "FAIL (self-test): not reported as 105 lines"; exit 1; }
  check "$scratch" 105 >/dev/null || { echo "FAIL (self-test): refused under a limit it meets"; exit 1; }
  echo "ok: a planted 105-line function is caught, and passes a limit of 105"
  exit 0
fi
[ $# -ge 1 ] || { echo "usage: $0 BAKER_DIR [LIMIT] | --self-test" >&2; exit 2; }
check "$1" "${2:-100}"
