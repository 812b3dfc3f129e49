#!/usr/bin/env bash
# End-to-end: the editing commands of the real orogen binary in batch mode
# (tool, dab, stroke, stamp, stamps, undo, redo, history) and what save keeps.
# Usage: e2e_edit.sh OROGEN TESTS_DIR
set -u
orogen=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-e2e-edit-XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
passes=0
check() { # name, status of the condition
    if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}
run() {
    "$orogen" "$@" >"$work/out" 2>"$work/err"
    status=$?
    grep -E '^[0-9a-f]{16}$' "$work/out" >"$work/hashes"
}
nth_hash() { sed -n "${1}p" "$work/hashes"; }
world='new flat; set size 1024; set spacing 2; generate'
area='hash 0 0 2046 2046'

# 1. every tool changes the terrain and undo restores it exactly; redo reapplies exactly
run -c "$world; $area"
h0=$(tail -n 1 "$work/out")
for t in "raise amount=5" "lower amount=5" "smooth" "flatten height=10" "set height=-30" \
         "noise amount=20 scale=30" "terrace step=15" "thermal talus=20" \
         "hydraulic droplets=300" "ramp"; do
    run -c "$world; tool $t radius=60 strength=1; stroke 400 400 700 500 900 900; $area; undo; $area; redo; $area"
    [ $status = 0 ]; check "tool $t runs" $?
    after=$(sed -n 1p "$work/out"); undone=$(sed -n 2p "$work/out"); redone=$(sed -n 3p "$work/out")
    [ "$after" != "$h0" ]; check "tool $t changes the terrain" $?
    [ "$undone" = "$h0" ]; check "tool $t: undo restores the exact hash" $?
    [ "$redone" = "$after" ]; check "tool $t: redo reapplies exactly" $?
done

# 2. a stroke is one undo step however many dabs it has
run -c "$world; tool raise radius=20 spacing=0.1; stroke 100 100 1500 100 1500 1500; history"
grep -q '^steps=2 undoable=2' "$work/out"; check "a long stroke is one step (after generate)" $?
grep -q 'raise stroke' "$work/out"; check "history names the stroke" $?

# 3. stamps: the list, functional and library stamps, every mode, undo
run -c 'stamps'
[ "$(grep -c ' library' "$work/out")" -ge 6 ]; check "at least 6 built-in library stamps" $?
[ "$(grep -c ' functional' "$work/out")" -eq 6 ]; check "6 functional stamps" $?
[ -z "$(cut -d' ' -f1 "$work/out" | sort | uniq -d)" ]; check "stamp names are unique (each one reachable)" $?
for s in gaussian crater cone volcano mesa ridge mountain dunes canyon; do
    run -c "$world; stamp $s 1000 1000 scale=2 rot=37 intensity=40; $area; undo; $area"
    [ $status = 0 ]; check "stamp $s runs" $?
    [ "$(sed -n 1p "$work/out")" != "$h0" ] && [ "$(sed -n 2p "$work/out")" = "$h0" ]; check "stamp $s changes, undo restores" $?
done
for m in add subtract max min blend; do
    run -c "$world; stamp gaussian 1000 1000 mode=$m intensity=600 mirror=x; $area"
    [ $status = 0 ] && [ "$(tail -n 1 "$work/out")" != "$h0" ]; check "stamp mode $m" $?
done
run -c "$world; stamp mesa 1000 1000 layer=detail; $area"
[ $status = 0 ] && [ "$(tail -n 1 "$work/out")" = "$h0" ]; check "a detail stamp leaves the coarse layer alone" $?

# 4. user stamps: a folder from OROGEN_STAMP_DIR, and an image path
mkdir -p "$work/mystamps"
oiiotool --pattern fill:topleft=0,0,0:topright=1,1,1:bottomleft=0.5,0,0:bottomright=0,0,1 64x48 3 -d uint16 -o "$work/mystamps/wedge.png" >/dev/null 2>&1
OROGEN_STAMP_DIR="$work/mystamps" run -c 'stamps'
grep -q '^wedge user' "$work/out"; check "user stamp folder is listed" $?
OROGEN_STAMP_DIR="$work/mystamps" run -c "$world; stamp wedge 1000 1000 scale=4; $area"
[ $status = 0 ] && [ "$(tail -n 1 "$work/out")" != "$h0" ]; check "a user stamp by name" $?
run -c "$world; stamp $work/mystamps/wedge.png 1000 1000; $area"
[ $status = 0 ] && [ "$(tail -n 1 "$work/out")" != "$h0" ]; check "a stamp from an image path" $?

