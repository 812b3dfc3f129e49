#!/usr/bin/env bash
# Installs every Debian 12 package Orogen needs to build, test and benchmark.
# Idempotent: packages already present are left alone. Uses sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libglfw3-dev libegl-dev libopengl-dev libgl-dev libgles-dev libepoxy-dev
  libegl1-mesa-dev libgl1-mesa-dri libglx-mesa0 mesa-utils
  libopenimageio-dev openimageio-tools
  libopenvdb-dev libboost-dev libtbb-dev libopenvdb-tools python3-openvdb
  libsqlite3-dev sqlite3 libzstd-dev zstd libdeflate-dev
  libcglm-dev libstb-dev fonts-dejavu-core
  libmeshoptimizer-dev libcmocka-dev
  xvfb xdotool xauth assimp-utils imagemagick
  python3 clang-format clang libclang-rt-14-dev
  libnoise-dev
  libgdal-dev gdal-bin parallel
  blender
)

sudo=""
if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
else
  echo "install-deps: installing ${missing[*]}"
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
fi

# Test tools from npm, into the checkout's .cache/npm (ignored by git): the Khronos
# glTF validator the interchange tests run on exported .glb files.
root=$(cd "$(dirname "$0")/.." && pwd)
if ! command -v npm >/dev/null; then # a node install of its own (e.g. NodeSource) brings npm
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends nodejs npm
fi
validator=2.0.0-dev.3.10
if [ ! -f "$root/.cache/npm/node_modules/gltf-validator/package.json" ] ||
  ! grep -q "\"version\": \"$validator\"" "$root/.cache/npm/node_modules/gltf-validator/package.json"; then
  echo "install-deps: npm install gltf-validator@$validator"
  npm install --prefix "$root/.cache/npm" --no-audit --no-fund --loglevel=error "gltf-validator@$validator"
fi
