#!/usr/bin/env bash
# End-to-end: the automatic material rules from the user's side (material_rules,
# material_rule add|set|move|delete|reset): a snow rule moved down to 500 m whitens the
# ground above 500 m in the picture and nothing below it, the heights (`hash`) never
# change, undo and redo give the pictures back exactly, save and load keep the stack,
# an old file gets the default stack, and bad input is refused naming what is wrong.
# Usage: e2e_material_rules.sh OROGEN TESTS_DIR
set -u
orogen=$1
rmse_tool="$(dirname "$orogen")/image_rmse"
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-e2e-rules-XXXXXX")
trap 'rm -rf "$work"' EXIT
export HOME="$work/home"
mkdir -p "$HOME"
failures=0
passes=0
check() { # name, status of the condition
    if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}
run() { "$orogen" "$@" >"$work/out" 2>"$work/err"; status=$?; }
rmse() { "$rmse_tool" "$1" "$2" | sed -n 's/^rmse=//p'; }
less() { awk -v a="$1" -v b="$2" 'BEGIN { n = "^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$"
                                          exit !(a ~ n && b ~ n && a + 0 < b + 0) }'; }

W=480
H=270
# A smooth 900 m hill on a plain at 0 m (its flanks under 20 degrees: snow may lie on
# all of it), seen from the south.
hill="new flat; set generator flat; set base_height 0; set size 2048; set spacing 4; generate;
      stamp gaussian 4096 4096 scale=12 intensity=900"
cam="camera 4096 1700 7000 0 -22 40"
area="hash 0 0 8188 8188"
no_snow="material_rule set 5 height=5000,inf,40"
snow500="material_rule set 5 height=500,inf,40"

# 1. The snow rule moved from out of reach down to 500 m; undo and redo.
run -c "$hill; $cam; $no_snow; screenshot $work/a.png $W $H; $area; $snow500; screenshot $work/b.png $W $H;
        $area; undo; screenshot $work/c.png $W $H; $area; redo; screenshot $work/d.png $W $H;
        material_rules; history"
[ $status = 0 ]; ok=$?; check "the rules change and render ($(cat "$work/err"))" $ok
hashes=$(grep -E '^[0-9a-f]{16}$' "$work/out" | sort -u | wc -l)
[ "$hashes" = 1 ]; check "the heights never change (one hash for all three, got $hashes)" $?
grep -q '^rule 5: snow height=500,inf,40 slope=0,28.8108,9.849$' "$work/out"
check "material_rules lists the changed rule" $?
grep -q 'material_rule set 5 height=500,inf,40' "$work/out"; check "history names the step" $?
r=$(rmse "$work/a.png" "$work/b.png"); less 3 "$r"; check "snow at 500 m shows (RMSE $r)" $?
r=$(rmse "$work/a.png" "$work/c.png"); less "$r" 0.001; check "undo gives the picture back (RMSE $r)" $?
r=$(rmse "$work/b.png" "$work/d.png"); less "$r" 0.001; check "redo gives it again (RMSE $r)" $?

# Where it changed: the ground under a grid of pixels (pick), above and below 500 m.
picks=""
for y in $(seq 96 12 262); do
    for x in $(seq 8 20 472); do picks="$picks pick $x $y $W $H;"; done
done
run -c "$hill; $cam; $picks"
[ $status = 0 ]; ok=$?; check "picks under the grid ($(cat "$work/err"))" $ok
oiiotool "$work/a.png" -o "$work/a.ppm" && oiiotool "$work/b.png" -o "$work/b.ppm"
check "the screenshots convert for reading" $?
verdict=$(python3 - "$work/a.ppm" "$work/b.ppm" "$work/out" <<'EOF'
import sys
def ppm(path):
    data = open(path, "rb").read()
    parts = data.split(maxsplit=4)  # P6 W H MAX pixels
    w, h = int(parts[1]), int(parts[2])
    return w, data[len(data) - w * h * 3:]
w, a = ppm(sys.argv[1])
_, b = ppm(sys.argv[2])
heights = [float(l.split()[2]) for l in open(sys.argv[3]) if l.startswith("pick ")]
points = [(x, y) for y in range(96, 263, 12) for x in range(8, 473, 20)]
def luma(img, x, y):
    i = (y * w + x) * 3
    return 0.3 * img[i] + 0.59 * img[i + 1] + 0.11 * img[i + 2]
low = high = low_changed = high_whiter = 0
for (x, y), h in zip(points, heights):
    d = luma(b, x, y) - luma(a, x, y)
    if h < 440: low += 1; low_changed += abs(d) > 8
    if h > 560: high += 1; high_whiter += d > 10
print(len(heights), len(points), low, low_changed, high, high_whiter)
EOF
)
read -r n want low low_changed high high_whiter <<<"$verdict"
echo "grid: $n picks, $low below 440 m ($low_changed changed), $high above 560 m ($high_whiter whiter)"
[ "$n" = "$want" ]; check "every grid pixel has ground under it ($n of $want)" $?
[ "${low:-0}" -gt 20 ] && [ "${high:-0}" -gt 20 ]
check "the grid sees ground both below 440 m ($low) and above 560 m ($high)" $?
[ "${low_changed:-1}" -le $((low / 30)) ]
check "below 440 m the picture stays ($low_changed of $low pixels changed)" $?
[ $((high_whiter * 10)) -ge $((${high:-1} * 9)) ]
check "above 560 m it whitens ($high_whiter of $high pixels)" $?

