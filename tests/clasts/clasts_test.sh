#!/usr/bin/env bash
# Stones on the apron (docs/model.md §13), checked the way a client reads them: from the exported
# GLB (bench/clast_figures.py reads nodes, transforms and meshes with its own GLB reader), on
# goblin and on the tall talus-cliff at a coarse resolution:
#   - at least 100 stones on each, sized over a broad range (95th percentile ≥ 6 × the 5th);
#   - fall-sorted: Spearman(size, distance from the rock's foot) ≥ 0.3;
#   - resting: every stone's lowest point within 0.25 voxel of the apron or ground under it;
#     no two overlapping by more than 10 % of the smaller's volume; none reaching into the rock;
#   - instances: nodes clast_<k> share at most clasts.shapes meshes;
#   - the same bytes at 1 and 2 threads (GLBs and the stones' maps);
#   - stones keep their world size under --resolution (clasts.size scaled unless --set gives it);
#   - bad clasts: settings refused with exit 2 and nothing written.
# Usage: clasts_test.sh ROCKBAKE SOURCE_DIR
set -euo pipefail
rockbake=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
figures() { /usr/bin/python3 "$source_dir/bench/clast_figures.py" "$1"; }
field() { /usr/bin/python3 -c "import json,sys; print(json.loads(sys.argv[1])[sys.argv[2]])" "$1" "$2"; }
at_least() { /usr/bin/python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) >= float(sys.argv[2]) else 1)" "$1" "$2"; }

for preset in goblin talus-cliff; do
  "$rockbake" bake "$source_dir/presets/$preset.yaml" -o "$work/t1" --resolution 48 --no-render --threads 1 \
    --set texture.size=512 > "$work/$preset.log" 2>&1 || { cat "$work/$preset.log"; fail "$preset did not bake"; }
  f=$(figures "$work/t1/$preset")
  echo "$preset: $f"
  at_least "$(field "$f" stones)" 100 || fail "$preset: fewer than 100 stones: $f"
  at_least "$(field "$f" size_ratio)" 6 || fail "$preset: sizes too alike: $f"
  at_least "$(field "$f" spearman_size_distance)" 0.3 || fail "$preset: stones not fall-sorted: $f"
  at_least 0.25 "$(field "$f" largest_gap_voxels)" || fail "$preset: a stone floats or sinks: $f"
  at_least 0.10 "$(field "$f" largest_overlap)" || fail "$preset: stones overlap: $f"
  [ "$(field "$f" into_rock)" = 0 ] || fail "$preset: a stone reaches into the rock: $f"
done

# Instances: several nodes, one mesh (glTF's own instancing), at most `shapes` meshes.
/usr/bin/python3 - "$work/t1/goblin/rock.glb" "$source_dir" <<'PY' || fail "goblin's stones are not instances of closed meshes"
import json, struct, sys
data = open(sys.argv[1], "rb").read()
size = struct.unpack_from("<I", data, 12)[0]
doc = json.loads(data[20:20 + size])
stones = [n for n in doc["nodes"] if n["name"].startswith("clast_")]
meshes = {n["mesh"] for n in stones}
assert len(stones) >= 100 and 1 <= len(meshes) <= 8, (len(stones), meshes)
assert all(doc["meshes"][m]["name"].startswith("clast_shape_") for m in meshes)
materials = {doc["meshes"][m]["primitives"][0]["material"] for m in meshes}
assert len(materials) == 1, materials
# Each stone mesh is closed: welded by position (a textured mesh is split along its uv seams),
# every edge is shared by exactly two triangles, in opposite directions.
import numpy as np
sys.path.insert(0, sys.argv[2] + "/bench")
from clast_figures import mesh_triangles, read_glb
_, binary = read_glb(sys.argv[1])
for m in meshes:
    pos, idx = mesh_triangles(doc, binary, m)
    _, weld = np.unique(pos.round(6), axis=0, return_inverse=True)
    tri = weld.reshape(-1)[idx]
    directed = {}
    for a, b, c in tri:
        for e in ((a, b), (b, c), (c, a)):
            directed[e] = directed.get(e, 0) + 1
    assert all(n == 1 and directed.get((e[1], e[0]), 0) == 1 for e, n in directed.items()), f"mesh {m} is not closed"
