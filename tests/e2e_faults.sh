#!/usr/bin/env bash
# The fault harness (issue 27): nothing a user made is lost, whatever happens.
#  - kill -9 at random moments of random edit sequences (2D tools, volume fill and
#    carve, arches, stamps, imports, generate, undo, redo), then `recover`: the terrain
#    (`hash`) and the volume (`vsample`) must be exactly those after the last step the
#    journal holds, and it must hold every step whose result was printed before the
#    kill; the journal must still be there after a session that recovered and left;
#  - mutated parameter files and tile stores: each opened (and saved over, for the
#    parameter files): a damaged one must never load silently (adopted), and no store
#    may change unless a save succeeded (destroyed);
#  - special files: FIFOs, devices, sockets and a symlinked lock, read and written;
#  - a full disk: a small tmpfs when this runs as root and may mount one, else a file
#    size limit (RLIMIT_FSIZE, `ulimit -f`) on the processes that write (said below).
# It prints trials / recovered / adopted / destroyed and fails on any loss.
# Usage: e2e_faults.sh OROGEN TESTS_DIR
# Longer runs by hand: FAULT_SEQUENCES (10; 3 kills each), FAULT_PARAMS (200),
# FAULT_STORES (100), FAULT_SEED; FAULT_NO_MOUNT=1 uses the file size limit even as root.
set -u
orogen=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/orogen-faults-XXXXXX")
RANDOM=${FAULT_SEED:-27}
sequences=${FAULT_SEQUENCES:-10}
param_cases=${FAULT_PARAMS:-200}
store_cases=${FAULT_STORES:-100}
# Under the sanitizers (scripts/test.sh --sanitize sets ASAN_OPTIONS) every process is
# a few times slower: the same 30 kill trials, half the mutations (the plain run does all).
if [ -n "${ASAN_OPTIONS:-}" ]; then
    param_cases=${FAULT_PARAMS:-100}
    store_cases=${FAULT_STORES:-50}
fi
export OROGEN_RECOVER_DIR="$work/recover-dir"
# stdbuf preloads a library: under AddressSanitizer its runtime then is not first.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
mounted=
app=
cleanup() {
    [ -n "$app" ] && kill -9 "$app" 2>/dev/null
    [ -n "$mounted" ] && umount "$mounted" 2>/dev/null
    rm -rf "$work"
}
trap cleanup EXIT
py=$(command -v python3)

# Line-buffered output, so a line printed before a kill is in the file; only the probe's
# lines (a hash, a vsample) are kept.
run() { stdbuf -oL "$orogen" "$@"; }
probe_lines() { grep -E '^[0-9a-f]{16}$|^-?[0-9.]+ (inside|outside)$' "$@"; }
sum() { md5sum <"$1" 2>/dev/null | cut -c1-32; }

probe='hash -200 -200 900 900; vsample 60 5 60; vsample 220 8 220; vsample 400 3 400'
"$orogen" -c "tool raise radius=40 strength=1; dab 450 450; save $work/base.world" >/dev/null 2>&1 ||
    { echo "FAIL: cannot make the base world"; exit 1; }
# Mutation cases look at the edited tile only (a smaller area: faster).
small_probe='hash 384 384 512 512; vsample 450 5 450'
base_small=$("$orogen" "$work/base.world" -c "$small_probe" 2>/dev/null)
"$py" -c "
import random, struct
r = random.Random(5)
open('$work/patch.r16', 'wb').write(b''.join(struct.pack('<H', r.randrange(65536)) for _ in range(64 * 64)))"

# ---- kill -9 during random edit sequences ------------------------------------------

