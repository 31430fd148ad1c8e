#!/usr/bin/env bash
# The .deb (cmake/Install.cmake): `cpack -G DEB` from the build folder, then
#   - its Depends name povray, fonts-dejavu-core and the package of every shared
#     library bin/rockbake loads (dpkg-shlibdeps);
#   - `dpkg --root` installs it into a scratch root (its dependencies are the
#     machine's, so they are not checked there);
#   - the installed /usr/bin/rockbake, there, bakes and renders a small preset and
#     serves the studio page with every module it imports;
#   - it ships the catalogue presets in /usr/share/rockbake/presets (with shapes/),
#     which lint clean there and which a preset extends by name (rockbake:NAME).
# Configures nothing: it packages what the build folder holds.
#
#   debian_package_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail

[ $# -eq 2 ] || {
  echo "usage: $0 BUILD_DIR SOURCE_DIR" >&2
  exit 2
}
build=$(realpath "$1")
source_dir=$(realpath "$2")
unset ROCKBAKE_DATA_DIR ROCKBAKE_RENDER_TEMPLATES

# shellcheck source=tests/install/common.sh
source "$source_dir/tests/install/common.sh"
make_work_dir rockbake-deb-test
for tool in cpack dpkg dpkg-deb dpkg-shlibdeps file readelf; do
  command -v "$tool" >/dev/null || die "$tool is missing: run scripts/setup.sh (it installs dpkg-dev, file and binutils)"
done

# ---------------------------------------------------------------- build the package
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/package" >"$work/cpack.log" 2>&1 || {
  cat "$work/cpack.log"
  die "cpack -G DEB failed"
}
debs=("$work"/package/rockbake_*.deb)
[ ${#debs[@]} -eq 1 ] && [ -f "${debs[0]}" ] || die "cpack wrote no single rockbake_*.deb: $(ls "$work/package")"
deb=${debs[0]}
pass "cpack wrote $(basename "$deb") ($(stat -c %s "$deb") bytes)"

# ---------------------------------------------------------------- its dependencies
depends=$(dpkg-deb -f "$deb" Depends)
depends_names=" $(sed -E 's/\([^)]*\)//g; s/[,|]/ /g' <<<"$depends" | tr -s ' ') "
for package in povray fonts-dejavu-core; do
  [[ "$depends_names" == *" $package "* ]] || fail_check "Depends lacks $package: $depends"
done
# Each library the executable loads comes from a package the .deb depends on.
binary=$(find "$work/package/_CPack_Packages" -path '*/usr/bin/rockbake' -type f | head -n 1)
[ -n "$binary" ] || die "no usr/bin/rockbake in cpack's staging folder"
ldd "$binary" >"$work/ldd.txt"
checked=0
for soname in $(readelf -d "$binary" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p'); do
  library=$(awk -v s="$soname" '$1 == s && $2 == "=>" { print $3 }' "$work/ldd.txt")
  [ -n "$library" ] || {
    fail_check "$soname: ldd does not find it"
    continue
  }
  # dpkg knows a library by the path its package installed; /lib is /usr/lib on merged-/usr systems.
  owner=
  for candidate in "$library" "$(readlink -f "$library")" "/usr$library" "$(readlink -f "/usr$library" 2>/dev/null)"; do
    [ -n "$owner" ] || owner=$(dpkg -S "$candidate" 2>/dev/null | sed -n '1s/:.*//p') || true
  done
  if [ -z "$owner" ]; then
    fail_check "$soname ($library) belongs to no Debian package"
    continue
  fi
  # Depends may name the package, or a name it provides (libspdlog1.10 provides libspdlog1.10-fmt9).
  named=
  for name in "$owner" $(dpkg-query -W -f='${Provides}' "$owner" | sed -E 's/\([^)]*\)//g; s/,/ /g'); do
    [[ "$depends_names" == *" $name "* ]] && named=$name
  done
  [ -n "$named" ] || fail_check "$soname comes from $owner, which Depends does not name: $depends"
  checked=$((checked + 1))
done
[ $checked -gt 5 ] || fail_check "only $checked shared libraries checked"
pass "Depends names povray, fonts-dejavu-core and the packages of all $checked libraries rockbake loads"

# ---------------------------------------------------------------- install into a scratch root
root=$work/root
mkdir -p "$root/var/lib/dpkg/info" "$root/var/lib/dpkg/updates"
touch "$root/var/lib/dpkg/status"
# The root holds none of the libraries, so dependencies are not checked there; ldconfig
# and friends must be on PATH for dpkg.
PATH=$PATH:/usr/sbin:/sbin dpkg --root="$root" --force-not-root --force-depends --log=/dev/null -i "$deb" \
  >"$work/dpkg.log" 2>&1 || {
  cat "$work/dpkg.log"
  die "dpkg --root -i failed"
}
status=$(dpkg --root="$root" -s rockbake 2>/dev/null | sed -n 's/^Status: //p')
[ "$status" = "install ok installed" ] || fail_check "dpkg --root -s rockbake: status '$status'"
listed=$(dpkg --root="$root" -L rockbake)
for f in /usr/bin/rockbake /usr/share/rockbake/render_templates/ocio/config.ocio /usr/share/rockbake/studio/index.html \
  /usr/share/rockbake/studio/node_modules/three/build/three.module.js /usr/share/doc/rockbake/THIRD_PARTY_NOTICES \
  /usr/share/rockbake/presets/base.yaml /usr/share/rockbake/presets/goblin.yaml \
  /usr/share/rockbake/presets/shapes/goblin.png /usr/share/rockbake/presets/shapes/boulder.obj; do
  # The listing read whole first: grep -q closing the pipe early would fail dpkg under pipefail.
  grep -q -x -F "$f" <<<"$listed" || fail_check "the package does not list $f"
  [ -s "$root$f" ] || fail_check "$root$f is missing after dpkg -i"
done
pass "dpkg --root -i installed it: $status, $(dpkg --root="$root" -L rockbake | wc -l) paths"

# ---------------------------------------------------------------- the installed tree runs
run=$work/run
mkdir -p "$run"
write_small_preset "$run/small.yaml"
cd "$run"
if "$root/usr/bin/rockbake" bake small.yaml -o out --threads 2 >"$work/bake.log" 2>&1; then
  pass "the packaged rockbake baked small.yaml"
  check_render out/small
else
  cat "$work/bake.log"
  fail_check "the packaged rockbake could not bake"
fi
if node "$source_dir/tests/install/studio_page.mjs" "$root/usr/bin/rockbake" "$run/small.yaml" >"$work/studio.log" 2>&1; then
  pass "the packaged studio serves its page and every module"
else
  cat "$work/studio.log"
  fail_check "the packaged rockbake's studio page"
fi

# The catalogue presets, where the package put them, and a preset elsewhere that extends one by name.
printf 'rockbake: 1\nextends: rockbake:goblin.yaml\nname: cousin\n' >cousin.yaml
if "$root/usr/bin/rockbake" lint "$root"/usr/share/rockbake/presets/*.yaml cousin.yaml >"$work/catalogue.log" 2>&1; then
  pass "the packaged catalogue lints clean, and cousin.yaml extends rockbake:goblin.yaml"
else
  cat "$work/catalogue.log"
  fail_check "the packaged catalogue presets"
fi

finish "the .deb installs into a scratch root, and what it installs runs"