print(f"{len(stones)} stone nodes share {len(meshes)} closed meshes and one material")
PY

# The same stones at any thread count.
"$rockbake" bake "$source_dir/presets/goblin.yaml" -o "$work/t2" --resolution 48 --no-render --threads 2 \
  --set texture.size=512 > "$work/t2.log" 2>&1 || { cat "$work/t2.log"; fail "goblin did not bake at 2 threads"; }
for f in rock.glb rock_lod1.glb rock_lod3.glb textures/goblin_Clasts_BaseColor.png textures/goblin_Clasts_Normal_LOD0.png \
  textures/goblin_Clasts_ORM.png; do
  cmp -s "$work/t1/goblin/$f" "$work/t2/goblin/$f" || fail "$f differs between 1 and 2 threads"
done

# Collision: no stone hulls by default; with collision.colluvium, the largest max_hulls stones get
# one each, named after their nodes, listed in asset.json.
stone_hulls() { /usr/bin/python3 -c "
import json, sys
hulls = [h['node'] for h in json.load(open(sys.argv[1] + '/asset.json'))['collision']['hulls']]
print(sum(1 for n in hulls if n.startswith('UCX_clast_')))" "$1"; }
[ "$(stone_hulls "$work/t1/goblin")" = 0 ] || fail "stones got hulls without collision.colluvium"
"$rockbake" bake "$source_dir/presets/goblin.yaml" -o "$work/hulls" --resolution 48 --no-render --no-textures \
  --set collision.colluvium=true --set collision.max_hulls=8 > "$work/hulls.log" 2>&1 || { cat "$work/hulls.log"; fail "hulls"; }
[ "$(stone_hulls "$work/hulls/goblin")" = 8 ] || fail "collision.colluvium gave $(stone_hulls "$work/hulls/goblin") stone hulls, not 8"
grep -qa "UCX_clast_7_00" "$work/hulls/goblin/collision.glb" || fail "collision.glb has no UCX_clast_7_00"

# Stones keep their size under --resolution: clasts.size is scaled from the preset's resolution
# (96) to the one asked for, unless the command line gave it.
sizes() { "$rockbake" preset show "$source_dir/presets/goblin.yaml" "$@" |
  /usr/bin/python3 -c "import json,sys; print(json.load(sys.stdin)['clasts']['size'])"; }
[ "$(sizes --resolution 48)" = "[0.5, 5.0]" ] || fail "--resolution 48 gave stones of $(sizes --resolution 48) voxels"
[ "$(sizes --resolution 192)" = "[2.0, 20.0]" ] || fail "--resolution 192 gave $(sizes --resolution 192)"
[ "$(sizes --resolution 48 --set 'clasts.size=[1, 10]')" = "[1.0, 10.0]" ] || fail "--set clasts.size was scaled"

# Bad settings: exit 2, the message names the key, nothing written.
for bad in 'clasts.size=[-1, 4]' 'clasts.count=6000' 'clasts.shapes=3' 'clasts.size=[8, 2]'; do
  status=0
  "$rockbake" bake "$source_dir/presets/goblin.yaml" -o "$work/bad" --resolution 32 --no-render --set "$bad" \
    > "$work/bad.log" 2>&1 || status=$?
  [ "$status" -eq 2 ] || { cat "$work/bad.log"; fail "--set $bad: exit $status, not 2"; }
  grep -q "clasts" "$work/bad.log" || { cat "$work/bad.log"; fail "--set $bad: the message does not name clasts"; }
  [ ! -e "$work/bad" ] || fail "--set $bad left $work/bad behind"
done
echo "PASS: stones rest, sort and instance; same bytes at 1 and 2 threads; bad settings refused"
