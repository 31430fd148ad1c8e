#!/usr/bin/env bash
# The installed tool, moved (docs/architecture.md, "Finding data"): the build is
# installed into a scratch prefix with `cmake --install`, the prefix is moved to
# another folder, and the moved rockbake
#   - has the layout the README's "Installing" gives, and nothing of node_modules
#     but the three.js files the page serves, each named in THIRD_PARTY_NOTICES;
#   - holds neither the source nor the build folder's path (strings);
#   - bakes and renders a small preset (a real POV-Ray render) and renders it again
#     with another template, from a folder that is not the prefix;
#   - serves the studio page and every module it imports (studio_page.mjs), and the
#     review page over a one-asset library the same way;
#   - reads everything from ROCKBAKE_DATA_DIR when that is set, and says what is
#     missing, writing nothing, when its data folder is not there;
#   - ships the catalogue presets (share/rockbake/presets, with shapes/), which lint
#     clean where installed, and which a preset elsewhere extends by name
#     (`extends: rockbake:base.yaml`) and packs with its installed base.
# Configures nothing: it installs what the build folder holds.
#
#   install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail

[ $# -eq 2 ] || {
  echo "usage: $0 BUILD_DIR SOURCE_DIR" >&2
  exit 2
}
build=$(realpath "$1")
source_dir=$(realpath "$2")
# What rockbake reads from the environment must come from this test alone.
unset ROCKBAKE_DATA_DIR ROCKBAKE_RENDER_TEMPLATES

# shellcheck source=tests/install/common.sh
source "$source_dir/tests/install/common.sh"
make_work_dir rockbake-install-test

# ---------------------------------------------------------------- install, then move
staged=$work/staged
cmake --install "$build" --prefix "$staged" >"$work/install.log" 2>&1 || {
  cat "$work/install.log"
  die "cmake --install $build --prefix $staged failed"
}
# A space in the new place: nothing may split the path.
prefix="$work/moved prefix/rockbake"
mkdir -p "$(dirname "$prefix")"
mv "$staged" "$prefix"
rockbake=$prefix/bin/rockbake
pass "installed into $staged and moved to $prefix"

for f in bin/rockbake \
  share/rockbake/render_templates/studio.pov share/rockbake/render_templates/turntable.pov \
  share/rockbake/render_templates/debug.pov share/rockbake/render_templates/ocio/config.ocio \
  share/rockbake/studio/index.html share/rockbake/studio/studio.js share/rockbake/studio/studio.css \
  share/rockbake/studio/node_modules/three/build/three.module.js \
  share/rockbake/review/index.html share/rockbake/review/review.js share/rockbake/review/review.css \
  share/rockbake/slurm/submit.sh share/rockbake/slurm/rockbake-library.sbatch \
  share/rockbake/slurm/rockbake-index.sbatch share/rockbake/blender/blender_library.py \
  share/rockbake/presets/base.yaml share/rockbake/presets/goblin.yaml share/rockbake/presets/library.yaml \
  share/rockbake/presets/shapes/goblin.png share/rockbake/presets/shapes/boulder.obj \
  share/doc/rockbake/LICENSE share/doc/rockbake/THIRD_PARTY_NOTICES share/doc/rockbake/README.md; do
  [ -s "$prefix/$f" ] || fail_check "the install has no $f"
done
[ -x "$rockbake" ] && [ -x "$prefix/share/rockbake/slurm/submit.sh" ] || fail_check "bin/rockbake or submit.sh is not executable"
vendored=$(cd "$prefix/share/rockbake/studio/node_modules" && find . -type f | sort)
unexpected=$(grep -v -E '^\./three/(build|examples/jsm)/[^ ]+\.js$|^\./three/examples/jsm/libs/basis/basis_transcoder\.wasm$' <<<"$vendored" || true)
[ -z "$unexpected" ] || fail_check "node_modules holds more than three.js modules: $unexpected"
[ "$(wc -l <<<"$vendored")" -le 16 ] || fail_check "node_modules holds $(wc -l <<<"$vendored") files, not the few the page imports"
[ ! -e "$prefix/share/rockbake/presets/shapes/make_shapes.py" ] || fail_check "the install holds presets/shapes/make_shapes.py"
pass "the layout: bin/, share/rockbake/{render_templates,studio,review,slurm,presets}, share/doc/rockbake; node_modules: $(echo $vendored)"
# Every file served from another project is named in the notices that ship with it.
while read -r f; do
  awk -v path="share/rockbake/studio/node_modules/${f#./}" '$1 == path { found = 1 } END { exit !found }' \
    "$prefix/share/doc/rockbake/THIRD_PARTY_NOTICES" || fail_check "THIRD_PARTY_NOTICES does not name the served file node_modules/${f#./}"
