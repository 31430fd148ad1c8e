#!/usr/bin/env bash
# Bakes a small library as a 4-task Slurm job array on a real single-node
# cluster, as a site runs it: the build installed into a prefix
# (`cmake --install`), its bin/ on PATH and its share/rockbake/slurm/submit.sh
# submitting with the default `--rockbake` (the rockbake on PATH). Checks that
# the result equals the same library baked on one machine by the build tree's
# rockbake without Slurm: meshes and VDBs byte for byte, images pixel for pixel,
# manifests and the index equal apart from what varies run to run ("timings",
# "host", stats.json's stage seconds).
#
#   library_on_slurm_test.sh ROCKBAKE_EXECUTABLE SOURCE_DIR BUILD_DIR
#
# Needs root and the Slurm, MUNGE, jq and OpenImageIO tools that
# scripts/setup.sh installs; without them it fails, saying so.
set -euo pipefail

[ $# -eq 3 ] || {
  echo "usage: $0 ROCKBAKE_EXECUTABLE SOURCE_DIR BUILD_DIR" >&2
  exit 2
}
rockbake=$(realpath "$1")
source_dir=$(realpath "$2")
build_dir=$(realpath "$3")

started=$SECONDS
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

# ---------------------------------------------------------------- requirements
[ "$(id -u)" = 0 ] || die "the Slurm test runs its own slurmctld, slurmd and munged and must run as root: run scripts/setup.sh as root, then the tests as root"
missing=()
for tool in slurmctld slurmd sbatch squeue sinfo scontrol munged mungekey munge unmunge jq idiff; do
  command -v "$tool" >/dev/null || missing+=("$tool")
