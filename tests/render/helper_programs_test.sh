#!/usr/bin/env bash
# Helper programs that are missing, lie or hang (docs/rendering.md, "Helper
# programs"), through the real executable with fake ones first on PATH:
# POV-Ray missing is said before the simulation; an FFmpeg that exits 0 with
# garbage publishes no turntable.mp4; an FFmpeg that hangs is killed (its whole
# process group) and the bake fails instead of waiting for ever.
# Usage: helper_programs_test.sh ROCKBAKE
set -euo pipefail
rockbake=$1
dir=$(mktemp -d "${TMPDIR:-/tmp}/rockbake-helpers-XXXXXX")
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }
# Runs a command with its output in LOG and its exit status in $status, without stopping the script.
status_of() {
  local log=$1
  shift
  set +e
  "$@" > "$log" 2>&1
  status=$?
  set -e
}
ok() { echo "ok: $*"; }
# A bake with the fake FFmpeg in $dir/bin first on PATH, as case N: it must fail, its message
# must match PATTERN, and no turntable.mp4 may be published. Says WHAT when it holds.
movie_refused() {
  local n=$1 pattern=$2 what=$3
  status_of "$dir/log$n" env PATH="$dir/bin:$PATH" "$rockbake" bake "$dir/small.yaml" -o "$dir/out$n"
  [ "$status" -ne 0 ] || fail "$what: the bake exited 0"
  grep -q "$pattern" "$dir/log$n" || fail "$what: the message does not say '$pattern': $(cat "$dir/log$n")"
  [ -z "$(find "$dir/out$n" -name turntable.mp4 2>/dev/null)" ] || fail "$what: a turntable.mp4 was published"
  ok "$what (exit $status)"
}

# The C++ tests' small preset (tests/data/small.yaml) with a small render and a two-frame turntable.
{
  cat "$(dirname "${BASH_SOURCE[0]}")/../data/small.yaml"
  echo 'render: {width: 96, height: 72, antialias: 0, turntable: {frames: 2}}'
} > "$dir/small.yaml"
mkdir "$dir/bin" "$dir/nopov"
# PATH without povray: only what a shell script needs.
for tool in sh bash cat sleep head; do ln -s "$(command -v $tool)" "$dir/nopov/$tool"; done

# POV-Ray missing: refused before the simulation, naming the package.
status_of "$dir/log1" env PATH="$dir/nopov" "$rockbake" bake "$dir/small.yaml" -o "$dir/out1"
grep -q "POV-Ray ('povray') was not found on PATH" "$dir/log1" || fail "no POV-Ray message: $(cat "$dir/log1")"
grep -qi "meshes" "$dir/log1" && fail "the simulation and meshes ran before POV-Ray was found missing: $(cat "$dir/log1")"
[ "$status" -ne 0 ] || fail "a bake without POV-Ray exited 0"
ok "POV-Ray missing: refused before the simulation (exit $status)"

# An FFmpeg that writes garbage and exits 0: no turntable.mp4, nothing published.
cat > "$dir/bin/ffmpeg" <<'SH'
#!/bin/sh
for last; do :; done
cat > /dev/null
printf 'this is not a movie' > "$last"
exit 0
SH
chmod +x "$dir/bin/ffmpeg"
movie_refused 2 "ftyp" "an FFmpeg writing garbage: no turntable.mp4"

# An FFmpeg that hangs (and its child): killed after the stall limit, the bake fails.
cat > "$dir/bin/ffmpeg" <<'SH'
#!/bin/sh
sleep 424 &
wait
SH
start=$(date +%s)
status_of "$dir/log3" env PATH="$dir/bin:$PATH" timeout 180 "$rockbake" bake "$dir/small.yaml" -o "$dir/out3"
elapsed=$(( $(date +%s) - start ))
[ "$status" -ne 124 ] || fail "the bake waited for a hanging FFmpeg for 180 s"
[ "$status" -ne 0 ] || fail "a bake whose FFmpeg hung exited 0"
grep -q "made no progress" "$dir/log3" || fail "the message does not say FFmpeg hung: $(cat "$dir/log3")"
sleep 1
pgrep -f "sleep 424" > /dev/null && fail "FFmpeg's child is still running after the bake"
[ -z "$(find "$dir/out3" -name turntable.mp4 2>/dev/null)" ] || fail "a turntable.mp4 was published"
ok "a hanging FFmpeg: killed with its process group after ${elapsed} s, the bake failed (exit $status)"
# In a library, the first Ctrl-C stops the job while FFmpeg runs (not only between frames): the
# library ends within seconds and takes the hanging FFmpeg's group with it.
cat > "$dir/bin/ffmpeg" <<'SH'
#!/bin/sh
sleep 425 &
wait
SH
printf -- '- preset: small.yaml\n' > "$dir/lib.yaml"
PATH="$dir/bin:$PATH" "$rockbake" library "$dir/lib.yaml" -o "$dir/out8" > "$dir/log8" 2>&1 &
library=$!
for _ in $(seq 1 600); do pgrep -f "sleep 425" > /dev/null && break; sleep 0.1; done
pgrep -f "sleep 425" > /dev/null || fail "the library never reached FFmpeg: $(cat "$dir/log8")"
kill -INT "$library"
for _ in $(seq 1 100); do kill -0 "$library" 2> /dev/null || break; sleep 0.1; done
if kill -0 "$library" 2> /dev/null; then
  kill -KILL "$library"
  fail "the library still ran 10 s after Ctrl-C while FFmpeg hung: $(cat "$dir/log8")"