done <<<"$vendored"

# ---------------------------------------------------------------- no paths of the build machine
strings -a "$rockbake" >"$work/strings.txt"
for path in "$source_dir" "$build" "$(readlink -f "$source_dir")" "$(readlink -f "$build")" "$staged"; do
  if grep -F -q -- "$path" "$work/strings.txt"; then
    fail_check "the installed rockbake holds the path $path: $(grep -F -m 3 -- "$path" "$work/strings.txt")"
  fi
done
pass "strings finds neither $source_dir nor $build in the installed rockbake"

# ---------------------------------------------------------------- bake and render
run=$work/run
mkdir -p "$run"
write_small_preset "$run/small.yaml"
cd "$run"
if "$rockbake" bake small.yaml -o out --threads 2 >"$work/bake.log" 2>&1; then
  pass "the moved rockbake baked small.yaml"
else
  cat "$work/bake.log"
  die "the moved rockbake could not bake"
fi
check_render out/small
if "$rockbake" render out/small --template debug >"$work/render.log" 2>&1 && [ -s out/small/render.png ]; then
  pass "rockbake render found the debug template"
else
  cat "$work/render.log"
  fail_check "rockbake render --template debug failed"
fi

# ---------------------------------------------------------------- the installed catalogue
# Every installed preset, base and library lints clean where it lies (its shapes found beside it).
if (cd / && "$rockbake" lint "$prefix"/share/rockbake/presets/*.yaml) >"$work/catalogue.log" 2>&1; then
  pass "the installed catalogue lints clean: $(grep -c ': ok' "$work/catalogue.log") files"
else
  cat "$work/catalogue.log"
  fail_check "the installed catalogue presets do not lint clean"
fi
# A preset of its own extends the installed house style by name, and bakes.
mkdir -p own/shapes
cp "$source_dir/presets/shapes/goblin.png" own/shapes/rock.png
cat >own/rock.yaml <<'YAML'
rockbake: 1
extends: rockbake:base.yaml
name: own
grid: {size: [3.0, 3.0, 3.0], resolution: 20}
shape:
  image: {path: shapes/rock.png, mode: extrude, height: 2.0}
time: 0.3
YAML
printf 'rockbake: 1\nextends: rockbake:goblin.yaml\nname: cousin\n' >own/cousin.yaml
if "$rockbake" lint own/rock.yaml own/cousin.yaml >"$work/own.log" 2>&1 &&
  "$rockbake" bake own/rock.yaml -o out-own --no-render --no-textures --threads 2 >>"$work/own.log" 2>&1 &&
  [ -s out-own/own/rock.glb ]; then
  pass "a preset elsewhere extends rockbake:base.yaml and rockbake:goblin.yaml, and bakes"
else
  cat "$work/own.log"
  fail_check "extends: rockbake:NAME with the moved install"
fi
# Packed, the installed bases (and goblin's image) travel in the pack, which lints clean.
if "$rockbake" preset pack own/rock.yaml own/cousin.yaml -o own-pack >"$work/pack.log" 2>&1 &&
  [ -s own-pack/rockbake/base.yaml ] && [ -s own-pack/rockbake/goblin.yaml ] &&
  [ -s own-pack/rockbake/shapes/goblin.png ] && grep -q '^extends: rockbake/base.yaml$' own-pack/rock.yaml &&
  "$rockbake" lint own-pack >>"$work/pack.log" 2>&1; then
  pass "rockbake preset pack copied the installed bases into the pack: $(tail -n 1 "$work/pack.log")"
else
  cat "$work/pack.log"
  fail_check "packing presets that extend installed ones"
fi

# ---------------------------------------------------------------- the studio
if node "$source_dir/tests/install/studio_page.mjs" "$rockbake" "$run/small.yaml" >"$work/studio.log" 2>&1; then
  pass "the studio serves its page and every module: $(tail -n 2 "$work/studio.log" | head -n 1)"
else
  cat "$work/studio.log"
  fail_check "the moved rockbake's studio page"
fi

# ---------------------------------------------------------------- the review page
printf -- '- {preset: small.yaml, seeds: [1]}\n' >lib.yaml
if "$rockbake" library lib.yaml -o out-lib --threads 2 >"$work/library.log" 2>&1 &&
  node "$source_dir/tests/install/studio_page.mjs" "$rockbake" --review "$run/out-lib" >"$work/review.log" 2>&1; then
  pass "review serves its page and every module: $(tail -n 2 "$work/review.log" | head -n 1)"
else
  cat "$work/library.log" "$work/review.log"
  fail_check "the moved rockbake's review page"
fi

# ---------------------------------------------------------------- ROCKBAKE_DATA_DIR
other="$work/other data"
cp -r "$prefix/share/rockbake" "$other"
cp "$other/render_templates/studio.pov" "$other/render_templates/probe.pov"
marker="<!-- the copy in ROCKBAKE_DATA_DIR -->"
printf '%s\n' "$marker" >>"$other/studio/index.html"
sed 's/^render: .*/render: {template: probe, width: 96, height: 72}/' small.yaml >probe.yaml
if "$rockbake" lint probe.yaml >"$work/lint.log" 2>&1; then
  fail_check "without ROCKBAKE_DATA_DIR, lint found a template only the other folder has"
fi
if ROCKBAKE_DATA_DIR=$other "$rockbake" lint probe.yaml >>"$work/lint.log" 2>&1; then
  pass "ROCKBAKE_DATA_DIR: lint finds the template only that folder has"
else
  cat "$work/lint.log"
  fail_check "ROCKBAKE_DATA_DIR=$other: lint did not find the probe template"
fi
if ROCKBAKE_DATA_DIR=$other node "$source_dir/tests/install/studio_page.mjs" "$rockbake" "$run/small.yaml" "$marker" \
  >"$work/studio-other.log" 2>&1; then
  pass "ROCKBAKE_DATA_DIR: the studio serves that folder's page"
else
  cat "$work/studio-other.log"
  fail_check "ROCKBAKE_DATA_DIR=$other: the studio's page"
fi
# The colour config comes from there too: a broken one fails the bake, naming it.
echo "not a config" >"$other/render_templates/ocio/config.ocio"
if ROCKBAKE_DATA_DIR=$other "$rockbake" bake small.yaml -o out-broken >"$work/broken.log" 2>&1; then
  fail_check "a bake with a broken OCIO config in ROCKBAKE_DATA_DIR succeeded"
elif grep -F -q "$other/render_templates/ocio/config.ocio" "$work/broken.log"; then
  pass "ROCKBAKE_DATA_DIR: the OCIO config is read from that folder"
else
  cat "$work/broken.log"
  fail_check "a broken OCIO config in ROCKBAKE_DATA_DIR: the message does not name it"
fi

# ---------------------------------------------------------------- data missing
expect_missing() { # WHAT LOG: exit status 1, a message naming the data folder, nothing written
  local what=$1 status=$2 log=$3
  if [ "$status" = 1 ] && grep -q "rockbake's data is missing" "$log" && [ ! -e out-missing ]; then
    pass "$what: exit 1, '$(grep -o "rockbake's data is missing [^(]*" "$log" | head -n 1)…', nothing written"
  else
    cat "$log"
    fail_check "$what: expected exit 1, a message that the data is missing and no out-missing/ (exit $status)"
  fi
}
status=0
ROCKBAKE_DATA_DIR="$work/nowhere" "$rockbake" bake small.yaml -o out-missing >"$work/nowhere.log" 2>&1 || status=$?
expect_missing "ROCKBAKE_DATA_DIR naming no folder" "$status" "$work/nowhere.log"
grep -q "ROCKBAKE_DATA_DIR=$work/nowhere" "$work/nowhere.log" || fail_check "the message does not say ROCKBAKE_DATA_DIR chose the folder"
mkdir -p "$work/alone/bin"
cp "$rockbake" "$work/alone/bin/"
status=0
"$work/alone/bin/rockbake" bake small.yaml -o out-missing >"$work/alone.log" 2>&1 || status=$?
expect_missing "the executable copied without its share/" "$status" "$work/alone.log"

finish "the moved install works and finds its data only where it should"
