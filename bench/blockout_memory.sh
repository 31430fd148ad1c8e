#!/usr/bin/env bash
# Peak memory of reading a large OBJ blockout, before and after in one run:
# `rockbake lint` (which reads the blockout and checks it is closed, as a bake
# does) on a generated closed sphere exported as DCCs export it (v, vt, vn,
# f a/b/c), and on a unit cube padded with that many vt/vn lines (the mesh is
# tiny); then this build's reader alone (build/bench/rockbake_blockout_reader).
# Figures: bench/README.md.
#
# Usage: bench/blockout_memory.sh BASELINE_ROCKBAKE [RINGS=700] [OUT=/tmp/blockout-memory]
#   RINGS   the sphere's latitude rings; it has RINGS × 2·RINGS vertices
set -euo pipefail
cd "$(dirname "$0")/.."
baseline=${1:?usage: bench/blockout_memory.sh BASELINE_ROCKBAKE [RINGS] [OUT]}
rings=${2:-700}
out=${3:-/tmp/blockout-memory}
current=build/baker/rockbake
rm -rf "$out"
mkdir -p "$out"

python3 - "$out" "$rings" <<'PY'
import math, sys
out, rings = sys.argv[1], int(sys.argv[2])
segments = 2 * rings
with open(f"{out}/sphere.obj", "w") as f:
    f.write("# a UV sphere, outward-facing, with texture coordinates and normals\n")
    f.write("v 0 0 1\nvt 0.5 1\nvn 0 0 1\n")
    for i in range(1, rings):
        t = math.pi * i / rings
        for j in range(segments):
            p = 2 * math.pi * j / segments
            x, y, z = math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)
            f.write(f"v {x:.6f} {y:.6f} {z + 1:.6f}\nvt {j / segments:.6f} {1 - i / rings:.6f}\n"
                    f"vn {x:.6f} {y:.6f} {z:.6f}\n")
    f.write("v 0 0 -1\nvt 0.5 0\nvn 0 0 -1\n")
    bottom = 2 + (rings - 1) * segments
    ring = lambda i, j: 2 + (i - 1) * segments + j % segments
    c = lambda v: f"{v}/{v}/{v}"
    for j in range(segments):
        f.write(f"f {c(1)} {c(ring(1, j))} {c(ring(1, j + 1))}\n")
        f.write(f"f {c(bottom)} {c(ring(rings - 1, j + 1))} {c(ring(rings - 1, j))}\n")
    for i in range(1, rings - 1):
        for j in range(segments):
            f.write(f"f {c(ring(i, j))} {c(ring(i + 1, j))} {c(ring(i + 1, j + 1))} {c(ring(i, j + 1))}\n")
    vertices, triangles = 2 + (rings - 1) * segments, 2 * segments * (rings - 1)
with open(f"{out}/padded.obj", "w") as f:
    f.write("v -0.5 -0.5 0\nv -0.5 -0.5 1\nv -0.5 0.5 0\nv -0.5 0.5 1\n"
            "v 0.5 -0.5 0\nv 0.5 -0.5 1\nv 0.5 0.5 0\nv 0.5 0.5 1\n")
    size = __import__("os").path.getsize(f"{out}/sphere.obj")
    line = "vt 0.123456 0.654321\nvn 0.577350 0.577350 0.577350\n"
    f.write(line * (size // len(line)))
    f.write("f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n")
print(f"sphere: {vertices} vertices, {triangles} triangles, {(24 * vertices + 12 * triangles) / 2**20:.0f} MiB as a mesh")
for name in ("sphere", "padded"):
    with open(f"{out}/{name}.yaml", "w") as f:
        f.write(f"rockbake: 1\nname: {name}\ngrid: {{size: [2.5, 2.5, 2.5], resolution: 24}}\n"
                f"shape:\n  mesh: {{path: {name}.obj}}\ntime: 0.5\n")
PY

for name in sphere padded; do
  echo "$name.obj: $(( $(stat -c %s "$out/$name.obj") / 1048576 )) MiB"
  for build in baseline current; do
    exe=$baseline
    [ "$build" = current ] && exe=$current
    /usr/bin/time -f '%M %e' -o "$out/$name.$build.time" "$exe" lint "$out/$name.yaml" > "$out/$name.$build.log" 2>&1 || true
    read -r kib seconds < "$out/$name.$build.time"
    echo "  $build: peak RSS $((kib / 1024)) MiB, $seconds s ($(tail -n 1 "$out/$name.$build.log"))"
  done
done

echo "this build's reader alone:"
for name in sphere padded; do
  echo "  $name.obj: $(build/bench/rockbake_blockout_reader "$out/$name.obj")"
done
