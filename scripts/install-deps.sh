#!/usr/bin/env bash
# Installs every Debian 12 package Orogen needs to build, test and benchmark.
# Idempotent: packages already present are left alone. Uses sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libglfw3-dev libegl-dev libopengl-dev libgl-dev libgles-dev libepoxy-dev
  libegl1-mesa-dev libgl1-mesa-dri libglx-mesa0 mesa-utils
  libopenimageio-dev openimageio-tools
  libopenvdb-dev libboost-dev libtbb-dev libopenvdb-tools
  libsqlite3-dev sqlite3 libzstd-dev zstd
  libcglm-dev libstb-dev fonts-dejavu-core
  libmeshoptimizer-dev libcmocka-dev
  xvfb xdotool xauth assimp-utils imagemagick
  python3 clang-format
  libnoise-dev
  libgdal-dev gdal-bin parallel
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
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
$sudo apt-get update
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
