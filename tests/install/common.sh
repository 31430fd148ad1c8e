# Shared by the install tests (sourced): pass/fail reporting, a scratch folder kept
# on failure, a small preset and the check that a bake rendered something.

failures=0
pass() { echo "PASS: $*"; }
fail_check() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
die() {
  echo "FAIL: $*"
  exit 1
}
# The last line: every check passed, or how many did not.
finish() {
  if [ $failures -eq 0 ]; then echo "PASS: $*"; else die "$failures check(s) failed"; fi
}

# work=<a fresh folder under /tmp>, removed on success, kept (and named) on failure.
make_work_dir() {
  work=$(mktemp -d "/tmp/$1.XXXXXX")
  trap 'rc=$?; if [ $rc -eq 0 ]; then rm -rf "$work"; else echo "files kept in $work" >&2; fi; exit $rc' EXIT
  trap 'exit 130' INT TERM
}

# write_small_preset FILE: a cube weathered for a few cycles at resolution 20, a 96×72 render
# (the C++ tests' small preset, tests/data/small.yaml, coarser and younger).
small_preset=$(cd "$(dirname "${BASH_SOURCE[0]}")/../data" && pwd)/small.yaml
write_small_preset() {
  sed -e 's/resolution: 24}$/resolution: 20}/' -e 's/^time: 0\.5$/time: 0.3/' "$small_preset" >"$1"
  echo 'render: {width: 96, height: 72}' >>"$1"
}

# check_render ASSET_DIR: render.exr is there, render.png is a PNG and not one flat colour
# (POV-Ray drew the rock; oiiotool from openimageio-tools measures it).
check_render() {
  local png=$1/render.png stddev
  if [ -s "$png" ] && [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; then
    pass "render.png is a PNG of $(stat -c %s "$png") bytes"
  else
    fail_check "$png is missing, empty or not a PNG"
    return
  fi
  [ -s "$1/render.exr" ] || fail_check "no render.exr in $1"
  stddev=$(oiiotool "$png" --printstats 2>/dev/null | sed -n 's/.*Stats StdDev: \([0-9. ]*\).*/\1/p' | head -n 1)
  if awk -v s="$stddev" 'BEGIN { n = split(s, v, " "); for (i = 1; i <= n; ++i) if (v[i] + 0 > 0.01) exit 0; exit 1 }'; then
    pass "the render shows something (channel std. dev. $stddev of 255)"
  else
    fail_check "$png is one flat colour (std. dev. '$stddev')"
  fi
}
