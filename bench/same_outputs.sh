#!/usr/bin/env bash
# Bakes every catalogue preset with two builds and compares what they write byte for byte:
# rock.vdb, meshes, GLBs, maps, EXRs, the scene and asset.json (stats.json and the manifest
# hold timings and are left out). Each preset at --resolution 48 with its texture set and no
# render; goblin at the house settings without, then with, its still.
# Usage: bench/same_outputs.sh OLD_ROCKBAKE OLD_DATA_DIR NEW_ROCKBAKE NEW_DATA_DIR OUT
#   a DATA_DIR holds that build's presets/ and render_templates/ (ROCKBAKE_DATA_DIR).
#   NEW_ARGS (environment, optional): more arguments for the new build's bakes, e.g.
#   NEW_ARGS="--set look=none" to compare a build with looks, turned off, against one without.
set -uo pipefail
[ $# -eq 5 ] || { echo "usage: $0 OLD_ROCKBAKE OLD_DATA_DIR NEW_ROCKBAKE NEW_DATA_DIR OUT" >&2; exit 2; }
out=$5
rm -rf "$out" && mkdir -p "$out"
bake() {  # old|new PRESET_NAME SUBFOLDER ARGS...
  local which=$1 name=$2 sub=$3 exe data
  shift 3
  exe=$([ "$which" = old ] && echo "$OLD" || echo "$NEW")
  data=$([ "$which" = old ] && echo "$OLD_DATA" || echo "$NEW_DATA")
  local extra=()
  [ "$which" = new ] && [ -n "${NEW_ARGS:-}" ] && read -r -a extra <<< "$NEW_ARGS"
  ROCKBAKE_DATA_DIR="$data" "$exe" bake "$data/presets/$name.yaml" -o "$out/$which/$sub" "$@" "${extra[@]}" >/dev/null 2>"$out/$which.$sub.$name.log" ||
    echo "$which: $name ($sub) failed: $out/$which.$sub.$name.log"
}
OLD=$1 OLD_DATA=$2 NEW=$3 NEW_DATA=$4
for preset in "$NEW_DATA"/presets/*.yaml; do
  name=$(basename "$preset" .yaml)
  case $name in base | library) continue ;; esac
  for which in old new; do bake $which "$name" small --resolution 48 --no-render; done
done
for which in old new; do bake $which goblin house --no-render; bake $which goblin render; done
cd "$out"
n=0 d=0
while IFS= read -r f; do
  n=$((n + 1))
  cmp -s "old/$f" "new/$f" || { echo "DIFFERS: $f"; d=$((d + 1)); }
done < <(cd old && find . -type f \( -name '*.vdb' -o -name '*.ply' -o -name '*.obj' -o -name '*.glb' -o -name '*.png' \
  -o -name '*.exr' -o -name '*.inc' -o -name '*.pov' -o -name asset.json -o -name '*.mp4' \) | sort)
echo "compared $n files, $d differ"
[ "$d" -eq 0 ]
