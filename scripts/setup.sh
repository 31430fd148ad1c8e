#!/usr/bin/env bash
# Installs every Debian package rockbake needs to build, test and render.
# Idempotent: when everything is present it only checks and returns.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git ccache clang-format
  libtbb-dev libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev
  libopenvdb-dev libboost-iostreams-dev libpng-dev libssl-dev libfreetype-dev fonts-dejavu-core
  libosd-dev libopenexr-dev libimath-dev libopencolorio-dev opencolorio-tools
  libtinygltf-dev libmeshoptimizer-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  povray openimageio-tools
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