# 2. The stack's other commands, each one step, and their errors.
run -c "material_rule add gravel slope=10,20,5 breakup=0.3 at=2; material_rule move 2 top;
        material_rule add moss curvature=0.5,inf,0.2; material_rule delete 1; material_rules;
        undo; undo; undo; undo; material_rules"
[ $status = 0 ]; ok=$?; check "add, move, delete run ($(cat "$work/err"))" $ok
grep -q '^added rule 2: gravel slope=10,20,5 breakup=0.3$' "$work/out"; check "add echoes the rule" $?
grep -q '^moved to rule 6: gravel' "$work/out"; check "move echoes where it went" $?
grep -q '^rule 1: grass height=1%+6,inf,6 (height -378..inf m here)$' "$work/out"
check "delete took the bottom rule away" $?
[ "$(grep -c '^rule ' "$work/out")" = 11 ] && [ "$(grep '^rule ' "$work/out" | tail -5 | cut -c1-11 | tr '\n' ' ')" = "rule 1: san rule 2: gra rule 3: roc rule 4: cli rule 5: sno " ]
check "four undos give the default stack back" $?
for bad in "material_rule set 9 height=1,2|expected a rule number 1..5, got '9'" \
           "material_rule set 2 height=5,1|height=5,1: the low end is above the high end" \
           "material_rule set 2 slope=10,95|slope=10,95: degrees must lie within 0..90" \
           "material_rule set 2 colour=red|colour=red: unknown rule key" \
           "material_rule add lava|material=lava: expected sand, grass" \
           "material_rule move 5 up|rule 5 is already at the top" \
           "material_rule spin 2|expected add, set, move, delete or reset, got 'spin'"; do
    run -c "${bad%%|*}"
    [ $status != 0 ] && grep -qF -- "${bad#*|}" "$work/err"
    ok=$?; check "'${bad%%|*}' is refused: ${bad#*|} ($(cat "$work/err"))" $ok
done

# A planet's rules lay over its own look: none at first, then as on a flat world.
run -c "new planet preset=moon; material_rules; material_rule add snow height=1000,inf,50;
        material_rules; material_rule reset; material_rules"
[ $status = 0 ] && grep -q "^material_rules: 0 rules, .*over the planet's own look" "$work/out" &&
    grep -q '^rule 1: snow height=1000,inf,50$' "$work/out" &&
    [ "$(grep -c '^material_rules: 0 rules' "$work/out")" = 2 ]
ok=$?; check "a planet starts with no rules, takes them and resets to none ($(cat "$work/err"))" $ok

# 3. Save and load keep the stack; an old file gets the default stack; a bad line is
# an error naming the file and line.
run -c "$snow500; material_rule add dirt height=-inf,10%; save $work/w.world; $cam;
        screenshot $work/saved.png $W $H"
[ $status = 0 ]; ok=$?; check "save ($(cat "$work/err"))" $ok
grep -q '^material_rule_5 = snow height=500,inf,40 slope=0,28.8108,9.849;$' "$work/w.world" &&
    grep -q '^material_rule_6 = dirt height=-inf,10%;$' "$work/w.world"
check "the parameter file holds the rules" $?
run "$work/w.world" -c "material_rules; $cam; screenshot $work/loaded.png $W $H"
[ $status = 0 ]; ok=$?; check "load ($(cat "$work/err"))" $ok
grep -q '^rule 6: dirt height=-inf,10% (height -inf..-240 m here)$' "$work/out"; check "load keeps the rules" $?
r=$(rmse "$work/saved.png" "$work/loaded.png"); less "$r" 0.5; check "and the picture (RMSE $r)" $?
grep -v '^material_rule' "$work/w.world" | grep -v '^# Saved by\|^# end of file' >"$work/old.world"
run "$work/old.world" -c "material_rules"
[ $status = 0 ] && grep -q '^rule 5: snow height=62%+40,inf,80 slope=0,28.8108,9.849' "$work/out" &&
    [ "$(grep -c '^rule ' "$work/out")" = 5 ]
ok=$?; check "a file without rules gets the default stack ($(cat "$work/err"))" $ok
sed 's/^material_rule_2 = .*/material_rule_2 = grass height=9,1;/' "$work/w.world" >"$work/bad.world"
run "$work/bad.world" --batch /dev/null
line=$(grep -n '^material_rule_2' "$work/bad.world" | cut -d: -f1)
grep -qF "bad.world:$line: error: material_rule_2: height=9,1: the low end is above the high end" "$work/err"
ok=$?; check "a bad rule line is an error naming file and line ($(head -c 300 "$work/err"))" $ok

echo "e2e_material_rules: $passes passed, $failures failed"
[ $failures = 0 ]
