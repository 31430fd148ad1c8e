#!/usr/bin/env bash
# `rockbake blender-library` refuses bad input with exit status 2 and writes nothing
# (docs/command-line.md): a folder that is not a bake, Blender missing from PATH or named where
# there is none (the message says what to install), an output folder that is not a Blender
# library rockbake wrote (a file, someone's folder, someone's own Blender library), and one
# another run is writing. Blender is not
# needed: where a Blender must be found first, a stand-in answers --version and would fail any
# script, so a check that came too late would show as exit status 1.
# Usage: blender_library_bad_input_test.sh ROCKBAKE SOURCE_DIR
set -euo pipefail
rockbake=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$rockbake" bake "$source_dir/tests/data/small.yaml" -o "$work/baked" --no-render 2>/dev/null
mkdir "$work/bin"
printf '#!/bin/sh\necho "Blender 3.4.1"\nexit 0\n' > "$work/bin/blender"
chmod +x "$work/bin/blender"
stand_in=$work/bin/blender

# expect_refusal NAME TEXT... -- COMMAND...: exit status 2, each TEXT in the message.
expect_refusal() {
  local name=$1; shift
  local -a texts=()
  while [ "$1" != "--" ]; do texts+=("$1"); shift; done
  shift
  local status=0
  "$@" >"$work/out.log" 2>&1 || status=$?
  [ "$status" = 2 ] || { cat "$work/out.log"; fail "$name: exit status $status, expected 2"; }
  for text in "${texts[@]}"; do
    grep -qF -- "$text" "$work/out.log" || { cat "$work/out.log"; fail "$name: the message lacks '$text'"; }
  done
  echo "ok: $name: $(head -1 "$work/out.log")"
}

mkdir "$work/photos"
echo x > "$work/photos/holiday.jpg"
expect_refusal "not a bake" "$work/photos: is not a rockbake bake" "expected an asset folder (holding manifest.json" -- \
  "$rockbake" blender-library "$work/photos" -o "$work/lib" --blender "$stand_in"
[ ! -e "$work/lib" ] || fail "not a bake: $work/lib was written"

expect_refusal "blender not on PATH" "no blender on PATH" "apt-get install blender" "scripts/setup.sh" -- \
  env -u ROCKBAKE_BLENDER PATH="$work/photos" "$rockbake" blender-library "$work/baked/small" -o "$work/lib"
[ ! -e "$work/lib" ] || fail "blender not on PATH: $work/lib was written"

expect_refusal "--blender names no file" "--blender $work/no/blender: there is no such file" "apt-get install blender" -- \
  "$rockbake" blender-library "$work/baked/small" -o "$work/lib" --blender "$work/no/blender"
expect_refusal "ROCKBAKE_BLENDER names no file" "ROCKBAKE_BLENDER=$work/no/blender: there is no such file" -- \
  env ROCKBAKE_BLENDER="$work/no/blender" "$rockbake" blender-library "$work/baked/small" -o "$work/lib"
[ ! -e "$work/lib" ] || fail "a missing blender: $work/lib was written"

mkdir "$work/mine"
echo "keep me" > "$work/mine/notes.txt"
expect_refusal "someone's folder" "$work/mine: is a folder that is not a Blender library rockbake wrote" -- \
  "$rockbake" blender-library "$work/baked/small" -o "$work/mine" --blender "$stand_in"
mkdir "$work/theirs"
printf 'VERSION 1\n' > "$work/theirs/blender_assets.cats.txt"
expect_refusal "someone's Blender library" "is a Blender asset library rockbake did not write" -- \
  "$rockbake" blender-library "$work/baked/small" -o "$work/theirs" --blender "$stand_in"
echo x > "$work/file"
expect_refusal "a file" "$work/file: is a file, not a folder" -- \
  "$rockbake" blender-library "$work/baked/small" -o "$work/file" --blender "$stand_in"
[ "$(ls -A "$work/mine")" = "notes.txt" ] && [ "$(cat "$work/mine/notes.txt")" = "keep me" ] ||
  fail "someone's folder was written: $(ls -A "$work/mine")"
[ "$(ls -A "$work/theirs")" = "blender_assets.cats.txt" ] && [ "$(cat "$work/theirs/blender_assets.cats.txt")" = "VERSION 1" ] ||
  fail "someone's Blender library was written"
[ "$(cat "$work/file")" = "x" ] || fail "the file was written"

# Another run writing the library (here this shell holds its lock): refused, nothing written.
mkdir "$work/busy"
exec 9>"$work/busy/.rockbake_blender_library.lock"
flock 9
expect_refusal "another run" "$work/busy: another rockbake blender-library is writing this library" -- \
  "$rockbake" blender-library "$work/baked/small" -o "$work/busy" --blender "$stand_in"
exec 9>&-
[ "$(ls -A "$work/busy")" = ".rockbake_blender_library.lock" ] || fail "the busy library was written: $(ls -A "$work/busy")"

expect_refusal "no -o" "--out is required" -- "$rockbake" blender-library "$work/baked/small"
echo "ok"
