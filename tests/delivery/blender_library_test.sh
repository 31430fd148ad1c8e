#!/usr/bin/env bash
# `rockbake blender-library` end to end (docs/libraries.md, "Blender's asset browser"): a small
# library (goblin and rounded-cobble × two seeds, at resolution 32 with 256-texel maps and a
# 128 × 96 still) and a plain bake without render in Unreal's profile (its maps embedded in its
# GLBs, docs/delivery.md) and at two world units a metre go into a Blender asset library,
# which Debian's Blender 3.4 then opens headless (tests/delivery/blender_library_check.py): every
# asset with its catalogue (through blender_assets.cats.txt), tags and preview, the LODs and hulls
# each .blend holds, and one asset appended into a new scene, textured and of asset.json's size in
# metres. A second run over the library, without the plain bake, replaces it: the same catalogue
# file less that asset's line, its .blend removed, no temporary left. A third, with one asset's
# LOD cut off, exits 1 for that asset alone.
# Usage: blender_library_test.sh ROCKBAKE SOURCE_DIR
set -euo pipefail
rockbake=$1
source_dir=$2
if ! command -v blender >/dev/null; then
  echo "FAIL: blender is missing; run scripts/setup.sh" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cat > "$work/lib.yaml" <<YAML
- {preset: $source_dir/presets/goblin.yaml, seeds: [1, 2]}
- {preset: $source_dir/presets/rounded-cobble.yaml, seeds: [1, 2]}
YAML
"$rockbake" library "$work/lib.yaml" -o "$work/baked" --jobs 2 --resolution 32 --set texture.size=256 \
  --set render.width=128 --set render.height=96 2>"$work/bake.log" || { cat "$work/bake.log"; fail "the library bake failed"; }
# Without a render (a preview made by Cycles), in Unreal's profile (SM_ names, embedded maps), two
# world units a metre (its GLBs, and so its .blend, half the size of its grid).
"$rockbake" bake "$source_dir/presets/cube-to-sphere.yaml" -o "$work/loose" --resolution 32 --no-render \
  --set texture.size=256 --set delivery.profile=unreal --set units_per_meter=2 2>"$work/bake.log" || { cat "$work/bake.log"; fail "the plain bake failed"; }

"$rockbake" blender-library "$work/baked" "$work/loose/cube-to-sphere" -o "$work/blender" --jobs 2
python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
assets = {f"{p}-s{s}": {"catalog": p, "dir": f"{work}/baked/{p}-s{s}"} for p in ("goblin", "rounded-cobble") for s in (1, 2)}
assets["cube-to-sphere"] = {"catalog": "cube-to-sphere", "dir": f"{work}/loose/cube-to-sphere"}
json.dump({"assets": assets, "append": "goblin-s2"}, open(f"{work}/expected.json", "w"))
marker = json.load(open(f"{work}/blender/rockbake_blender_library.json"))
previews = {a["name"]: a["preview"] for a in marker["assets"]}
assert all(a["status"] == "ok" for a in marker["assets"]), marker
assert previews["goblin-s1"] == "render.png" and previews["cube-to-sphere"] == "generated", previews
PY
# Blender exits 0 even when the script fails: the script's own exit status is what counts.
blender --background --factory-startup --python-exit-code 1 \
  --python "$source_dir/tests/delivery/blender_library_check.py" -- "$work/blender" "$work/expected.json"

# Re-run over it without the plain bake, after a run killed while Blender saved (its temporaries
# planted): replaced, deterministic catalogues, nothing left over.
cp "$work/blender/blender_assets.cats.txt" "$work/cats-1.txt"
echo partial > "$work/blender/.goblin-s1.999999.partial.blend"
echo partial > "$work/blender/.goblin-s1.999999.partial.blend@"
"$rockbake" blender-library "$work/baked" -o "$work/blender" --jobs 2 2>"$work/rerun.log" ||
  { cat "$work/rerun.log"; fail "the re-run failed"; }
grep -q "1 earlier .blend files removed" "$work/rerun.log" || { cat "$work/rerun.log"; fail "the re-run removed nothing"; }
grep -v ':cube-to-sphere:' "$work/cats-1.txt" | cmp - "$work/blender/blender_assets.cats.txt" ||
  fail "the re-run's catalogue file is not the first one less cube-to-sphere"
left=$(cd "$work/blender" && ls -A | LC_ALL=C sort | tr '\n' ' ')
[ "$left" = ".rockbake_blender_library.lock blender_assets.cats.txt goblin-s1.blend goblin-s2.blend rockbake_blender_library.json rounded-cobble-s1.blend rounded-cobble-s2.blend " ] ||
  fail "after the re-run the library holds: $left"

# Blender failing on one asset (a LOD cut off): exit status 1 naming it, the others written, its
# earlier .blend left as it was.
truncate -s 100 "$work/baked/rounded-cobble-s2/rock_lod1.glb"
before=$(stat -c %Y.%i "$work/blender/rounded-cobble-s2.blend")
status=0
"$rockbake" blender-library "$work/baked" -o "$work/blender" 2>"$work/failed.log" || status=$?
[ "$status" = 1 ] || { cat "$work/failed.log"; fail "a failing asset: exit status $status, expected 1"; }
grep -q "rounded-cobble-s2: Blender failed: Blender's glTF importer cannot read .*/rock_lod1.glb" "$work/failed.log" &&
  grep -q "3 written, 1 failed" "$work/failed.log" || { cat "$work/failed.log"; fail "a failing asset: not reported"; }
[ "$(stat -c %Y.%i "$work/blender/rounded-cobble-s2.blend")" = "$before" ] || fail "the failed asset's .blend was replaced"
python3 -c '
import json, sys
m = json.load(open(sys.argv[1]))
s = {a["name"]: a["status"] for a in m["assets"]}
assert s == {"goblin-s1": "ok", "goblin-s2": "ok", "rounded-cobble-s1": "ok", "rounded-cobble-s2": "failed"}, s
' "$work/blender/rockbake_blender_library.json"
left=$(cd "$work/blender" && ls -A | LC_ALL=C sort | tr '\n' ' ')
[ "$left" = ".rockbake_blender_library.lock blender_assets.cats.txt goblin-s1.blend goblin-s2.blend rockbake_blender_library.json rounded-cobble-s1.blend rounded-cobble-s2.blend " ] ||
  fail "after the failed run the library holds: $left"
echo "ok"
