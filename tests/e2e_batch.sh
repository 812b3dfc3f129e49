#!/usr/bin/env bash
# End-to-end: the real orogen binary in batch mode. Usage: e2e_batch.sh ORGOEN TESTS_DIR
set -u
orogen=$1
tests=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-e2e-XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
passes=0

check() { # name, condition already evaluated as $?
    if [ "$2" = 0 ]; then passes=$((passes + 1)); else echo "FAIL: $1"; failures=$((failures + 1)); fi
}
run() { # captures stdout, stderr and status of orogen
    "$orogen" "$@" >"$work/out" 2>"$work/err"
    status=$?
}

# 1. info prints key=value facts
run -c 'info'
check "info exits 0" $status
grep -q '^kind=flat$' "$work/out"; check "info has kind=flat" $?
grep -q '^cache_workers=2$' "$work/out"; check "info has cache_workers" $?

# 2. first failure in a batch file: FILE:LINE: error, non-zero exit, rest not run
printf 'seed 5\n\nfrobnicate 1 2\nsave %s/never.world\n' "$work" >"$work/script.og"
run --batch "$work/script.og"
[ $status = 1 ]; check "batch failure exits 1" $?
grep -q "^$work/script.og:3: error: unknown command 'frobnicate'" "$work/err"; check "batch error names file:line" $?
[ ! -e "$work/never.world" ]; check "commands after the failure do not run" $?

# 3. -c with several commands; errors name -c and the command's line
run -c 'seed 1; octaves abc'
[ $status = 1 ]; check "-c failure exits 1" $?
grep -q "^-c:1: error: octaves: expected" "$work/err"; check "-c error message" $?
run -c 'octaves 30.5'
[ $status = 1 ]; check "out-of-range octaves rejected" $?

# 4. determinism: same digest for 1 and 2 workers and across runs; the seed matters
area='hash -3000 -2000 2500 3100'
run --workers 1 -c "$area"; h1=$(cat "$work/out")
run --workers 2 -c "$area"; h2=$(cat "$work/out")
run --workers 4 -c "$area"; h4=$(cat "$work/out")
[ -n "$h1" ] && [ "$h1" = "$h2" ] && [ "$h2" = "$h4" ]; check "hash independent of worker count" $?
run -c "seed 99; generate; $area"; h5=$(cat "$work/out")
[ "$h5" != "$h1" ]; check "hash changes with the seed" $?
for g in fbm fbm_advanced ridged diamond_square faults flat; do
    run --workers 1 -c "generator $g; generate; $area"; a=$(cat "$work/out")
    run --workers 2 -c "generator $g; generate; $area"; b=$(cat "$work/out")
    [ -n "$a" ] && [ "$a" = "$b" ]; check "generator $g deterministic across workers" $?
done

# 5. save -> load -> save is exact, and the terrain is the same after loading
run -c "generator ridged; seed 7; octaves 6.5; generate; save $work/a.world; $area"
check "save exits 0" $status
ha=$(tail -n 1 "$work/out")
run -c "load $work/a.world; save $work/b.world; $area"
hb=$(tail -n 1 "$work/out")
cmp -s "$work/a.world" "$work/b.world"; check "load/save round trip is byte-identical" $?
[ "$ha" = "$hb" ]; check "loaded world regenerates the same terrain" $?
run "$work/a.world" -c 'params'
grep -q '^octaves = 6.5;$' "$work/out"; check "world file given on the command line" $?

# 6. a planet file from Kahoun 2010 (seed 004) loads unchanged
run -c "load $tests/data/params/seed004.planet; params"
check "seed 004 planet loads" $status
grep -q '^kind = planet;$' "$work/out" && grep -q '^radius = 10;$' "$work/out" &&
    grep -q '^w_factor = 0.5;$' "$work/out"; check "seed 004 values kept" $?