# One random step that makes exactly one journal record; undo and redo only where the
# history allows (depth: undoable steps, redoable: undone ones).
depth=0
redoable=0
random_step() {
    local x=$((RANDOM % 700)) z=$((RANDOM % 700)) pick=$((RANDOM % 13))
    if [ $pick -ge 11 ] && [ $depth -gt 0 ]; then
        echo "undo"
        depth=$((depth - 1)) redoable=$((redoable + 1))
        return
    fi
    if [ $pick -eq 10 ] && [ $redoable -gt 0 ]; then
        echo "redo"
        depth=$((depth + 1)) redoable=$((redoable - 1))
        return
    fi
    depth=$((depth + 1)) redoable=0
    case $((pick % 10)) in
    0) echo "tool raise radius=$((20 + RANDOM % 60)) strength=1; dab $x $z" ;;
    1) echo "tool lower radius=40 strength=0.7; stroke $x $z $(((x + 200) % 700)) $z" ;;
    2) echo "stamp crater $x $z scale=0.5" ;;
    3) echo "tool fill radius=$((4 + RANDOM % 6)) falloff=constant; dab 60 5 60" ;;
    4) echo "tool carve radius=$((3 + RANDOM % 5)); dab 220 8 220" ;;
    5) echo "arch 390 0 390 410 0 410 rise=$((5 + RANDOM % 10))" ;;
    6) echo "import $work/patch.r16 min=0 max=$((10 + RANDOM % 40)) x=$x z=$z" ;;
    7) echo "seed $((RANDOM % 1000)); generate" ;;
    8) echo "tool smooth radius=60; stroke $x 0 $x 700" ;;
    9) echo "tool hydraulic radius=200 droplets=40000; dab $x $z" ;; # a long step
    esac
}

