#!/usr/bin/env bash
# Builds the libFuzzer targets (CMake preset `fuzz`: clang 14, ASan + UBSan)
# and runs each for SECONDS, on a corpus seeded from presets/ and fuzz/seeds/.
# Every input in fuzz/regressions/<target>/ (past findings) is replayed first.
# Prints one line per target (executions, findings) and exits 1 on a finding;
# the input that found it is left in build-fuzz/findings/.
#
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (default 30 s, every target)
# The test suite runs `scripts/fuzz.sh 20`; before a release run an hour or
# more per target (docs/fuzzing.md).
# FUZZ_SEED (default 1) fixes libFuzzer's mutations, so a run that finds something
# finds it again on any machine that gets as far; FUZZ_SEED=0 draws a new seed
# each run, for long campaigns that should explore.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-30}"
fuzz_seed="${FUZZ_SEED:-1}"
shift || true
all=(fuzz_preset fuzz_set fuzz_library fuzz_png fuzz_mesh fuzz_checkpoint)
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${all[@]}")

cmake --preset fuzz > build-fuzz.configure.log 2>&1 || {
  cat build-fuzz.configure.log
  echo "fuzz: cmake configure failed (log above)" >&2
  exit 1
}
rm -f build-fuzz.configure.log
cmake --build --preset fuzz

# Seed corpora: the shipped presets, libraries and shapes, plus fuzz/seeds/<target>/.
corpus_root=build-fuzz/corpus
seed() {  # seed TARGET FILE...
  mkdir -p "$corpus_root/$1"
  local target="$1"
  shift
  for f in "$@"; do [ -f "$f" ] && cp -n "$f" "$corpus_root/$target/" || true; done
}
seed fuzz_preset presets/*.yaml fuzz/seeds/preset/*
seed fuzz_set fuzz/seeds/set/*
seed fuzz_library presets/library.yaml presets/libraries/*.yaml fuzz/seeds/library/*
seed fuzz_png presets/shapes/*.png fuzz/seeds/png/*
seed fuzz_mesh fuzz/seeds/mesh/*
mkdir -p "$corpus_root/fuzz_mesh"
for obj in presets/shapes/*.obj; do  # the mesh target's first byte picks the format: 0 = OBJ
  { printf '\0'; cat "$obj"; } > "$corpus_root/fuzz_mesh/$(basename "$obj").bin"
done
mkdir -p "$corpus_root/fuzz_checkpoint"
for rbk in fuzz/seeds/checkpoint/*.rbk; do  # first byte 0: the whole file; 1: without its checksum, appended by the target
  { printf '\0'; cat "$rbk"; } > "$corpus_root/fuzz_checkpoint/$(basename "$rbk").whole"
  { printf '\1'; head -c -64 "$rbk"; } > "$corpus_root/fuzz_checkpoint/$(basename "$rbk").body"
done

mkdir -p build-fuzz/findings
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
total=0
for target in "${targets[@]}"; do
  binary="build-fuzz/fuzz/$target"
  log="build-fuzz/$target.log"
  # Past findings first: each must now run clean.
  regressions=(fuzz/regressions/"$target"/*)
  if [ -e "${regressions[0]}" ]; then
    if ! "$binary" -rss_limit_mb=2048 -malloc_limit_mb=256 "${regressions[@]}" > "$log.regressions" 2>&1; then
      echo "$target: a past finding fails again (build-fuzz/$target.log.regressions)"
      status=1
      continue
    fi
  fi
  # -malloc_limit_mb: no single allocation may exceed 256 MiB (a header claiming a huge size must be refused
  # before allocating); -timeout: no input may run away.
  max_len=8192
  [ "$target" = fuzz_checkpoint ] && max_len=16384  # its seeds, real checkpoints of small grids, are about 10 KB
  set +e
  "$binary" "$corpus_root/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=256 -max_len="$max_len" -seed="$fuzz_seed" -print_final_stats=1 -artifact_prefix="build-fuzz/findings/$target-" \
    > "$log" 2>&1
  rc=$?
  set -e
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  execs="${execs:-0}"
  total=$((total + execs))
  if [ $rc -ne 0 ]; then
    echo "$target: FINDING after $execs executions (build-fuzz/$target.log, build-fuzz/findings/)"
    grep -m 5 -E 'ERROR|FINDING|runtime error|==ERROR' "$log" || tail -20 "$log"
    status=1
  else
    echo "$target: $execs executions in ${seconds} s, no finding"
  fi
done
echo "fuzz: $total executions in all"
exit $status
