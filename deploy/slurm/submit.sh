#!/usr/bin/env bash
# Submits a rockbake library to Slurm: a job array with one shard per task, then
# a merge job that builds the index once the array is over.
#
#   submit.sh [OPTIONS] LIBRARY.yaml OUT [-- EXTRA rockbake library ARGS...]
#
# Installed as <prefix>/share/rockbake/slurm/submit.sh beside the job scripts; runs
# the installed rockbake on PATH unless told otherwise. OUT must be on a filesystem
# every node shares. Prints the two job ids.
set -euo pipefail

usage() {
  cat <<'USAGE'
usage: submit.sh [OPTIONS] LIBRARY.yaml OUT [-- EXTRA rockbake library ARGS...]
       submit.sh [OPTIONS] --index-only OUT

Bakes LIBRARY.yaml into OUT as a Slurm job array (task i runs
`rockbake library --shard i/N`), then submits `rockbake library --index-only OUT`
to run after the array.

options:
  -n, --shards N          shards = array tasks (default 4)
  -c, --cpus-per-task C   CPUs per shard; rockbake runs that many threads (default 4)
      --tasks LIST        submit only these array tasks of the N shards, e.g. 2,5
                          (re-running failed shards; finished jobs are skipped anyway)
      --rockbake PATH     the rockbake executable, installed where every node sees it
                          at the same path (default: $ROCKBAKE_BIN, else the installed
                          `rockbake` on PATH)
      --index-after any|ok  build the index after the array ends whatever happened
                          (any, default: a partial index of what finished) or only
                          when every task succeeded (ok)
      --index-only        submit only the merge step for OUT
      --logs DIR          Slurm task logs (default: OUT.slurm-logs)
      --sbatch ARG        pass ARG to both sbatch calls (repeatable), e.g.
                          --sbatch --partition=cpu --sbatch --time=04:00:00
      --parsable          print only "ARRAY_JOB_ID INDEX_JOB_ID"
  -h, --help              this help
Arguments after -- go to every `rockbake library` shard as they are, e.g.
  -- --resolution 64 --no-render --set render.width=320
USAGE
}

fail() {
  echo "submit.sh: $*" >&2
  echo "run 'submit.sh --help' for usage" >&2
  exit 2
}

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
shards=4
cpus=4
tasks=
bin=${ROCKBAKE_BIN:-rockbake}
index_after=any
index_only=0
logs=
parsable=0
sbatch_args=()
positional=()
extra=()

need_value() { [ $# -ge 2 ] || fail "$1 needs a value"; }
while [ $# -gt 0 ]; do
  case "$1" in
    -n | --shards) need_value "$@"; shards=$2; shift 2 ;;
    -c | --cpus-per-task) need_value "$@"; cpus=$2; shift 2 ;;
    --tasks) need_value "$@"; tasks=$2; shift 2 ;;
    --rockbake) need_value "$@"; bin=$2; shift 2 ;;
    --index-after) need_value "$@"; index_after=$2; shift 2 ;;
    --index-only) index_only=1; shift ;;
    --logs) need_value "$@"; logs=$2; shift 2 ;;
    --sbatch) need_value "$@"; sbatch_args+=("$2"); shift 2 ;;
    --parsable) parsable=1; shift ;;
    -h | --help) usage; exit 0 ;;
    --) shift; extra=("$@"); break ;;
    -*) fail "unknown option '$1'" ;;
    *) positional+=("$1"); shift ;;
  esac
done

[[ "$shards" =~ ^[1-9][0-9]*$ ]] || fail "--shards '$shards' is not a positive integer"
[[ "$cpus" =~ ^[1-9][0-9]*$ ]] || fail "--cpus-per-task '$cpus' is not a positive integer"
case "$index_after" in any | ok) ;; *) fail "--index-after must be 'any' or 'ok', not '$index_after'" ;; esac
if [ -n "$tasks" ]; then
  [[ "$tasks" =~ ^[0-9]+(-[0-9]+)?(,[0-9]+(-[0-9]+)?)*$ ]] \
    || fail "--tasks '$tasks' is not a list of task ids like 2,5 or 0-3"
  for t in ${tasks//[,-]/ }; do
    ((10#$t < shards)) || fail "--tasks: task $t is outside shards 0..$((shards - 1))"
  done
else
  tasks=0-$((shards - 1))
fi

if [ "$index_only" = 1 ]; then
  [ ${#positional[@]} -eq 1 ] || fail "--index-only takes one argument, OUT"
  [ ${#extra[@]} -eq 0 ] || fail "--index-only takes no rockbake arguments after --"
  out=${positional[0]}
  [ -d "$out" ] || fail "OUT '$out' is not a folder"
else
  [ ${#positional[@]} -eq 2 ] || fail "expected LIBRARY.yaml and OUT, got ${#positional[@]} argument(s)"
  library=${positional[0]}
  out=${positional[1]}
  { [ -f "$library" ] && [ -r "$library" ]; } || fail "library '$library' is not a readable file"
  library=$(realpath "$library")
fi

command -v sbatch >/dev/null || fail "sbatch not found: run this on a Slurm submit host"
resolved=$(command -v "$bin") \
  || fail "rockbake executable '$bin' not found: install rockbake where every node sees it (cmake --install build --prefix /shared/rockbake, or the .deb on every node) and put its bin/ on PATH, or pass --rockbake PATH"
# The real file, not a link to it: rockbake finds its data beside its own bin/ folder.
bin=$(realpath "$resolved")

mkdir -p "$out"
out=$(realpath "$out")
logs=${logs:-$out.slurm-logs}
mkdir -p "$logs"
logs=$(realpath "$logs")

# The job scripts read their configuration from the environment sbatch passes on;
# values may hold commas, which --export=VAR=value could not carry.
export ROCKBAKE_BIN=$bin ROCKBAKE_OUT=$out

array_id=
if [ "$index_only" = 0 ]; then
  export ROCKBAKE_LIBRARY=$library ROCKBAKE_SHARDS=$shards
  array_id=$(sbatch --parsable --export=ALL "${sbatch_args[@]}" \
    --array="$tasks" --cpus-per-task="$cpus" \
    --output="$logs/shard-%A_%a.out" \
    "$here/rockbake-library.sbatch" "${extra[@]}")
  array_id=${array_id%%;*} # "id;cluster" on multi-cluster sites
  [ "$parsable" = 1 ] || echo "submitted array job $array_id: tasks $tasks of $shards shards, $cpus CPUs each; logs in $logs"
fi

dependency=()
if [ -n "$array_id" ]; then
  dependency=(--dependency="after$index_after:$array_id")
  # afterok never fires after a failed task; without this the merge would stay pending forever.
  [ "$index_after" = ok ] && dependency+=(--kill-on-invalid-dep=yes)
fi
index_id=$(sbatch --parsable --export=ALL "${sbatch_args[@]}" "${dependency[@]}" \
  --output="$logs/index-%j.out" \
  "$here/rockbake-index.sbatch")
index_id=${index_id%%;*}

if [ "$parsable" = 1 ]; then
  echo "${array_id:--} $index_id"
else
  echo "submitted index job $index_id${array_id:+ (after$index_after:$array_id)}: $out/index.json"
fi