trials=0 recovered=0 lost=0 finished=0
for ((s = 0; s < sequences; s++)); do
    depth=0 redoable=0
    script="$probe; history"
    n=$((4 + RANDOM % 5))
    for ((i = 0; i < n; i++)); do script+="; $(random_step); $probe; history"; done
    # The reference: the whole sequence, uninterrupted; 4 probe lines per state, and
    # the history's counts after each step: a step that changed nothing (a carve
    # inside an earlier one) makes no undo step and no journal record.
    rm -rf "$work/ref" && mkdir "$work/ref" && cp "$work"/base.world "$work"/base.tiles "$work/ref/"
    start=$(date +%s%N)
    run "$work/ref/base.world" -c "$script" >"$work/ref.out" 2>"$work/ref.err" ||
        { fail "sequence $s does not run: $(tail -n 1 "$work/ref.err")"; continue; }
    span_ms=$((($(date +%s%N) - start) / 1000000))
    mapfile -t ref < <(probe_lines "$work/ref.out")
    # records[k]: journal records after step k.
    records_after=(0)
    prev=
    while read -r counts; do
        counts=${counts#steps=* }
        counts=${counts%% bytes=*}
        if [ -n "$prev" ] && [ "$counts" != "$prev" ]; then
            records_after+=($((records_after[-1] + 1)))
        elif [ -n "$prev" ]; then
            records_after+=("${records_after[-1]}")
        fi
        prev=$counts
    done < <(grep '^steps=' "$work/ref.out")
    for kill_at in 1 2 3; do
        trials=$((trials + 1))
        rm -rf "$work/t" && mkdir "$work/t" && cp "$work"/base.world "$work"/base.tiles "$work/t/"
        stdbuf -oL "$orogen" "$work/t/base.world" -c "$script" >"$work/t.out" 2>"$work/t.err" &
        app=$!
        sleep "$(awk -v r=$RANDOM -v s=$span_ms 'BEGIN { printf "%.3f", r / 32768 * s / 1000 * 1.1 }')"
        kill -9 $app 2>/dev/null
        wait $app 2>/dev/null
        ended=$? # 0: the script ran to its end before the kill
        app=
        shown=$(($(probe_lines "$work/t.out" | wc -l) / 4 - 1)) # steps whose result was printed
        [ $shown -lt 0 ] && shown=0
        out=$("$orogen" "$work/t/base.world" -c "recover" 2>&1)
        records=$(sed -n 's/^recovered \([0-9]*\) journal record.*/\1/p' <<<"$out")
        [ -z "$records" ] && records=0
        got=$("$orogen" "$work/t/base.world" -c "recover; $probe" 2>/dev/null | probe_lines)
        [ $records = 0 ] && got=$("$orogen" "$work/t/base.world" -c "$probe" 2>/dev/null | probe_lines)
        # The state after the last step whose records the journal holds.
        state=0
        for ((k = 0; k < ${#records_after[@]}; k++)); do
            [ "${records_after[k]}" = "$records" ] && state=$k
        done
        want=$(printf '%s\n' "${ref[@]:$((state * 4)):4}")
        must=${records_after[shown]:-0} # every step printed before the kill
        all_shown=0
        [ $shown -ge $((${#records_after[@]} - 1)) ] && all_shown=1
        if [ $ended = 0 ] || { [ $all_shown = 1 ] && [ ! -e "$work/t/base.world.recover" ]; }; then
            # A script that succeeded is the record of its edits: it removed its journal
            # (a kill during its exit, after the last step, may come after that), and the
            # world is as saved.
            finished=$((finished + 1))
            want=$(printf '%s\n' "${ref[@]:0:4}")
            if [ $records = 0 ] && [ "$got" = "$want" ] && [ ! -e "$work/t/base.world.recover" ]; then
                recovered=$((recovered + 1))
            else
                lost=$((lost + 1))
                fail "kill trial $trials (sequence $s: $script): ended before the kill, but left $records journal records or changed the world: got '$got', want '$want'"
            fi
        elif [ "$records" -ge "$must" ] && [ "${records_after[state]}" = "$records" ] &&
            [ "$got" = "$want" ] &&
            { [ $records = 0 ] || [ -s "$work/t/base.world.recover" ]; }; then
            recovered=$((recovered + 1))
        else
            lost=$((lost + 1))
            fail "kill trial $trials (sequence $s: $script; $shown steps shown, $records recovered): got '$got', want '$want' ($out)"
        fi
    done
done
echo "kill -9 trials: $trials, recovered exactly: $recovered (of which $finished ended before the kill), lost: $lost"

# ---- mutated parameter files --------------------------------------------------------

adopted=0 destroyed=0 refused=0 read_only=0 warned=0
base_text="$work/base.world"
base_len=$(stat -c %s "$base_text")
lines=$(wc -l <"$base_text")
mutate_params() { # $1: case number, $2: output file
    local kind=$(($1 % 8)) at=$((RANDOM * 32768 + RANDOM))
    case $kind in
    0) head -c $((at % base_len)) "$base_text" >"$2" ;;                 # cut short
    1) : >"$2" ;;                                                       # empty
    2) sed "$((at % lines + 1))d" "$base_text" >"$2" ;;                 # a line lost
    3) "$py" -c "import sys; d = bytearray(open('$base_text', 'rb').read()); d[$at % len(d)] ^= 1 << ($RANDOM % 8); sys.stdout.buffer.write(d)" >"$2" ;;
    4) head -n -1 "$base_text" >"$2" ;;                                 # the seal lost
    5) { cat "$base_text"; echo "garbage $RANDOM"; } >"$2" ;;             # junk after it
    6) head -c $((at % base_len)) "$base_text" >"$2"                    # a cut, then
       head -c 512 /dev/urandom >>"$2" ;;                               # a torn block
    7) sed "s/^seed = .*/seed = $RANDOM;/" "$base_text" >"$2" ;;        # a hand edit
    esac
}
for ((c = 0; c < param_cases; c++)); do
    d="$work/p"
    rm -rf "$d" && mkdir "$d" && cp "$work/base.tiles" "$d/m.tiles"
    mutate_params $c "$d/m.world"
    cmp -s "$d/m.world" "$base_text" && continue # no change (a cut at the very end)
    before=$(sum "$d/m.world") store_before=$(sum "$d/m.tiles")
    "$orogen" "$d/m.world" -c "$small_probe; save" >"$d/out" 2>"$d/err"
    status=$?
    after=$(sum "$d/m.world") store_after=$(sum "$d/m.tiles")
    if [ $status = 0 ] && ! grep -q "m.world" "$d/err"; then
        adopted=$((adopted + 1))
        fail "parameter case $c (kind $((c % 8))) loaded and was saved over without a word"
    elif [ $status != 0 ] && { [ "$before" != "$after" ] || [ "$store_before" != "$store_after" ]; }; then
        destroyed=$((destroyed + 1))
        fail "parameter case $c (kind $((c % 8))): a run that failed changed the files: $(head -c 300 "$d/err")"
    elif grep -q "not an Orogen world" "$d/err"; then
        refused=$((refused + 1))
    elif grep -q "opened read-only" "$d/err"; then
        read_only=$((read_only + 1))
    else
        warned=$((warned + 1))
    fi
