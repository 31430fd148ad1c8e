#!/usr/bin/env bash
# With --meshes first, the whole bake but the render instead (below: MESHES).
#
# The hero-resolution bake, before and after in one run: goblin `--no-mesh` at
# a high resolution, simulation time per phase, peak memory, and whether the
# builds' rock.vdb files are the same. Figures: bench/README.md.
#
# Usage: bench/hero_bake.sh BASELINE_ROCKBAKE [RESOLUTION=384] [OUT=/tmp/hero-bake] [SCALING_RESOLUTION]
#   BASELINE_ROCKBAKE   the rockbake executable to compare against
#   SCALING_RESOLUTION  resolution of the thread-scaling runs (default RESOLUTION)
# Environment:
#   GOBLIN_SETS        `--set` overrides for this build's goblin, space-separated
#                      (default none: the shipped preset). The first hero
#                      figures were taken with `shape.variation=null
#                      durability.joints=null`, goblin before its geology.
#   BASELINE_PRESET    the goblin preset the baseline reads, for a baseline that
#                      predates keys of this one (default presets/goblin.yaml,
#                      with GOBLIN_SETS)
#   PREVIOUS_ROCKBAKE  a second build to compare against (say, the previous
#                      commit's), baked after the baseline at 2 threads
#   BASELINE_THREADS   also bake the baseline at 1 thread (default 1: yes)
# Runs, one after another (run it alone on the machine):
#   the baseline at 2 threads (and at 1), this build at 2 threads (RESOLUTION);
#   then at SCALING_RESOLUTION this build at 2 threads and at 1 thread, and two
#   copies of it at 1 thread at once (the machine's own ceiling for two
#   single-threaded workers).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = --meshes ]; then
  shift
  exec bash bench/hero_mesh_bake.sh "$@"
fi
baseline=${1:?usage: bench/hero_bake.sh BASELINE_ROCKBAKE [RESOLUTION] [OUT]}
resolution=${2:-384}
out=${3:-/tmp/hero-bake}
scaling=${4:-$resolution}
current=build/baker/rockbake
[ -x "$current" ] || current=$(find build -name rockbake -type f -perm -u+x | head -n 1)
preset=presets/goblin.yaml
sets=()
for s in ${GOBLIN_SETS:-}; do sets+=(--set "$s"); done
rm -rf "$out"
mkdir -p "$out"

# bake NAME EXECUTABLE THREADS [RESOLUTION]: one bake with its peak memory (GNU time).
bake() {
  local input=("$preset" "${sets[@]}")
  [ "$2" = "$baseline" ] && [ -n "${BASELINE_PRESET:-}" ] && input=("$BASELINE_PRESET")
  /usr/bin/time -f '%M' -o "$out/$1.rss" "$2" bake "${input[@]}" --no-mesh --resolution "${4:-$resolution}" \
    --threads "$3" -o "$out/$1" > "$out/$1.log" 2>&1
}

# Prints one line of figures for a finished bake.
report() {
  python3 - "$out/$1" "$(cat "$out/$1.rss")" "$1" <<'PY'
import json, sys
folder, rss_kb, name = sys.argv[1], int(sys.argv[2]), sys.argv[3]
stats = json.load(open(folder + "/goblin/stats.json"))
s = stats["stages"]
print(f"{name:>14}: simulate {s['simulate']:7.2f} s (curvature {s['simulate_curvature']:6.2f}, "
      f"colluvium {s['simulate_colluvium']:5.2f}, rockfall {s['simulate_rockfall']:5.2f}, "
      f"other {s['simulate'] - s['simulate_curvature'] - s['simulate_colluvium'] - s['simulate_rockfall']:5.2f}), "
      f"write_vdb {s['write_vdb']:5.2f} s, peak {rss_kb / 1024:7.1f} MiB")
PY
}

bake baseline "$baseline" 2
report baseline
if [ "${BASELINE_THREADS:-1}" = 1 ]; then
  bake baseline-1 "$baseline" 1
  report baseline-1
fi
if [ -n "${PREVIOUS_ROCKBAKE:-}" ]; then
  bake previous "$PREVIOUS_ROCKBAKE" 2
  report previous
fi
bake current "$current" 2
report current
if [ -n "${PREVIOUS_ROCKBAKE:-}" ]; then
  cmp -s "$out/previous/goblin/rock.vdb" "$out/current/goblin/rock.vdb" &&
    echo "rock.vdb: byte-identical to the previous build's" || echo "rock.vdb: DIFFERS from the previous build's"
fi
if cmp -s "$out/baseline/goblin/rock.vdb" "$out/current/goblin/rock.vdb"; then
  echo "rock.vdb: byte-identical to the baseline's"
elif build/bench/rockbake_vdb_same "$out/baseline/goblin/rock.vdb" "$out/current/goblin/rock.vdb" > /dev/null; then
  # A baseline that frames the asset differently (pivot, metadata) may still hold the same grids.
  echo "rock.vdb: the same grids as the baseline's (transform and metadata differ)"
else
  echo "rock.vdb: other grids than the baseline's"
fi
echo "thread scaling at resolution $scaling:"
bake current-2 "$current" 2 "$scaling"
report current-2
bake current-1 "$current" 1 "$scaling"
report current-1
cmp -s "$out/current-2/goblin/rock.vdb" "$out/current-1/goblin/rock.vdb" && echo "rock.vdb: 1 and 2 threads identical"
# Two single-threaded bakes at once: each one's speed against running alone.
bake pair-a "$current" 1 "$scaling" &
bake pair-b "$current" 1 "$scaling" &
wait
report pair-a
report pair-b