# 5. bad input: clear errors, nothing changes
echo "not an image" >"$work/bad.png"
bad() { # name, commands, expected error text
    run -c "$world; $2"
    [ $status = 1 ]; check "$1 fails" $?
    grep -q -- "$3" "$work/err"; check "$1 says '$3'" $?
}
bad "unknown tool" "tool chisel" "unknown tool 'chisel'"
bad "unknown stamp" "stamp nosuch 10 10" "unknown stamp 'nosuch'"
bad "unreadable stamp image" "stamp $work/bad.png 10 10" "bad.png"
bad "missing stamp image" "stamp $work/none.png 10 10" "does not exist"
bad "NaN radius" "tool raise radius=nan" "radius: expected a number in \[0.001, 1e+06\], got 'nan'"
bad "huge radius" "tool raise radius=1e999" "radius"
bad "strength out of range" "tool raise strength=2" "strength: expected a number in \[0, 1\], got '2'"
bad "unknown setting" "tool raise sharpen=1" "unknown brush setting 'sharpen'"
bad "NaN position" "dab nan 5" "X: expected a finite number, got 'nan'"
bad "inf position" "stroke 1 1 inf 2" "X: expected a finite number, got 'inf'"
bad "outside a bounded world" "dab 5000 5" "outside the world"
bad "pressure out of range" "dab 5 5 1.5" "pressure: expected a number in \[0, 1\], got '1.5'"
bad "odd stroke" "stroke 1 2 3" "X Z pairs"
bad "set without height" "tool set; dab 10 10" "give the height"
bad "invert on flatten" "tool flatten invert=1; dab 10 10" "invert: has no meaning for flatten"
bad "stamp scale" "stamp crater 10 10 scale=0" "scale: expected a number in (0, 1000\], got '0'"
bad "stamp mode" "stamp crater 10 10 mode=multiply" "mode: 'multiply'"
bad "undo with nothing" "undo; undo" "nothing to undo"
bad "redo with nothing" "redo" "nothing to redo"
# a bad setting stops the batch before the next edit
run -c "$world; tool raise radius=60; dab 100 100; tool raise strength=7; dab 300 300"
[ $status = 1 ] && ! grep -q . "$work/hashes"; check "bad setting fails the batch" $?

# 6. save keeps edits; edits after the save are not in the files until saved again
run -c "$world; tool raise radius=80 amount=30 strength=1; dab 600 600; save $work/w.world; $area; info"
[ $status = 0 ]; check "save after edits" $?
h_saved=$(nth_hash 1)
grep -q '^unsaved_changes=0$' "$work/out"; check "saved world has no unsaved changes" $?
cp "$work/w.tiles" "$work/w.tiles.before"
run -c "load $work/w.world; $area; tool raise radius=80 amount=30; dab 900 900; info"
[ "$(nth_hash 1)" = "$h_saved" ]; check "loading gives the saved terrain" $?
grep -q '^unsaved_changes=1$' "$work/out"; check "an edit makes the world unsaved" $?
cmp -s "$work/w.tiles" "$work/w.tiles.before"; check "unsaved edits never touch the saved tiles" $?
run -c "load $work/w.world; $area"
[ "$(tail -n 1 "$work/out")" = "$h_saved" ]; check "closing without saving drops the edit" $?
run -c "load $work/w.world; tool raise radius=80 amount=30; dab 900 900; save; $area; undo; $area; info"
h_two=$(nth_hash 1)
[ "$(nth_hash 2)" = "$h_saved" ]; check "undo works after save" $?
grep -q '^unsaved_changes=1$' "$work/out"; check "undo after save is an unsaved change" $?
run -c "load $work/w.world; $area"
[ "$(tail -n 1 "$work/out")" = "$h_two" ]; check "the second save holds both edits" $?

# 7. generate is undoable
run -c "$world; $area; seed 77; generate; $area; undo; $area"
[ "$(sed -n 1p "$work/out")" != "$(sed -n 2p "$work/out")" ] && [ "$(sed -n 3p "$work/out")" = "$(sed -n 1p "$work/out")" ]
check "undo of generate restores the terrain" $?

# 8. history budget: old steps are dropped and the user is told
run -c "$world; history budget=1; tool noise radius=400 amount=50 scale=20; dab 500 500; dab 1500 1500; dab 500 1500; dab 1500 500; history"
grep -q 'history: dropped the' "$work/err"; check "dropping history steps is reported" $?
grep -q 'dropped=[1-9]' "$work/out"; check "history counts dropped steps" $?

# 9. paint and detail targets
run -c "$world; tool paint material=3 radius=50; dab 500 500; tool raise target=detail amount=0.2 radius=5; dab 500 500; $area; history"
[ $status = 0 ]; check "paint and detail sculpt run" $?
[ "$(nth_hash 1)" = "$h0" ]; check "paint and detail leave coarse heights alone" $?

echo "e2e_edit: $passes passed, $failures failed"
[ $failures = 0 ]