done
echo "mutated parameter files: $param_cases (refused $refused, opened read-only $read_only, loaded with a warning $warned), adopted: $adopted, destroyed: $destroyed"

# ---- mutated tile stores --------------------------------------------------------------

"$orogen" -c "tool raise radius=30 strength=1; dab 50 50; save $work/other.world" >/dev/null 2>&1
# Another store's WAL: a writer (as Orogen writes, its meta page included) killed
# before the checkpoint.
foreign_wal() {
    cp "$work/other.tiles" "$work/o.tiles"
    "$py" -c "
import sqlite3, os
c = sqlite3.connect('$work/o.tiles', isolation_level=None); c.execute('PRAGMA wal_autocheckpoint=0')
c.execute('BEGIN'); c.execute(\"UPDATE meta SET value=value WHERE key='store_id'\"); c.execute('DELETE FROM tiles'); c.execute('COMMIT')
os._exit(0)"
    cp "$work/o.tiles-wal" "$1-wal"
    rm -f "$work"/o.tiles*
}
sql() { "$py" -c "import sqlite3, sys; c = sqlite3.connect(sys.argv[1]); c.executescript(sys.argv[2]); c.commit()" "$@"; }
store_adopted=0 store_destroyed=0 store_reported=0 store_same=0
store_len=$(stat -c %s "$work/base.tiles")
for ((c = 0; c < store_cases; c++)); do
    d="$work/s"
    rm -rf "$d" && mkdir "$d" && cp "$work/base.world" "$d/m.world" && cp "$work/base.tiles" "$d/m.tiles"
    at=$(((RANDOM * 32768 + RANDOM) % store_len))
    case $((c % 6)) in
    0 | 1) "$py" -c "
f = open('$d/m.tiles', 'r+b'); f.seek($at); b = f.read(16); f.seek($at)
f.write(bytes(x ^ (1 << ($RANDOM % 8)) for x in b))" ;;
    2) sql "$d/m.tiles" "UPDATE meta SET value='$((2 + RANDOM % 98))' WHERE key='$([ $((RANDOM % 2)) = 0 ] && echo schema || echo blob)_version'" ;;
    3) sql "$d/m.tiles" "INSERT OR REPLACE INTO tiles SELECT layer, face, level, tx + $((RANDOM % 3 - 1)), ty + 1, data FROM tiles WHERE rowid = (SELECT min(rowid) FROM tiles)" ;; # a blob copied under another key
    4) foreign_wal "$d/m.tiles" ;;
    5) truncate -s $((at / 4096 * 4096)) "$d/m.tiles" ;;
    esac
    before=$(sum "$d/m.tiles")
    "$orogen" "$d/m.world" -c "$small_probe" >"$d/out" 2>"$d/err"
    got=$(cat "$d/out")
    if [ "$before" != "$(sum "$d/m.tiles")" ]; then
        store_destroyed=$((store_destroyed + 1))
        fail "store case $c (kind $((c % 6))): opening changed the store: $(head -c 300 "$d/err")"
    elif [ -s "$d/err" ]; then
        store_reported=$((store_reported + 1))
    elif [ "$got" = "$base_small" ]; then
        store_same=$((store_same + 1)) # the damage hit bytes no tile uses
    else
        store_adopted=$((store_adopted + 1))
        fail "store case $c (kind $((c % 6))): a damaged store gave other terrain without a word"
    fi
done
echo "mutated tile stores: $store_cases (reported $store_reported, unaffected $store_same), adopted: $store_adopted, destroyed: $store_destroyed"
adopted=$((adopted + store_adopted))
destroyed=$((destroyed + store_destroyed))

# ---- special files ----------------------------------------------------------------------