done
[ ${#missing[@]} -eq 0 ] || die "missing ${missing[*]}: run scripts/setup.sh as root (it installs slurmctld slurmd slurm-client munge jq openimageio-tools)"
[ -x "$rockbake" ] || die "rockbake executable '$rockbake' not found"

# shellcheck source=tests/slurm/single_node_cluster.sh
source "$source_dir/tests/slurm/single_node_cluster.sh"

work=$(mktemp -d /tmp/rockbake-slurm-test.XXXXXX)
chmod 755 "$work" # munged checks every folder above its socket is a+x
on_exit() {
  local rc=$?
  if [ $rc -ne 0 ]; then
    cluster_dump_logs
    for f in "$work"/cluster-out.slurm-logs/*; do
      [ -s "$f" ] || continue
      echo "---- $f" >&2
      tail -n 30 "$f" >&2
    done
  fi
  cluster_stop
  if [ $rc -eq 0 ]; then rm -rf "$work"; else echo "files kept in $work" >&2; fi
  exit $rc
}
trap on_exit EXIT
trap 'exit 130' INT TERM

# ---------------------------------------------------------------- the library
# Four jobs from two presets: two seeds of a free cube, two wedges of a layered
# column that drops rock onto colluvium. Tiny grids and renders, all exports.
mkdir -p "$work/library"
cat >"$work/library/cube.yaml" <<'YAML'
rockbake: 1
name: cube
seed: 1
grid: {size: [2.0, 2.0, 2.0], resolution: 24, ground: false}
shape:
  box: {size: [1.6, 1.6, 1.6]}
bubbles:
  - up_to: 1.0
    bubble: {sphere: {radius: 0.3}}
    spheroidal: 1.0
    cavernous: 0.3
durability:
  points: [[0.0, 1.0], [1.0, 1.4]]
  noise:
    - {amplitude: 0.3, period: 0.5, octaves: 2}
time: 0.3
mesh: {smoothing: 1.0, subdivision: 1, lods: [0.5]}
export: [ply, obj, glb, vdb]
render: {template: studio, width: 48, height: 36}
YAML
cat >"$work/library/column.yaml" <<'YAML'
rockbake: 1
name: column
seed: 7
grid: {size: [2.0, 2.0, 3.0], resolution: 26, ground: true}
shape:
  cylinder: {radius: 0.7, height: 2.6}
durability:
  points: [[0.0, 1.8], [0.4, 0.5], [0.7, 2.0], [1.0, 0.8]]
bubbles:
  - up_to: 1.0
    bubble: {sphere: {radius: 0.25}}
    spheroidal: 1.0
    cavernous: 0.5
rockfall: {mode: drop}
colluvium: {yield: 0.6, talus_angle: 35, removal: 0.05}
time: 0.4
mesh: {smoothing: 1.0, subdivision: 1, lods: [0.5]}
export: [ply, obj, glb, vdb]
render: {template: studio, width: 48, height: 36}
YAML
cat >"$work/library/library.yaml" <<'YAML'
- preset: cube.yaml
  seeds: [3, 4]
- preset: column.yaml
  wedges:
    - {name: soft, set: {colluvium.yield: 0.9}}
    - {name: hard, set: {durability.points: [[0.0, 2.5], [0.5, 1.0], [1.0, 2.5]]}}
YAML
jobs=(cube-s3 cube-s4 column-soft column-hard)

# ---------------------------------------------------------------- the installed tool
prefix=$work/prefix
cmake --install "$build_dir" --prefix "$prefix" >"$work/install.log" 2>&1 || {
  cat "$work/install.log"
  die "cmake --install $build_dir --prefix $prefix failed"
}
export PATH=$prefix/bin:$PATH
[ "$(command -v rockbake)" = "$prefix/bin/rockbake" ] || die "the installed rockbake is not first on PATH"
pass "installed into $prefix; its bin/ is first on PATH"

# ---------------------------------------------------------------- on the cluster
cluster_start "$work/cluster" || die "the single-node Slurm cluster did not come up"
pass "single-node Slurm cluster up after $((SECONDS - started)) s ($(sinfo -h -N -o '%N %c CPUs %T' | head -n 1))"

submit=$prefix/share/rockbake/slurm/submit.sh
logs=$work/cluster-out.slurm-logs

# expect_completed JOBID COUNT WHAT: COUNT tasks of JOBID completed with exit status 0.
expect_completed() {
  local n
  n=$(scontrol -o show job "$1" | grep -c 'JobState=COMPLETED .*ExitCode=0:0' || true)
  [ "$n" = "$2" ] || die "$3: expected $2 task(s) COMPLETED with exit 0, got $n: $(scontrol -o show job "$1")"
  pass "$3: $2 task(s) COMPLETED, exit 0"
}

ids=$("$submit" --parsable --shards 4 --cpus-per-task 1 "$work/library/library.yaml" "$work/cluster-out") \
  || die "the installed submit.sh could not submit the library"
read -r array_id index_id <<<"$ids"
echo "array job $array_id, index job $index_id"
cluster_wait_jobs 300 "$array_id" "$index_id" || die "the Slurm jobs did not finish within 300 s"
expect_completed "$array_id" 4 "array job"
expect_completed "$index_id" 1 "index job"

# The tasks ran the installed rockbake (submit.sh's default: the one on PATH).
if grep -q -F "with $prefix/bin/rockbake" "$logs/shard-${array_id}_0.out" 2>/dev/null; then
  pass "the array tasks ran the installed $prefix/bin/rockbake"
else
  fail_check "array task 0 did not run $prefix/bin/rockbake: $(head -n 3 "$logs/shard-${array_id}_0.out" 2>/dev/null)"
fi
# Each task baked its own shard: rockbake in task i says it baked shard i/4.
for i in 0 1 2 3; do
  log=$logs/shard-${array_id}_$i.out
  if grep -q -- "(shard $i/4 of 4)" "$log" 2>/dev/null; then
    pass "array task $i baked shard $i/4"
  else
    fail_check "array task $i: no 'shard $i/4' in $log"
  fi
done

# A lost shard: as if task 2's node died while baking its job (column-soft,
# job 2 of 4) for the first time, the asset is not in place; what is left is
# the bake's hidden staging folder, without a manifest and a render, and its
# lock file, whose holder is gone. Re-running just that task bakes it again,
# clears what the lost bake left, and leaves the other shards' assets alone.
stamps() { stat -c '%n %i %Y' "$work"/cluster-out/{cube-s3,cube-s4,column-hard}/manifest.json; }
before=$(stamps)
lost=$work/cluster-out/.column-soft.baking-999999
mv "$work/cluster-out/column-soft" "$lost"
rm "$lost/manifest.json" "$lost/render.png"
echo "pid 999999 on host lost-node, since 2026-01-01T00:00:00Z" >"$work/cluster-out/.column-soft.lock"
ids=$("$submit" --parsable --shards 4 --tasks 2 --cpus-per-task 1 "$work/library/library.yaml" "$work/cluster-out") \
  || die "the installed submit.sh could not submit the re-run of task 2"
read -r rerun_id rerun_index_id <<<"$ids"
cluster_wait_jobs 200 "$rerun_id" "$rerun_index_id" || die "the re-run did not finish within 200 s"
expect_completed "$rerun_id" 1 "re-run of task 2"
expect_completed "$rerun_index_id" 1 "index job after the re-run"
rerun_log=$logs/shard-${rerun_id}_2.out
if grep -q -- "(shard 2/4 of 4)" "$rerun_log" && [ -f "$work/cluster-out/column-soft/manifest.json" ] \
  && [ ! -e "$lost" ] && [ ! -e "$work/cluster-out/.column-soft.lock" ] \
  && [ -f "$work/cluster-out/column-soft/render.png" ]; then
  pass "the re-run task baked shard 2/4 again: column-soft"
else
  fail_check "the re-run task did not bake shard 2/4's one job again: $(cat "$rerun_log")"
fi
if [ "$(stamps)" = "$before" ]; then
  pass "the re-run left the other shards' assets untouched"
else
  fail_check "the re-run rewrote other shards' manifests"
fi
cluster_seconds=$((SECONDS - started))
cluster_stop

# ---------------------------------------------------------------- on one machine
timeout 300 "$rockbake" library "$work/library/library.yaml" -o "$work/local-out" --jobs 2 --threads 2 \
  >"$work/local.log" 2>&1 || {
  cat "$work/local.log"
  die "rockbake library on one machine failed"
}
pass "the same library baked on one machine"

# ---------------------------------------------------------------- compare
cd "$work"
a=cluster-out
b=local-out
for job in "${jobs[@]}"; do
  { [ -f "$a/$job/manifest.json" ] && [ -f "$b/$job/manifest.json" ]; } \
    || fail_check "$job: a manifest.json is missing"
done

files_a=$(cd "$a" && find . -type f | sort)
files_b=$(cd "$b" && find . -type f | sort)
if [ "$files_a" = "$files_b" ]; then
  pass "both runs wrote the same $(wc -l <<<"$files_a") files"
else
  fail_check "the runs wrote different files:"
  diff <(echo "$files_a") <(echo "$files_b") || true
fi

# JSON without what varies run to run: top-level "timings" and "host"; the
# stage seconds of stats.json, and so its size and sha256 wherever a file list
# names it.
json_filter='del(.timings, .host)
  | if has("stages") and has("cycles") then del(.stages) else . end
  | walk(if type == "object" and ((.path? // "") | tostring | test("(^|/)stats\\.json$"))
         then del(.size, .sha256) else . end)'

images_identical=0
images=0
counted=0
while IFS= read -r f; do
  f=${f#./}
  [ -f "$b/$f" ] || continue
  counted=$((counted + 1))
  case "$f" in
    *.json)
      if ! diff <(jq -S "$json_filter" "$a/$f") <(jq -S "$json_filter" "$b/$f") >"$work/json.diff"; then
        fail_check "$f differs beyond timings and host:"
        head -n 40 "$work/json.diff"
      fi
      ;;
    *.exr | *.png)
      images=$((images + 1))
      cmp -s "$a/$f" "$b/$f" && images_identical=$((images_identical + 1))
      if ! idiff -q -a -fail 0 -failpercent 0 -warn 0 "$a/$f" "$b/$f" >"$work/idiff.log" 2>&1; then
        fail_check "$f: pixels differ"
        cat "$work/idiff.log"
      fi
      ;;
    *)
      cmp -s "$a/$f" "$b/$f" || fail_check "$f: bytes differ"
      ;;
  esac
done <<<"$files_a"

meshes=$(grep -c -E '\.(ply|obj|glb|vdb)$' <<<"$files_a" || true)
[ "$meshes" -ge 16 ] || fail_check "expected at least 16 mesh and VDB files (4 jobs × ply, obj, glb, vdb), found $meshes"
[ "$images" -ge 9 ] || fail_check "expected at least 9 images (4 jobs × exr + png, and the contact sheet), found $images"
{ [ -f "$a/index.json" ] && [ -f "$a/contact_sheet.png" ]; } || fail_check "the merge step left no index.json and contact_sheet.png"
names=$(jq -r '[.assets[] | select(.status == "ok") | .name] | join(" ")' "$a/index.json" 2>/dev/null || true)
expected=$(printf '%s\n' "${jobs[@]}" | sort | tr '\n' ' ')
if [ "$names " = "$expected" ]; then
  pass "the merged index lists the 4 assets as ok: $names"
else
  fail_check "the merged index lists '$names' as ok, expected '$expected'"
fi
echo "compared $counted files; $meshes meshes and VDBs byte for byte; $images images pixel for pixel ($images_identical of them byte-identical too)"

echo "cluster part: ${cluster_seconds} s, whole test: $((SECONDS - started)) s"
if [ $failures -eq 0 ]; then
  echo "PASS: the library baked as a Slurm job array equals the one baked on one machine"
else
  die "$failures check(s) failed"
fi