[ ! -s "$work/err" ]; check "seed 004 planet loads without diagnostics" $?
# Its ocean_level is a radius (seed 004): saved as such, and generate accepts it.
run -c "load $tests/data/params/seed004.planet; save $work/s4.planet; generate"
check "seed 004 planet saves and generates" $status
grep -q '^ocean_level = 10.1;$' "$work/s4.planet"; check "saved planet keeps ocean_level as a radius" $?
run -c 'new planet; radius 3389500; generate'
[ $status = 1 ] && grep -q "ocean_level: on a planet the sea's radius" "$work/err"
check "a planet's ocean_level beyond radius + max_height is refused by name" $?
run -c 'new planet; radius 3389500; ocean_level 3389500; generate'
check "a planet's ocean_level set as a radius generates" $status
# new planet: a preset, then any parameter (File > New planet... sends every field).
run -c 'new planet preset=moon radius=2000000 seed=7 ocean_level=2000010; params'
[ $status = 0 ] && grep -q '^radius = 2000000;$' "$work/out" && grep -q '^seed = 7;$' "$work/out" &&
    grep -q '^ocean_level = 2000010;$' "$work/out" && grep -q '^max_height = 6000;$' "$work/out" &&
    grep -q '^w_factor = 0.7;$' "$work/out" && grep -q '^octaves = 18;$' "$work/out"
check "new planet preset=moon with parameters over the preset (and the preset's relief)" $?
run -c 'new planet; params'
[ $status = 0 ] && grep -q '^w_factor = 0.5;$' "$work/out" && grep -q '^octaves = 12.5;$' "$work/out"
check "new planet without a preset keeps seed 004's gain and octaves" $?
run -c 'new planet seed=4x2'
[ $status = 1 ] && grep -q "seed: expected an integer, got '4x2'" "$work/err"
check "new planet names a bad parameter" $?
run -c 'new planet radius=1000 preset=earth'
[ $status = 1 ] && grep -q "preset= must come first" "$work/err"; check "new planet: preset first" $?
run -c 'new planet preset=moon ocean_level=9000000'
[ $status = 1 ] && grep -q "ocean_level" "$work/err"; check "new planet validates the whole set" $?

# 7. a parameter file with a bad value and an unknown key: reported with lines, rest read
printf 'seed = 12;\noctaves = lots;\ncolour = blue;\nmax_height = 900;\n' >"$work/bad.world"
run -c "load $work/bad.world; params"
[ $status = 1 ] && grep -q '^loaded .*bad.world (with errors' "$work/out"
check "file with bad values still loads, and the batch exits 1 for its errors" $?
grep -q "1 error reported above; exit status 1" "$work/err"; check "the exit status is explained" $?
grep -q "bad.world:2: error: " "$work/err"; check "bad value reported with its line" $?
grep -q "bad.world:3: warning: unknown key 'colour'" "$work/err"; check "unknown key warned with its line" $?
grep -q '^max_height = 900;$' "$work/out" && grep -q '^octaves = 8;$' "$work/out"; check "bad key keeps default, later keys read" $?

# 8. no display: a clear message pointing at batch mode, not a crash
env -u DISPLAY -u WAYLAND_DISPLAY "$orogen" >"$work/out" 2>"$work/err" </dev/null
[ $? = 2 ] && grep -q "no display" "$work/err" && grep -q -- "--batch" "$work/err"; check "no display message" $?

# 9. bounded worlds, faces and bad numbers
run -c 'size 1024; generate; sample 100 100; sample 5000 10'
[ $status = 1 ] && grep -q "outside the world" "$work/err"; check "sample outside a bounded world" $?
[ "$(head -n 1 "$work/out" | grep -c '^-\?[0-9]*\.[0-9]*$')" = 1 ]; check "sample prints a number" $?
# An edge as the import prints it (rounded to 6 digits) is the edge; a step beyond is not.
# (N44W072's world is 94007.86538 m wide: 'placed at 0, 0 .. 94007.9, 94007.9 m'.)
run -c "new flat from=$tests/data/dem/N44W072.hgt; sample 94007.9 0; sample 0 -0.00001"
[ $status = 0 ] && [ "$(grep -c '^[-0-9.]*$' "$work/out")" = 2 ]
ok=$?; check "an edge read as printed ($(cat "$work/err"))" $ok
run -c "new flat from=$tests/data/dem/N44W072.hgt; sample 94008 0"
[ $status = 1 ] && grep -q "outside the world (0 to 94007.86538 m" "$work/err"; check "a metre past it is outside" $?
run -c 'new planet; sample 1000 2000 3; hash 0 0 5000 5000 5'
check "planet sample and hash on faces" $status
run -c 'new planet; info'
n=$(sed -n 's/^face_samples=//p' "$work/out"); e=$(sed -n 's/^face_extent_m=//p' "$work/out")
# Earth-sized at 100 m: the face's arc (pi/2 x 6371 km) in whole 256-sample tiles, in
# true metres on the sphere (the arc per sample a little under the spacing).
[ "$n" = 100096 ] && awk -v e="$e" -v n="$n" 'BEGIN { t = (n - 1) * 3.14159265358979 / 2 * 6371000 / n
                                                     exit !((e - t) ^ 2 < 1e-6) }'
