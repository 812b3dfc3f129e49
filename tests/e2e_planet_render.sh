#!/usr/bin/env bash
# End-to-end: planets in the viewport, offscreen in batch mode (headless EGL). An
# Earth-radius planet at 1 m spacing from orbit, from 10 km up and from 2 m above the
# ground against golden images (RMSE tolerance, as e2e_render); a descent from
# 40,000 km to 2 m where each small step of the camera changes the picture only a
# little (no precision jitter); an edit, paint and the detail layer's parallax show and
# their undo restores the picture; ground hidden behind nearer ground is left out with
# the picture unchanged; the seed-004 planet and the airless preset render;
# bad camera input fails clearly.
# Usage: e2e_planet_render.sh OROGEN TESTS_DIR
# Regenerate the goldens after a deliberate change: tests/golden_update.sh
set -u
orogen=$1
tests=$2
golden="$tests/data/golden"
rmse_tool="$(dirname "$orogen")/image_rmse"
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-planet-render-XXXXXX")
failed_dir="${TMPDIR:-/tmp}/orogen-render-failures/planet" # its own: e2e_render empties its folder
failures=0
passes=0
check() { if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi; }
trap 'rm -rf "$work"' EXIT
[ -x "$rmse_tool" ] || { echo "FAIL: $rmse_tool is missing (it is built with orogen)"; exit 1; }
if [ -n "${ASAN_OPTIONS:-}" ]; then export ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0"; fi

run() { "$orogen" -c "$1" >"$work/out" 2>"$work/err"; }
rmse() { "$rmse_tool" "$1" "$2" | sed -n 's/^rmse=//p'; }
less() {
    awk -v a="$1" -v b="$2" 'BEGIN { n = "^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$"
                                     exit !(a ~ n && b ~ n && a + 0 < b + 0) }'
}
size="320 180"
earth="new planet; spacing 1; generate"
# A land spot of that planet (ground ~1700 m above the datum).
spot="40 -30"

# --- goldens ---------------------------------------------------------------------
run "$earth; camera_geo $spot 15000000; screenshot $work/planet_orbit.png $size;
     camera_geo $spot 10000 0 -15 ground; screenshot $work/planet_10km.png $size;
     camera_geo $spot 2 0 -5 ground; screenshot $work/planet_2m.png $size;
     camera_geo $spot 15000000; view wireframe; screenshot $work/planet_wire.png $size"
rc=$?; check "Earth-radius planet renders from orbit, 10 km and 2 m ($(cat "$work/err"))" $rc
run "load $tests/data/params/seed004.planet; screenshot $work/planet_seed004.png $size"
rc=$?; check "the seed-004 planet renders ($(cat "$work/err"))" $rc
run "new planet preset=moon; screenshot $work/planet_moon.png $size"
rc=$?; check "the moon preset renders ($(cat "$work/err"))" $rc
# Issue 29's reproducers: the sea 100 m below a camera looking out to the horizon (its
# near part was left out, black), and a camera 2 m up on a face edge (the neighbouring
# face's near ground was missing: its edge stood higher than the camera); the ground
# 2 m over a face edge and at a cube corner (the textures' pattern broke along the edge).
# The face reproducers on the planet they were filed on (the preset's generator then:
# land there; the planet generator puts sea over them).
run "new planet preset=earth; camera_geo 0 20 100 90 -10; screenshot $work/planet_sea_low.png $size;
     new planet preset=earth generator=fbm_advanced;
     camera_geo 10.004 45 2 110 -12 60 ground; screenshot $work/planet_face_edge.png $size;
     camera_geo 10 45 2 0 -8 60 ground; screenshot $work/planet_face_seam.png $size;
     camera_geo 35.2644 -45 3 200 -40 60 ground; screenshot $work/planet_face_corner.png $size"
rc=$?; check "the issue-29 reproducers render ($(cat "$work/err"))" $rc
# The Earth-like preset reads as a planet: continents and snowy ranges from orbit, a
# range's ridges and valleys from 10 km (editor/gen/gen_planet.c).
run "new planet preset=earth; camera_geo 20 10 2000000 0 -90; screenshot $work/planet_earth_ranges.png $size;
     camera_geo 22 3 10000 30 -30 60 ground; screenshot $work/planet_earth_10km.png $size"
rc=$?; check "the Earth-like preset's ranges render ($(cat "$work/err"))" $rc
# Over the sea `ground` means the surface a person floats on, and pick finds the
# surface (the floor under it on request): the camera never lands on the sea floor.
run "new planet preset=earth; camera_geo 0 20 100 90 -10 60 ground; camera; pick 640 600;
     pick 640 600 1280 720 floor"