fi
sleep 0.5
pgrep -f "sleep 425" > /dev/null && fail "FFmpeg's child outlived the cancelled library"
ok "Ctrl-C in a library while FFmpeg hangs: stopped within seconds, FFmpeg's group gone"

# An FFmpeg that writes a real MP4 of fewer frames than it was given and exits 0: ffprobe's count
# refuses it, nothing is published.
cat > "$dir/bin/ffmpeg" <<'SH'
#!/bin/sh
n=$#
i=0
for a; do
  i=$((i + 1))
  if [ $i -eq $n ]; then set -- "$@" -frames:v 1 "$a"; else set -- "$@" "$a"; fi
done
shift $n
exec /usr/bin/ffmpeg "$@"
SH
movie_refused 7 "it holds 1 frames, not the 2 it was given" "an FFmpeg dropping frames: refused by ffprobe's count"

# An FFmpeg that writes an ftyp box and garbage after it, exit 0: ffprobe cannot read it, refused.
cat > "$dir/bin/ffmpeg" <<'SH'
#!/bin/sh
for last; do :; done
cat > /dev/null
printf '\000\000\000\030ftypisom\000\000\002\000isomiso2 and then no movie at all' > "$last"
exit 0
SH
movie_refused 9 "ffprobe" "an FFmpeg writing an ftyp box and garbage: refused by ffprobe"

# A POV-Ray that fails to parse: its own words, as lines, without the banner it prints first.
cat > "$dir/bin/povray" <<'SH'
#!/bin/sh
i=0
while [ $i -lt 40 ]; do echo "  Banner option line $i......On"; i=$((i + 1)); done
echo "==== [Parsing...] =========================================================="
echo "File 'scene.pov' line 3: Parse Error: No matching } in 'sphere', box found instead"
echo "Fatal error in parser: Cannot parse input."
echo "Render failed"
exit 1
SH
chmod +x "$dir/bin/povray"
status_of "$dir/log4" env PATH="$dir/bin:$PATH" "$rockbake" bake "$dir/small.yaml" -o "$dir/out4"
[ "$status" -ne 0 ] || fail "a bake whose POV-Ray failed exited 0"
grep -q '\\x0a' "$dir/log4" && fail "POV-Ray's lines arrive escaped on one line: $(cat "$dir/log4")"
grep -q "^  File 'scene.pov' line 3: Parse Error: No matching }" "$dir/log4" ||
  fail "the parse error is not a line of its own: $(cat "$dir/log4")"
grep -q "Banner option line" "$dir/log4" && fail "POV-Ray's banner buries its error: $(cat "$dir/log4")"
ok "a POV-Ray parse error: shown as POV-Ray's own lines, without its banner (exit $status)"
# A re-render whose movie step fails commits nothing: the still, the frames, the old movie and
# the manifest stay as the bake left them, so the manifest's hashes still hold.
"$rockbake" bake "$dir/small.yaml" -o "$dir/out5" > "$dir/log5" 2>&1 || fail "the real tools' bake failed: $(cat "$dir/log5")"
(cd "$dir/out5/small" && find . -type f | sort | xargs sha256sum) > "$dir/before5"
cat > "$dir/bin/povray" <<'SH'
#!/bin/sh
exec /usr/bin/povray "$@" +A0.5
SH
cat > "$dir/bin/ffmpeg" <<'SH'
#!/bin/sh
echo "Conversion failed!" >&2
exit 1
SH
status_of "$dir/log6" env PATH="$dir/bin:$PATH" "$rockbake" render "$dir/out5/small"
[ "$status" -ne 0 ] || fail "a re-render whose FFmpeg failed exited 0"
grep -q "Conversion failed" "$dir/log6" || fail "FFmpeg's words are not shown: $(cat "$dir/log6")"
(cd "$dir/out5/small" && find . -type f | sort | xargs sha256sum) > "$dir/after5"
diff "$dir/before5" "$dir/after5" > "$dir/diff5" || fail "a failed re-render changed the folder: $(cat "$dir/diff5")"
[ -z "$(find "$dir/out5/small" -name '.*')" ] || fail "a failed re-render left hidden files: $(find "$dir/out5/small" -name '.*')"
ok "a re-render whose movie failed: the folder as the bake left it (exit $status)"
echo "helper programs: all checks passed"