special=0 special_ok=0
d="$work/sp"
mkdir -p "$d"
mkfifo "$d/fifo" "$d/fifo.png" "$d/fifo.world"
"$py" -c "import socket; socket.socket(socket.AF_UNIX).bind('$d/sock.png')"
[ "$(id -u)" = 0 ] && mknod "$d/dev.png" c 1 3 && mknod "$d/dev.world" c 1 3
expect_refused() { # $1: what, then the orogen arguments; it must end quickly with a message
    special=$((special + 1))
    local what=$1
    shift
    timeout 20 "$orogen" "$@" >/dev/null 2>"$d/err"
    local status=$?
    if [ $status = 124 ]; then
        fail "special: $what blocked"
    elif [ $status = 0 ] || ! grep -q "$d/" "$d/err"; then
        fail "special: $what was not refused with a message naming it ($(head -c 200 "$d/err"))"
    else
        special_ok=$((special_ok + 1))
    fi
}
for f in fifo /dev/full; do
    p=$f
    [ "$f" = fifo ] && p="$d/fifo"
    [ "$f" = /dev/full ] && { ln -sf /dev/full "$d/full.r16"; p="$d/full.r16"; }
    expect_refused "import $f" -c "import $p"
    expect_refused "new flat from=$f" -c "new flat from=$p"
    expect_refused "recover $f" -c "recover $p"
    expect_refused "load $f" -c "load $p"
done
expect_refused "--batch fifo" --batch "$d/fifo"
for t in fifo.png sock.png dev.png; do
    [ -e "$d/$t" ] || continue
    kind=$(stat -c %F "$d/$t")
    expect_refused "export to $t" -c "new flat; generate; export $d/$t region=0,0,64,64"
    expect_refused "screenshot to $t" -c "new flat; screenshot $d/$t"
    expect_refused "--record to $t" --record "$d/$t" -c "new flat"
    [ "$(stat -c %F "$d/$t")" = "$kind" ] || fail "special: $t was replaced"
done
for t in fifo.world dev.world; do
    [ -e "$d/$t" ] || continue
    expect_refused "save to $t, forced" -c "save $d/$t force=1"
done
[ -c "$d/dev.world" ] || [ "$(id -u)" != 0 ] || fail "special: a device was replaced"
# A symlinked lock: never written through; the world opens read-only.
special=$((special + 1))
cp "$work/base.world" "$d/l.world" && cp "$work/base.tiles" "$d/l.tiles"
echo "precious" >"$d/target"
ln -s "$d/target" "$d/l.tiles.lock"
"$orogen" "$d/l.world" -c "dab 10 10; save" >/dev/null 2>"$d/err"
if [ "$(cat "$d/target")" = precious ] && grep -q "symbolic link" "$d/err"; then
    special_ok=$((special_ok + 1))
else
    fail "special: a symlinked lock was written through ($(head -c 200 "$d/err"))"
fi
# A lock file naming a live process that does not hold it (this shell): taken over,
# and said to be another process's pid, not "no longer running".
special=$((special + 1))
rm -f "$d/l.tiles.lock"
echo $$ >"$d/l.tiles.lock"
"$orogen" "$d/l.world" -c "info" >/dev/null 2>"$d/err"
if grep -q "naming process $$, which does not hold it" "$d/err"; then
    special_ok=$((special_ok + 1))
else
    fail "special: a lock naming a live process that does not hold it ($(head -c 200 "$d/err"))"
fi
echo "special files: $special cases, refused as they should be: $special_ok"

# ---- a full disk ------------------------------------------------------------------------

full="$work/full"
mkdir -p "$full"
how="RLIMIT_FSIZE (ulimit -f)"
limit=
if [ "$(id -u)" = 0 ] && [ -z "${FAULT_NO_MOUNT:-}" ] && mount -t tmpfs -o size=6m tmpfs "$full" 2>/dev/null; then
    mounted=$full
    how="a 6 MiB tmpfs"
