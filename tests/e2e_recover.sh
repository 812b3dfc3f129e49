#!/usr/bin/env bash
# End-to-end: crash recovery of the real editor. The editor runs under a private Xvfb
# with its console on standard input; a session of strokes, dabs and stamps is cut
# by kill -9 at several moments (after a step, in the middle of a long one, at the
# end); each time `recover` gives a prefix of the committed steps (never part of one)
# and, for a kill after the last step, exactly the terrain before the kill.
# Usage: e2e_recover.sh OROGEN TESTS_DIR
set -u
orogen=$1
. "$2/support/window_session.sh"
begin_window_test recover
require_tools Xvfb xdotool import
start_xvfb 1024x768
app=
cleanup() {
    exec 3>&- 2>/dev/null
    [ -n "$app" ] && kill -9 "$app" 2>/dev/null
    kill $xvfb 2>/dev/null
    wait 2>/dev/null
    rm -rf "$work"
}
trap cleanup EXIT
trap '' PIPE

area='hash -200 -200 900 900'
# The saved world every session starts from.
"$orogen" -c "tool raise radius=40 strength=1; dab 450 450; save $work/base.world" >/dev/null 2>&1
saved=$("$orogen" "$work/base.world" -c "$area" 2>/dev/null)

# The session's steps: each is one undo step (the last is long: some 5 s of erosion,
# longer under the sanitizers); layer commands among them (the stack is journaled too).
droplets=300000
steps=(
    "tool raise radius=30 strength=1; dab 100 100"
    "stroke 0 0 300 300 600 0"
    "layer new Roads opacity=0.8"
    "stamp crater 500 500 scale=0.5"
    "tool lower radius=50 strength=0.7; dab 200 400"
    "layer set Sculpt opacity=0.5"
    "undo"
    "tool smooth radius=60; stroke 100 600 700 100"
    "tool hydraulic radius=300 droplets=$droplets; stroke 0 0 300 300"
)

# Starts the editor on a fresh copy of the saved world, console on a fifo.
start() {
    rm -f "$work"/w.*
    cp "$work/base.world" "$work/w.world"
    cp "$work/base.tiles" "$work/w.tiles"
    launch
}
# Starts the editor on the world as it is (with "-", on a new unsaved world).
launch() {
    rm -f "$work/stdin"
    mkfifo "$work/stdin"
    : >"$work/out"
    local world=("$work/w.world")
    [ "${1:-}" = - ] && world=()
    "$orogen" "${world[@]}" <"$work/stdin" >"$work/out" 2>"$work/err" &
    app=$!
    exec 3>"$work/stdin"
}
# Runs a console command and waits (up to 3 min) for a new output line matching pattern.
ask() {
    local before
    before=$(wc -l <"$work/out")
    echo "$1" >&3
    for _ in $(seq 1800); do
        line=$(tail -n +$((before + 1)) "$work/out" | grep -m 1 -- "$2") && { echo "$line"; return 0; }
        kill -0 "$app" 2>/dev/null || return 1
        sleep 0.1
    done
    return 1
}
# Runs step i and prints the hash after it.
step() {
    echo "${steps[$1]}" >&3
    ask "$area" '^[0-9a-f]\{16\}$'
}
kill9() {
    kill -9 "$app"
    wait "$app" 2>/dev/null
    exec 3>&-
    app=
}
# What recover gives on the killed session's world (killed before its first step:
# nothing to recover, the saved terrain).
recovered() {
    local out
    out=$("$orogen" "$work/w.world" -c "recover; $area" 2>"$work/recover.err" | tail -n 1)
    if [ -z "$out" ] && grep -q "no unsaved edits to recover" "$work/recover.err"; then
        out=$("$orogen" "$work/w.world" -c "$area" 2>/dev/null)
    fi
    echo "$out"
}

# The hash after each step, from a session that is not killed.
start
hashes=("$saved")
for i in "${!steps[@]}"; do
    h=$(step "$i")
    hashes+=("$h")