rc=$?; check "the sea's surface and floor are picked ($(cat "$work/err"))" $rc
alt=$(awk '/^camera_geo /{print $4}' "$work/out")
[ "$alt" = "100.000" ]; check "camera_geo ... ground over the sea stands 100 m above the sea's surface (got $alt)" $?
read -r surface floor <<<"$(awk '/^pick /{r = sqrt($2*$2 + $3*$3 + $4*$4) - 6371000; printf "%s ", r}' "$work/out")"
awk -v s="$surface" -v f="$floor" 'BEGIN { exit !(s * s < 0.01 && f < -100) }'
check "pick reports the sea's surface (${surface} m) and, with floor, the sea floor (${floor} m)" $?
# One unit everywhere: seed 004's radius-10 planet counts face-local metres on the sphere
# (a face's arc is pi/2 x 10 m, not 256 samples x its nominal spacing of 100).
run "load $tests/data/params/seed004.planet; info"
extent=$(sed -n 's/^face_extent_m=//p' "$work/out")
awk -v e="$extent" 'BEGIN { t = 3.14159265358979 / 2 * 10 * 255 / 256; exit !((e - t) ^ 2 < 1e-12) }'
check "seed 004's face is 15.6 m across in face-local metres (face_extent_m=$extent)" $?
max_golden=2.0
mkdir -p "$failed_dir"
for name in planet_orbit planet_10km planet_2m planet_wire planet_seed004 planet_moon \
    planet_sea_low planet_face_edge planet_face_seam planet_face_corner planet_earth_ranges \
    planet_earth_10km; do
    if [ -n "${OROGEN_UPDATE_GOLDEN:-}" ]; then
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
    if [ $status != 0 ]; then
        cp "$golden/$name.png" "$failed_dir/$name-golden.png" && cp "$work/$name.png" "$failed_dir/$name-got.png"
    fi
    check "$name matches its golden within RMSE $max_golden ($(cat "$work/rmse"); on failure see $failed_dir)" $status
done
# Not blank: the planet from orbit differs from black space, the ground from the sky.
black=$(rmse "$work/planet_orbit.png" "$work/planet_wire.png")
less 1 "$black"; check "the shaded and wireframe orbit views differ (rmse $black)" $?

# --- a descent: every small step of the camera moves the picture only a little ------
# Altitudes above the ground from 40,000 km to 2 m; at each, a second frame 0.1% lower.
# In single precision at Earth's radius (0.5 m steps) the 2 m views would jump.
cmds="$earth"
alts="40000000 4000000 400000 40000 4000 400 40 2"
for a in $alts; do
    b=$(awk -v a="$a" 'BEGIN { printf "%.6f", a * 0.999 }')
    cmds="$cmds; camera_geo $spot $a 0 -20 ground; screenshot $work/d_$a.png $size"
    cmds="$cmds; camera_geo $spot $b 0 -20 ground; screenshot $work/e_$a.png $size"
done
run "$cmds"
rc=$?; check "the descent renders ($(cat "$work/err"))" $rc
for a in $alts; do
    r=$(rmse "$work/d_$a.png" "$work/e_$a.png")
    less "$r" 3.0; check "a 0.1% step at ${a} m changes the frame by rmse $r < 3" $?
done
# And the frames differ from one altitude to the next (the camera did move).
r=$(rmse "$work/d_40.png" "$work/d_2.png")
less 1 "$r"; check "40 m and 2 m views differ (rmse $r)" $?

# --- ground hidden behind nearer ground is left out, and the picture is the same ----
# 2 m up, the chunks past the horizon the nearby ground makes pass the frustum and
# horizon tests; `render culling=off` draws them too.
run "$earth; camera_geo $spot 2 90 -5 ground; screenshot $work/occ_on.png $size;
     render culling=off; screenshot $work/occ_off.png $size"
rc=$?; check "2 m views with and without occlusion culling ($(cat "$work/err"))" $rc
# triangles NAME: the triangles the last run's screenshot NAME.png drew.
triangles() { sed -n "s/^screenshot .*$1\.png.* triangles=\([0-9]*\).*/\1/p" "$work/out"; }
tris_on=$(triangles occ_on)
tris_off=$(triangles occ_off)
less "${tris_on:-x}" "${tris_off:-x}"
check "occlusion culling draws fewer triangles ($tris_on against $tris_off)" $?
r=$(rmse "$work/occ_on.png" "$work/occ_off.png")
less "$r" 0.001; check "and the same picture (rmse $r)" $?
# In rough hills (the moon preset at 1 m) the horizon of nearer ground hides most of
# the rest, past crests too: 28 of 197 chunks here (the solids under nearer ground alone
# leave 89), and the same picture.
run "new planet preset=moon; spacing 1; generate; camera_geo 40 -30 2 240 -5 ground;
     screenshot $work/hills_on.png $size; render culling=off; screenshot $work/hills_off.png $size"
