#!/usr/bin/env bash
# End-to-end: the viewport renders offscreen in batch mode (headless EGL, no display).
# Golden images with a tolerance (RMSE over 8-bit channels, Tabakovic 2024's method) and
# behaviour: edits and undo show, parallax changes the image, a camera 10,000 km out
# is as steady as one at the origin, picking agrees with the heights, bad input fails
# clearly. Usage: e2e_render.sh OROGEN TESTS_DIR
# Regenerate the goldens after a deliberate change to the renderer (and look at them):
#   tests/golden_update.sh [BUILD_DIR]   (= OROGEN_UPDATE_GOLDEN=1 bash tests/e2e_render.sh ...)
set -u
orogen=$1
tests=$2
golden="$tests/data/golden"
rmse_tool="$(dirname "$orogen")/image_rmse"
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-render-XXXXXX")
failed_dir="${TMPDIR:-/tmp}/orogen-render-failures/flat" # its own: ctest -j runs the planet one beside it
failures=0
passes=0
check() { if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi; }
trap 'rm -rf "$work"' EXIT
[ -x "$rmse_tool" ] || { echo "FAIL: $rmse_tool is missing (it is built with orogen)"; exit 1; }
# Under the sanitizers Mesa's driver keeps allocations LeakSanitizer cannot name.
if [ -n "${ASAN_OPTIONS:-}" ]; then export ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0"; fi

run() { "$orogen" -c "$1" >"$work/out" 2>"$work/err"; }
rmse() { "$rmse_tool" "$1" "$2" | sed -n 's/^rmse=//p'; }
# less A B: A < B as numbers (false when either is not a number: a failed comparison)
less() {
    awk -v a="$1" -v b="$2" 'BEGIN { n = "^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$"
                                     exit !(a ~ n && b ~ n && a + 0 < b + 0) }'
}

W=320
H=180
size="$W $H"
# A land spot on the default world (fbm_advanced, seed 1337): ground ~53 m at (2000, 0).
spot_x=2000
spot_z=0

# --- scenes -------------------------------------------------------------------------
# Every golden scene, rendered into folder $1. Run twice (in fresh processes, so the
# tile workers finish in a different order) to show the images do not depend on it.
crater_cam="camera $spot_x 350 650 0 -35"
detail="tool noise target=detail radius=25 strength=1 scale=3; stroke $spot_x -10 $spot_x 10"
near_cam="camera $spot_x 62 30 0 -30"
scenes() {
    local d=$1
    mkdir -p "$d"
    run "screenshot $d/default.png $size; view wireframe; screenshot $d/wireframe.png $size;
         view levels; screenshot $d/levels.png $size; view height; screenshot $d/height.png $size;
         view slope; screenshot $d/slope.png $size"
    rc=$?; check "default and debug views render ($(cat "$work/err"))" $rc

    run "$crater_cam; screenshot $d/before.png $size; stamp crater $spot_x $spot_z scale=2 intensity=150;
         screenshot $d/crater.png $size; undo; screenshot $d/undone.png $size"
    rc=$?; check "a crater is stamped and undone in view ($(cat "$work/err"))" $rc

    run "$near_cam; screenshot $d/no_detail.png $size; $detail; render parallax=on;
         screenshot $d/parallax_on.png $size; render parallax=off; screenshot $d/parallax_off.png $size"
    rc=$?; check "detail sculpted and rendered with parallax on and off ($(cat "$work/err"))" $rc

    # A tunnel through a hill and an arch over the plain (volume meshes): the tunnel shows
    # as a hole, and a pick ray along it passes through the hill (the same ray meets the
    # hill before the carve).
    run "set generator flat; set base_height 0; set size 1024; set spacing 1; generate;
         stamp gaussian 500 500 scale=1.5 intensity=60; camera 340 8 500 90 -1 60;
         pick $((W / 2)) $((H / 2)) $size;
         tool carve radius=7 falloff=constant; stroke 380 8 500 620 8 500;
         tool fill radius=3 falloff=constant; stroke 430 30 560 470 42 560 510 30 560;
         pick $((W / 2)) $((H / 2)) $size; camera 340 12 500 90 -2 60;
         screenshot $d/cave.png $size"
    rc=$?; check "a tunnel and an arch render ($(cat "$work/err"))" $rc
    picks=$(sed -n 's/^pick \([-0-9.]*\) .*/\1/p' "$work/out" | tr '\n' ' ')
    read -r before after <<<"$picks"
    less "$before" 460 && less 620 "$after"
    check "a pick ray meets the hill (x $before) and, once carved, goes through the tunnel (x $after)" $?

    run "camera 10000000 300 0 30 -18; screenshot $d/far.png $size; camera 10000000.001 300 0 30 -18;
         screenshot $d/far_1mm.png $size; camera 10000000.01 300 0 30 -18; screenshot $d/far_1cm.png $size"
    rc=$?; check "a camera 10,000 km from the origin renders ($(cat "$work/err"))" $rc
}
scenes "$work/a"
scenes "$work/b"
golden_names="default wireframe crater parallax_on parallax_off far cave"
max_repeat=0.5
for name in $golden_names levels height slope before undone no_detail; do
    r=$(rmse "$work/a/$name.png" "$work/b/$name.png")
    less "$r" $max_repeat; check "$name renders the same in a second run (RMSE $r < $max_repeat)" $?