check "info on a planet: face_samples=$n face_extent_m=$e" $?
run -c "new planet; sample $e $e 2; sample $(awk -v e="$e" 'BEGIN { printf "%.17g", e + 1 }') 0 2"
[ $status = 1 ] && grep -q "outside" "$work/err"; check "face_extent_m is the last position a face takes" $?
run -c 'new planet; sample 1000 2000 6'
[ $status = 1 ] && grep -q "face 6 does not exist" "$work/err"; check "bad face rejected" $?
run -c 'sample nan 3'
[ $status = 1 ]; check "NaN position rejected" $?
run -c 'new planet; generator diamond_square; generate'
[ $status = 1 ] && grep -q "flat worlds only" "$work/err"; check "diamond-square on a planet rejected" $?

run -c 'hash -1e9 -1e9 1e9 1e9'
[ $status = 1 ] && grep -q "at most 2^32" "$work/err"; check "huge hash rectangle refused" $?
run -c 'set spacing 0'
[ $status = 1 ] && grep -q "spacing" "$work/err"; check "zero spacing refused" $?
run -c 'size 999999999999999'
[ $status = 1 ] && grep -q "size" "$work/err"; check "huge size refused" $?

# 10. files that cannot be read or are not what they claim
run --batch "$work/does-not-exist.og"
[ $status = 1 ] && grep -q "does-not-exist.og" "$work/err"; check "missing batch file named" $?
head -c 5000 /dev/urandom >"$work/garbage.tiles"
printf 'tiles = garbage.tiles;\n' >"$work/g.world"
run -c "load $work/g.world"
[ $status = 1 ] && grep -q "garbage.tiles" "$work/err"; check "corrupt tile store named" $?
printf 'tiles = ../escape.tiles;\n' >"$work/e.world"
run -c "load $work/e.world"
[ $status = 1 ] && grep -q "tiles" "$work/err"; check "tiles path escaping the folder refused" $?
run -c "save $work/no/such/folder/x.world"
[ $status = 1 ] && grep -q "$work/no/such/folder" "$work/err"; check "unwritable save path named" $?

# 11. help and the command list cover the issue's commands
run -c 'cmdlist'
for c in new load save generate generator seed octaves w_factor exponent radius max_height \
    ocean_level omega spacing size set params nparams info sample hash help cmdlist exit; do
    grep -qx "$c" "$work/out" || { echo "missing command $c"; false; }
done
check "cmdlist complete" $?
run -c 'help hash'
grep -q 'hash X0 Z0 X1 Z1' "$work/out"; check "help for one command" $?
run -c 'exit; frobnicate'
check "exit stops before later commands" $status

# A bare save keeps the world's file (it once left the world with no path).
run -c "save $work/again.world; save; info"
[ $status = 0 ] && [ "$(grep -c "^saved $work/again.world$" "$work/out")" = 2 ] && grep -q "^path=$work/again.world$" "$work/out"
check "save without a file saves to the world's file again" $?

# 12. never lose work: what is not a parameter file is refused and left alone; a file
# that loaded with errors is not saved over without force=1; save names its files.
head -c 3000 /dev/urandom >"$work/junk.world"
cp "$work/junk.world" "$work/junk.orig"
run -c "load $work/junk.world; save"
[ $status = 1 ] && grep -q "^-c:1: error: $work/junk.world: not an Orogen world or planet parameter file (" "$work/err"
check "random bytes are refused as a parameter file" $?
cmp -s "$work/junk.world" "$work/junk.orig" && ! grep -q "binary data" "$work/err"
check "and left byte-identical, with one message instead of one per line" $?
run -c "save $work/junk.world"
[ $status = 1 ] && grep -q "will not replace $work/junk.world: .*force=1" "$work/err" &&
    cmp -s "$work/junk.world" "$work/junk.orig"
check "save does not write over a file that is not a parameter file" $?
run -c "save $work/junk.world force=1"
[ $status = 0 ] && grep -q "^saved $work/junk.world$" "$work/out"; check "unless force=1" $?

