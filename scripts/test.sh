#!/usr/bin/env bash
# Installs, builds with warnings as errors and runs the whole test suite.
#   scripts/test.sh              Release build
#   scripts/test.sh --sanitize   the same suite under ASan + UBSan
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ "${1:-}" = "--sanitize" ]; then
  "$root/scripts/build.sh" --sanitize -DOROGEN_WERROR=ON
  dir="$root/build-sanitize"
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
else
  "$root/scripts/build.sh" -DOROGEN_WERROR=ON
  dir="$root/build"
fi
cd "$dir"
ctest --output-on-failure -j 2