rc=$?; check "2 m in the moon's hills with and without culling ($(cat "$work/err"))" $rc
tris_on=$(triangles hills_on)
tris_off=$(triangles hills_off)
less "$((${tris_on:-0} * 4))" "${tris_off:-0}"
check "culling in hills draws under a quarter of the triangles ($tris_on against $tris_off)" $?
r=$(rmse "$work/hills_on.png" "$work/hills_off.png")
less "$r" 0.001; check "and the same picture (rmse $r)" $?

# --- on rough ground the camera stands on the ground that is drawn ----------------
# The moon preset's relief at 100 m spacing: the drawn mesh (corners bilinear between
# samples) and the bilinear samples differ by tens of metres in places. Here, in a
# hollow, a camera 2 m above the samples was under the drawn ground and saw through it
# (the bottom of the picture black); 2 m above the drawn ground it sees the ground.
run "new planet preset=moon w_factor=0.7 octaves=18; camera_geo 40 -30 2 0 -5 ground;
     screenshot $work/rough.png $size"
rc=$?; check "2 m above rough ground ($(cat "$work/err"))" $rc
bottom=$(convert "$work/rough.png" -crop 320x30+0+150 +repage -format "%[fx:mean]" info:)
less 0.2 "$bottom"; check "the bottom of the picture shows ground (mean $bottom > 0.2)" $?

# --- an edit shows, its undo restores the picture ----------------------------------
# Face 4 (+Z) centre is latitude 0, longitude 0; face-local metres of its centre.
centre=5004750
run "new planet; camera_geo 0 0 30000 0 -70 ground; screenshot $work/edit0.png $size;
     tool raise radius=6000 amount=3000 strength=1 face=4; dab $centre $centre;
     screenshot $work/edit1.png $size; undo; screenshot $work/edit2.png $size"
rc=$?; check "edit on a planet face, then undo ($(cat "$work/err"))" $rc
r1=$(rmse "$work/edit0.png" "$work/edit1.png")
r2=$(rmse "$work/edit0.png" "$work/edit2.png")
less 1 "$r1"; check "the dab shows in the view (rmse $r1)" $?
less "$r2" 0.3; check "undo restores the view (rmse $r2)" $?

