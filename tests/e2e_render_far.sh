#!/usr/bin/env bash
# End-to-end: a small bounded world seen from afar is drawn with its own heights. The
# viewport's coarser clipmap levels read the coarse layer's mip levels, and those once
# stopped being updated past the level where one tile covers the world: a 600 x 200 m
# heightmap seen from 805 m (the first view in a 900 x 700 window) was drawn as a flat
# plate and the pick at the view's centre found no ground. For worlds made from a
# heightmap (wide and tall) and a small `new flat` world sculpted by a dab, from
# 300 m to 3 km, the pick at the view's centre must meet the ground within the world and
# at the height `sample` gives there (within the drawn level's sampling error). A world
# saved before the far levels followed edits gets them on load.
# Usage: e2e_render_far.sh OROGEN TESTS_DIR
set -u
orogen=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-render-far-XXXXXX")
failures=0
passes=0
check() { if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi; }
trap 'rm -rf "$work"' EXIT
if [ -n "${ASAN_OPTIONS:-}" ]; then export ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0"; fi

# Two heightmaps cut from the default world's rough ground: 600 x 200 m and 200 x 600 m.
"$orogen" -c "new flat; export $work/wide.exr region=1000,1000,1600,1200;
              export $work/tall.exr region=1000,1000,1200,1600" >"$work/out" 2>"$work/err"
ok=$?; check "heightmaps exported ($(cat "$work/err"))" $ok

# sweep NAME SETUP WIDTH DEPTH: the world SETUP makes (WIDTH x DEPTH m from the origin)
# seen from 300 m to 3 km toward its middle; picks at the centre of a 900 x 700 view.
sweep() {
    local name=$1 setup=$2 width=$3 depth=$4
    local mx mz
    mx=$(awk -v w="$width" 'BEGIN { print w / 2 }')
    mz=$(awk -v d="$depth" 'BEGIN { print d / 2 }')
    "$orogen" -c "$setup; sample $mx $mz" >"$work/out" 2>"$work/err"
    local ok=$?
    check "$name: made ($(cat "$work/err"))" $ok
    local ground
    ground=$(tail -n 1 "$work/out")
    local script="$setup" d
    for d in 300 566 805 1500 3000; do
        script="$script; camera $(awk -v d="$d" -v x="$mx" -v y="$ground" -v z="$mz" 'BEGIN {
            pi = atan2(0, -1); p = -18 * pi / 180; yaw = 30 * pi / 180
            printf "%.3f %.3f %.3f", x - d * cos(p) * sin(yaw), y - d * sin(p), z + d * cos(p) * cos(yaw) }') 30 -18 60"
        script="$script; pick 450 350 900 700"
    done
    "$orogen" -c "$script" >"$work/picks" 2>"$work/err"
    ok=$?
    check "$name: every pick meets the ground ($(tr '\n' ' ' <"$work/err"))" $ok
    # Each hit lies in the world and on its ground: `sample` there, within the height
    # step to the neighbours one drawn-level sample away (level 3's 16 m: the levels
    # these views draw at the centre are finer). One run samples around every hit.
    grep '^pick ' "$work/picks" >"$work/hits"
    "$orogen" -c "$setup$(awk -v w="$width" -v d="$depth" '{
        x = $2; z = $4; s = 16; printf "; sample %.3f %.3f", x, z
        for (k = 0; k < 4; k++) {
            a = x + s * (k == 0) - s * (k == 1); b = z + s * (k == 2) - s * (k == 3)
            a = a < 0 ? 0 : a > w ? w : a; b = b < 0 ? 0 : b > d ? d : b
            printf "; sample %.3f %.3f", a, b } }' "$work/hits")" >"$work/all" 2>"$work/err"
    ok=$?
    check "$name: sample answers around the hits ($(cat "$work/err"))" $ok
    local hits
    hits=$(wc -l <"$work/hits")
    tail -n $((hits * 5)) "$work/all" >"$work/samples" # after what making the world printed
    local i px py pz verdict
    for i in $(seq "$hits"); do
        read -r _ px py pz <<<"$(sed -n "${i}p" "$work/hits")"
        verdict=$(sed -n "$((i * 5 - 4)),$((i * 5))p" "$work/samples" | awk -v y="$py" -v x="$px" -v z="$pz" -v w="$width" -v d="$depth" '
            NR == 1 { g = $1 } NR > 1 { s = $1 - g; if (s < 0) s = -s; if (s > m) m = s }
            END { e = y - g; if (e < 0) e = -e
                  inside = x >= -1 && x <= w + 1 && z >= -1 && z <= d + 1
                  printf "%s, ground %.2f, off %.2f m, allowed %.2f", inside ? "in the world" : "OUTSIDE", g, e, m + 1
                  exit !(NR == 5 && inside && e <= m + 1) }')
        ok=$?
        check "$name: view $i's centre pick ($px, $py, $pz) is on the ground ($verdict)" $ok
    done
}

sweep "600 x 200 m heightmap" "new flat from=$work/wide.exr" 600 200
sweep "200 x 600 m heightmap" "new flat from=$work/tall.exr" 200 600
# Small worlds made by `new flat` (flat ground, 2 m apart, wide and tall), raised by a
# dab into a 150 m hill whose near flank is the world's middle: the hill must show from
# afar, not the flat ground under it.
sculpt="set generator flat; generate; tool raise radius=140 strength=1 amount=150 falloff=smooth"
sweep "300 x 200 m new flat, sculpted" "new flat; set size 151; set size_z 101; $sculpt; dab 150 40" 300 200
sweep "200 x 300 m new flat, sculpted" "new flat; set size 101; set size_z 151; $sculpt; dab 100 90" 200 300

# A world saved before its far levels followed edits (its store ends at the level where
# one tile covers it, level 1 here: the tiles past it deleted and the count mended) has
# them rebuilt on load (the mended file warns that it was changed after saving).
"$orogen" -c "new flat; set size 151; set size_z 101; $sculpt; dab 150 40; save $work/old.world" \
    >/dev/null 2>"$work/err"
ok=$?
check "a sculpted world saved ($(cat "$work/err"))" $ok
sqlite3 "$work/old.tiles" "delete from tiles where layer = 0 and level > 1" &&
    sed -i "s/^tiles_saved = .*/tiles_saved = $(sqlite3 "$work/old.tiles" "select count(*) from tiles");/" \
        "$work/old.world"
ok=$?
check "its store made as an older build saved it" $ok
sweep "300 x 200 m sculpted, saved without far levels" "load $work/old.world" 300 200

echo "e2e_render_far: $passes passed, $failures failed"
[ $failures = 0 ]