done
kill9
n=${#steps[@]}
[ "${#hashes[@]}" = $((n + 1)) ] && [ -n "${hashes[$n]}" ]
check "a session of $n steps gives a hash after each (${hashes[*]})" $?
last=${hashes[$n]}
line=$(recovered)
[ "$line" = "$last" ]; check "kill -9 after the last step: recover gives the exact terrain ($line, wanted $last)" $?
grep -q "unsaved edits from .* ($((n + 0)) steps) can be recovered: 'recover' restores them" "$work/recover.err"
rc=$?; check "loading says what can be recovered ($(head -c 300 "$work/recover.err"))" $rc

# A prefix: the hash is one of those after 0..k steps.
in_prefix() { # hash k
    local j
    for ((j = 0; j <= $2; j++)); do [ "$1" = "${hashes[$j]}" ] && return 0; done
    return 1
}

# Killed right after step 3 (before any fsync could run: the journal's write is enough).
start
for i in 0 1 2; do step "$i" >/dev/null; done
kill9
line=$(recovered)
[ "$line" = "${hashes[3]}" ]; check "kill -9 right after step 3: exactly the first 3 steps ($line)" $?

# Killed in the middle of the long erosion step: the steps before it, none of it.
start
for i in $(seq 0 $((n - 2))); do step "$i" >/dev/null; done
echo "${steps[$((n - 1))]}" >&3
sleep 2
kill9
line=$(recovered)
[ "$line" = "${hashes[$((n - 1))]}" ]
check "kill -9 in the middle of a long step: the steps before it, not part of it ($line)" $?

# Killed at random moments of a fast session: always a prefix.
for delay in 0.3 0.9 1.6; do
    start
    for i in 0 1 2 3 4 5; do echo "${steps[$i]}" >&3; done
    sleep "$delay"
    kill9
    line=$(recovered)
    in_prefix "$line" 6; check "kill -9 after ${delay} s: a prefix of the committed steps ($line)" $?
done

# The recovered world is unsaved and its steps undo; save keeps them and ends the journal.
start
for i in 0 1; do step "$i" >/dev/null; done
kill9
out=$("$orogen" "$work/w.world" -c "recover; info; undo; $area; save; info" 2>/dev/null)
echo "$out" | grep -q '^unsaved_changes=1$' && echo "$out" | grep -q "^${hashes[1]}$" &&
    [ ! -e "$work/w.world.recover" ]
check "recovered steps are unsaved and undoable; save removes the journal" $?

# The window offers the recovery when the world opens (like Blender's Recover Last
# Session): Recover restores the steps.
start
for i in 0 1 2; do step "$i" >/dev/null; done
kill9
launch
# The rectangle "X Y W H" of the widget called NAME in the last frame (up to 10 s).
widget() {
    local l
    for _ in $(seq 40); do
        ask "ui_widgets \"$1\"" '^Viewport ' >/dev/null
        sleep 0.1
        l=$(grep -F -- "$1 " "$work/out" | tail -n 1 | grep -oE '(-?[0-9]+ ){3}-?[0-9]+$') && { echo "$l"; return 0; }
        sleep 0.2
    done
    return 1
}
# Asks for the hash until it is WANT (a click acts a frame later; up to ~10 s); prints
# the last one.
hash_until() {
    local line
    for _ in $(seq 50); do
        line=$(ask "$area" '^[0-9a-f]\{16\}$')
        [ "$line" = "$1" ] && break
        sleep 0.2
    done
    echo "$line"
}
# Clicks the button NAME (the dialog's Recover of one journal) until the hash is WANT:
# the pointer is moved there a moment before the click (a move and a press in one frame
# of a busy machine can miss the button), and a click the dialog did not take is tried
# again; prints the hash.
recover_click() {
    local line=
    for _ in 1 2 3; do
        read -r x y w h <<<"$(widget "$1")"
        [ -n "${h:-}" ] || break
        xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2))
        sleep 0.3
        xdotool click 1
        line=$(hash_until "$2")
        [ "$line" = "$2" ] && break
    done
    echo "$line"
}
wid=$(timeout 30 xdotool search --sync --name '^Orogen' | head -n 1)
own="Recover unsaved edits/w.world.recover"
read -r x y w h <<<"$(widget "$own/Recover")"
[ -n "${h:-}" ] && widget "$own/w.world was not saved when Orogen last stopped." >/dev/null
check "the window offers to recover the killed session's edits" $?
[ -n "$wid" ] && timeout 20 import -window "$wid" "$art/recover_dialog.png" 2>/dev/null
line=$(recover_click "$own/Recover" "${hashes[3]}")
[ "$line" = "${hashes[3]}" ]; check "Recover restores them ($line, wanted ${hashes[3]})" $?
kill9