fi
disk_cases=0 disk_ok=0
full_run() { # runs orogen with the disk full (tmpfs filled, or a file size limit)
    if [ -n "$mounted" ]; then
        "$orogen" "$@"
    else
        (trap '' XFSZ; ulimit -f 1; "$orogen" "$@")
    fi
}
cp "$work/base.world" "$work/base.tiles" "$full/"
[ -n "$mounted" ] && { dd if=/dev/zero of="$full/filler" bs=4k >/dev/null 2>&1; true; }
store_before=$(sum "$full/base.tiles") world_before=$(sum "$full/base.world")
# 1. Edits and a save on the full disk: the save fails, nothing of the old files changes.
disk_cases=$((disk_cases + 1))
full_run "$full/base.world" -c "tool raise radius=200 strength=1; dab 300 300; dab 900 900; save" >/dev/null 2>"$work/full.err"
status=$?
if [ $status != 0 ] && [ "$(sum "$full/base.tiles")" = "$store_before" ] &&
    [ "$(sum "$full/base.world")" = "$world_before" ]; then
    disk_ok=$((disk_ok + 1))
else
    fail "full disk: a failed save changed the files or did not fail ($(tail -n 2 "$work/full.err"))"
fi
# 2. The world opens (read-only on a full tmpfs, naming it) and saves elsewhere.
disk_cases=$((disk_cases + 1))
edited=$("$orogen" -c "load $full/base.world; tool raise radius=30 strength=1; dab 100 100; $probe; save $work/elsewhere.world" 2>"$work/full.err" | grep -v '^loaded\|^saved\|^  and')
again=$("$orogen" "$work/elsewhere.world" -c "$probe" 2>/dev/null)
if [ -n "$edited" ] && [ "$edited" = "$again" ] &&
    { [ -z "$mounted" ] || grep -q "disk is full" "$work/full.err"; }; then
    disk_ok=$((disk_ok + 1))
else
    fail "full disk: the world did not open and save elsewhere ($(tail -n 2 "$work/full.err"))"
fi
# 3. A save that fails for want of space keeps the journal of its edits: the next
#    session recovers them (tmpfs only: room for the journal, not for the save).
if [ -n "$mounted" ]; then
    disk_cases=$((disk_cases + 1))
    rm -f "$full"/*
    cp "$work/base.world" "$work/base.tiles" "$full/"
    avail=$(df --output=avail -B1 "$full" | tail -n 1)
    fallocate -l $((avail - 400 * 1024)) "$full/filler" 2>/dev/null ||
        head -c $((avail - 400 * 1024)) /dev/zero >"$full/filler"
    edits="tool raise radius=200 strength=1; dab 300 300; dab 1500 1500; dab -900 700"
    live=$("$orogen" "$full/base.world" -c "$edits; $probe; save" 2>"$work/full.err" | probe_lines)
    status=$?
    back=$("$orogen" "$full/base.world" -c "recover; $probe" 2>/dev/null | probe_lines)
    if grep -q "save" "$work/full.err" && [ -n "$live" ] && [ "$back" = "$live" ]; then
        disk_ok=$((disk_ok + 1))
    else
        fail "full disk: a failed save lost the journal of its edits (recovered '$back', live '$live'; $(tail -n 2 "$work/full.err"))"
    fi
fi
# 4. A read-only file system (the tmpfs remounted read-only): the world opens
#    read-only naming that cause (not "No such file or directory"), saves elsewhere.
if [ -n "$mounted" ]; then
    rm -f "$full"/*
    cp "$work/base.world" "$work/base.tiles" "$full/"
    if mount -o remount,ro "$full" 2>/dev/null; then
        disk_cases=$((disk_cases + 1))
        edited=$("$orogen" "$full/base.world" -c "tool raise radius=30 strength=1; dab 100 100; $probe; save $work/ro-copy.world" 2>"$work/full.err" | probe_lines)
        again=$("$orogen" "$work/ro-copy.world" -c "$probe" 2>/dev/null)
        if grep -q "read-only file system" "$work/full.err" && [ -n "$edited" ] && [ "$edited" = "$again" ]; then
            disk_ok=$((disk_ok + 1))
        else
            fail "read-only file system: not opened read-only with the cause, or no save elsewhere ($(tail -n 2 "$work/full.err"))"
        fi
        mount -o remount,rw "$full"
    fi
fi
echo "full disk and read-only file system ($how): $disk_cases cases, behaved: $disk_ok"

echo "faults: trials $trials, recovered $recovered, lost $lost, adopted $adopted, destroyed $destroyed"
[ $failures = 0 ] && [ $recovered = $trials ]
