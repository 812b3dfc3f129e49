#!/usr/bin/env bash
# Regenerates the golden images (tests/data/golden/*.png) from the current renderer and UI,
# after a deliberate change to the shaders or the renderer:
#   tests/golden_update.sh [BUILD_DIR]     (BUILD_DIR: build)
# then look at the images (git diff shows which changed) before committing them.
set -u
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-"$here/../build"}
[ -x "$build/orogen" ] || { echo "golden_update: $build/orogen is missing (build first)" >&2; exit 1; }
OROGEN_UPDATE_GOLDEN=1 bash "$here/e2e_render.sh" "$build/orogen" "$here"
OROGEN_UPDATE_GOLDEN=1 bash "$here/e2e_planet_render.sh" "$build/orogen" "$here"
# The whole editor window at two UI scales (after a deliberate change to the UI).
OROGEN_UPDATE_GOLDEN=1 bash "$here/e2e_window_golden.sh" "$build/orogen" "$here"