# --- paint shows on the planet too (level-0 chunks blend the painted weights) -------
# Face 4's metres of latitude 20, longitude -30 (land on the default planet).
read -r px pz < <(python3 -c "
import math
la, lo = math.radians(20), math.radians(-30)
x, y, z = math.cos(la) * math.sin(lo), math.sin(la), math.cos(la) * math.cos(lo)
s, t = math.atan(x / z) * 4 / math.pi, math.atan(y / z) * 4 / math.pi
print(((s + 1) / 2 * 100096 - 0.5) * 100, ((t + 1) / 2 * 100096 - 0.5) * 100)")
run "new planet; camera_geo 20 -30 2500 0 -89 ground; screenshot $work/paint0.png $size;
     tool paint radius=800 strength=1 material=4 face=4; dab $px $pz;
     screenshot $work/paint1.png $size; undo; screenshot $work/paint2.png $size"
rc=$?; check "paint on a planet, then undo ($(cat "$work/err"))" $rc
r1=$(rmse "$work/paint0.png" "$work/paint1.png")
r2=$(rmse "$work/paint0.png" "$work/paint2.png")
less 5 "$r1"; check "the painted snow shows (rmse $r1)" $?
less "$r2" 0.3; check "undo takes it away (rmse $r2)" $?

# --- detail near the camera: the detail layer's relief by parallax and normals -----
# Face 4's metres of latitude 40, longitude -30 on the 1 m Earth, 12 m north of it.
read -r dx dz < <(python3 -c "
import math
la, lo = math.radians(40), math.radians(-30)
x, y, z = math.cos(la) * math.sin(lo), math.sin(la), math.cos(la) * math.cos(lo)
s, t = math.atan(x / z) * 4 / math.pi, math.atan(y / z) * 4 / math.pi
n = 10007552
print(((s + 1) / 2 * n - 0.5), ((t + 1) / 2 * n - 0.5) + 12)")
run "$earth; camera_geo 40 -30 3 0 -35 ground; screenshot $work/detail0.png $size;
     tool noise target=detail radius=60 strength=1 scale=3 face=4; dab $dx $dz;
     render parallax=on; screenshot $work/detail_on.png $size;
     render parallax=off; screenshot $work/detail_off.png $size; render parallax=on;
     camera_geo 40 -30 400 0 -35 ground; screenshot $work/detail_far.png $size;
     camera_geo 40 -30 3 0 -35 ground; undo; screenshot $work/detail_undone.png $size"
rc=$?; check "detail sculpted on a planet, parallax on and off, undo ($(cat "$work/err"))" $rc
r=$(rmse "$work/detail_on.png" "$work/detail_off.png")
less 3 "$r"; check "parallax changes the planet's picture (rmse $r)" $?
r=$(rmse "$work/detail0.png" "$work/detail_off.png")
less 3 "$r"; check "the detail's normals show without parallax (rmse $r)" $?
r=$(rmse "$work/detail0.png" "$work/detail_undone.png")
less "$r" 0.3; check "undo takes the detail away (rmse $r)" $?
# Seen from 400 m (past the fade distance) the edit does not show.
run "$earth; camera_geo 40 -30 400 0 -35 ground; screenshot $work/detail_far0.png $size"
r=$(rmse "$work/detail_far0.png" "$work/detail_far.png")
less "$r" 0.3; check "detail fades out with distance (rmse $r)" $?

# --- detail across a face edge: the neighbouring face shows it too ------------------
# Face 4's top edge at longitude -30 (latitude 40.8934), the camera 10 m south of it
# looking north: the ground past the edge (the image's upper left) is face 2's. A noise
# dab on the detail layer at the edge reaches both faces.
read -r ex ez < <(python3 -c "
import math
lo = math.radians(-30.0)
la = math.atan(math.cos(lo))
x, y, z = math.cos(la) * math.sin(lo), math.sin(la), math.cos(la) * math.cos(lo)
s, t = math.atan(x / z) * 4 / math.pi, math.atan(y / z) * 4 / math.pi
n = 10007552
print(((s + 1) / 2 * n - 0.5), ((t + 1) / 2 * n - 0.5) - 0.6)")
run "$earth; camera_geo 40.8933 -30 3 0 -20 ground; screenshot $work/edge0.png $size;
     tool noise target=detail radius=60 strength=1 scale=3 face=4; dab $ex $ez;
     screenshot $work/edge1.png $size; undo; screenshot $work/edge2.png $size"
rc=$?; check "detail sculpted at a face edge ($(cat "$work/err"))" $rc
for i in 0 1 2; do convert "$work/edge$i.png" -crop 160x40+0+38 +repage "$work/edge_past$i.png"; done
r=$(rmse "$work/edge_past0.png" "$work/edge_past1.png")
less 3 "$r"; check "the detail shows past the face edge, on the neighbouring face (rmse $r)" $?
r=$(rmse "$work/edge_past0.png" "$work/edge_past2.png")
less "$r" 0.3; check "undo takes it away there too (rmse $r)" $?

# --- the debug overlays: the face's tile grid and the chunks' vertex grids ---------
run "$earth; camera_geo $spot 3000 0 -40 ground; view levels; screenshot $work/grid0.png $size;
     render tile_grid=on; screenshot $work/grid_tiles.png $size;
     render tile_grid=off level_grid=on; screenshot $work/grid_levels.png $size"
rc=$?; check "the overlays render on a planet ($(cat "$work/err"))" $rc
r=$(rmse "$work/grid0.png" "$work/grid_tiles.png")
less 1 "$r"; check "the tile grid shows on a planet (rmse $r)" $?
r=$(rmse "$work/grid_tiles.png" "$work/grid_levels.png")
less 1 "$r"; check "the level grid shows on a planet, and differs from the tile grid (rmse $r)" $?

# --- bad input ---------------------------------------------------------------------
run "new planet; camera_geo 91 0 100"
grep -q "LAT: expected degrees in \[-90, 90\]" "$work/err"; check "latitude over 90 refused" $?
run "camera_geo 10 10 100"
grep -q "camera_geo: planets only" "$work/err"; check "camera_geo on a flat world refused" $?
run "new planet; camera_geo 10 10 nan"
grep -q "ALT" "$work/err"; check "NaN altitude refused" $?

# A camera placed for the flat world before `new planet` is not the planet's: the batch
# shows the new world from its default camera (the whole disc from the day side, 28
# degrees from under the default sun at 35 N, 45 E, north up; test_planet_first_view
# measures it), not from the planet's centre.
run "camera 400 -50 600 30 -25; new planet preset=moon; screenshot $work/after_new.png 64 36; camera"
grep -q '^camera_geo 15.000000 23.000000 [0-9.]* 0.000 -89.900' "$work/out"
rc=$?; check "after new planet a batch screenshot places the planet's own camera ($(grep '^camera' "$work/out" | tr '\n' ' '))" $rc

echo "$passes passed, $failures failed"
[ "$failures" = 0 ]
