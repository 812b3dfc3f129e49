#!/usr/bin/env bash
# Builds (Release) and runs every benchmark in bench/. Each prints Orogen's figure
# next to its peer's (or a physical limit's) from the same run.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" >&2
for b in "$root"/build/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  "$b"
done