done
for f in "$work"/a/*.png; do cp "$f" "$work/"; done

# --- goldens ------------------------------------------------------------------------
max_golden=2.0
rm -rf "$failed_dir" && mkdir -p "$failed_dir" # only this run's failures
for name in $golden_names; do
    if [ "${OROGEN_UPDATE_GOLDEN:-0}" = 1 ]; then
        mkdir -p "$golden" && cp "$work/$name.png" "$golden/$name.png"
        echo "updated $golden/$name.png"
        continue
    fi
    if [ ! -f "$golden/$name.png" ]; then
        check "golden $name.png exists (OROGEN_UPDATE_GOLDEN=1 makes it)" 1
        continue
    fi
    "$rmse_tool" "$golden/$name.png" "$work/$name.png" --max $max_golden \
        --diff "$failed_dir/$name-diff.png" >"$work/rmse" 2>&1
    status=$?
    if [ $status != 0 ]; then # the golden, what this run drew and |difference| x 4, side by side
        cp "$golden/$name.png" "$failed_dir/$name-golden.png" && cp "$work/$name.png" "$failed_dir/$name-got.png"
    else
        rm -f "$failed_dir/$name-diff.png"
    fi
    check "$name matches its golden within RMSE $max_golden ($(cat "$work/rmse"); on failure see $failed_dir)" $status
done
[ $failures = 0 ] && rm -rf "$failed_dir"

# --- behaviour ----------------------------------------------------------------------
r=$(rmse "$work/before.png" "$work/crater.png"); less 3 "$r"; check "the crater is visible (RMSE $r vs before)" $?
r=$(rmse "$work/before.png" "$work/undone.png"); less "$r" 0.5; check "undo removes it from the view (RMSE $r)" $?
r=$(rmse "$work/parallax_on.png" "$work/parallax_off.png"); less 1 "$r"; check "parallax changes the image (RMSE $r)" $?
r=$(rmse "$work/no_detail.png" "$work/parallax_off.png"); less 1 "$r"; check "detail normals show without parallax (RMSE $r)" $?
for v in wireframe levels height slope; do
    r=$(rmse "$work/default.png" "$work/$v.png"); less 5 "$r"; check "view $v differs from shaded (RMSE $r)" $?
done
# Paint shows (the levels switch to the program that blends painted weights once the
# material window holds paint), and undo takes it away again.
run "camera $spot_x 250 $spot_z 0 -89; screenshot $work/paint0.png $size; tool paint material=3 radius=60 strength=1;
     dab $spot_x $spot_z; screenshot $work/paint1.png $size; undo; screenshot $work/paint2.png $size"
rc=$?; check "paint and undo render ($(cat "$work/err"))" $rc
r=$(rmse "$work/paint0.png" "$work/paint1.png"); less 2 "$r"; check "the painted rock shows (RMSE $r)" $?
r=$(rmse "$work/paint0.png" "$work/paint2.png"); less "$r" 0.5; check "undo takes the paint away (RMSE $r)" $?
# A stroke shows while it goes on (the coarser levels follow each stroke_to), and its
# end changes nothing more on screen.
run "$crater_cam; screenshot $work/open0.png $size; tool raise radius=60 amount=40 strength=1;
     stroke_begin; stroke_to $spot_x $spot_z; screenshot $work/open1.png $size; stroke_end;
     screenshot $work/open2.png $size"
rc=$?; check "a stroke renders while open ($(cat "$work/err"))" $rc
r=$(rmse "$work/open0.png" "$work/open1.png"); less 1 "$r"; check "the open stroke shows before it ends (RMSE $r)" $?
r=$(rmse "$work/open1.png" "$work/open2.png"); less "$r" 0.05; check "ending it changes nothing more on screen (RMSE $r)" $?

# The View menu's overlays each draw over the shaded view, and off again is as before.
run "screenshot $work/plain.png $size; render contours=50; screenshot $work/contours.png $size;
     render contours=0 tile_grid=on; screenshot $work/tile_grid.png $size;
     render tile_grid=off level_grid=on; screenshot $work/level_grid.png $size;
     render level_grid=off auto_materials=off; screenshot $work/auto_off.png $size;
     render auto_materials=on; screenshot $work/plain_again.png $size"
rc=$?; check "the overlays render ($(cat "$work/err"))" $rc
for o in contours tile_grid level_grid auto_off; do
    r=$(rmse "$work/plain.png" "$work/$o.png"); less 1 "$r"; check "the $o overlay shows (RMSE $r)" $?
done
r=$(rmse "$work/plain.png" "$work/plain_again.png"); less "$r" 0.5; check "with the overlays off the view is as before (RMSE $r)" $?
r=$(rmse "$work/far.png" "$work/far_1mm.png"); less "$r" 1; check "10,000 km out, 1 mm of camera motion does not jitter (RMSE $r)" $?
r=$(rmse "$work/far.png" "$work/far_1cm.png"); less "$r" 1; check "10,000 km out, 1 cm of camera motion does not jitter (RMSE $r)" $?

# Flat terrain looks the same at the origin and 10,000 km out (9,999,924 m is a whole
# number of both texture periods, 6 m and 97 m): no precision is lost far away.
run "set generator flat; set base_height 10; generate; camera 0 40 0 30 -20; screenshot $work/flat0.png $size;
     camera 9999924 40 0 30 -20; screenshot $work/flatfar.png $size"
rc=$?; check "flat world renders near and far ($(cat "$work/err"))" $rc
r=$(rmse "$work/flat0.png" "$work/flatfar.png"); less "$r" 1; check "flat terrain 10,000 km out matches the origin (RMSE $r)" $?

# Picking: the point under the centre pixel lies on the terrain, within one coarse
# sample's height step there (the largest change to a neighbouring sample).
run "camera $spot_x 200 300 0 -30; pick $((W / 2)) $((H / 2)) $size"
rc=$?; check "pick answers ($(cat "$work/err"))" $rc
read -r _ px py pz <"$work/out"
run "params"
spacing=$(sed -n 's/^spacing = \(.*\);$/\1/p' "$work/out")
# (sample wants plain numbers, so awk works the neighbours out)
run "$(awk -v x="$px" -v z="$pz" -v s="$spacing" 'BEGIN { printf "sample %.3f %.3f; sample %.3f %.3f; sample %.3f %.3f; sample %.3f %.3f; sample %.3f %.3f", x, z, x + s, z, x - s, z, x, z + s, x, z - s }')"
rc=$?; check "sample answers around the hit ($(cat "$work/err"))" $rc
ground=$(sed -n 1p "$work/out")
step=$(awk 'NR == 1 { c = $1 } NR > 1 { d = $1 - c; if (d < 0) d = -d; if (d > m) m = d } END { print m + 0.01 }' "$work/out")
awk -v a="$py" -v b="$ground" -v t="$step" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'
check "pick hit ($px, $py, $pz) is on the ground (sample says $ground, step $step m)" $?
awk -v z="$pz" 'BEGIN { exit !(z < 300 && z > -400) }'
check "pick hit lies ahead of the camera (z $pz)" $?

run "render levels=3; screenshot $work/l3.png $size; render levels=12; screenshot $work/l12.png $size"
rc=$?; check "3 and 12 clipmap levels render ($(cat "$work/err"))" $rc

# Bad input: clear errors, status 1, nothing written.
expect_error() { # label, commands, text the error must contain
    "$orogen" -c "$2" >"$work/out" 2>"$work/err"
    status=$?
    [ $status = 1 ] && grep -q -- "$3" "$work/err"
    rc=$?; check "$1 fails clearly (status $status: $(head -c 300 "$work/err"))" $rc
}
expect_error "an unwritable folder" "screenshot $work/missing/dir/shot.png 64 64" "$work/missing/dir"
expect_error "a too small image" "screenshot $work/x.png 8 8" "W: expected an integer in \[16, 8192\], got '8'"
expect_error "W without H" "screenshot $work/x.png 64" "give both W and H"
expect_error "an unknown view" "view bogus" "unknown mode 'bogus'"
expect_error "too few levels" "render levels=2" "levels: expected an integer in \[3, 12\], got '2'"
expect_error "an unknown render setting" "render shadows=on" "unknown setting 'shadows'"
expect_error "a camera with a bad number" "camera 1 2 3 abc 0" "YAW: expected a finite number, got 'abc'"
expect_error "a camera looking past straight up" "camera 0 0 0 0 120" "PITCH: expected degrees in \[-90, 90\], got '120'"
[ ! -e "$work/x.png" ]; check "failed screenshots write no file" $?

# --- regression: the level-edge shading seam ------------------------------------------
# Central differences at a level's low edge once read the far side of the toroidal
# window: a line of wrong slope along every level edge (fixed in bef06c4; the old
# shader gives RMSE 2.1 here). The slope view shows gradients alone, at a size where
# the lines are several pixels long, against its golden with a tight tolerance.
mkdir -p "$failed_dir"
run "view slope; screenshot $work/seams.png 640 360"
if [ -n "${OROGEN_UPDATE_GOLDEN:-}" ]; then
    cp "$work/seams.png" "$golden/seams.png" && echo "updated $golden/seams.png"
fi
"$rmse_tool" "$golden/seams.png" "$work/seams.png" --max 1.0 --diff "$failed_dir/seams-diff.png" >"$work/rmse" 2>&1
rc=$?; check "no shading seam along the clipmap level edges (slope view vs golden: $(cat "$work/rmse"))" $rc

# Blocks hidden by nearer ground (and outside the view) are left out, and the picture is
# the same: low over the cliffs, looking across them (`render culling=off` draws all).
run "camera 1000 250 1500 0 -5; screenshot $work/occ_on.png 480 270; render culling=off;
     screenshot $work/occ_off.png 480 270"
rc=$?; check "a low view with and without culling ($(cat "$work/err"))" $rc
tris_on=$(sed -n 's/^screenshot .*occ_on\.png.* triangles=\([0-9]*\).*/\1/p' "$work/out")
tris_off=$(sed -n 's/^screenshot .*occ_off\.png.* triangles=\([0-9]*\).*/\1/p' "$work/out")
less "${tris_on:-x}" "${tris_off:-x}"; check "culling draws fewer triangles ($tris_on against $tris_off)" $?
r=$(rmse "$work/occ_on.png" "$work/occ_off.png")
less "$r" 0.001; check "and the same picture (RMSE $r)" $?