# A session that edited without recovering set the killed session's journal aside, and
# was killed too: the window offers both journals, and Recover on the one set aside
# gives its terrain (issue 27: a journal set aside is never out of reach).
start
for i in 0 1 2; do step "$i" >/dev/null; done
kill9
launch
step 3 >/dev/null # the first edit sets the earlier journal aside
kill9
[ -e "$work/w.world.recover.old" ] && [ -e "$work/w.world.recover" ]
check "a second killed session leaves its own journal and the one it set aside" $?
launch
wid=$(timeout 30 xdotool search --sync --name '^Orogen' | head -n 1)
aside="Recover unsaved edits/w.world.recover.old"
widget "$own/Recover" >/dev/null && widget "$aside/Edits an earlier session set aside (w.world.recover.old)." >/dev/null
check "the window offers both: the last session's journal and the one set aside" $?
[ -n "$wid" ] && timeout 20 import -window "$wid" "$art/recover_dialog_two.png" 2>/dev/null
line=$(recover_click "$aside/Recover" "${hashes[3]}")
[ "$line" = "${hashes[3]}" ]; check "Recover on the set-aside journal restores its steps ($line, wanted ${hashes[3]})" $?
# Not now puts the other offer off; File > Recover unsaved edits... still lists every
# journal, and its Discard (naming the steps it drops) removes only that one.
ask "recover list" 'w.world.recover:' >/dev/null
grep -q "w.world.recover: 1 step" "$work/out"
check "recover list shows the last session's journal after the other was recovered" $?
kill9
launch
wid=$(timeout 30 xdotool search --sync --name '^Orogen' | head -n 1)
read -r x y w h <<<"$(widget "Recover unsaved edits/Not now")"
xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)); sleep 0.3; xdotool click 1
shown=1
for _ in $(seq 30); do
    before=$(wc -l <"$work/out")
    ask "ui_widgets \"Recover unsaved edits/Not now\"" '^Viewport ' >/dev/null
    tail -n +$((before + 1)) "$work/out" | grep -qF "Recover unsaved edits/Not now " || { shown=0; break; }
    sleep 0.2
done
[ $shown = 0 ]
check "Not now closes the offer" $?
read -r x y w h <<<"$(widget "Menu/File")"
xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)); sleep 0.3; xdotool click 1
read -r x y w h <<<"$(widget "Menu/File/Recover unsaved edits...")"
xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)); sleep 0.3; xdotool click 1
read -r x y w h <<<"$(widget "$own/Discard 1 step")"
[ -n "${h:-}" ]; check "File > Recover unsaved edits... lists the journal put off, with its Discard" $?
[ -n "$wid" ] && timeout 20 import -window "$wid" "$art/recover_dialog_all.png" 2>/dev/null
xdotool mousemove --window "$wid" $((x + w / 2)) $((y + h / 2)); sleep 0.3; xdotool click 1
for _ in $(seq 30); do [ -e "$work/w.world.recover" ] || break; sleep 0.2; done
[ ! -e "$work/w.world.recover" ]; check "its Discard removes that journal" $?
kill9

# A world that was never saved: its journal lives in the recovery folder, and the next
# editor to start offers it.
launch -
step 0 >/dev/null
h_unsaved=$(step 1)
kill9
ls "$XDG_STATE_HOME"/orogen/recover/unsaved-*.recover >/dev/null 2>&1
check "a never-saved world's steps are journaled in the recovery folder" $?
unsaved=$(basename "$(ls -t "$XDG_STATE_HOME"/orogen/recover/unsaved-*.recover | head -n 1)")
launch -
widget "Recover unsaved edits/$unsaved/A world that was never saved was open when Orogen stopped." >/dev/null
check "the next editor offers a never-saved world's edits" $?
wid=$(timeout 30 xdotool search --sync --name '^Orogen' | head -n 1)
line=$(recover_click "Recover unsaved edits/$unsaved/Recover" "$h_unsaved")
[ "$line" = "$h_unsaved" ]; check "Recover restores the never-saved world's terrain ($line, wanted $h_unsaved)" $?
kill9

