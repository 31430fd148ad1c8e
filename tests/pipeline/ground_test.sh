#!/usr/bin/env bash
# Rocks that sit in the ground (docs/meshes.md, "The pivot and the frames"; docs/model.md §7,
# "The toe"), read from the files a client reads:
#   - the apron's toe: LOD0's colluvium within a voxel of the ground slopes at most 15° on goblin
#     (bench/clast_figures.py), and without the toe (mesh.apron_toe: 0) it stands much steeper;
#   - asset.json's ground: a footprint polygon around the pivot, a suggested burial depth of at
#     least a voxel; mesh.sink: suggested sinks the GLB by exactly that (its lowest point);
#   - a sink deeper than the rock is tall: exit 2, the key named, nothing written.
# Usage: ground_test.sh ROCKBAKE SOURCE_DIR
set -euo pipefail
rockbake=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
py() { /usr/bin/python3 -c "$@"; }
bake() {
  local out=$1
  shift
  "$rockbake" bake "$source_dir/presets/goblin.yaml" -o "$work/$out" --resolution 48 --no-render --no-textures \
    "$@" > "$work/$out.log" 2>&1 || { cat "$work/$out.log"; fail "goblin did not bake ($*)"; }
}
bake toe
bake lip --set mesh.apron_toe=0
toe=$(/usr/bin/python3 "$source_dir/bench/clast_figures.py" "$work/toe/goblin")
lip=$(/usr/bin/python3 "$source_dir/bench/clast_figures.py" "$work/lip/goblin")
echo "toe: $toe"
echo "lip: $lip"
py "import json,sys; t=json.loads(sys.argv[1])['toe_slope_deg']; l=json.loads(sys.argv[2])['toe_slope_deg']; \
sys.exit(0 if t <= 15 and l >= 40 else 1)" "$toe" "$lip" || fail "the toe slopes more than 15° (or the lip less than 40°)"

# asset.json's ground, then the asset sunk by its suggested depth.
bake sunk --set mesh.sink=suggested
py '
import json, struct, sys
sys.path.insert(0, sys.argv[3] + "/bench")
from clast_figures import read_glb, mesh_triangles
flat = json.load(open(sys.argv[1] + "/asset.json"))["ground"]
sunk = json.load(open(sys.argv[2] + "/asset.json"))["ground"]
h = json.load(open(sys.argv[1] + "/asset.json"))["clasts"]["voxel_size_m"]
assert flat["pivot"] == "ground-contact" and flat["sink_m"] == 0, flat
assert flat["suggested_burial_m"] >= h - 1e-9, (flat["suggested_burial_m"], h)
foot = flat["footprint_m"]
assert len(foot) >= 4 and flat["contact_area_m2"] > 0, flat
xs = [p[0] for p in foot]; ys = [p[1] for p in foot]
assert min(xs) < 0 < max(xs) and min(ys) < 0 < max(ys), "the pivot is not inside the footprint"
area = 0.5 * abs(sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(foot, foot[1:] + foot[:1])))
assert area >= flat["contact_area_m2"] - 1e-6, (area, flat["contact_area_m2"])
assert sunk["sink_m"] == flat["suggested_burial_m"], (sunk, flat)
for folder, depth in ((sys.argv[1], 0.0), (sys.argv[2], sunk["sink_m"])):
    doc, binary = read_glb(folder + "/rock.glb")
    low = min(mesh_triangles(doc, binary, n["mesh"])[0][:, 1].min() for n in doc["nodes"] if n["name"].endswith("_lod0"))
    assert abs(low + depth) < 1e-4, (folder, low, depth)
print("footprint", len(foot), "points,", round(area, 3), "m² hull over", flat["contact_area_m2"], "m² contact; sunk",
      sunk["sink_m"], "m")
' "$work/toe/goblin" "$work/sunk/goblin" "$source_dir" || fail "asset.json's ground or the sunk GLB is wrong"

status=0
"$rockbake" bake "$source_dir/presets/goblin.yaml" -o "$work/deep" --resolution 32 --no-render --set mesh.sink=50 \
  > "$work/deep.log" 2>&1 || status=$?
[ "$status" -eq 2 ] || { cat "$work/deep.log"; fail "a sink deeper than the rock: exit $status, not 2"; }
grep -q "mesh.sink" "$work/deep.log" || { cat "$work/deep.log"; fail "the message does not name mesh.sink"; }
[ ! -e "$work/deep/goblin" ] || fail "a refused sink left $(ls -A "$work/deep/goblin") behind"
echo "PASS: the toe, the ground's footprint and burial depth, sinking, and a sink too deep refused"
