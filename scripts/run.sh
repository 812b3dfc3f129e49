#!/usr/bin/env bash
# Installs, builds (Release) and opens Orogen on the built-in default world.
# Arguments are passed to orogen (a world file, --batch FILE, -c 'CMDS', ...).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" >&2
exec "$root/build/orogen" "$@"
