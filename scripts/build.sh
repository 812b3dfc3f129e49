#!/usr/bin/env bash
# Installs the Debian packages Orogen needs and builds it.
#   scripts/build.sh              Release build in build/
#   scripts/build.sh --sanitize   ASan + UBSan build in build-sanitize/
# Extra arguments after the flag go to cmake's configure step (e.g. -DOROGEN_WERROR=ON).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"

dir="$root/build"
config=(-DCMAKE_BUILD_TYPE=Release)
if [ "${1:-}" = "--sanitize" ]; then
  shift
  dir="$root/build-sanitize"
  config=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DOROGEN_SANITIZE=ON)
fi
cmake -S "$root" -B "$dir" "${config[@]}" "$@" >/dev/null
cmake --build "$dir" -j "$(nproc)"
echo "built: $dir/orogen"