# Far rough ground refined where its error shows (`render refine=1`): more triangles,
# the same picture but for the far ridges (it moves only the coarse levels' new vertices).
run "camera 4000 400 6500 0 -4; view height; screenshot $work/refine_off.png 480 270;
     render refine=1; screenshot $work/refine_on.png 480 270; render"
rc=$?; check "a far view with refined coarse levels ($(cat "$work/err"))" $rc
grep -q "refine=1 " "$work/out"; check "render prints the refine setting" $?
tris_off=$(sed -n 's/^screenshot .*refine_off\.png.* triangles=\([0-9]*\).*/\1/p' "$work/out")
tris_on=$(sed -n 's/^screenshot .*refine_on\.png.* triangles=\([0-9]*\).*/\1/p' "$work/out")
less "${tris_off:-x}" "${tris_on:-x}"; check "refining draws more triangles ($tris_on against $tris_off)" $?
r=$(rmse "$work/refine_on.png" "$work/refine_off.png")
less 0.1 "$r" && less "$r" 8; check "and changes the far ridges only (RMSE $r)" $?
expect_error "a negative refine" "render refine=-1" "refine: expected a number in \[0, 64\], got '-1'"
# Only the far ground near the skyline refined (`render skyline=1`): more triangles than
# none, fewer than refining everywhere, and the picture changed at the far ridges only.
run "camera 4000 400 6500 0 -4; view height; render skyline=1; screenshot $work/sky_on.png 480 270;
     render"
rc=$?; check "a far view with the skyline refined ($(cat "$work/err"))" $rc
grep -q "skyline=1 " "$work/out"; check "render prints the skyline setting" $?
tris_sky=$(sed -n 's/^screenshot .*sky_on\.png.* triangles=\([0-9]*\).*/\1/p' "$work/out")
less "${tris_off:-x}" "${tris_sky:-x}" && less "${tris_sky:-x}" "${tris_on:-x}"
check "the skyline refined draws more triangles than none, fewer than all ($tris_off < $tris_sky < $tris_on)" $?
r=$(rmse "$work/sky_on.png" "$work/refine_off.png")
less 0.1 "$r" && less "$r" 8; check "and changes the far ridges only (RMSE $r)" $?

echo "e2e_render: $passes passed, $failures failed"
[ $failures = 0 ]