cp "$work/bad.world" "$work/bad.orig"
run -c "load $work/bad.world; save"
[ $status = 1 ] && grep -q "bad.world had 1 error when loaded (2: error: octaves" "$work/err" &&
    cmp -s "$work/bad.world" "$work/bad.orig"
rc=$?; check "a file that loaded with an error is not saved over ($(tail -n 1 "$work/err" | head -c 300))" $rc
run -c "load $work/bad.world; save force=1"
grep -q "^saved $work/bad.world$" "$work/out" && ! cmp -s "$work/bad.world" "$work/bad.orig" &&
    grep -q '^octaves = 8;$' "$work/bad.world"
check "save force=1 replaces it, the bad line with its default" $?
printf 'seed = 12;\ncolour = blue;\n' >"$work/warned.world"
run -c "load $work/warned.world; save"
[ $status = 0 ] && grep -q "warning: unknown key 'colour'" "$work/err"
check "warnings stay warnings: exit 0, and the file saves" $?
run -c "dab 10 10; save $work/named.world"
grep -q "^saved $work/named.world$" "$work/out" &&
    grep -q "^  and its tile store $work/named.tiles ([1-9][0-9]* tiles)$" "$work/out"
rc=$?; check "save names the parameter file and the tile store it wrote ($(head -c 300 "$work/out"))" $rc
printf 'seed = 3;\noctaves = lots;\n' >"$work/arg.world"
run "$work/arg.world" -c 'info'
[ $status = 1 ]; check "a world given on the command line with errors fails the batch too" $?

# 13. a world knows its edits: a tile store that went missing, empty or was swapped for
# another world's is said so and opens read-only; save refuses without force=1.
run -c "tool raise radius=30 strength=1; dab 100 100; save $work/kept.world; hash 0 0 400 400"
h_edit=$(tail -n 1 "$work/out")
grep -q '^tiles_saved = [1-9][0-9]*;$' "$work/kept.world" && grep -q '^tiles_id = [0-9a-f]\{32\};$' "$work/kept.world"
check "save records the world's id and its tile count in the file" $?
run -c "load $work/kept.world; hash 0 0 400 400; info"
[ $status = 0 ] && [ "$(head -n 2 "$work/out" | tail -n 1)" = "$h_edit" ] && grep -q '^read_only=$' "$work/out"
check "an intact world loads its edits, not read-only" $?
run -c "tool raise radius=30 strength=1; dab 300 300; save $work/other.world"
cp "$work/kept.world" "$work/kept.world.orig"
cp "$work/kept.tiles" "$work/kept.tiles.orig"
cp "$work/other.tiles" "$work/kept.tiles"
run -c "load $work/kept.world; save"
[ $status = 1 ] && grep -q "kept.tiles belongs to another world" "$work/err" &&
    grep -q "save: $work/kept.world was opened read-only" "$work/err" && cmp -s "$work/kept.world" "$work/kept.world.orig"
check "a swapped tile store is another world's: read-only, save refused" $?
: >"$work/kept.tiles"
run -c "load $work/kept.world; info; save"
[ $status = 1 ] && grep -q "kept.tiles is empty (0 bytes)" "$work/err" && grep -q "^read_only=its tile store" "$work/out" &&
    [ ! -s "$work/kept.tiles" ] && cmp -s "$work/kept.world" "$work/kept.world.orig"
check "an emptied tile store is noticed, left empty, and not saved over" $?
rm "$work/kept.tiles"
run -c "load $work/kept.world; save"
[ $status = 1 ] && grep -q "kept.tiles is missing (it held [1-9][0-9]* tiles when saved)" "$work/err" && [ ! -e "$work/kept.tiles" ]
check "a missing tile store is noticed and not recreated empty" $?
run -c "load $work/kept.world; save $work/elsewhere.world"
[ -s "$work/elsewhere.world" ]; check "a read-only world saves to another file" $?
run -c "load $work/kept.world; save force=1; info"
grep -q "^saved $work/kept.world$" "$work/out" && grep -q '^read_only=$' "$work/out" && [ -s "$work/kept.tiles" ]
check "save force=1 writes over it and the world is writable again" $?
cp "$work/kept.tiles.orig" "$work/kept.tiles"
cp "$work/kept.world.orig" "$work/kept.world"
run -c "load $work/kept.world; hash 0 0 400 400"
[ $status = 0 ] && [ "$(tail -n 1 "$work/out")" = "$h_edit" ]; check "the restored store is this world's again" $?

echo "$passes passed, $failures failed"
[ $failures = 0 ]
