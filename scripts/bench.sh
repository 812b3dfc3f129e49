#!/usr/bin/env bash
# Builds (Release) and runs every benchmark in bench/. Each prints Orogen's figure
# next to its peer's (or a physical limit's) from the same run.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" >&2
for b in "$root"/build/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  case "$(basename "$b")" in
    # Writes its accuracy and parallax images (PNG) into this folder.
    bench_render) "$b" "$root/build/bench/render-images" ;;
    *) "$b" ;;
  esac
done