# A script that edits a never-saved world and ends normally leaves no journal behind
# (the script is the record of its edits; they piled up unseen in the recovery folder);
# one killed leaves its journal, and standard input, maybe a person typing, keeps one.
rdir="$XDG_STATE_HOME/orogen/recover"
count() { find "$rdir" -name 'unsaved-*.recover' 2>/dev/null | wc -l; }
n0=$(count)
"$orogen" -c "tool raise radius=30 strength=1; dab 10 10; new flat; dab 20 20" >/dev/null 2>&1
n1=$(count)
echo "tool raise radius=30 strength=1; dab 10 10" | "$orogen" --batch - >/dev/null 2>&1
n2=$(count)
[ "$n1" = "$n0" ] && [ "$n2" = $((n0 + 1)) ]
check "a script leaves no never-saved journal, standard input keeps one ($n0 -> $n1 -> $n2)" $?

# A script that fails after its edits (here its save cannot be written, as on a full
# disk) keeps the journal: nothing else holds those edits.
"$orogen" -c "tool raise radius=30 strength=1; dab 10 10; save /proc/no/w.world" >/dev/null 2>&1
n3=$(count)
[ "$n3" = $((n2 + 1)) ]
check "a script whose save fails keeps its never-saved journal ($n2 -> $n3)" $?

# The same for a saved world: each scripted run on it used to set the last run's journal
# aside, and WORLD.recover.old* piled up without limit. A journal another session left
# (here standard input's, maybe a person typing) is still set aside and kept, and a
# failed script keeps its own.
sdir=$(mktemp -d "${TMPDIR:-/tmp}/orogen-scripted.XXXXXX")
"$orogen" -c "new flat; size 256; generate; save $sdir/w.world" >/dev/null 2>&1
for run in 1 2 3; do
    "$orogen" -c "load $sdir/w.world; tool raise radius=30 strength=1; dab 10 10" >/dev/null 2>&1
done
n_saved=$(find "$sdir" -name 'w.world.recover*' | wc -l)
echo "load $sdir/w.world; tool raise radius=30 strength=1; dab 10 10" |
    "$orogen" --batch - >/dev/null 2>&1
"$orogen" -c "load $sdir/w.world; tool raise radius=30 strength=1; dab 30 30" >/dev/null 2>&1
n_aside=$(find "$sdir" -name 'w.world.recover.old*' | wc -l)
n_own=$(find "$sdir" -name 'w.world.recover' | wc -l)
"$orogen" -c "load $sdir/w.world; tool raise radius=30 strength=1; dab 50 50; save /proc/no/w.world" \
    >/dev/null 2>&1
n_failed=$(find "$sdir" -name 'w.world.recover' | wc -l)
[ "$n_saved" = 0 ] && [ "$n_aside" = 1 ] && [ "$n_own" = 0 ] && [ "$n_failed" = 1 ]
check "scripts on a saved world leave no journal; another session's is set aside and kept; a failed script keeps its own ($n_saved, $n_aside, $n_own, $n_failed)" $?
rm -rf "$sdir"

# One writer: while the editor has the world open, a second orogen opens it read-only
# and cannot save over it, but can save elsewhere.
start
step 0 >/dev/null
"$orogen" "$work/w.world" -c "dab 10 10; save" >"$work/second.out" 2>"$work/second.err"
status=$?
[ $status = 1 ] && grep -q "w.world is open in process $app: opened read-only" "$work/second.err" &&
    grep -q "save: $work/w.world is open in process $app; save to another file" "$work/second.err"
rc=$?; check "a second process opens the world read-only and cannot save over it ($(tail -n 1 "$work/second.err" | head -c 200))" $rc
"$orogen" "$work/w.world" -c "dab 10 10; save $work/copy.world" >/dev/null 2>&1
[ -s "$work/copy.world" ]; check "it saves to another file" $?
kill9

# A quit without saving keeps this session's journal (only a save of its edits or an
# explicit discard removes one): the next session lists and offers it.
start
step 0 >/dev/null
ask "exit" 'xyz-never' >/dev/null
wait "$app" 2>/dev/null
app=
exec 3>&-
[ -s "$work/w.world.recover" ] && "$orogen" "$work/w.world" -c 'recover list' 2>/dev/null |
    grep -q "w.world.recover: 1 step.*recoverable"
check "a quit without saving keeps the journal, and 'recover list' offers it" $?

end_window_test
